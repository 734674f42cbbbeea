//! Circle words the control rejects or that do nothing (reference §6.2, §5.3, §9): CR, AR or I/J/K on a
//! G0/G1 line, G2/G3 without any definition also where the plane is inherited, a circle given two ways
//! at once, a circle of radius zero, CIP without a usable intermediate point, and a pole with one
//! coordinate. The circle geometry itself is checked in `circles.rs`.

use crate::analysis::engine::block_words::{statements_span, CircleWords, PolarWords};
use crate::analysis::engine::engine_state::Engine;
use crate::diagnostics::{Code, Diagnostic, Span};
use crate::syntax::ast::{AddressKind, Extension, NamedAddress, Statement};
use crate::syntax::gcodes::GCode;

/// Below this distance (in the basic unit system) two points are the same point.
const SAME_POINT: f64 = 1e-9;

/// The circle words one block writes, with their spans, read from its statements.
#[derive(Default)]
struct WrittenWords {
    centre: Option<Span>,
    intermediate: Option<Span>,
    radius: Option<Span>,
    opening_angle: Option<Span>,
    polar: Option<Span>,
}

impl WrittenWords {
    fn of(statements: &[Statement]) -> WrittenWords {
        let mut words = WrittenWords::default();
        for statement in statements {
            let Statement::Address(word) = statement else {
                continue;
            };
            let slot = match word.kind {
                AddressKind::Interpolation => match word.extension {
                    None => &mut words.centre,
                    Some(Extension::Number { value: 1, .. }) => &mut words.intermediate,
                    _ => continue,
                },
                AddressKind::Named(NamedAddress::CircleRadius) => &mut words.radius,
                AddressKind::Named(NamedAddress::OpeningAngle) => &mut words.opening_angle,
                AddressKind::Named(NamedAddress::PolarAngle | NamedAddress::PolarRadius) => {
                    &mut words.polar
                }
                _ => continue,
            };
            *slot = Some(slot.map_or(word.span, |span| span.to(word.span)));
        }
        words
    }
}

/// What the circle checks need of one block, gathered by the engine's step.
pub(super) struct CircleBlock<'b> {
    pub line: &'b str,
    pub statements: &'b [Statement],
    /// The motion (group 1) after the block, `""` when unknown.
    pub motion: &'b str,
    /// Whether the block moves along a path (not a frame, pole or dwell block).
    pub moves_path: bool,
    pub frame_or_pole: Option<GCode>,
    pub words: &'b CircleWords,
    pub polar: &'b PolarWords,
    pub start_positions: &'b [Option<f64>],
}

impl Engine<'_> {
    /// The findings of this file for one block. Returns true when the block's circle is rejected
    /// here, so that its geometry is not checked a second time.
    pub(super) fn check_circle_words(
        &self,
        block: &CircleBlock,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> bool {
        let written = WrittenWords::of(block.statements);
        if let Some(code) = block.frame_or_pole {
            self.check_pole_coordinates(code, &written, block, diagnostics);
            return false;
        }
        match block.motion {
            "G0" | "G1" => {
                self.check_words_without_circle(block.motion, &written, diagnostics);
                false
            }
            "G2" | "G3" if block.moves_path => self.check_circle(block, &written, diagnostics),
            "CIP" if block.moves_path => {
                self.check_intermediate_point(block, &written, diagnostics)
            }
            _ => false,
        }
    }

    /// CR, AR or I/J/K under G0/G1: the control ignores them (§9, issue 18).
    fn check_words_without_circle(
        &self,
        motion: &str,
        written: &WrittenWords,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        for (span, name) in [
            (written.radius, "CR does"),
            (written.opening_angle, "AR does"),
            (written.centre, "I, J and K do"),
        ] {
            if let Some(span) = span {
                diagnostics.push(Diagnostic::new(
                    Code::CircleWordWithoutCircle,
                    span,
                    format!("{name} nothing on a {motion} line: the block moves in a straight line; write G2 or G3 for a circle, or remove the word"),
                ));
            }
        }
    }

    /// G2/G3: no definition at all (also where the plane is inherited and unknown), two definitions
    /// at once, or radius zero. Returns true when the circle is rejected here.
    fn check_circle(
        &self,
        block: &CircleBlock,
        written: &WrittenWords,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> bool {
        let span = block.words.span.unwrap_or_default();
        if self.plane_axes().0.is_none()
            && written.centre.is_none()
            && written.radius.is_none()
            && written.opening_angle.is_none()
            && written.polar.is_none()
        {
            // Where the plane is known `resolve_circle` reports this; without a centre, radius, angle
            // or polar value the block is wrong in every plane.
            diagnostics.push(Diagnostic::new(
                Code::CircleWithoutCentre,
                span,
                "G2/G3 needs a centre (I, J, K), a radius (CR=), an opening angle (AR=) or polar values (AP=, RP=), whatever the plane",
            ));
            return true;
        }
        if self.plane_axes().0.is_none()
            && written.opening_angle.is_some()
            && written.centre.is_none()
            && written.radius.is_none()
            && written.polar.is_none()
            && !self.writes_geometry_axis(block)
        {
            // `G3 AR=90` alone where the plane is inherited: no end point and no centre in any plane
            // (where the plane is known `resolve_circle` reports it).
            diagnostics.push(Diagnostic::new(
                Code::CircleWithoutCentre,
                span,
                "AR needs the end point or the centre (I, J, K) of the circle: neither is given, whatever the plane",
            ));
            return true;
        }
        if let Some(radius_span) = written.radius {
            let other = match (written.centre, written.opening_angle) {
                (Some(_), _) => Some("I/J/K"),
                (None, Some(_)) => Some("AR"),
                _ => None,
            };
            if let Some(other) = other {
                diagnostics.push(Diagnostic::new(
                    Code::CircleDefinedTwice,
                    radius_span,
                    format!("the circle is given two ways at once, by CR and by {other}: the control rejects the block; keep one of them"),
                ));
                return true;
            }
        }
        if written.polar.is_some() {
            if block.polar.radius == Some(Some(0.0)) {
                diagnostics.push(Diagnostic::new(
                    Code::CircleRadiusZero,
                    span,
                    "RP=0 makes a circle of radius zero around the pole (alarm 14040)",
                ));
                return true;
            }
            return false;
        }
        if written.centre.is_some() && written.opening_angle.is_none() {
            if let Some(true) = self.centre_is_start(block) {
                diagnostics.push(Diagnostic::new(
                    Code::CircleRadiusZero,
                    span,
                    "the centre given by I, J, K is the start point: a circle of radius zero (alarm 14040); I/J/K are measured from the start point, also under G90",
                ));
                return true;
            }
        }
        false
    }

    /// Whether the block writes a geometry axis (an axis of any of the three planes).
    fn writes_geometry_axis(&self, block: &CircleBlock) -> bool {
        block.statements.iter().any(|statement| match statement {
            Statement::Address(word) if word.kind == AddressKind::Axis => self
                .axes
                .index(self.config, block.line, word)
                .is_none_or(|index| {
                    self.plane_axis_cache
                        .iter()
                        .any(|(first, second)| [*first, *second].contains(&Some(index)))
                }),
            _ => false,
        })
    }

    /// Whether the programmed centre is the start point; `None` when a value is unknown.
    fn centre_is_start(&self, block: &CircleBlock) -> Option<bool> {
        if block.words.centre_unknown {
            return None;
        }
        let (Some(first), Some(second)) = self.plane_axes() else {
            // The plane is inherited and unknown: centre offsets that are all 0 (`I0 J0`, measured
            // from the start point) put the centre on the start point in every plane.
            let mut written = block.words.centre.iter().flatten().peekable();
            let zero = written.peek().is_some()
                && written.all(|(value, absolute)| !absolute && value.abs() <= SAME_POINT);
            return zero.then_some(true);
        };
        let mut offsets = [0.0; 2];
        for (offset, index) in offsets.iter_mut().zip([first, second]) {
            let slot = self.slots.slot(index)?;
            *offset = match block.words.centre[slot] {
                Some((value, false)) => value,
                Some((value, true)) => value - block.start_positions[index]?,
                None => 0.0,
            };
        }
        Some(offsets.iter().all(|offset| offset.abs() <= SAME_POINT))
    }

    /// CIP without I1/J1/K1, or with an intermediate point equal to the start or the end point.
    fn check_intermediate_point(
        &self,
        block: &CircleBlock,
        written: &WrittenWords,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> bool {
        let span = block.words.span.unwrap_or_default();
        if written.intermediate.is_none() {
            diagnostics.push(Diagnostic::new(
                Code::IntermediatePointMissing,
                span,
                "CIP needs an intermediate point (I1=, J1=, K1=): without it no circle is defined (alarm 14920)",
            ));
            return true;
        }
        let Some(point) = self.intermediate_point(block) else {
            return false;
        };
        let (Some(first), Some(second)) = self.plane_axes() else {
            return false;
        };
        let same = |positions: &[Option<f64>]| -> bool {
            match (positions[first], positions[second]) {
                (Some(a), Some(b)) => {
                    (a - point.0).abs() <= SAME_POINT && (b - point.1).abs() <= SAME_POINT
                }
                _ => false,
            }
        };
        let which = if same(block.start_positions) {
            "start"
        } else if same(&self.state.positions) {
            "end"
        } else {
            return false;
        };
        diagnostics.push(Diagnostic::new(
            Code::IntermediatePointMissing,
            written.intermediate.unwrap_or(span),
            format!("the intermediate point of CIP equals its {which} point: no circle is defined (alarm 14920)"),
        ));
        true
    }

    /// The intermediate point of CIP in the plane, when both of its coordinates are written and known
    /// (a left-out coordinate is not documented, so it is not guessed).
    fn intermediate_point(&self, block: &CircleBlock) -> Option<(f64, f64)> {
        let (Some(first), Some(second)) = self.plane_axes() else {
            return None;
        };
        let coordinate = |index: usize| -> Option<f64> {
            let slot = self.slots.slot(index)?;
            let (value, absolute) = block.words.intermediate[slot]??;
            if absolute {
                Some(value)
            } else {
                Some(block.start_positions[index]? + value)
            }
        };
        Some((coordinate(first)?, coordinate(second)?))
    }

    /// A pole with one coordinate of the plane (`G111 X10`): reference §5.3 recommends a warning.
    fn check_pole_coordinates(
        &self,
        code: GCode,
        written: &WrittenWords,
        block: &CircleBlock,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        let statements = block.statements;
        if !matches!(code.name().as_ref(), "G110" | "G111" | "G112") || written.polar.is_some() {
            return;
        }
        // The axis words of a pole block are not applied as moves, so they are looked up here.
        let given = |index: usize| {
            statements.iter().any(|statement| match statement {
                Statement::Address(word) if word.kind == AddressKind::Axis => {
                    self.axes.index(self.config, block.line, word) == Some(index)
                }
                _ => false,
            })
        };
        let (Some(first), Some(second)) = self.plane_axes() else {
            // The plane is inherited and unknown: one geometry axis alone is one coordinate (or none)
            // of every plane.
            let mut geometry: Vec<usize> = self
                .plane_axis_cache
                .iter()
                .flat_map(|(first, second)| [*first, *second])
                .flatten()
                .collect();
            geometry.sort_unstable();
            geometry.dedup();
            let written: Vec<usize> = geometry.into_iter().filter(|index| given(*index)).collect();
            if let [only] = written[..] {
                diagnostics.push(Diagnostic::new(
                    Code::PoleWithOneCoordinate,
                    statements_span(statements).unwrap_or_default(),
                    format!(
                        "the pole is given by {} alone: whatever the plane, a coordinate of the plane is missing, which is not documented; write both coordinates of the plane",
                        self.config.axes[only].name
                    ),
                ));
            }
            return;
        };
        let given = [given(first), given(second)];
        if given[0] == given[1] {
            return;
        }
        let missing = if given[0] { second } else { first };
        diagnostics.push(Diagnostic::new(
            Code::PoleWithOneCoordinate,
            statements_span(statements).unwrap_or_default(),
            format!(
                "the pole is given by one coordinate only: {} is taken as 0 from the reference of {}, which is not documented; write both coordinates of the plane",
                self.config.axes[missing].name,
                code.name()
            ),
        ));
    }
}
