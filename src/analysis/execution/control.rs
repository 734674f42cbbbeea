//! The decisions of one block: control structures (IF/ELSE, WHILE, FOR, REPEAT/UNTIL, LOOP, CASE),
//! jumps with and without conditions, and the program ends. A condition whose value is known takes
//! the way the control takes; an unknown one lets both ways run (see `Interpreter::fork`).

use crate::analysis::engine::engine_state::Engine;
use crate::analysis::eval::{evaluate, real_equal, real_less_equal, Variables};
use crate::analysis::execution::block_run::Next;
use crate::analysis::execution::interpreter::Interpreter;
use crate::analysis::execution::jump_targets::JumpOutcome;
use crate::analysis::execution::outcome::{ends_program, ProgramEnd};
use crate::analysis::execution::paths::{Control, LoopFrame};
use crate::analysis::execution::program::{Partner, ProgramUnit};
use crate::analysis::execution::ways::mark_unknown_loop;
use crate::diagnostics::{Code, Span};
use crate::syntax::ast::{AssignTarget, Block, ExprId, Statement, StructureKeyword};

/// Passes of one loop after which the interpreter compares the state at its head with the state one
/// such interval before: equal states mean the loop never ends.
const ENDLESS_CHECK_INTERVAL: u32 = 1000;

impl<'a, 's> Interpreter<'a, 's> {
    /// The value of a condition: `Some(true)` or `Some(false)` when the program determines it.
    fn decide(
        &self,
        engine: &Engine<'a>,
        block: &Block,
        line: &str,
        condition: Option<ExprId>,
    ) -> Option<bool> {
        let id = condition?;
        match evaluate(block, line, id, &engine.state.variables) {
            Ok(Some(value)) => Some(value != 0.0),
            _ => None,
        }
    }

    /// Runs the control statements of `block` (the engine has applied the block already, unless
    /// `retest`: the arrival at a FOR line from its ENDFOR).
    pub(super) fn control_statements(
        &mut self,
        control: &mut Control,
        engine: &mut Engine<'a>,
        unit: &ProgramUnit,
        pc: usize,
        block: &Block,
        retest: bool,
    ) -> Next {
        let line = unit.line(pc);
        let statements = block.interpreted_statements();
        let mut case_value: Option<Option<f64>> = None;
        // The CASE branch before the next jump: whether it matches (`None`: not decided), and
        // whether an earlier branch was not decided.
        let mut branch: Option<Option<bool>> = None;
        let mut earlier_undecided = false;
        for (index, statement) in statements.iter().enumerate() {
            match statement {
                Statement::Structure {
                    keyword,
                    condition,
                    span,
                } => {
                    let partner = unit.flow.partner(pc);
                    match (keyword, partner) {
                        (StructureKeyword::If, Some(Partner::If { otherwise, end })) => {
                            let skip_to = otherwise.unwrap_or(end) + 1;
                            return match self.decide(engine, block, line, *condition) {
                                Some(true) => Next::Line(pc + 1),
                                Some(false) => Next::Line(skip_to),
                                None => {
                                    self.undecided(control, pc, *span);
                                    self.fork(control, engine, skip_to);
                                    Next::Line(pc + 1)
                                }
                            };
                        }
                        (StructureKeyword::Else, Some(Partner::Else { end })) => {
                            return Next::Line(end + 1)
                        }
                        (StructureKeyword::EndIf, _) => return Next::Line(pc + 1),
                        (StructureKeyword::While, Some(Partner::Opens { end })) => {
                            enter_loop(control, pc, end, pc, self.next_fork);
                            let decision = self.decide(engine, block, line, *condition);
                            return self.loop_test(control, engine, pc, end, decision, *span);
                        }
                        (StructureKeyword::For, Some(Partner::Opens { end })) => {
                            if !retest {
                                enter_loop(control, pc, end, pc, self.next_fork);
                            }
                            let decision =
                                self.for_test(engine, block, line, statements, *condition, retest);
                            return self.loop_test(control, engine, pc, end, decision, *span);
                        }
                        (
                            StructureKeyword::Repeat | StructureKeyword::Loop,
                            Some(Partner::Opens { end }),
                        ) => {
                            enter_loop(control, pc, end, pc + 1, self.next_fork);
                            return Next::Line(pc + 1);
                        }
                        (
                            StructureKeyword::EndWhile | StructureKeyword::EndLoop,
                            Some(Partner::Closes { start }),
                        ) => {
                            let back_to = if *keyword == StructureKeyword::EndWhile {
                                start
                            } else {
                                start + 1
                            };
                            return self.transfer(control, engine, pc, back_to);
                        }
                        (StructureKeyword::EndFor, Some(Partner::Closes { start })) => {
                            control.level_mut().retest_for = Some(start);
                            return self.transfer(control, engine, pc, start);
                        }
                        (StructureKeyword::Until, Some(Partner::Closes { start })) => {
                            match self.decide(engine, block, line, *condition) {
                                Some(true) => {
                                    control.level_mut().loops.pop();
                                    return Next::Line(pc + 1);
                                }
                                Some(false) => {
                                    return self.transfer(control, engine, pc, start + 1)
                                }
                                None => {
                                    self.undecided(control, pc, *span);
                                    let depth = control.levels.len() - 1;
                                    mark_unknown_loop(control, depth, start + 1, pc);
                                    self.fork(control, engine, pc + 1);
                                    return self.transfer(control, engine, pc, start + 1);
                                }
                            }
                        }
                        (StructureKeyword::Case, _) => {
                            case_value = Some(condition.and_then(|id| {
                                evaluate(block, line, id, &engine.state.variables)
                                    .ok()
                                    .flatten()
                            }));
                        }
                        _ => {
                            self.report(
                                control,
                                pc,
                                Code::FlowNotFollowed,
                                *span,
                                "this control structure does not nest soundly (see S190): from here on the program is read in program order".to_string(),
                            );
                            control.level_mut().pc = pc + 1;
                            return Next::LoseTrack;
                        }
                    }
                }
                Statement::Jump {
                    kind,
                    target,
                    condition,
                    span,
                } => {
                    let decision = match (case_value, condition) {
                        (Some(_), _) => branch.take().unwrap_or(None),
                        (None, None) => Some(true),
                        (None, Some(_)) => self.decide(engine, block, line, *condition),
                    };
                    if decision == Some(false) {
                        continue;
                    }
                    let target_line = match self
                        .jump_target(engine, unit, block, line, pc, *kind, target)
                    {
                        JumpOutcome::Line(target_line) => target_line,
                        JumpOutcome::GoOn => {
                            // GOTOS without a restart, GOTOC to a missing target: the program goes on.
                            continue;
                        }
                        JumpOutcome::Missing(code, message) => {
                            // The control stops with alarm 14080 where the jump is taken; the way on
                            // which it is not goes on.
                            self.report(control, pc, code, *span, message);
                            if decision == Some(true) {
                                return Next::Stop;
                            }
                            continue;
                        }
                        JumpOutcome::Unknown => {
                            self.report(
                                control,
                                pc,
                                Code::FlowNotFollowed,
                                *span,
                                "the target of this jump is not known statically: from here on the program is read in program order".to_string(),
                            );
                            control.level_mut().pc = pc + 1;
                            return Next::LoseTrack;
                        }
                    };
                    if decision == Some(true) {
                        return self.transfer(control, engine, pc, target_line);
                    }
                    self.undecided(control, pc, *span);
                    let last_jump = !statements[index + 1..]
                        .iter()
                        .any(|statement| matches!(statement, Statement::Jump { .. }));
                    if target_line <= pc {
                        // A backward jump that may or may not be taken: a loop whose passes are not
                        // known. The way past it waits; this way takes the jump.
                        let depth = control.levels.len() - 1;
                        mark_unknown_loop(control, depth, target_line, pc);
                        if last_jump {
                            self.fork(control, engine, pc + 1);
                            return self.transfer(control, engine, pc, target_line);
                        }
                    }
                    self.fork(control, engine, target_line);
                }
                Statement::CaseBranch { value, .. } => {
                    let matches = match (value, case_value) {
                        // DEFAULT: taken when no branch before matched.
                        (None, _) if earlier_undecided => None,
                        (None, _) => Some(true),
                        (Some(id), Some(Some(selector))) => {
                            evaluate(block, line, *id, &engine.state.variables)
                                .ok()
                                .flatten()
                                .map(|constant| real_equal(constant, selector))
                        }
                        (Some(_), _) => None,
                    };
                    earlier_undecided |= matches.is_none();
                    branch = Some(matches);
                }
                Statement::SectionRepeat {
                    start,
                    end,
                    count,
                    span,
                    ..
                } => {
                    let start_name = line[start.start()..start.end()].to_ascii_uppercase();
                    let Some(&first) = unit
                        .flow
                        .label_lines(&start_name)
                        .iter()
                        .rev()
                        .find(|labelled| **labelled < pc)
                    else {
                        continue;
                    };
                    let last = match end {
                        Some(end) => {
                            let end_name = line[end.start()..end.end()].to_ascii_uppercase();
                            match unit
                                .flow
                                .label_lines(&end_name)
                                .iter()
                                .find(|labelled| **labelled >= first)
                            {
                                Some(&last) => last,
                                None => continue,
                            }
                        }
                        None => pc - 1,
                    };
                    return self.repeat_section(
                        control, engine, block, line, pc, first, last, *count, *span,
                    );
                }
                Statement::BlockRepeat {
                    label: Some(label),
                    count,
                    span,
                } => {
                    let name = line[label.start()..label.end()].to_ascii_uppercase();
                    let lines = unit.flow.label_lines(&name);
                    let Some(&target) = lines
                        .iter()
                        .rev()
                        .find(|labelled| **labelled < pc)
                        .or(lines.first())
                    else {
                        continue;
                    };
                    return self.repeat_section(
                        control, engine, block, line, pc, target, target, *count, *span,
                    );
                }
                Statement::Return { .. } => {
                    return self.end_level(control, engine, ProgramEnd::Return)
                }
                Statement::Address(word) => {
                    if let Some(end) = ends_program(word) {
                        return self.end_level(control, engine, end);
                    }
                }
                _ => {}
            }
        }
        Next::Line(pc + 1)
    }

    /// A condition the program does not determine: an information finding, once per line.
    fn undecided(&mut self, control: &Control, pc: usize, span: Span) {
        self.report(
            control,
            pc,
            Code::ConditionNotKnown,
            span,
            "this condition depends on values the program does not determine: both ways are followed, and what differs between them is unknown afterwards".to_string(),
        );
    }

    /// The test of a WHILE or FOR at `pc` whose closer is `end`.
    fn loop_test(
        &mut self,
        control: &mut Control,
        engine: &mut Engine<'a>,
        pc: usize,
        end: usize,
        decision: Option<bool>,
        span: Span,
    ) -> Next {
        match decision {
            Some(true) => Next::Line(pc + 1),
            Some(false) => {
                leave_loop(control, pc);
                Next::Line(end + 1)
            }
            None => {
                self.undecided(control, pc, span);
                let depth = control.levels.len() - 1;
                mark_unknown_loop(control, depth, pc, end);
                self.fork(control, engine, end + 1);
                Next::Line(pc + 1)
            }
        }
    }

    /// Whether a FOR loop runs another pass: the counter (counted up first when the test comes from
    /// ENDFOR) is at most the end value (reference §18.2).
    fn for_test(
        &self,
        engine: &mut Engine<'a>,
        block: &Block,
        line: &str,
        statements: &[Statement],
        end_value: Option<ExprId>,
        count_up: bool,
    ) -> Option<bool> {
        let (target, target_span) = statements.iter().find_map(|statement| match statement {
            Statement::Assignment {
                target,
                target_span,
                ..
            } => Some((target, *target_span)),
            _ => None,
        })?;
        let name = line[target_span.start()..target_span.end()].to_ascii_uppercase();
        let variables = &mut engine.state.variables;
        let counter = read_counter(variables, target, &name);
        let counter = if count_up {
            let next = counter.map(|value| value + 1.0);
            write_counter(variables, target, &name, next);
            next
        } else {
            counter
        };
        let end_value = end_value.and_then(|id| {
            evaluate(block, line, id, &engine.state.variables)
                .ok()
                .flatten()
        });
        let (counter, end_value) = (counter?, end_value?);
        Some(real_less_equal(counter, end_value))
    }

    /// Continues the way at `target` of the same level: forward, or backward as the next pass of a
    /// loop, counted against the pass limit and checked for a state that never changes.
    pub(super) fn transfer(
        &mut self,
        control: &mut Control,
        engine: &mut Engine<'a>,
        pc: usize,
        target: usize,
    ) -> Next {
        let level = control.level_mut();
        while level
            .loops
            .last()
            .is_some_and(|frame| !(frame.head..=frame.end).contains(&target))
        {
            level.loops.pop();
        }
        if target > pc {
            return Next::Line(target);
        }
        let depth = control.levels.len() - 1;
        let unknown = control
            .unknown_loops
            .iter()
            .position(|unknown| unknown.depth == depth && unknown.head == target);
        // The passes of a loop whose passes are not known are not counted: ways in it meet whatever
        // pass they are in.
        let counted = u32::from(unknown.is_none());
        let next_fork = self.next_fork;
        let level = control.level_mut();
        let (passes, mark) = match level.loops.last_mut() {
            Some(frame) if frame.back_to == target => {
                frame.passes += counted;
                (
                    frame.passes,
                    std::mem::replace(&mut frame.fork_mark, next_fork),
                )
            }
            _ => {
                let mark = level
                    .label_marks
                    .binary_search_by_key(&target, |&(labelled, _)| labelled)
                    .map_or(0, |index| level.label_marks[index].1);
                // Both lists are sorted by line, so that programs with many loops of jumps stay fast.
                let passes = match level
                    .jump_passes
                    .binary_search_by_key(&target, |&(line, _)| line)
                {
                    Ok(index) => {
                        level.jump_passes[index].1 += counted;
                        level.jump_passes[index].1
                    }
                    Err(index) => {
                        level.jump_passes.insert(index, (target, counted));
                        counted
                    }
                };
                (passes, mark)
            }
        };
        if let Some(position) = unknown {
            return self.widen(control, engine, position, target, mark);
        }
        // A way that still depends on a condition met in this pass and decided neither way: whether
        // and when the loop ends is not known.
        if control
            .open_decisions(&self.covered)
            .any(|decision| decision >= mark)
        {
            mark_unknown_loop(control, depth, target, pc);
            let position = control.unknown_loops.len() - 1;
            return self.widen(control, engine, position, target, mark);
        }
        if passes > self.options.max_loop_passes {
            self.report(
                control,
                pc,
                Code::LoopPassLimit,
                Span::default(),
                format!(
                    "this loop ran {} passes, the configured limit (`max_loop_passes`): what its body changes is unknown after it",
                    self.options.max_loop_passes
                ),
            );
            mark_unknown_loop(control, depth, target, pc);
            let position = control.unknown_loops.len() - 1;
            return self.widen(control, engine, position, target, mark);
        }
        if passes % ENDLESS_CHECK_INTERVAL == 0 {
            let key = (depth, control.level().unit, target);
            let snapshot = engine.snapshot();
            if self.loop_heads.get(&key) == Some(&snapshot) {
                self.report(
                    control,
                    pc,
                    Code::EndlessLoop,
                    Span::default(),
                    "this loop never ends: its state at the start of a pass is the same as a thousand passes before, so the control runs it forever and nothing after it is reached on this way".to_string(),
                );
                return Next::Stop;
            }
            self.loop_heads.insert(key, snapshot);
        }
        Next::Line(target)
    }

    /// The next pass of a loop whose passes are not known: the state at its head joins the state of
    /// this pass; when nothing changes any more, every way out of the loop has been seen and this way
    /// ends. The way of the decisions of its last pass (from `pass_mark` on) goes on as an earlier
    /// pass did: the ways that took them the other way are no longer conditional on them.
    fn widen(
        &mut self,
        control: &mut Control,
        engine: &mut Engine<'a>,
        position: usize,
        target: usize,
        pass_mark: u32,
    ) -> Next {
        let snapshot = engine.snapshot();
        let unknown = &mut control.unknown_loops[position];
        match &mut unknown.state {
            None => unknown.state = Some(snapshot),
            Some(stored) => {
                let mut joined = stored.clone();
                joined.join(&snapshot);
                if joined == *stored {
                    self.covered.extend(
                        control
                            .forks
                            .iter()
                            .filter(|(decision, _)| *decision >= pass_mark),
                    );
                    return Next::Stop;
                }
                *stored = joined.clone();
                *engine = self.engine_from(joined);
            }
        }
        Next::Line(target)
    }
}

/// Enters the loop `head..=end` unless the way is in it already (a WHILE tests again at its head).
fn enter_loop(control: &mut Control, head: usize, end: usize, back_to: usize, fork_mark: u32) {
    let level = control.level_mut();
    if level.loops.last().is_some_and(|frame| frame.head == head) {
        return;
    }
    level.loops.push(LoopFrame {
        head,
        end,
        back_to,
        passes: 1,
        fork_mark,
    });
}

fn leave_loop(control: &mut Control, head: usize) {
    let level = control.level_mut();
    if level.loops.last().is_some_and(|frame| frame.head == head) {
        level.loops.pop();
    }
}

fn read_counter(variables: &Variables, target: &AssignTarget, name: &str) -> Option<f64> {
    match target {
        AssignTarget::RParameter(number) => variables.r_parameter(*number),
        AssignTarget::Variable { indexes } if indexes.is_empty() => variables.variable(name),
        _ => None,
    }
}

fn write_counter(variables: &mut Variables, target: &AssignTarget, name: &str, value: Option<f64>) {
    match target {
        AssignTarget::RParameter(number) => variables.set_r_parameter(*number, value),
        AssignTarget::Variable { indexes } if indexes.is_empty() => {
            variables.set_variable(name, value)
        }
        _ => {}
    }
}
