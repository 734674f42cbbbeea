//! One block of a way: parsed, counted, run through the engine with its call, cycle, table and
//! control statements, and its move handed out; and the findings of the run, at the line of the
//! analysed program.

use crate::analysis::engine::engine_state::Engine;
use crate::analysis::engine::moves::Move;
use crate::analysis::execution::interpreter::Interpreter;
use crate::analysis::execution::outcome::{ExecutedMove, ProgramEnd};
use crate::analysis::execution::paths::Control;
use crate::analysis::execution::tables::table_mark;
use crate::diagnostics::{Code, Diagnostic, LineDiagnostic, Span};
use crate::syntax::ast::Block;
use std::sync::Arc;

/// Where a way goes after a block.
pub(super) enum Next {
    /// The next line of the same level (a transfer within the level is made by the statement).
    Line(usize),
    /// The way has been moved already (a call or a return).
    Moved,
    /// The way ends here (program end, an endless loop, an alarm).
    Stop,
    /// The rest of the program is read in program order from here.
    LoseTrack,
}

impl<'a, 's> Interpreter<'a, 's> {
    /// Runs the block at the current line of `control`'s innermost level.
    pub(super) fn step(&mut self, control: &mut Control, engine: &mut Engine<'a>) -> Next {
        let unit_index = control.level().unit;
        let unit = Arc::clone(&self.units[unit_index]);
        let pc = control.level().pc;
        if pc >= unit.line_count() {
            // A program that ends without M17/RET/M30 ends at its last block.
            return self.end_level(control, engine, ProgramEnd::Return);
        }
        let mut block = std::mem::take(&mut self.block);
        unit.parse(&mut self.parser, pc, &mut block);
        if let Some(recorder) = self.recorder.as_mut() {
            recorder.executing(
                unit_index,
                pc,
                unit.line_count(),
                self.executed,
                self.passes[unit_index][pc],
            );
        }
        self.executed += 1;
        self.passes[unit_index][pc] += 1;
        let line = unit.line(pc);
        if block.label.is_some() {
            let mark = self.next_fork;
            let marks = &mut control.level_mut().label_marks;
            // Sorted by line (see `transfer`).
            match marks.binary_search_by_key(&pc, |&(labelled, _)| labelled) {
                Ok(index) => marks[index].1 = mark,
                Err(index) => marks.insert(index, (pc, mark)),
            }
        }
        self.first_pass_before(control, engine, unit_index);
        let retest = control.level().retest_for == Some(pc);
        let next = if retest {
            control.level_mut().retest_for = None;
            self.control_statements(control, engine, &unit, pc, &block, true)
        } else {
            let call = self.prepare_call(control, engine, &unit, pc, &block);
            let builtin = match call {
                None => self.builtin_call(control, engine, &block, line),
                Some(_) => None,
            };
            if call.is_some() || builtin.is_some() {
                engine.follow_call_of_next_block();
            }
            let table = table_mark(&block, line);
            if let Some(mark) = table {
                self.table_start(control, engine, mark);
            }
            self.scratch.clear();
            let moved = engine.step(line, &block, &mut self.scratch)
                && control.level().curve_table.is_none();
            if let Some(flag) = self.corner_flag.filter(|_| moved) {
                flag.set(flag.get() || engine.has_contour_request());
            }
            self.update_assumptions(control, engine, line, &block);
            if moved && !self.counting && !control.widening() {
                self.record_move(control, engine, unit_index, pc, line, &block);
            } else if self.options.dwell_moves
                && !self.counting
                && !control.widening()
                && control.level().curve_table.is_none()
            {
                self.record_dwell(control, engine, unit_index, pc, line, &block);
            }
            if let Some(mark) = table {
                self.table_end(control, engine, mark);
            }
            if let Some(builtin) = builtin {
                self.run_builtin(control, engine, pc, line, &block, builtin);
            }
            let modal = self.modal_call_after(control, engine, &block, pc, moved);
            let callee = call.as_ref().or(modal.as_ref()).map(|call| call.unit());
            self.first_pass_after(control, engine, unit_index, pc, callee);
            match (call, modal) {
                (Some(call), _) | (None, Some(call)) => {
                    control.level_mut().pc = pc + 1;
                    self.enter(control, engine, call)
                }
                (None, None) => self.control_statements(control, engine, &unit, pc, &block, false),
            }
        };
        self.block = block;
        match next {
            Next::Line(next) if next == pc + 1 => Next::Line(self.after_section_line(control, pc)),
            other => other,
        }
    }

    /// Hands out the dwell of a `G4` block as a move of no axis, when the run is asked for them.
    pub(super) fn record_dwell(
        &mut self,
        control: &Control,
        engine: &Engine<'a>,
        unit_index: usize,
        pc: usize,
        line: &str,
        block: &Block,
    ) {
        if let Some(dwell) = engine.describe_last_dwell(pc, line, block) {
            self.hand_out(control, unit_index, pc, dwell);
        }
    }

    pub(super) fn record_move(
        &mut self,
        control: &Control,
        engine: &Engine<'a>,
        unit_index: usize,
        pc: usize,
        line: &str,
        block: &Block,
    ) {
        let movement = engine.describe_last_move(pc, line, block);
        self.hand_out(control, unit_index, pc, movement);
    }

    /// Hands a move of the current way to the sink, named after the cycle whose model makes it.
    fn hand_out(&mut self, control: &Control, unit_index: usize, pc: usize, mut movement: Move) {
        movement.cycle = self.cycles.current.clone();
        let assumed = if control.assumed_axes == 0 {
            Vec::new()
        } else {
            let names = &self.config.axes;
            movement
                .end
                .iter()
                .filter(|(name, _)| {
                    names
                        .iter()
                        .position(|axis| axis.name.as_str() == name.as_ref())
                        .is_some_and(|index| index < 64 && control.assumed_axes & 1 << index != 0)
                })
                .map(|(name, _)| name.clone())
                .collect()
        };
        let level = control.level();
        let pass = self.pass_of(unit_index, pc);
        (self.sink)(ExecutedMove {
            movement,
            path: self.units[unit_index].path.clone(),
            stack: Arc::clone(&level.stack),
            pass,
            conditional: { control.open_decisions(&self.covered).next().is_some() },
            assumed,
        });
        if let Some(recorder) = self.recorder.as_mut() {
            recorder.emitted += 1;
        }
    }

    /// The line of the analysed program where the way is: its own line, or the outermost call.
    pub(super) fn outer_line(&self, control: &Control) -> usize {
        control.levels[0]
            .pc
            .min(self.units[0].line_count().saturating_sub(1))
    }

    /// A finding at `line` of `unit` on the current way: at that line in the analysed program, else
    /// at the outermost call, naming the program and line where it happened.
    pub(super) fn report(
        &mut self,
        control: &Control,
        pc: usize,
        code: Code,
        span: Span,
        message: String,
    ) {
        if control.levels.len() == 1 {
            self.report_at(pc, code, span, message);
            return;
        }
        let level = control.level();
        let call_line = level.stack.first().map_or(pc, |site| site.line);
        let name = &self.units[level.unit].name;
        let message = format!("in {name} (line {}): {message}", pc + 1);
        let length = self.units[0].line(call_line).len();
        self.report_at(call_line, code, Span::new(0, length), message);
    }

    pub(super) fn report_at(&mut self, line: usize, code: Code, span: Span, message: String) {
        if !self.reported.insert((line, code)) {
            return;
        }
        let span = if span.is_empty() {
            Span::new(0, self.units[0].line(line).len())
        } else {
            span
        };
        let mut diagnostic = Diagnostic::new(code, span, message);
        diagnostic.severity = self.config.severity_of(code);
        self.findings.push(LineDiagnostic { line, diagnostic });
    }
}
