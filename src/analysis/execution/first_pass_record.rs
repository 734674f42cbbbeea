//! How a run records the first passes of the analysed program's lines (`first_pass.rs`): the state
//! after a block's first execution, and the program a first call runs with its state on return.

use crate::analysis::document::report::summarize;
use crate::analysis::engine::engine_state::Engine;
use crate::analysis::execution::first_pass::{PassState, GROUPS};
use crate::analysis::execution::interpreter::Interpreter;
use crate::analysis::execution::paths::Control;

impl<'a, 's> Interpreter<'a, 's> {
    /// Before a block of the analysed program's own level: a call awaiting its return has returned.
    pub(super) fn first_pass_before(
        &mut self,
        control: &Control,
        engine: &Engine<'a>,
        unit: usize,
    ) {
        let Some(passes) = self.first_passes.as_mut() else {
            return;
        };
        if unit != 0 || control.levels.len() != 1 {
            return;
        }
        if let Some(line) = passes.awaiting.take() {
            let after = summarize(self.config, &engine.state, engine.flow_uncertain());
            if let Some(call) = passes.calls.iter_mut().find(|call| call.0 == line) {
                call.2 = Some(after);
            }
        }
    }

    /// After the block on `pc` of the analysed program: its state when this is its first pass, and
    /// the program a first call on it runs (`callee`).
    pub(super) fn first_pass_after(
        &mut self,
        control: &Control,
        engine: &Engine<'a>,
        unit: usize,
        pc: usize,
        callee: Option<usize>,
    ) {
        if self.first_passes.is_none() || unit != 0 || control.levels.len() != 1 {
            return;
        }
        if self.passes_so_far(pc) != 1 {
            return;
        }
        let callee_path = callee.map(|index| self.units[index].path.clone());
        let Some(passes) = self.first_passes.as_mut() else {
            return;
        };
        if passes.states.len() <= pc {
            passes.states.resize(pc + 1, None);
        }
        let state = &engine.state;
        passes.states[pc] = Some(PassState {
            groups: GROUPS.map(|group| state.groups[group]),
            feed: state.feed,
        });
        if let Some(path) = callee_path {
            passes.calls.push((pc, path, None));
            passes.awaiting = Some(pc);
        }
    }
}
