//! Polar coordinates (reference §5): the pole (G110, G111, G112), a move to AP/RP around it, and the
//! circle of a polar G2/G3 block.

use crate::analysis::engine::block_words::PolarWords;
use crate::analysis::engine::engine_state::Engine;
use crate::config::AxisKind;
use crate::diagnostics::{Code, Diagnostic};
use crate::syntax::ast::*;
use crate::syntax::gcodes::GCode;

impl<'a> Engine<'a> {
    /// G110 (relative to the last programmed position), G111 (absolute), G112 (relative to the last
    /// pole): the pole of the active plane, from the plane axes or from AP/RP (reference §5.1).
    pub(super) fn define_pole(
        &mut self,
        code: GCode,
        line: &str,
        block: &Block,
        statements: &[Statement],
        polar: &PolarWords,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        use crate::analysis::state::Pole;
        self.state.polar_angle = None;
        // What a stored RP means for the new pole is not documented (reference §5.2 [?]).
        self.state.polar_radius = None;
        self.memory.pole_changed = true;
        let Some(plane) = self.state.plane_index() else {
            return;
        };
        let (first, second) = self.plane_axes();
        let reference = match code.name().as_ref() {
            "G111" => Some((0.0, 0.0)),
            "G110" => first.zip(second).and_then(|(first, second)| {
                self.state.positions[first].zip(self.state.positions[second])
            }),
            _ => match self.state.poles[plane] {
                Pole::At(first, second) => Some((first, second)),
                Pole::Undefined => Some((0.0, 0.0)),
                Pole::Unknown => None,
            },
        };
        let offset = if polar.angle.is_some() || polar.radius.is_some() {
            match (polar.angle, polar.radius) {
                (Some((Some(angle), false)), Some(Some(radius))) => {
                    let radians = angle.to_radians();
                    Some((radius * radians.cos(), radius * radians.sin()))
                }
                _ => None,
            }
        } else {
            let mut values = [Some(0.0), Some(0.0)];
            for (index, word) in self.configured_axis_words(line, statements) {
                let slot = if Some(index) == first {
                    0
                } else if Some(index) == second {
                    1
                } else {
                    continue;
                };
                let factor = self.state.length_factor(self.config.metric);
                // Whether a pole coordinate on a transverse axis is a diameter is not documented
                // (reference §5.2 [?]): it stays unknown unless the axis reads radii.
                let diameter = self.config.axes[index].kind == AxisKind::Transverse
                    && self.state.diameter_mode() != Some((false, false));
                values[slot] = if diameter {
                    None
                } else {
                    self.word_value(line, block, word, diagnostics)
                        .zip(factor)
                        .map(|(value, factor)| value * factor)
                };
            }
            values[0].zip(values[1])
        };
        self.state.poles[plane] = match reference.zip(offset) {
            Some((reference, offset)) => Pole::At(reference.0 + offset.0, reference.1 + offset.1),
            None => Pole::Unknown,
        };
    }
    /// A move to AP/RP around the pole; returns the pole (the centre of a polar circle) when known.
    pub(super) fn apply_polar_move(
        &mut self,
        line: &str,
        statements: &[Statement],
        polar: &PolarWords,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> Option<(f64, f64)> {
        use crate::analysis::state::Pole;
        let span = polar.span.unwrap_or_default();
        let (first, second) = self.plane_axes();
        // With the plane unknown, any geometry axis may be a plane axis.
        let plane_axes = self.plane_axis_indexes();
        let forget_plane = |engine: &mut Engine| {
            for index in &plane_axes {
                engine.program_axis(*index, None);
            }
        };
        let angle = match polar.angle {
            Some((Some(value), true)) => self.state.polar_angle.map(|stored| stored + value),
            Some((value, false)) => value,
            Some((None, true)) => None,
            None => self.state.polar_angle,
        };
        let radius = match polar.radius {
            Some(value) => value,
            None => self.state.polar_radius,
        };
        self.state.polar_angle = angle;
        self.state.polar_radius = radius;
        // Only the axis perpendicular to the plane may join AP/RP (reference §5.3, T97).
        let plane_axis_written = statements.iter().any(|statement| {
            matches!(statement, Statement::Address(word) if word.kind == AddressKind::Axis && {
                self.axes.index(self.config, line, word).is_some_and(|index| plane_axes.contains(&index))
            })
        });
        if plane_axis_written {
            diagnostics.push(Diagnostic::new(
                Code::PolarWithPlaneAxis,
                span,
                "a polar block may add only the axis perpendicular to the plane; a plane axis cannot join AP and RP",
            ));
            forget_plane(self);
            return None;
        }
        let (Some(first), Some(second), Some(plane)) = (first, second, self.state.plane_index())
        else {
            forget_plane(self);
            return None;
        };
        let pole = match self.state.poles[plane] {
            Pole::At(first, second) => Some((first, second)),
            Pole::Undefined => {
                diagnostics.push(Diagnostic::new(
                    Code::PolarWithoutPole,
                    span,
                    "no pole is defined (G110, G111, G112): the pole is the zero point of the workpiece coordinate system",
                ));
                Some((0.0, 0.0))
            }
            Pole::Unknown => None,
        };
        let transverse_in_plane = [first, second]
            .iter()
            .any(|index| self.config.axes[*index].kind == AxisKind::Transverse)
            && self.state.diameter_mode() != Some((false, false));
        let (Some(pole), Some(angle), Some(radius), false) =
            (pole, angle, radius, transverse_in_plane)
        else {
            forget_plane(self);
            return None;
        };
        let radians = angle.to_radians();
        self.program_axis(first, Some(pole.0 + radius * radians.cos()));
        self.program_axis(second, Some(pole.1 + radius * radians.sin()));
        Some(pole)
    }
    /// The circle of a polar G2/G3 block: around the pole, from the start to the polar end point.
    pub(super) fn polar_circle(
        &self,
        clockwise: bool,
        start_positions: &[Option<f64>],
        centre: (f64, f64),
        polar: &PolarWords,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> Option<crate::analysis::circle::Circle> {
        let (Some(first), Some(second)) = self.plane_axes() else {
            return None;
        };
        let start = (start_positions[first]?, start_positions[second]?);
        let end = (self.state.positions[first]?, self.state.positions[second]?);
        match crate::analysis::circle::from_centre(
            start,
            end,
            centre,
            clockwise,
            self.config.circle_error_const,
            self.config.circle_error_factor,
        ) {
            Ok(circle) => Some(circle),
            Err(_) => {
                diagnostics.push(Diagnostic::new(
                    Code::CircleEndNotOnCircle,
                    polar.span.unwrap_or_default(),
                    "the start point does not lie on the polar circle around the pole within the tolerance (alarm 14040)",
                ));
                None
            }
        }
    }
}
