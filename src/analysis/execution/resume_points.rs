//! Where a recorded run takes its checkpoints and where a resumed run rejoins its earlier run: at a
//! block where one way runs on the main level (`resume.rs` holds what is recorded).

use crate::analysis::engine::engine_state::Engine;
use crate::analysis::execution::interpreter::Interpreter;
use crate::analysis::execution::paths::Control;
use crate::analysis::execution::resume::{Checkpoint, PassDelta, Recorder, Rejoin};
use crate::diagnostics::{Code, LineDiagnostic};
use std::collections::{HashMap, HashSet};

impl<'a> Interpreter<'a, '_> {
    /// At a block where one way runs on the main level: rejoins the earlier run when its state is
    /// reached again (the index of its checkpoint), else takes a checkpoint when one is due.
    pub(super) fn at_simple_point(
        &mut self,
        control: &mut Control,
        engine: &Engine<'a>,
    ) -> Option<usize> {
        control.forget_condition_marks();
        if let Some(index) = self.rejoin_point(control, engine) {
            return Some(index);
        }
        let awaiting = self.awaiting_call();
        let recorder = self.recorder.as_mut()?;
        if !recorder.due(self.executed) {
            return None;
        }
        let delta = recorder.take_delta(&self.passes);
        let checkpoint = Checkpoint {
            executed: self.executed,
            moves: recorder.emitted,
            findings: self.findings.len(),
            next_fork: self.next_fork,
            control: control.clone(),
            engine: engine.snapshot(),
            loop_heads: self.loop_heads.clone(),
            awaiting,
            delta,
        };
        recorder.push(checkpoint);
        None
    }

    /// The earlier run's checkpoint whose state this run has reached, when the rest of the earlier
    /// run is the rest of this one.
    fn rejoin_point(&self, control: &Control, engine: &Engine<'a>) -> Option<usize> {
        let rejoin = self.recorder.as_ref()?.rejoin.as_ref()?;
        let candidates = rejoin.by_line.get(&control.level().pc)?;
        let mut snapshot = None;
        for &index in candidates {
            let checkpoint = &rejoin.earlier[index];
            let rest = rejoin.earlier_executed - checkpoint.executed;
            if checkpoint.next_fork != self.next_fork
                || self.executed.saturating_add(rest) > self.options.max_blocks
                || checkpoint.control != *control
                || checkpoint.loop_heads != self.loop_heads
                || checkpoint.awaiting != self.awaiting_call()
            {
                continue;
            }
            let snapshot = snapshot.get_or_insert_with(|| engine.snapshot());
            if checkpoint.engine != *snapshot
                || !self.same_findings_since_resume(rejoin, checkpoint)
                || !self.same_passes_since_resume(rejoin, index)
            {
                continue;
            }
            return Some(index);
        }
        None
    }

    /// Whether this run reported the same findings (by line and code) since the resume as the
    /// earlier run up to `checkpoint`: the findings of the rest are reported once per line and code.
    fn same_findings_since_resume(&self, rejoin: &Rejoin, checkpoint: &Checkpoint) -> bool {
        let start = rejoin.earlier[rejoin.resumed_from].findings;
        let keys = |findings: &[LineDiagnostic]| -> HashSet<(usize, Code)> {
            findings
                .iter()
                .map(|finding| (finding.line, finding.diagnostic.code))
                .collect()
        };
        let earlier = rejoin
            .earlier_findings
            .get(start..checkpoint.findings)
            .unwrap_or(&[]);
        let now = self.findings.get(start..).unwrap_or(&[]);
        earlier.len() == now.len() && keys(earlier) == keys(now)
    }

    /// Whether every line ran as often since the resume as in the earlier run up to checkpoint
    /// `index`: then every later pass number is the same.
    fn same_passes_since_resume(&self, rejoin: &Rejoin, index: usize) -> bool {
        let mut earlier: HashMap<(u32, u32), u32> = HashMap::new();
        for checkpoint in &rejoin.earlier[rejoin.resumed_from + 1..=index] {
            for &(unit, line, count) in &checkpoint.delta {
                *earlier.entry((unit, line)).or_default() += count;
            }
        }
        for &(unit, line, before) in &rejoin.since_resume {
            let count = self.passes[unit as usize][line as usize] - before;
            match earlier.remove(&(unit, line)) {
                Some(earlier_count) if earlier_count == count => {}
                None if count == 0 => {}
                _ => return false,
            }
        }
        earlier.values().all(|&count| count == 0)
    }

    fn awaiting_call(&self) -> Option<usize> {
        self.first_passes
            .as_ref()
            .and_then(|passes| passes.awaiting())
    }

    /// The record of this run, once it ended.
    pub(super) fn take_record(&mut self) -> (Recorder<'a>, PassDelta) {
        let mut recorder = self.recorder.take().unwrap_or_else(|| Recorder::new(0));
        let tail = recorder.take_delta(&self.passes);
        (recorder, tail)
    }
}
