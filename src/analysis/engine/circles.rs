//! The circle of a G2/G3, CIP or CT block in the working plane (reference §6.2): by centre (I/J/K), by
//! radius (CR), by opening angle (AR, with the end point or with the centre, whose end point is the
//! start turned about the centre), through an intermediate point (CIP with I1/J1/K1), or tangential to
//! the previous path element (CT); TURN adds full turns. What the control rejects is reported.

use crate::analysis::circle::{self, Circle, CircleError};
use crate::analysis::engine::block_words::CircleWords;
use crate::analysis::engine::engine_state::Engine;
use crate::analysis::four_decimals::FourDecimals;
use crate::config::AxisKind;
use crate::diagnostics::{Code, Diagnostic, Span};
use crate::syntax::ast::{AddressWord, Block, Modifier};

impl Engine<'_> {
    /// The circle of a G2/G3 block written with I/J/K, CR or AR.
    pub(super) fn resolve_circle(
        &mut self,
        clockwise: bool,
        start_positions: &[Option<f64>],
        words: &CircleWords,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> Option<Circle> {
        let span = words.span.unwrap_or_default();
        let (Some(first), Some(second)) = self.plane_axes() else {
            return None;
        };
        let centre_given = [first, second].iter().any(|index| {
            self.slots
                .slot(*index)
                .is_some_and(|slot| words.centre[slot].is_some())
        });
        if !words.radius_written && !centre_given && !words.opening_angle && !words.centre_unknown {
            diagnostics.push(Diagnostic::new(
                Code::CircleWithoutCentre,
                span,
                "G2/G3 needs a centre (I, J, K), a radius (CR=), an opening angle (AR=) or polar values (AP=, RP=)",
            ));
            return None;
        }
        if words.opening_angle {
            return self.resolve_opening_angle(
                clockwise,
                start_positions,
                words,
                centre_given,
                diagnostics,
            );
        }
        if words.centre_unknown || (words.radius_written && words.radius.is_none()) {
            // A value of the circle is unknown: nothing can be checked.
            return None;
        }
        let start = (start_positions[first]?, start_positions[second]?);
        let end = (self.state.positions[first]?, self.state.positions[second]?);
        let error_const = self.config.circle_error_const;
        let error_factor = self.config.circle_error_factor;
        if let Some(radius) = words.radius {
            return circle::from_radius(start, end, radius, clockwise, error_const, error_factor)
                .map_err(|error| report_circle_error(error, span, diagnostics))
                .ok();
        }
        let centre = self.programmed_centre(first, second, start, words);
        match circle::from_centre(start, end, centre, clockwise, error_const, error_factor) {
            Ok(circle) => Some(circle),
            Err(error) => {
                report_circle_error(error, span, diagnostics);
                self.check_centre_looks_absolute(
                    first,
                    second,
                    start,
                    end,
                    clockwise,
                    words,
                    diagnostics,
                );
                None
            }
        }
    }

    /// The centre from I/J/K: incremental from the start unless `=AC`; a left-out parameter is 0
    /// (reference §3.2).
    fn programmed_centre(
        &self,
        first: usize,
        second: usize,
        start: (f64, f64),
        words: &CircleWords,
    ) -> (f64, f64) {
        let coordinate = |index: usize, start_value: f64| -> f64 {
            match self.slots.slot(index).and_then(|slot| words.centre[slot]) {
                Some((value, true)) => value,
                Some((value, false)) => start_value + value,
                None => start_value,
            }
        };
        (coordinate(first, start.0), coordinate(second, start.1))
    }

    /// §9.2 #2: under G90, I and J written as if they were absolute coordinates. Reported only when the
    /// circle is rejected and the absolute reading would give a valid one, so the hint is never a guess.
    #[allow(clippy::too_many_arguments)]
    fn check_centre_looks_absolute(
        &self,
        first: usize,
        second: usize,
        start: (f64, f64),
        end: (f64, f64),
        clockwise: bool,
        words: &CircleWords,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        if self.state.is_incremental() != Some(false) {
            return;
        }
        let value = |index: usize| match self.slots.slot(index).and_then(|slot| words.centre[slot])
        {
            Some((value, false)) => Some(value),
            _ => None,
        };
        let (Some(centre_first), Some(centre_second)) = (value(first), value(second)) else {
            return;
        };
        let absolute = circle::from_centre(
            start,
            end,
            (centre_first, centre_second),
            clockwise,
            self.config.circle_error_const,
            self.config.circle_error_factor,
        );
        if absolute.is_ok() {
            diagnostics.push(Diagnostic::new(
                Code::CentreLooksAbsolute,
                words.span.unwrap_or_default(),
                "I, J and K are measured from the circle's start point, also under G90; read as absolute coordinates they would fit this circle: write them as `I=AC(..)`",
            ));
        }
    }

    /// AR with the end point (`G3 X20 Y0 AR=180`) or with the centre (`G3 I-10 J0 AR=90`, the end
    /// being the start turned about the centre). Plane axes whose end cannot be computed are unknown.
    fn resolve_opening_angle(
        &mut self,
        clockwise: bool,
        start_positions: &[Option<f64>],
        words: &CircleWords,
        centre_given: bool,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> Option<Circle> {
        let span = words.span.unwrap_or_default();
        let (Some(first), Some(second)) = self.plane_axes() else {
            return None;
        };
        let end_written = self.written[first] == 1 || self.written[second] == 1;
        let start = start_positions[first].zip(start_positions[second]);
        if centre_given && !end_written {
            let result = match (start, words.opening_angle_value, words.centre_unknown) {
                (Some(start), Some(angle), false) => {
                    let centre = self.programmed_centre(first, second, start, words);
                    Some(circle::from_opening_angle_and_centre(
                        start, centre, angle, clockwise,
                    ))
                }
                _ => None,
            };
            return match result {
                Some(Ok((end, circle))) => {
                    self.program_axis(first, Some(end.0));
                    self.program_axis(second, Some(end.1));
                    Some(circle)
                }
                other => {
                    if let Some(Err(error)) = other {
                        report_circle_error(error, span, diagnostics);
                    }
                    self.program_axis(first, None);
                    self.program_axis(second, None);
                    None
                }
            };
        }
        if centre_given {
            // Centre, end point and angle together over-determine the circle; not followed.
            return None;
        }
        if !end_written {
            // `G3 AR=90` alone: neither the end point nor the centre is given, so the angle has
            // nothing to open from; the missing definition is the mistake, not the angle.
            diagnostics.push(Diagnostic::new(
                Code::CircleWithoutCentre,
                span,
                "AR needs the end point (X, Y, Z) or the centre (I, J, K) of the circle: neither is given",
            ));
            return None;
        }
        let end = self.state.positions[first].zip(self.state.positions[second]);
        let (Some(start), Some(end), Some(angle)) = (start, end, words.opening_angle_value) else {
            return None;
        };
        circle::from_opening_angle(start, end, angle, clockwise)
            .map_err(|error| report_circle_error(error, span, diagnostics))
            .ok()
    }

    /// Reads I1=, J1=, K1= of CIP: like the end point, absolute under G90 or `=AC`, incremental from
    /// the start under G91 or `=IC` (reference §6.2), converted by G70 and read as a diameter where the
    /// end point would be.
    pub(super) fn collect_intermediate_word(
        &self,
        line: &str,
        block: &Block,
        word: &AddressWord,
        words: &mut CircleWords,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        let slot = match line.as_bytes()[word.name.start()].to_ascii_uppercase() {
            b'I' => 0,
            b'J' => 1,
            _ => 2,
        };
        let absolute = match word.value.modifier.map(|(modifier, _)| modifier) {
            Some(Modifier::Ac) => Some(true),
            Some(Modifier::Ic) => Some(false),
            Some(_) => None,
            None => self.state.is_incremental().map(|incremental| !incremental),
        };
        let value = self
            .word_value(line, block, word, diagnostics)
            .zip(self.state.length_factor(self.config.metric))
            .map(|(value, factor)| value * factor);
        let transverse = self
            .config
            .axis(["X", "Y", "Z"][slot])
            .is_some_and(|axis| axis.kind == AxisKind::Transverse);
        let value = match (value, absolute) {
            (Some(value), Some(absolute)) if transverse => {
                self.state
                    .diameter_mode()
                    .map(|(absolute_diameter, incremental_diameter)| {
                        let diameter = if absolute {
                            absolute_diameter
                        } else {
                            incremental_diameter
                        };
                        if diameter {
                            (value / 2.0, absolute)
                        } else {
                            (value, absolute)
                        }
                    })
            }
            (Some(value), Some(absolute)) => Some((value, absolute)),
            _ => None,
        };
        words.intermediate[slot] = Some(value);
    }

    /// The circle of CIP through the intermediate point; collinear points are alarm 14920 unless the
    /// intermediate point lies between the others (a straight line).
    pub(super) fn resolve_cip(
        &self,
        start_positions: &[Option<f64>],
        words: &CircleWords,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> Option<Circle> {
        let (Some(first), Some(second)) = self.plane_axes() else {
            return None;
        };
        let start = (start_positions[first]?, start_positions[second]?);
        let end = (self.state.positions[first]?, self.state.positions[second]?);
        let coordinate = |index: usize, start_value: f64| -> Option<f64> {
            let (value, absolute) = words.intermediate[self.slots.slot(index)?]??;
            Some(if absolute { value } else { start_value + value })
        };
        let via = (coordinate(first, start.0)?, coordinate(second, start.1)?);
        circle::through_points(start, via, end)
            .map_err(|error| {
                report_circle_error(error, words.span.unwrap_or_default(), diagnostics)
            })
            .ok()
            .flatten()
    }

    /// The circle of CT, tangent to the previous path element in the same plane.
    pub(super) fn resolve_ct(&self, start_positions: &[Option<f64>]) -> Option<Circle> {
        let (Some(first), Some(second)) = self.plane_axes() else {
            return None;
        };
        let (plane, tangent) = self.tangent?;
        if Some(plane) != self.state.plane_index() {
            return None;
        }
        let start = (start_positions[first]?, start_positions[second]?);
        let end = (self.state.positions[first]?, self.state.positions[second]?);
        circle::tangential(start, tangent, end)
    }

    /// Remembers the direction at the end of this block's path in the plane, for a following CT: a
    /// straight move's direction, or the tangent at a circle's end. Unknown after a circle the engine
    /// could not resolve or a move that leaves the plane.
    pub(super) fn update_tangent(
        &mut self,
        motion: &str,
        start_positions: &[Option<f64>],
        arc: Option<&Circle>,
    ) {
        let Some(plane) = self.state.plane_index() else {
            self.tangent = None;
            return;
        };
        let (Some(first), Some(second)) = self.plane_axis_cache[plane] else {
            self.tangent = None;
            return;
        };
        let start = start_positions[first].zip(start_positions[second]);
        let end = self.state.positions[first].zip(self.state.positions[second]);
        self.tangent = match (arc, start, end) {
            (Some(arc), _, Some(end)) => Some((plane, circle::end_tangent(arc, end))),
            (None, Some(start), Some(end)) if matches!(motion, "G0" | "G1") => {
                let direction = (end.0 - start.0, end.1 - start.1);
                (direction.0 * direction.0 + direction.1 * direction.1 > 1e-18)
                    .then_some((plane, direction))
            }
            _ => None,
        };
    }

    /// TURN=n adds n full turns to a circle (a helix); 0 to 999 are allowed (reference §3.3, T105).
    pub(super) fn apply_turns(
        &self,
        circle: Option<Circle>,
        words: &CircleWords,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> Option<Circle> {
        let Some((turns, span)) = words.turns else {
            return circle;
        };
        let Some(turns) = turns else {
            return circle;
        };
        if !(0.0..=999.0).contains(&turns) {
            diagnostics.push(Diagnostic::new(
                Code::TurnsOutOfRange,
                span,
                format!("TURN={turns} is not allowed: the number of additional full turns is from 0 to 999 (alarm 14048)"),
            ));
            return None;
        }
        if turns.fract() != 0.0 {
            // How the control reads a fractional number of turns is not documented.
            return None;
        }
        circle.map(|mut circle| {
            circle.sweep += 360.0 * turns;
            circle
        })
    }

    /// Reads I, J or K: incremental from the circle's start unless `=AC` (reference §3.2), converted by
    /// G70/G700; on a transverse axis an absolute value under diameter programming is a diameter.
    pub(super) fn collect_centre_word(
        &self,
        line: &str,
        block: &Block,
        word: &AddressWord,
        circle_words: &mut CircleWords,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        let letter = line.as_bytes()[word.name.start()].to_ascii_uppercase();
        let slot = match letter {
            b'I' => 0,
            b'J' => 1,
            _ => 2,
        };
        let absolute = matches!(word.value.modifier, Some((Modifier::Ac, _)));
        let value = self.word_value(line, block, word, diagnostics);
        if value == Some(0.0) {
            // 0 is 0 in every unit and as a diameter: known where the units are inherited.
            circle_words.centre[slot] = Some((0.0, absolute));
            return;
        }
        let (Some(value), Some(factor)) = (value, self.state.length_factor(self.config.metric))
        else {
            circle_words.centre_unknown = true;
            return;
        };
        let mut value = value * factor;
        let axis_name = ["X", "Y", "Z"][slot];
        let transverse = self
            .config
            .axis(axis_name)
            .is_some_and(|axis| axis.kind == AxisKind::Transverse);
        if transverse && absolute {
            match self.state.diameter_mode() {
                Some((true, _)) => value /= 2.0,
                Some(_) => {}
                None => {
                    circle_words.centre_unknown = true;
                    return;
                }
            }
        }
        circle_words.centre[slot] = Some((value, absolute));
    }
}

/// The finding for a circle the control rejects.
fn report_circle_error(error: CircleError, span: Span, diagnostics: &mut Vec<Diagnostic>) {
    let (code, message) = match error {
        CircleError::EndNotOnCircle {
            difference,
            tolerance,
        } => (
            Code::CircleEndNotOnCircle,
            format!(
                "the end point is {} off the circle, more than the tolerance {} (alarm 14040)",
                FourDecimals(difference),
                FourDecimals(tolerance)
            ),
        ),
        CircleError::RadiusTooSmall { chord, radius } => (
            Code::CircleRadiusTooSmall,
            format!(
                "CR={} is smaller than half the distance to the end point ({}): no such circle exists",
                FourDecimals(radius),
                FourDecimals(chord / 2.0)
            ),
        ),
        CircleError::RadiusFullCircle => (
            Code::CircleRadiusFullCircle,
            "CR cannot program a full circle: the end point equals the start point (alarm 14040)".to_string(),
        ),
        CircleError::OpeningAngleOutOfRange => (
            Code::OpeningAngleOutOfRange,
            "the opening angle AR must be greater than 0 and less than 360 degrees, with the end point away from the start: AR cannot program a full circle".to_string(),
        ),
        CircleError::IntermediatePointOnLine => (
            Code::IntermediatePointOnLine,
            "start, intermediate and end point of CIP lie on one line, the intermediate point not between the others: no circle passes through them (alarm 14920)".to_string(),
        ),
    };
    diagnostics.push(Diagnostic::new(code, span, message));
}
