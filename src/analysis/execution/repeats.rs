//! Section repetitions (`REPEAT L1 [L2 | ENDLABEL] P=n`, `REPEATB L1 P=n`, reference §17.7): where
//! a repetition starts, and where the program goes once a repeated section ends.

use crate::analysis::engine::engine_state::Engine;
use crate::analysis::eval::evaluate;
use crate::analysis::execution::block_run::Next;
use crate::analysis::execution::interpreter::Interpreter;
use crate::analysis::execution::paths::{Control, RepeatFrame};
use crate::diagnostics::{Code, Span};
use crate::syntax::ast::{Block, ExprId};

/// Section repetitions one program level follows inside each other.
const MAX_NESTED_REPEATS: usize = 64;

impl<'a, 's> Interpreter<'a, 's> {
    /// Starts the repetitions of the lines `first..=last` (reference §17.7: the section has run once
    /// already; it runs `P` more times, once when `P` is not written) and goes on after `pc`.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn repeat_section(
        &mut self,
        control: &mut Control,
        engine: &Engine<'a>,
        block: &Block,
        line: &str,
        pc: usize,
        first: usize,
        last: usize,
        count: Option<ExprId>,
        span: Span,
    ) -> Next {
        let repetitions = match count {
            None => Some(1.0),
            Some(id) => evaluate(block, line, id, &engine.state.variables)
                .ok()
                .flatten(),
        };
        let Some(repetitions) = repetitions.filter(|value| *value >= 0.0 && value.fract() == 0.0)
        else {
            self.report(
                control,
                pc,
                Code::FlowNotFollowed,
                span,
                "how often this section repeats is not known statically: from here on the program is read in program order".to_string(),
            );
            control.level_mut().pc = pc + 1;
            return Next::LoseTrack;
        };
        if repetitions < 1.0 || last < first {
            return Next::Line(pc + 1);
        }
        // A section that contains its own REPEAT block would start itself again on every pass, and
        // sections nested without end cannot be followed: the rest is read in program order.
        let level = control.level();
        if (first..=last).contains(&pc) || level.repeats.len() >= MAX_NESTED_REPEATS {
            self.report(
                control,
                pc,
                Code::FlowNotFollowed,
                span,
                "this section repetition contains its own REPEAT block or is nested too deeply to follow: from here on the program is read in program order".to_string(),
            );
            control.level_mut().pc = pc + 1;
            return Next::LoseTrack;
        }
        control.level_mut().repeats.push(RepeatFrame {
            start: first,
            end: last,
            remaining: repetitions.min(u32::MAX as f64) as u32,
            return_to: pc + 1,
        });
        control.level_mut().pc = first;
        Next::Moved
    }

    /// The line after `pc` in normal flow, or the start of the next repetition of a section that
    /// ends at `pc`, or the line after the REPEAT block once the section is done.
    pub(super) fn after_section_line(&self, control: &mut Control, pc: usize) -> usize {
        let level = control.level_mut();
        match level.repeats.last_mut() {
            Some(frame) if frame.end == pc => {
                if frame.remaining > 1 {
                    frame.remaining -= 1;
                    frame.start
                } else {
                    let return_to = frame.return_to;
                    level.repeats.pop();
                    return_to
                }
            }
            _ => pc + 1,
        }
    }
}
