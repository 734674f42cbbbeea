//! Where a jump goes: a label or block number written in the jump, or the label a STRING variable or
//! expression holds when the program determines it (reference §8.4: the control evaluates the target
//! as a string).

use crate::analysis::engine::engine_state::Engine;
use crate::analysis::eval::{evaluate_value, EvalOptions, Value};
use crate::analysis::execution::interpreter::Interpreter;
use crate::analysis::execution::program::ProgramUnit;
use crate::diagnostics::Code;
use crate::syntax::ast::{Block, JumpKind, JumpTarget};
use crate::syntax::jumps::{resolve_jump, JumpResolution};

/// What a jump does on this way.
#[derive(Debug, Clone, PartialEq)]
pub enum JumpOutcome {
    /// It goes to this line of the same program.
    Line(usize),
    /// The program goes on with the next block (GOTOS without a restart, GOTOC to a missing target).
    GoOn,
    /// Its target is not known: a string whose value the program does not determine, or a label the
    /// program does not contain (reported statically as W304/W305).
    Unknown,
    /// Its target is the value of a string the program determines, and the program has no such label
    /// in the jump's direction: the control stops with alarm 14080. The finding: W304 (no such label)
    /// or W305 (only in the other direction), and its text.
    Missing(Code, String),
}

fn keyword(kind: JumpKind) -> &'static str {
    match kind {
        JumpKind::Gotof => "GOTOF",
        JumpKind::Gotob => "GOTOB",
        JumpKind::Goto => "GOTO",
        JumpKind::Gotoc => "GOTOC",
        JumpKind::Gotos => "GOTOS",
    }
}

/// The lines a target name reaches: a label, or `N<digits>` as a block number.
fn name_lines<'u>(unit: &'u ProgramUnit, name: &str) -> &'u [usize] {
    let labelled = unit.flow.label_lines(name);
    if !labelled.is_empty() {
        return labelled;
    }
    match name.strip_prefix('N').map(str::parse::<u64>) {
        Some(Ok(number)) => unit.flow.block_number_lines(number),
        _ => labelled,
    }
}

impl<'a, 's> Interpreter<'a, 's> {
    /// The outcome of the jump `kind` to `target` at line `pc`.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn jump_target(
        &mut self,
        engine: &Engine<'a>,
        unit: &ProgramUnit,
        block: &Block,
        line: &str,
        pc: usize,
        kind: JumpKind,
        target: &JumpTarget,
    ) -> JumpOutcome {
        if kind == JumpKind::Gotos {
            return match self.options.gotos_restarts {
                Some(true) => JumpOutcome::Line(unit.flow.first_executable),
                Some(false) => JumpOutcome::GoOn,
                None => JumpOutcome::Unknown,
            };
        }
        let variables = &engine.state.variables;
        // The name written, and the string it stands for when it is a variable rather than a label.
        let (candidates, held): (&[usize], Option<(String, String)>) = match target {
            JumpTarget::Label(span) => {
                let name = line[span.start()..span.end()].to_ascii_uppercase();
                let lines = unit.flow.label_lines(&name);
                match variables.var_type(&name) {
                    Some(_) if lines.is_empty() => match variables.value(&name, &[]) {
                        Some(Value::Text(text)) => {
                            let label = text.trim().to_ascii_uppercase();
                            (name_lines(unit, &label), Some((label, format!("`{name}`"))))
                        }
                        _ => return JumpOutcome::Unknown,
                    },
                    _ => (lines, None),
                }
            }
            JumpTarget::BlockNumber { value, .. } => (unit.flow.block_number_lines(*value), None),
            JumpTarget::Computed(id) => {
                match evaluate_value(block, line, *id, variables, &EvalOptions::default()) {
                    Ok(Some(Value::Text(text))) => {
                        let label = text.trim().to_ascii_uppercase();
                        let shown = "the target expression".to_string();
                        (name_lines(unit, &label), Some((label, shown)))
                    }
                    _ => return JumpOutcome::Unknown,
                }
            }
            JumpTarget::None => return JumpOutcome::Unknown,
        };
        match resolve_jump(kind, pc, candidates) {
            JumpResolution::Found(target_line) => JumpOutcome::Line(target_line),
            _ if kind == JumpKind::Gotoc => JumpOutcome::GoOn,
            resolution => match held {
                Some((label, source)) => {
                    let keyword = keyword(kind);
                    let (code, found) = if matches!(resolution, JumpResolution::WrongDirection(_)) {
                        (
                            Code::JumpWrongDirection,
                            "which is not in the direction it searches",
                        )
                    } else {
                        (
                            Code::UndefinedJumpTarget,
                            "which this program does not contain",
                        )
                    };
                    JumpOutcome::Missing(code, format!(
                        "{keyword} jumps to `{label}` (the value of {source}), {found} (alarm 14080): the program stops here"
                    ))
                }
                // A label written in the jump: the control stops with alarm 14080 (reported as
                // W304/W305); nothing runs after it.
                None => JumpOutcome::Unknown,
            },
        }
    }
}
