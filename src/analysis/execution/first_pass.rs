//! What the first execution of each line of the analysed program had: the modal state after the
//! block (for a status bar that shows one state of a block that runs many times), and for a call the
//! program it ran and the state when it returned (for the hover of the call). Recorded only when a
//! caller asks for it ([`RunSetup::record_first_passes`](super::RunSetup)): a preview of a large
//! program does not pay for a state per line.

use crate::analysis::document::{summarize, StateSummary};
use crate::analysis::engine::Engine;
use crate::analysis::execution::interpreter::Interpreter;
use crate::analysis::execution::paths::Control;
use crate::syntax::gcodes::GCode;
use std::sync::Arc;

/// The G groups a first pass keeps: motion, plane, units, distance, diameter, settable offset.
const GROUPS: [usize; 6] = [1, 6, 13, 14, 29, 8];

/// The modal state after the first execution of a block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassState {
    groups: [Option<GCode>; 6],
    /// The modal feed in the basic unit system.
    pub feed: Option<f64>,
}

impl PassState {
    fn group(&self, index: usize) -> Option<String> {
        self.groups[index].map(|code| code.name().into_owned())
    }
    pub fn motion(&self) -> Option<String> {
        self.group(0)
    }
    pub fn plane(&self) -> Option<String> {
        self.group(1)
    }
    pub fn units(&self) -> Option<String> {
        self.group(2)
    }
    pub fn distance(&self) -> Option<String> {
        self.group(3)
    }
    pub fn diameter(&self) -> Option<String> {
        self.group(4)
    }
    pub fn settable_offset(&self) -> Option<String> {
        self.group(5)
    }
}

/// The first passes of the analysed program's lines.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FirstPasses {
    /// Per line, once it ran: the state after its block (before a call on it runs).
    states: Vec<Option<PassState>>,
    /// Per call line: the called program's path and, once the first call returned, the state then.
    calls: Vec<(usize, Option<Arc<str>>, Option<StateSummary>)>,
    /// The call line whose first call has not returned yet.
    awaiting: Option<usize>,
}

impl FirstPasses {
    /// The state after the first execution of `line`, when it ran.
    pub fn state(&self, line: usize) -> Option<&PassState> {
        self.states.get(line)?.as_ref()
    }

    /// For a call on `line`: the called program's path (`None`: the analysed program itself) and the
    /// state when its first call returned (`None` when it never returned to the analysed program).
    pub fn call(&self, line: usize) -> Option<(Option<&str>, Option<&StateSummary>)> {
        self.calls
            .iter()
            .find(|(call_line, _, _)| *call_line == line)
            .map(|(_, path, after)| (path.as_deref(), after.as_ref()))
    }
}

impl FirstPasses {
    /// The call line whose first call has returned but whose state after it is not taken yet.
    pub(super) fn awaiting(&self) -> Option<usize> {
        self.awaiting
    }

    /// What was recorded before block execution `at`, given when each line first ran
    /// (`first_run`), with the call awaiting its state then.
    pub(super) fn before(
        &self,
        first_run: &[u64],
        at: u64,
        awaiting: Option<usize>,
    ) -> FirstPasses {
        let ran_before = |line: usize| first_run.get(line).is_some_and(|&time| time < at);
        let mut states: Vec<Option<PassState>> = self
            .states
            .iter()
            .enumerate()
            .map(|(line, state)| if ran_before(line) { *state } else { None })
            .collect();
        trim(&mut states);
        let calls = self
            .calls
            .iter()
            .filter(|(line, _, _)| ran_before(*line))
            .map(|(line, path, after)| {
                let after = if Some(*line) == awaiting {
                    None
                } else {
                    after.clone()
                };
                (*line, path.clone(), after)
            })
            .collect();
        FirstPasses {
            states,
            calls,
            awaiting,
        }
    }

    /// These first passes, up to block execution `now`, followed by those of `earlier` from its
    /// block execution `at` on (the earlier run's rest, which this run takes over from there).
    pub(super) fn joined(
        mut self,
        earlier: &FirstPasses,
        earlier_first_run: &[u64],
        at: u64,
    ) -> FirstPasses {
        let ran_from = |line: usize| earlier_first_run.get(line).is_some_and(|&time| time >= at);
        if self.states.len() < earlier.states.len() {
            self.states.resize(earlier.states.len(), None);
        }
        for (line, state) in earlier.states.iter().enumerate() {
            if ran_from(line) {
                self.states[line] = *state;
            }
        }
        // The call that awaited its state at the meeting point gets it in the earlier run's rest.
        if let Some(line) = self.awaiting.take() {
            let after = earlier.call(line).and_then(|(_, after)| after.cloned());
            if let Some(call) = self.calls.iter_mut().find(|call| call.0 == line) {
                call.2 = after;
            }
        }
        for call in &earlier.calls {
            if ran_from(call.0) {
                self.calls.push(call.clone());
            }
        }
        self.awaiting = earlier.awaiting;
        trim(&mut self.states);
        self
    }
}

/// Drops the lines at the end that did not run: a run keeps its states up to the last line that ran.
fn trim(states: &mut Vec<Option<PassState>>) {
    while states.last().is_some_and(Option::is_none) {
        states.pop();
    }
}

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
