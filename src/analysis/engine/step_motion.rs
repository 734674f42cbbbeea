//! What one block does as a whole once its words are read: the unit and machine checks, a plane
//! change, a frame instruction, a pole or a polar move, the feed (`apply_block_functions`); and the
//! path of its move with the circle it follows (`resolve_path`).

use crate::analysis::circle::Circle;
use crate::analysis::engine::block_words::{find_word, statements_span};
use crate::analysis::engine::circle_checks::CircleBlock;
use crate::analysis::engine::engine_state::Engine;
use crate::analysis::engine::step::BlockStep;
use crate::analysis::machine::{reexpress, Replaced};
use crate::diagnostics::{Code, Diagnostic};
use crate::syntax::ast::{AddressKind, Block};

impl Engine<'_> {
    /// Applies what the block does besides its axis words: checks of its units and machine words, a
    /// plane change, a frame instruction, a pole, a polar move and the feed. Returns the pole of a
    /// polar move (the centre of a polar circle) when known.
    #[inline]
    pub(super) fn apply_block_functions(
        &mut self,
        line: &str,
        block: &Block,
        step: &mut BlockStep,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> Option<(f64, f64)> {
        let statements = step.statements;
        self.check_units(
            step.units_before,
            step.unit_word,
            step.feed_in_block.is_some(),
            statements,
            diagnostics,
        );
        self.check_machine_words(line, block, statements, diagnostics);
        if self.state.plane_index() != step.plane_before {
            // The stored AP and RP belong to the old plane (reference §5.2).
            self.state.polar_angle = None;
            self.state.polar_radius = None;
            self.memory.pole_changed = true;
        }
        let mut polar_circle_centre = None;
        if let Some(code) = step.functions.frame_or_pole {
            if matches!(code.name().as_ref(), "G110" | "G111" | "G112") {
                self.define_pole(code, line, block, statements, &step.polar, diagnostics);
            } else {
                let frame_before = self.state.frame;
                self.apply_frame_instruction(code, line, block, statements, diagnostics);
                if let (Some(before), Some(after)) = (frame_before, self.state.frame) {
                    for (slot, rotated) in self.memory.rotated_slots.iter_mut().enumerate() {
                        *rotated |=
                            (0..3).any(|row| before.matrix[row][slot] != after.matrix[row][slot]);
                    }
                }
                // A frame instruction moves nothing: the axes keep their machine set-points.
                reexpress(&mut self.state, &self.slots, Replaced::Frame(frame_before));
            }
        } else if step.polar.angle.is_some() || step.polar.radius.is_some() {
            step.moved = true;
            self.check_polar_words(&step.polar, diagnostics);
            polar_circle_centre = self.apply_polar_move(line, statements, &step.polar, diagnostics);
        }
        if let Some(feed) = step.feed_in_block {
            match feed {
                Some(value) => {
                    if value <= 0.0 {
                        if let Some(word) = find_word(statements, AddressKind::Feed) {
                            diagnostics.push(Diagnostic::new(
                                Code::FeedNotPositive,
                                word.span,
                                "the feedrate must be greater than 0 (alarm 14800)",
                            ));
                        }
                    }
                    self.state.feed = self
                        .state
                        .feed_factor(self.config.metric)
                        .map(|factor| value * factor);
                }
                None => self.state.feed = None,
            }
        }
        polar_circle_centre
    }

    /// The circle the block's move follows under `motion` (with its checks), the path's tangent for
    /// CT, and the finding of a feed move without a feed.
    #[inline]
    pub(super) fn resolve_path(
        &mut self,
        line: &str,
        motion: &str,
        step: &mut BlockStep,
        polar_circle_centre: Option<(f64, f64)>,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> Option<Circle> {
        let statements = step.statements;
        let moves_path = step.moves_axes();
        // The span of the block's words is needed only by findings about a circle (and the rare ones
        // after it): it is worked out for the blocks that may have one, not for every block.
        if moves_path && matches!(motion, "G2" | "G3" | "CIP") {
            step.circle_words.span = statements_span(statements);
        }
        let step = &*step;
        let polar = &step.polar;
        let circle_words = &step.circle_words;
        let start_positions = &step.start_positions;
        let polar_move = polar.angle.is_some() || polar.radius.is_some();
        let circle_rejected = self.check_circle_words(
            &CircleBlock {
                line,
                statements,
                motion,
                moves_path,
                frame_or_pole: step.functions.frame_or_pole,
                words: circle_words,
                polar,
                start_positions,
            },
            diagnostics,
        );
        let arc = if moves_path && !circle_rejected {
            match motion {
                // A polar circle turns around the pole; the start must lie on it (reference §5.2).
                "G2" | "G3" if polar_move => polar_circle_centre.and_then(|centre| {
                    self.polar_circle(motion == "G2", start_positions, centre, polar, diagnostics)
                }),
                "G2" | "G3" => {
                    self.resolve_circle(motion == "G2", start_positions, circle_words, diagnostics)
                }
                "CIP" => self.resolve_cip(start_positions, circle_words, diagnostics),
                "CT" => self.resolve_ct(start_positions),
                _ => None,
            }
        } else {
            None
        };
        let arc = self.apply_turns(arc, circle_words, diagnostics);
        if moves_path {
            self.update_tangent(motion, start_positions, arc.as_ref());
            self.check_feed(motion, statements, diagnostics);
        }
        arc
    }
}
