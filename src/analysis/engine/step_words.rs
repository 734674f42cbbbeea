//! The words of one block as the engine reads them: axis words program positions, and the feed, polar,
//! circle, contour, tool change and call words are collected into the block's `BlockStep` for the
//! phases that apply the block as a whole (`engine/step_motion.rs`).

use crate::analysis::engine::block_words::changes_kinematics;
use crate::analysis::engine::engine_state::Engine;
use crate::analysis::engine::step::BlockStep;
use crate::diagnostics::{Code, Diagnostic};
use crate::syntax::ast::{
    AddressKind, Block, CallKind, ExprKind, Extension, Modifier, NamedAddress, Statement,
};

impl Engine<'_> {
    /// Reads the words of the block in their order: axis words are applied at once, the others are
    /// collected into `step`.
    #[inline]
    pub(super) fn read_words(
        &mut self,
        line: &str,
        block: &Block,
        step: &mut BlockStep,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        let statements = step.statements;
        for statement in statements {
            match statement {
                Statement::Address(word) => match word.kind {
                    AddressKind::Axis => {
                        if step.functions.frame_or_pole.is_some() || step.functions.dwell {
                            continue;
                        }
                        // A word of an axis the machine does not have (reported as S180) moves
                        // nothing the engine can follow: the block is no move of its own, so no
                        // finding about its motion is made from it.
                        let axis = self.axes.index(self.config, line, word);
                        step.moved |= axis.is_some();
                        // A word of an axis that is not configured was reported by the syntax
                        // layer; there is nothing to track.
                        if let Some(index) = axis {
                            self.apply_axis_word(
                                index,
                                line,
                                block,
                                word,
                                &step.functions,
                                diagnostics,
                            );
                        }
                    }
                    AddressKind::Feed if !step.functions.dwell => {
                        step.feed_in_block = Some(self.word_value(line, block, word, diagnostics));
                    }
                    AddressKind::Named(NamedAddress::PolarAngle) => {
                        let incremental = matches!(word.value.modifier, Some((Modifier::Ic, _)));
                        let value = self.word_value(line, block, word, diagnostics);
                        step.polar.angle = Some((value, incremental));
                        step.polar.span = Some(word.span);
                        if word.value.modifier.is_none() && step.functions.frame_or_pole.is_none() {
                            step.polar.plain_angle_span = Some(word.span);
                        }
                    }
                    AddressKind::Named(NamedAddress::PolarRadius) => {
                        let value = self.word_value(line, block, word, diagnostics);
                        let factor = self.state.length_factor(self.config.metric);
                        step.polar.radius =
                            Some(value.zip(factor).map(|(value, factor)| value * factor));
                        if value.is_some_and(|value| value < 0.0) {
                            diagnostics.push(Diagnostic::new(
                                Code::PolarRadiusNegative,
                                word.span,
                                "RP is a distance from the pole and must not be negative",
                            ));
                        }
                        step.polar.span =
                            Some(step.polar.span.map_or(word.span, |span| span.to(word.span)));
                    }
                    AddressKind::Interpolation if word.extension.is_none() => {
                        self.collect_centre_word(
                            line,
                            block,
                            word,
                            &mut step.circle_words,
                            diagnostics,
                        );
                    }
                    AddressKind::Interpolation
                        if matches!(word.extension, Some(Extension::Number { value: 1, .. })) =>
                    {
                        self.collect_intermediate_word(
                            line,
                            block,
                            word,
                            &mut step.circle_words,
                            diagnostics,
                        );
                    }
                    AddressKind::Named(NamedAddress::Positioning | NamedAddress::IndirectAxis)
                        if step.functions.frame_or_pole.is_none() && !step.functions.dwell =>
                    {
                        step.moved |= self.apply_named_axis_word(
                            line,
                            block,
                            word,
                            &step.functions,
                            diagnostics,
                        );
                    }
                    AddressKind::Named(NamedAddress::Turns) => {
                        step.circle_words.turns =
                            Some((self.word_value(line, block, word, diagnostics), word.span));
                    }
                    AddressKind::Named(NamedAddress::CircleRadius) => {
                        step.circle_words.radius_written = true;
                        step.circle_words.radius = self
                            .word_value(line, block, word, diagnostics)
                            .zip(self.state.length_factor(self.config.metric))
                            .map(|(value, factor)| value * factor);
                    }
                    AddressKind::Named(NamedAddress::OpeningAngle) => {
                        // `G3 I10 J0 AR=90` moves without any axis word.
                        step.circle_words.opening_angle = true;
                        step.circle_words.opening_angle_value =
                            self.word_value(line, block, word, diagnostics);
                        step.moved |=
                            step.functions.frame_or_pole.is_none() && !step.functions.dwell;
                    }
                    AddressKind::Named(NamedAddress::Other) => {
                        self.read_contour_address(
                            line,
                            block,
                            word,
                            &mut step.contour,
                            diagnostics,
                        );
                    }
                    AddressKind::MFunction => {
                        // A tool change (M6) may run a machine-specific cycle that moves axes.
                        let value = self.word_value(line, block, word, diagnostics);
                        if word.extension.is_none() && value == Some(6.0) {
                            step.forget_after = true;
                        }
                    }
                    _ => {}
                },
                // `ANG=30` (and a configured name the parser does not know) reads as an assignment.
                Statement::Assignment {
                    target,
                    target_span,
                    value,
                    ..
                } if self.read_contour_assignment(
                    line,
                    block,
                    target,
                    *target_span,
                    *value,
                    &mut step.contour,
                    diagnostics,
                ) => {}
                Statement::Assignment {
                    target,
                    target_span,
                    value,
                    ..
                } => {
                    self.apply_assignment(line, block, target, *target_span, *value, diagnostics);
                }
                Statement::Definition {
                    declarators,
                    data_type,
                    ..
                } => {
                    self.apply_definition(line, block, *data_type, declarators, diagnostics);
                }
                Statement::Call { kind, args, .. }
                    if *kind != CallKind::Modal && !step.call_followed =>
                {
                    step.forget_after = true;
                    // Only a `VAR` parameter reaches the caller's own variables, and only a variable
                    // can be passed to one.
                    step.locals_may_change |= args.iter().flatten().any(|&argument| {
                        matches!(block.expr(argument).kind, ExprKind::Name { .. })
                    });
                    step.frame_data_changed = true;
                }
                Statement::Instruction { name, .. } => {
                    let upper = line[name.start()..name.end()].to_ascii_uppercase();
                    if changes_kinematics(&upper) {
                        step.forget_after = true;
                        step.locals_may_change = true;
                        step.frame_data_changed = true;
                    }
                }
                _ => {}
            }
        }
    }
}
