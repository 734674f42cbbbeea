//! What the first execution of each line of the analysed program had: the modal state after the
//! block (for a status bar that shows one state of a block that runs many times), and for a call the
//! program it ran and the state when it returned (for the hover of the call). Recorded only when a
//! caller asks for it ([`RunSetup::record_first_passes`](crate::analysis::execution::entry::RunSetup)): a preview of a large
//! program does not pay for a state per line.

use crate::analysis::document::report::StateSummary;
use crate::syntax::gcodes::GCode;
use std::sync::Arc;

/// The G groups a first pass keeps: motion, plane, units, distance, diameter, settable offset.
pub(super) const GROUPS: [usize; 6] = [1, 6, 13, 14, 29, 8];

/// The modal state after the first execution of a block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassState {
    pub(super) groups: [Option<GCode>; 6],
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
    pub(super) states: Vec<Option<PassState>>,
    /// Per call line: the called program's path and, once the first call returned, the state then.
    pub(super) calls: Vec<(usize, Option<Arc<str>>, Option<StateSummary>)>,
    /// The call line whose first call has not returned yet.
    pub(super) awaiting: Option<usize>,
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
