//! Assignments that change frames or G groups (reference §7.4): `$P_UIFR[n]=CTRANS(..)` and
//! `$P_UIFR[n,X,TR]=v` write the stored data of a settable frame, which become active at its next
//! selection; `$P_IFRAME` and `$P_PFRAME` change the active frames at once (not followed: they become
//! unknown); writes to basic and system frames make every settable offset unknown; `G[n]=v` selects a
//! G function by group and number.

use crate::analysis::engine::engine_state::Engine;
use crate::analysis::engine::evaluation::evaluate_or_report;
use crate::analysis::machine;
use crate::diagnostics::Span;
use crate::syntax::ast::{Block, ExprId, ExprKind};
use crate::syntax::gcodes::GCode;

impl Engine<'_> {
    /// The active settable offset becomes `offset`; the axes keep their machine set-points.
    pub(super) fn change_offset(&mut self, offset: Vec<Option<f64>>) {
        let before = std::mem::replace(&mut self.state.offset, offset);
        machine::reexpress(
            &mut self.state,
            &self.slots,
            machine::Replaced::Offset(before),
        );
    }

    /// The programmable frame becomes `frame`; the axes keep their machine set-points.
    pub(super) fn change_frame(&mut self, frame: Option<crate::analysis::frame::Frame>) {
        let before = std::mem::replace(&mut self.state.frame, frame);
        machine::reexpress(
            &mut self.state,
            &self.slots,
            machine::Replaced::Frame(before),
        );
    }

    /// An assignment to a system variable: only frame variables matter to the modal state.
    pub(super) fn apply_system_variable_write(
        &mut self,
        line: &str,
        block: &Block,
        target_span: Span,
        indexes: &[ExprId],
        value: Option<ExprId>,
        diagnostics: &mut Vec<crate::diagnostics::Diagnostic>,
    ) {
        let written = &line[target_span.start()..target_span.end()];
        let name = written
            .split('[')
            .next()
            .unwrap_or_default()
            .trim()
            .to_ascii_uppercase();
        match name.as_str() {
            "$P_UIFR" => self.write_settable_data(line, block, indexes, value, diagnostics),
            "$P_IFRAME" => {
                // The active settable frame changes at once to a value that is not followed.
                self.change_offset(vec![None; self.config.axes.len()]);
            }
            "$P_PFRAME" => self.change_frame(None),
            _ if name.starts_with("$P_") && (name.ends_with("FRAME") || name.ends_with("FR")) => {
                // A basic or system frame: assumed identity, now unknown, and with it every offset.
                self.state.settable_data.forget_all();
                self.change_offset(vec![None; self.config.axes.len()]);
            }
            _ => {}
        }
    }

    /// `$P_UIFR[n]=CTRANS(X,v,...)` or `$P_UIFR[n,X,TR]=v`; anything else written to `$P_UIFR[n]`
    /// makes frame n's data unknown.
    fn write_settable_data(
        &mut self,
        line: &str,
        block: &Block,
        indexes: &[ExprId],
        value: Option<ExprId>,
        diagnostics: &mut Vec<crate::diagnostics::Diagnostic>,
    ) {
        let index = indexes
            .first()
            .and_then(|id| evaluate_or_report(block, line, *id, &self.state.variables, diagnostics))
            .filter(|index| {
                index.fract() == 0.0
                    && (0.0..f64::from(crate::analysis::offsets::SETTABLE_FRAME_COUNT))
                        .contains(index)
            });
        let Some(index) = index.map(|index| index as u8) else {
            // Any frame may have been written.
            self.state.settable_data.forget_all();
            return;
        };
        let axis_count = self.config.axes.len();
        // The assignment's value was evaluated (and its findings reported) already; evaluating its
        // parts again must not report them twice.
        let diagnostics = &mut Vec::new();
        let values = if self.flow_uncertain {
            // The write may run any number of times, or not at all.
            None
        } else {
            match indexes.len() {
                1 => value.and_then(|id| self.translation_values(line, block, id, diagnostics)),
                3 => {
                    let axis = self.name_of(line, block, indexes[1]);
                    let component = self.name_of(line, block, indexes[2]);
                    match (axis.and_then(|axis| self.axis_index(&axis)), component) {
                        (Some(axis), Some(component)) if component == "TR" => {
                            let mut values = self.state.settable_data.values(self.config, index);
                            values[axis] = value
                                .and_then(|id| {
                                    evaluate_or_report(
                                        block,
                                        line,
                                        id,
                                        &self.state.variables,
                                        diagnostics,
                                    )
                                })
                                .and_then(|value| self.frame_value(axis, value));
                            Some(values)
                        }
                        _ => None,
                    }
                }
                _ => None,
            }
        };
        self.state
            .settable_data
            .write(index, values.unwrap_or_else(|| vec![None; axis_count]));
        let active = self.state.groups[8].and_then(crate::analysis::offsets::frame_index);
        if active == Some(index) {
            self.stale_offset_data = Some(index);
        }
    }

    /// The translations of `CTRANS(X, 10, Y, 20)` per configured axis (0 for axes not listed), or
    /// `None` for any other frame expression (a rotation, a chain with `:`).
    fn translation_values(
        &self,
        line: &str,
        block: &Block,
        id: ExprId,
        diagnostics: &mut Vec<crate::diagnostics::Diagnostic>,
    ) -> Option<Vec<Option<f64>>> {
        let mut id = id;
        while let ExprKind::Parenthesized(inner) = block.expr(id).kind {
            id = inner;
        }
        let ExprKind::Call { name, args } = &block.expr(id).kind else {
            return None;
        };
        if !line[name.start()..name.end()].eq_ignore_ascii_case("CTRANS") || args.len() % 2 != 0 {
            return None;
        }
        let mut values = vec![Some(0.0); self.config.axes.len()];
        for pair in args.chunks(2) {
            let axis = pair[0]
                .and_then(|axis| self.name_of(line, block, axis))
                .and_then(|axis| self.axis_index(&axis))?;
            values[axis] = pair[1]
                .and_then(|value| {
                    evaluate_or_report(block, line, value, &self.state.variables, diagnostics)
                })
                .and_then(|value| self.frame_value(axis, value));
        }
        Some(values)
    }

    /// A frame translation as written, in the basic system: system variables are read in the
    /// programmed system only under G700/G710 (reference §4); angles are not converted.
    fn frame_value(&self, axis: usize, value: f64) -> Option<f64> {
        if self.config.axes[axis].kind.is_rotary() {
            return Some(value);
        }
        self.state
            .feed_factor(self.config.metric)
            .map(|factor| value * factor)
    }

    /// The upper-case text of a plain name expression (`X`, `TR`).
    fn name_of(&self, line: &str, block: &Block, id: ExprId) -> Option<String> {
        let expr = block.expr(id);
        match &expr.kind {
            ExprKind::Name { indexes } if indexes.is_empty() => {
                Some(line[expr.span.start()..expr.span.end()].to_ascii_uppercase())
            }
            _ => None,
        }
    }

    /// `G[group]=number`: selects the function with that internal number; a group or number that is
    /// not known makes the groups that decide how axis words read unknown.
    pub(super) fn apply_group_write(
        &mut self,
        line: &str,
        block: &Block,
        group: ExprId,
        value: Option<ExprId>,
        diagnostics: &mut Vec<crate::diagnostics::Diagnostic>,
    ) {
        let variables = &self.state.variables;
        let evaluate = |id: ExprId, diagnostics: &mut Vec<crate::diagnostics::Diagnostic>| {
            evaluate_or_report(block, line, id, variables, diagnostics)
                .filter(|value| value.fract() == 0.0 && *value >= 0.0 && *value < 256.0)
                .map(|value| value as u16)
        };
        let group = evaluate(group, diagnostics)
            .filter(|group| (*group as usize) < crate::analysis::state::GROUP_COUNT);
        // The value was evaluated, and its findings reported, with the assignment.
        let number = if self.flow_uncertain {
            None
        } else {
            value.and_then(|id| evaluate(id, &mut Vec::new()))
        };
        let Some(group) = group else {
            self.state.forget_inherited_groups();
            return;
        };
        let code = number.and_then(|number| {
            crate::syntax::gcodes::TABLE
                .iter()
                .position(|info| {
                    u16::from(info.group) == group && u16::from(info.index_in_group) == number
                })
                .map(|index| GCode::Known(index as u16))
                .or_else(|| {
                    (group == 8 && (6..=100).contains(&number))
                        .then(|| GCode::WorkOffset(number - 6 + 505))
                })
        });
        self.state.groups[group as usize] = code;
        if group == 8 {
            self.change_offset(self.state.selected_offset(self.config));
        }
    }
}
