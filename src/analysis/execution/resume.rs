//! Recording a run so that it can be run again after an edit without starting from the first block.
//!
//! A recorded run keeps checkpoints: the whole state of the interpreter at blocks where a single way
//! runs on the main level (no waiting way, no undecided condition, no loop of unknown passes), every
//! few thousand executed blocks. It also keeps, per line of the analysed program, when the line ran
//! first and last, and per interval between checkpoints, how often each line ran in it.
//!
//! After an edit that leaves the program's flow as it was (`again.rs` decides), the new run starts
//! at the last checkpoint before the first execution of an edited line. At every later simple state
//! it looks for a checkpoint of the earlier run at the same place with the same state, after which
//! the earlier run never executed an edited line and before which both runs executed every line
//! equally often: from there the earlier run's moves, findings and checkpoints are the new run's.
//!
//! What a checkpoint leaves out is what cannot change the rest of a run from a simple state: the
//! decisions that ended on a loop's unchanged state (`covered`) and the undecided-condition marks of
//! labels and loops only matter for decisions a way still depends on, and a simple way depends on
//! none; every later decision has a higher number.

use crate::analysis::engine::snapshot::EngineSnapshot;
use crate::analysis::execution::paths::Control;
use crate::analysis::execution::program::ProgramUnit;
use crate::diagnostics::LineDiagnostic;
use std::collections::HashMap;
use std::sync::Arc;

/// A line that did not run.
pub(super) const NEVER: u64 = u64::MAX;

/// Executed blocks between two checkpoints at first; the interval doubles when the checkpoints hold
/// too much.
const FIRST_INTERVAL: u64 = 1024;

/// How many entries (counters, marks, pass records) the checkpoints of one run may hold before every
/// other one is dropped: about 16 bytes each.
const MAX_STORED_ENTRIES: usize = 1 << 21;

/// How often each line ran in an interval: (program, line, count).
pub(super) type PassDelta = Vec<(u32, u32, u32)>;

/// The state of a run before the block numbered `executed`.
#[derive(Debug, Clone)]
pub(super) struct Checkpoint {
    pub executed: u64,
    /// Moves made and findings reported before it.
    pub moves: usize,
    pub findings: usize,
    pub next_fork: u32,
    pub control: Control,
    pub engine: EngineSnapshot,
    pub loop_heads: HashMap<(usize, usize, usize), EngineSnapshot>,
    /// The call line whose first call returned just before (its state after the call is taken at
    /// the next block), when first passes are recorded.
    pub awaiting: Option<usize>,
    /// How often each line ran since the previous checkpoint.
    pub delta: PassDelta,
}

impl Checkpoint {
    fn size(&self) -> usize {
        let levels: usize = self
            .control
            .levels
            .iter()
            .map(|level| level.jump_passes.len() + level.label_marks.len() + level.loops.len())
            .sum();
        1 + levels + self.delta.len() + self.loop_heads.len()
    }

    /// The main program's line where the way goes on.
    pub fn line(&self) -> usize {
        self.control.levels[0].pc
    }
}

/// Where a resumed run may rejoin its earlier run.
pub(super) struct Rejoin<'a> {
    pub earlier: &'a [Arc<Checkpoint>],
    pub earlier_findings: &'a [LineDiagnostic],
    pub earlier_executed: u64,
    /// The earlier checkpoints by their line.
    pub by_line: HashMap<usize, Vec<usize>>,
    /// The earlier checkpoint the run was resumed from.
    pub resumed_from: usize,
    /// Lines that ran since the resume, with their count before it.
    pub(super) since_resume: Vec<(u32, u32, u32)>,
    since_resume_seen: Vec<Vec<bool>>,
}

impl<'a> Rejoin<'a> {
    pub fn new(
        earlier: &'a [Arc<Checkpoint>],
        earlier_findings: &'a [LineDiagnostic],
        earlier_executed: u64,
        resumed_from: usize,
        last_edited_run: u64,
    ) -> Rejoin<'a> {
        let mut by_line: HashMap<usize, Vec<usize>> = HashMap::new();
        for (index, checkpoint) in earlier.iter().enumerate().skip(resumed_from + 1) {
            if checkpoint.executed > last_edited_run {
                by_line.entry(checkpoint.line()).or_default().push(index);
            }
        }
        Rejoin {
            earlier,
            earlier_findings,
            earlier_executed,
            by_line,
            resumed_from,
            since_resume: Vec::new(),
            since_resume_seen: Vec::new(),
        }
    }
}

/// What a recorded run keeps besides its moves.
pub(super) struct Recorder<'a> {
    pub checkpoints: Vec<Arc<Checkpoint>>,
    pub interval: u64,
    stored: usize,
    /// Lines that ran since the last checkpoint, with their count before it.
    touched: Vec<(u32, u32, u32)>,
    /// Per program, per line: the interval (its number + 1) in which the line last ran.
    marks: Vec<Vec<u32>>,
    interval_number: u32,
    /// Per line of the analysed program: the number of the block execution that ran it first and
    /// last ([`NEVER`] when it did not run).
    pub first_run: Vec<u64>,
    pub last_run: Vec<u64>,
    /// Moves made so far.
    pub emitted: usize,
    pub rejoin: Option<Rejoin<'a>>,
}

impl<'a> Recorder<'a> {
    pub fn new(main_lines: usize) -> Recorder<'a> {
        Recorder {
            checkpoints: Vec::new(),
            interval: FIRST_INTERVAL,
            stored: 0,
            touched: Vec::new(),
            marks: Vec::new(),
            interval_number: 0,
            first_run: vec![NEVER; main_lines],
            last_run: vec![NEVER; main_lines],
            emitted: 0,
            rejoin: None,
        }
    }

    /// Continues the record of an earlier run from its checkpoint `checkpoints.last()`.
    pub fn resumed(
        checkpoints: Vec<Arc<Checkpoint>>,
        first_run: Vec<u64>,
        last_run: Vec<u64>,
        emitted: usize,
        interval: u64,
        rejoin: Rejoin<'a>,
    ) -> Recorder<'a> {
        let stored = checkpoints.iter().map(|checkpoint| checkpoint.size()).sum();
        Recorder {
            checkpoints,
            interval,
            stored,
            touched: Vec::new(),
            marks: Vec::new(),
            interval_number: 0,
            first_run,
            last_run,
            emitted,
            rejoin: Some(rejoin),
        }
    }

    /// Notes that line `line` of program `unit` (of `lines` lines) runs as block execution `time`,
    /// after `before` earlier executions.
    pub fn executing(&mut self, unit: usize, line: usize, lines: usize, time: u64, before: u32) {
        if unit == 0 {
            if let Some(first) = self.first_run.get_mut(line) {
                if *first == NEVER {
                    *first = time;
                }
                self.last_run[line] = time;
            }
        }
        while self.marks.len() <= unit {
            self.marks.push(Vec::new());
        }
        let marks = &mut self.marks[unit];
        if marks.len() < lines {
            marks.resize(lines, 0);
        }
        if let Some(mark) = marks.get_mut(line) {
            if *mark != self.interval_number + 1 {
                *mark = self.interval_number + 1;
                self.touched.push((unit as u32, line as u32, before));
            }
        }
        if let Some(rejoin) = self.rejoin.as_mut() {
            while rejoin.since_resume_seen.len() <= unit {
                rejoin.since_resume_seen.push(Vec::new());
            }
            let seen = &mut rejoin.since_resume_seen[unit];
            if seen.len() < lines {
                seen.resize(lines, false);
            }
            if let Some(seen) = seen.get_mut(line) {
                if !*seen {
                    *seen = true;
                    rejoin.since_resume.push((unit as u32, line as u32, before));
                }
            }
        }
    }

    /// How often each line ran since the last checkpoint; starts the next interval.
    pub(super) fn take_delta(&mut self, passes: &[Vec<u32>]) -> PassDelta {
        self.interval_number += 1;
        self.touched
            .drain(..)
            .map(|(unit, line, before)| {
                let now = passes[unit as usize][line as usize];
                (unit, line, now - before)
            })
            .collect()
    }

    pub(super) fn due(&self, executed: u64) -> bool {
        match self.checkpoints.last() {
            None => true,
            Some(last) => executed >= last.executed + self.interval,
        }
    }

    pub(super) fn push(&mut self, checkpoint: Checkpoint) {
        self.stored += checkpoint.size();
        self.checkpoints.push(Arc::new(checkpoint));
        if self.stored > MAX_STORED_ENTRIES {
            self.thin_out();
        }
    }

    /// Drops every other checkpoint (the first and the last stay) and doubles the interval, so that
    /// the checkpoints of a long run hold a bounded amount.
    fn thin_out(&mut self) {
        let count = self.checkpoints.len();
        let mut kept: Vec<Arc<Checkpoint>> = Vec::with_capacity(count / 2 + 2);
        let mut carried: PassDelta = Vec::new();
        for (index, checkpoint) in self.checkpoints.drain(..).enumerate() {
            let keep = index == 0 || index + 1 == count || index % 2 == 0;
            if keep {
                if carried.is_empty() {
                    kept.push(checkpoint);
                } else {
                    let mut merged = (*checkpoint).clone();
                    carried.append(&mut merged.delta);
                    merged.delta = std::mem::take(&mut carried);
                    kept.push(Arc::new(merged));
                }
            } else {
                carried.extend_from_slice(&checkpoint.delta);
            }
        }
        self.checkpoints = kept;
        self.stored = self
            .checkpoints
            .iter()
            .map(|checkpoint| checkpoint.size())
            .sum();
        self.interval *= 2;
    }
}

/// The programs of a run and what they are called, as the run found them.
pub(super) fn unit_paths(units: &[Arc<ProgramUnit>]) -> HashMap<&str, usize> {
    let mut paths = HashMap::new();
    for (index, unit) in units.iter().enumerate() {
        if let Some(path) = unit.path.as_deref() {
            paths.entry(path).or_insert(index);
        }
    }
    paths
}
