//! Contour definitions in the engine (reference §14): the words `RND`, `RNDM`, `CHF`, `CHR`, `FRC`,
//! `FRCM` and `ANG` of a block. The engine only reads them and resolves what changes the programmed
//! position (`ANG`, §14.6); the rounding or chamfer itself changes only the path, which the corner
//! stage of the simulation inserts (`analysis::simulation::corners`) from the request a move carries.

use crate::analysis::engine::corner_requests::{ContourRequest, CornerElement, OpenAngle};
use crate::analysis::engine::engine_state::Engine;
use crate::analysis::engine::evaluation::evaluate_value_or_report;
use crate::analysis::eval::Value;
use crate::diagnostics::{Code, Diagnostic, Span};
use crate::syntax::ast::{AddressWord, AssignTarget, Block, ExprId};

/// The contour words of one block as read.
#[derive(Default)]
pub(super) struct ContourWords {
    rounding: Option<(Option<f64>, Span)>,
    chamfer: Option<(Option<f64>, bool, Span)>,
    feed: Option<Option<f64>>,
    angle: Option<(Option<f64>, Span)>,
}

impl ContourWords {
    /// Whether the block wrote any contour word that concerns its own corner or position.
    pub(super) fn any(&self) -> bool {
        self.rounding.is_some()
            || self.chamfer.is_some()
            || self.feed.is_some()
            || self.angle.is_some()
    }
}

/// Which contour word a name is, given the configured names (MD10652, MD10654, MD10656).
#[derive(Clone, Copy, PartialEq)]
enum Word {
    Angle,
    Rounding,
    ModalRounding,
    ChamferLeg,
    ChamferLength,
    Feed,
    ModalFeed,
}

impl Engine<'_> {
    fn contour_word_of(&self, name: &str) -> Option<Word> {
        let names = &self.config.contours;
        if name.eq_ignore_ascii_case(&names.angle_name) {
            Some(Word::Angle)
        } else if name.eq_ignore_ascii_case(&names.radius_name) {
            Some(Word::Rounding)
        } else if name.eq_ignore_ascii_case(&names.chamfer_name) {
            Some(Word::ChamferLeg)
        } else if name.eq_ignore_ascii_case("RNDM") {
            Some(Word::ModalRounding)
        } else if name.eq_ignore_ascii_case("CHF") {
            Some(Word::ChamferLength)
        } else if name.eq_ignore_ascii_case("FRC") {
            Some(Word::Feed)
        } else if name.eq_ignore_ascii_case("FRCM") {
            Some(Word::ModalFeed)
        } else {
            None
        }
    }

    /// Reads a named address word (`RND=5`) if it is a contour word.
    pub(super) fn read_contour_address(
        &mut self,
        line: &str,
        block: &Block,
        word: &AddressWord,
        contour: &mut ContourWords,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        let name = &line[word.name.start()..word.name.end()];
        let Some(kind) = self.contour_word_of(name) else {
            return;
        };
        let value = self.word_value(line, block, word, diagnostics);
        self.apply_contour_word(kind, value, word.span, contour);
    }

    /// Reads an assignment to a plain name (`ANG=30`, or a configured name the parser does not know
    /// as an address) as a contour word; returns false when it is none, so that it is an assignment.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn read_contour_assignment(
        &mut self,
        line: &str,
        block: &Block,
        target: &AssignTarget,
        target_span: Span,
        value: Option<ExprId>,
        contour: &mut ContourWords,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> bool {
        if !matches!(target, AssignTarget::Variable { indexes } if indexes.is_empty()) {
            return false;
        }
        let name = &line[target_span.start()..target_span.end()];
        let Some(kind) = self.contour_word_of(name) else {
            return false;
        };
        // A program that declares a variable of this name uses it as a variable.
        if self
            .state
            .variables
            .var_type(&name.to_ascii_uppercase())
            .is_some()
        {
            return false;
        }
        let evaluated = value
            .and_then(|id| {
                evaluate_value_or_report(block, line, id, &self.state.variables, diagnostics)
            })
            .as_ref()
            .and_then(Value::number)
            .filter(|_| !self.flow_uncertain);
        self.apply_contour_word(kind, evaluated, target_span, contour);
        true
    }

    fn apply_contour_word(
        &mut self,
        kind: Word,
        value: Option<f64>,
        span: Span,
        contour: &mut ContourWords,
    ) {
        let value = value.filter(|value| value.is_finite());
        // A negative radius, chamfer or feed is not a length the control can insert; nothing is.
        let value = match kind {
            Word::Angle => value,
            _ => value.map(|value| value.max(0.0)),
        };
        let length = self.state.length_factor(self.config.metric);
        let as_length = value.zip(length).map(|(value, factor)| value * factor);
        let feed_factor = self.state.feed_factor(self.config.metric);
        let as_feed = value.zip(feed_factor).map(|(value, factor)| value * factor);
        match kind {
            Word::Angle => contour.angle = Some((value, span)),
            Word::Rounding => contour.rounding = Some((as_length, span)),
            Word::ChamferLeg => contour.chamfer = Some((as_length, false, span)),
            Word::ChamferLength => contour.chamfer = Some((as_length, true, span)),
            Word::Feed => contour.feed = Some(as_feed),
            Word::ModalRounding => self.state.rounding_modal = as_length,
            Word::ModalFeed => self.state.chamfer_feed_modal = as_feed,
        }
    }

    /// What the block's move asks of its corner; `None` for most blocks.
    pub(super) fn contour_request(
        &self,
        contour: &ContourWords,
        angle_open: bool,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> Option<Box<ContourRequest>> {
        let modal = self.state.rounding_modal;
        if !contour.any() && modal == Some(0.0) && !angle_open {
            return None;
        }
        let rounding = contour.rounding.map(|(value, _)| value).or(match modal {
            Some(0.0) => None,
            other => Some(other),
        });
        if let (Some((_, rounding_span)), Some((_, _, chamfer_span))) =
            (contour.rounding, contour.chamfer)
        {
            diagnostics.push(Diagnostic::new(
                Code::RoundingAndChamfer,
                rounding_span.to(chamfer_span),
                "a rounding and a chamfer in one block: only the rounding is inserted",
            ));
        }
        let element = match (rounding, contour.chamfer) {
            // `RND=0` inserts nothing; RNDM, if active, rounds the corner instead (reference §14.1).
            (Some(Some(0.0)), _) => None,
            (Some(radius), _) => Some(radius.map(CornerElement::Rounding)),
            (None, Some((value, is_length, _))) => match value {
                Some(0.0) => None,
                Some(value) if is_length => Some(Some(CornerElement::ChamferLength(value))),
                Some(value) => Some(Some(CornerElement::ChamferLeg(value))),
                None => Some(None),
            },
            (None, None) => None,
        };
        let feed = contour.feed.or(match self.state.chamfer_feed_modal {
            Some(0.0) => None,
            other => Some(other),
        });
        if element.is_none() && !angle_open {
            return None;
        }
        Some(Box::new(ContourRequest {
            element,
            feed,
            angle_open,
            modal: contour.rounding.is_none() && contour.chamfer.is_none(),
        }))
    }

    /// Whether the block last applied asks for a rounding, chamfer or angle at its corner.
    pub fn has_contour_request(&self) -> bool {
        self.last_contour.is_some()
    }

    /// Resolves `ANG` (reference §14.6): with one coordinate of the plane, the other; with none, the
    /// first line of a two-block definition (its end is unknown until the next block); with both and
    /// an open first line, the corner where the two lines meet, which becomes this block's start.
    /// Returns whether the block moves because of its angle, and whether it opened a definition.
    pub(super) fn apply_contour_angle(
        &mut self,
        contour: &ContourWords,
        start_positions: &mut [Option<f64>],
        diagnostics: &mut Vec<Diagnostic>,
    ) -> (bool, bool) {
        let open = self.state.open_angle.take();
        let Some((angle, span)) = contour.angle else {
            return (false, false);
        };
        let (Some(plane), (Some(first), Some(second))) =
            (self.state.plane_index(), self.plane_axes())
        else {
            return (false, false);
        };
        let written = (self.written[first] == 1, self.written[second] == 1);
        let start = start_positions[first].zip(start_positions[second]);
        match written {
            (false, false) => {
                // The first line of a two-block definition: it ends where the next line meets it.
                self.state.program(first, None);
                self.state.program(second, None);
                self.written[first] = 1;
                self.written[second] = 1;
                if let (Some(degrees), Some(start)) = (angle, start) {
                    self.state.open_angle = Some(OpenAngle {
                        plane,
                        start,
                        degrees,
                    });
                }
                (true, true)
            }
            (true, true) => {
                let end = self.state.positions[first].zip(self.state.positions[second]);
                let Some(open) = open.filter(|open| open.plane == plane) else {
                    return (false, false);
                };
                let (Some(degrees), Some(end)) = (angle, end) else {
                    return (false, false);
                };
                match intersection(open.start, open.degrees, end, degrees) {
                    Some(corner) => {
                        start_positions[first] = Some(corner.0);
                        start_positions[second] = Some(corner.1);
                    }
                    None => diagnostics.push(Diagnostic::new(
                        Code::AngleNoSolution,
                        span,
                        "the two lines of this contour definition are parallel: they have no corner",
                    )),
                }
                (false, false)
            }
            (first_written, _) => {
                let (Some(degrees), Some(start)) = (angle, start) else {
                    self.state
                        .program(if first_written { second } else { first }, None);
                    return (false, false);
                };
                let radians = degrees.to_radians();
                let (cos, sin) = (radians.cos(), radians.sin());
                let (given, other, given_start, other_start, along, across) = if first_written {
                    (first, second, start.0, start.1, cos, sin)
                } else {
                    (second, first, start.1, start.0, sin, cos)
                };
                let Some(target) = self.state.positions[given] else {
                    self.state.program(other, None);
                    return (false, false);
                };
                if along.abs() < 1e-9 {
                    diagnostics.push(Diagnostic::new(
                        Code::AngleNoSolution,
                        span,
                        format!("ANG={degrees} is parallel to the axis of the only coordinate given: the line never reaches it"),
                    ));
                    self.state.program(other, None);
                    return (false, false);
                }
                let delta = target - given_start;
                if delta * along < 0.0 {
                    diagnostics.push(Diagnostic::new(
                        Code::AngleDirectionMismatch,
                        span,
                        format!("ANG={degrees} points away from the end coordinate: the control rejects a line whose angle does not lead to its end point"),
                    ));
                }
                self.program_axis(other, Some(other_start + delta * across / along));
                (false, false)
            }
        }
    }
}

/// Where the line through `a` at `angle_a` degrees meets the line through `b` at `angle_b`; `None`
/// when they are parallel.
fn intersection(a: (f64, f64), angle_a: f64, b: (f64, f64), angle_b: f64) -> Option<(f64, f64)> {
    let (da, db) = (angle_a.to_radians(), angle_b.to_radians());
    let (ua, ub) = ((da.cos(), da.sin()), (db.cos(), db.sin()));
    let cross = ua.0 * ub.1 - ua.1 * ub.0;
    if cross.abs() < 1e-9 {
        return None;
    }
    // a + s·ua = b + t·ub, solved for s by the cross product with ub.
    let s = ((b.0 - a.0) * ub.1 - (b.1 - a.1) * ub.0) / cross;
    Some((a.0 + s * ua.0, a.1 + s * ua.1))
}

#[cfg(test)]
mod tests {
    use super::intersection;

    #[test]
    fn lines_meet_at_their_corner() {
        let corner = intersection((0.0, 0.0), 45.0, (60.0, 20.0), 0.0).unwrap();
        assert!((corner.0 - 20.0).abs() < 1e-9 && (corner.1 - 20.0).abs() < 1e-9);
        assert!(intersection((0.0, 0.0), 30.0, (5.0, 5.0), 210.0).is_none());
    }
}
