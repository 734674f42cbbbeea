//! A run of a program kept for the editor: its moves, findings and pass counts, with the record that
//! lets the next revision of the program run again from the last checkpoint before its first edited
//! block instead of from the start (`resume.rs`).
//!
//! An edit runs the program again from the start when it changes the program's flow (a label, a
//! block number, a jump, a structure, a call, a program end, a definition), adds or removes lines,
//! or when the earlier run lost track (a budget ran out), or when a called program changed. Every
//! other edit resumes the earlier run: the result is the same as running the new text from the
//! start, which the tests check after random edits.

use crate::analysis::execution::entry::RunSetup;
use crate::analysis::execution::interpreter::Interpreter;
use crate::analysis::execution::library_macros::LibraryMacros;
use crate::analysis::execution::outcome::{ExecutedMove, Execution};
use crate::analysis::execution::program::ProgramUnit;
use crate::analysis::execution::resume::{
    unit_paths, Checkpoint, PassDelta, Recorder, Rejoin, NEVER,
};
use crate::analysis::execution::run_program::add_stage_findings;
use crate::analysis::execution::ways::RunEnd;
use crate::analysis::library::{LibraryProgram, ProgramLibrary};
use crate::analysis::program_kind::ProgramKind;
use crate::config::{execution::ExecutionOptions, MachineConfig};
use crate::diagnostics::LineDiagnostic;
use crate::syntax::LineParser;
use std::{collections::HashMap, sync::Arc};

/// How a recorded run was made, for tests and figures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunStart {
    /// From the first block.
    Fresh,
    /// The edited lines never ran: the earlier run is this one.
    Unchanged,
    /// From the earlier run's checkpoint before block execution `from`; `rejoined`: the earlier
    /// run's rest was taken from block execution `at` of the new run on.
    Resumed { from: u64, rejoined: Option<u64> },
}

/// A run with its moves and the record to run it again.
pub struct RecordedRun {
    pub execution: Execution,
    pub moves: Arc<Vec<ExecutedMove>>,
    /// The path: `moves` with the corner stage's roundings and chamfers (the same when none).
    pub path_moves: Arc<Vec<ExecutedMove>>,
    pub start: RunStart,
    /// The pass number of every move, also for blocks that ran once (shown as 0 in `moves`).
    raw_passes: Arc<Vec<u32>>,
    findings_in_order: Arc<Vec<LineDiagnostic>>,
    units: Vec<Arc<ProgramUnit>>,
    unit_names: HashMap<String, Option<usize>>,
    checkpoints: Vec<Arc<Checkpoint>>,
    /// How often each line ran after the last checkpoint.
    tail_delta: PassDelta,
    first_run: Vec<u64>,
    last_run: Vec<u64>,
    /// Executed blocks between checkpoints.
    interval: u64,
    /// Whether the run can be resumed: it did not lose track.
    resumable: bool,
    kind: ProgramKind,
    options: ExecutionOptions,
    setup: RunSetup,
    /// The library's macro definition files and what they define, as the run read them.
    macro_files: Vec<Arc<LibraryProgram>>,
    macros: Arc<LibraryMacros>,
}

impl std::fmt::Debug for RecordedRun {
    fn fmt(&self, formatter: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        formatter
            .debug_struct("RecordedRun")
            .field("moves", &self.moves.len())
            .field("start", &self.start)
            .field("checkpoints", &self.checkpoints.len())
            .finish()
    }
}

impl RecordedRun {
    /// `path_moves` and the corner stage's findings (an unchanged run has the earlier run's).
    fn with_corners(mut self, config: &MachineConfig) -> RecordedRun {
        use crate::analysis::simulation::corners::path_of;
        let main = self.units.first().cloned();
        let Some(main) = main.filter(|_| self.start != RunStart::Unchanged) else {
            return self;
        };
        if let Some((path, findings)) = path_of(&self.moves, config, main.text()) {
            add_stage_findings(&mut self.execution.findings, findings);
            self.path_moves = Arc::new(path);
        }
        self
    }
}

impl PartialEq for RecordedRun {
    /// Two runs are equal when they give the same moves and the same execution.
    fn eq(&self, other: &RecordedRun) -> bool {
        self.execution == other.execution && self.moves == other.moves
    }
}

/// Runs `text`, resuming `earlier` (a run of an earlier revision with the same configuration) when
/// the edit allows it.
pub fn run_recorded(
    text: Arc<str>,
    config: &MachineConfig,
    kind: ProgramKind,
    library: &dyn ProgramLibrary,
    options: &ExecutionOptions,
    setup: &RunSetup,
    earlier: Option<&RecordedRun>,
) -> RecordedRun {
    let context = RunContext {
        kind,
        options,
        setup,
        macro_files: library.macro_files(),
    };
    if let Some(earlier) = earlier {
        if let Some(run) = run_again(&text, config, library, &context, earlier) {
            return run.with_corners(config);
        }
    }
    let macros = Arc::new(LibraryMacros::read(library, config));
    let main = Arc::new(ProgramUnit::with_macro_names(
        String::new(),
        None,
        text,
        config,
        macros.names(),
    ));
    let lines = main.line_count();
    let mut moves = Vec::new();
    let mut sink = |movement| moves.push(movement);
    let mut interpreter = Interpreter::new(config, library, options, &mut sink)
        .with_library_macros(Arc::clone(&macros))
        .with_setup(setup.clone());
    interpreter.recorder = Some(Recorder::new(lines));
    let start = interpreter.start(main, kind);
    let end = interpreter.run_from(start);
    let parts = Parts::take(interpreter);
    parts
        .into_run(moves, end, RunStart::Fresh, &context, macros, None)
        .with_corners(config)
}

/// The run of `text` resumed from `earlier`, when the edit allows it (see the module's comment);
/// `None` when the program must run from its first block.
#[allow(clippy::too_many_arguments)]
pub fn resume_run(
    text: Arc<str>,
    config: &MachineConfig,
    kind: ProgramKind,
    library: &dyn ProgramLibrary,
    options: &ExecutionOptions,
    setup: &RunSetup,
    earlier: &RecordedRun,
) -> Option<RecordedRun> {
    let context = RunContext {
        kind,
        options,
        setup,
        macro_files: library.macro_files(),
    };
    run_again(&text, config, library, &context, earlier).map(|run| run.with_corners(config))
}

/// What a run depends on besides the program's text and the called programs.
struct RunContext<'c> {
    kind: ProgramKind,
    options: &'c ExecutionOptions,
    setup: &'c RunSetup,
    macro_files: Vec<Arc<LibraryProgram>>,
}

/// The run of `text` from `earlier`, or `None` when it must start from the first block.
fn run_again(
    text: &Arc<str>,
    config: &MachineConfig,
    library: &dyn ProgramLibrary,
    context: &RunContext,
    earlier: &RecordedRun,
) -> Option<RecordedRun> {
    let (kind, options) = (context.kind, context.options);
    if !earlier.resumable
        || earlier.kind != kind
        || earlier.options != *options
        || earlier.setup != *context.setup
        || !same_programs(&earlier.macro_files, &context.macro_files)
    {
        return None;
    }
    let old_main = earlier.units.first()?;
    let main = ProgramUnit::with_flow_of(old_main, Arc::clone(text));
    if main.line_count() != old_main.line_count() || !earlier.same_library(library) {
        return None;
    }
    let edited = edited_lines(old_main, &main)?;
    let main = Arc::new(main);
    let mut units = earlier.units.clone();
    units[0] = Arc::clone(&main);
    let first_edited_run = edited
        .iter()
        .map(|&line| earlier.first_run[line])
        .min()
        .unwrap_or(NEVER);
    if first_edited_run == NEVER {
        // No edited line ran: the earlier run is the run of this text.
        return Some(RecordedRun {
            execution: earlier.execution.clone(),
            moves: Arc::clone(&earlier.moves),
            path_moves: Arc::clone(&earlier.path_moves),
            start: RunStart::Unchanged,
            raw_passes: Arc::clone(&earlier.raw_passes),
            findings_in_order: Arc::clone(&earlier.findings_in_order),
            units,
            unit_names: earlier.unit_names.clone(),
            checkpoints: earlier.checkpoints.clone(),
            tail_delta: earlier.tail_delta.clone(),
            first_run: earlier.first_run.clone(),
            last_run: earlier.last_run.clone(),
            interval: earlier.interval,
            resumable: true,
            kind,
            options: options.clone(),
            setup: earlier.setup.clone(),
            macro_files: earlier.macro_files.clone(),
            macros: Arc::clone(&earlier.macros),
        });
    }
    let last_edited_run = edited
        .iter()
        .map(|&line| earlier.last_run[line])
        .filter(|&time| time != NEVER)
        .max()
        .unwrap_or(0);
    let from = earlier
        .checkpoints
        .partition_point(|checkpoint| checkpoint.executed <= first_edited_run)
        .checked_sub(1)?;
    let checkpoint = Arc::clone(&earlier.checkpoints[from]);

    // The pass counts at the checkpoint: the earlier totals less every later interval.
    let mut passes = earlier.execution.pass_totals.clone();
    for later in earlier.checkpoints[from + 1..]
        .iter()
        .map(|later| &later.delta)
        .chain(std::iter::once(&earlier.tail_delta))
    {
        for &(unit, line, count) in later {
            passes[unit as usize][line as usize] -= count;
        }
    }
    let at = checkpoint.executed;
    let first_run: Vec<u64> = earlier
        .first_run
        .iter()
        .map(|&time| if time < at { time } else { NEVER })
        .collect();
    // A line that ran before the checkpoint and again after it ran last at some time before the
    // checkpoint; the latest such time is an upper bound, which only makes a later rejoin rarer.
    let last_run: Vec<u64> = earlier
        .last_run
        .iter()
        .zip(&earlier.first_run)
        .map(|(&last, &first)| match (first < at, last < at) {
            (_, true) => last,
            (true, false) => at - 1,
            (false, false) => NEVER,
        })
        .collect();
    let mut moves: Vec<ExecutedMove> = earlier.moves[..checkpoint.moves].to_vec();
    let mut raw_passes: Vec<u32> = earlier.raw_passes[..checkpoint.moves].to_vec();
    let findings: Vec<LineDiagnostic> = earlier.findings_in_order[..checkpoint.findings].to_vec();

    let rejoin = Rejoin::new(
        &earlier.checkpoints,
        &earlier.findings_in_order,
        earlier.execution.executed_blocks,
        from,
        last_edited_run,
    );
    let run_end;
    let parts;
    {
        let mut sink = |movement| moves.push(movement);
        let mut interpreter = Interpreter::new(config, library, options, &mut sink)
            .with_library_macros(Arc::clone(&earlier.macros))
            .with_setup(context.setup.clone());
        if let (Some(passes), true) = (
            earlier.execution.first_passes.as_deref(),
            interpreter.first_passes.is_some(),
        ) {
            interpreter.first_passes =
                Some(passes.before(&earlier.first_run, at, checkpoint.awaiting));
        }
        interpreter.units = units;
        interpreter.unit_names = earlier.unit_names.clone();
        interpreter.passes = passes;
        interpreter.reported = findings
            .iter()
            .map(|finding| (finding.line, finding.diagnostic.code))
            .collect();
        interpreter.findings = findings;
        interpreter.executed = at;
        interpreter.next_fork = checkpoint.next_fork;
        interpreter.loop_heads = checkpoint.loop_heads.clone();
        interpreter.assumed = earlier.execution.assumed.clone();
        interpreter.recorder = Some(Recorder::resumed(
            earlier.checkpoints[..=from].to_vec(),
            first_run,
            last_run,
            checkpoint.moves,
            earlier.interval,
            rejoin,
        ));
        let engine = interpreter.engine_from(checkpoint.engine.clone());
        run_end = interpreter.run_from((checkpoint.control.clone(), engine));
        parts = Parts::take(interpreter);
    }
    let rejoined = match run_end {
        RunEnd::Rejoined(index) => Some((index, parts.executed)),
        _ => None,
    };
    let start = RunStart::Resumed {
        from: at,
        rejoined: rejoined.map(|(_, executed)| executed),
    };
    let Some((index, _)) = rejoined else {
        raw_passes.extend(
            moves[raw_passes.len()..]
                .iter()
                .map(|movement| movement.pass),
        );
        let macros = Arc::clone(&earlier.macros);
        return Some(parts.into_run(moves, run_end, start, context, macros, Some(raw_passes)));
    };
    Some(parts.rejoin(earlier, index, moves, raw_passes, start))
}

/// The lines where `new` differs from `old` (of the same length), when every such line plays the
/// same part in the flow and lies after the definition part; `None` otherwise.
fn edited_lines(old: &ProgramUnit, new: &ProgramUnit) -> Option<Vec<usize>> {
    let count = old.line_count();
    let first = (0..count).find(|&line| old.line(line) != new.line(line));
    let Some(first) = first else {
        return Some(Vec::new());
    };
    let last = (first..count)
        .rev()
        .find(|&line| old.line(line) != new.line(line))
        .unwrap_or(first);
    if first <= old.flow.first_executable {
        return None;
    }
    let mut parser = LineParser::new();
    let mut edited = Vec::new();
    for line in first..=last {
        if old.line(line) == new.line(line) {
            continue;
        }
        if !old.same_flow(line, new, line, &mut parser) {
            return None;
        }
        edited.push(line);
    }
    Some(edited)
}

/// Whether two lists of macro definition files are the same files with the same texts.
fn same_programs(earlier: &[Arc<LibraryProgram>], now: &[Arc<LibraryProgram>]) -> bool {
    earlier.len() == now.len()
        && earlier
            .iter()
            .zip(now)
            .all(|(earlier, now)| earlier.path == now.path && earlier.text == now.text)
}

impl RecordedRun {
    /// How often each line of each program ran, by the program's path (`None`: the analysed
    /// program), without the programs that did not run. A resumed run keeps the table of programs
    /// of the run it resumed, in that run's order, also programs the new text no longer calls: this
    /// is the table's meaning, the same for a resumed and a fresh run.
    pub fn passes_by_program(&self) -> std::collections::BTreeMap<Option<String>, Vec<u32>> {
        self.units
            .iter()
            .zip(&self.execution.pass_totals)
            .enumerate()
            .filter(|(index, (_, counts))| *index == 0 || counts.iter().any(|&count| count > 0))
            .map(|(_, (unit, counts))| (unit.path.as_deref().map(str::to_string), counts.clone()))
            .collect()
    }

    /// Whether `library` gives every program this run looked up as it was then.
    fn same_library(&self, library: &dyn ProgramLibrary) -> bool {
        self.unit_names.iter().all(|(name, found)| {
            let now = library.find(name);
            match (found, now) {
                (None, None) => true,
                (Some(index), Some(program)) => {
                    let unit = &self.units[*index];
                    unit.path.as_deref() == Some(&*program.path) && **unit.text() == *program.text
                }
                _ => false,
            }
        })
    }
}

/// What an interpreter leaves after its run.
struct Parts<'a> {
    execution: Execution,
    findings_in_order: Vec<LineDiagnostic>,
    units: Vec<Arc<ProgramUnit>>,
    unit_names: HashMap<String, Option<usize>>,
    recorder: Recorder<'a>,
    tail_delta: PassDelta,
    executed: u64,
}

impl<'a> Parts<'a> {
    fn take(mut interpreter: Interpreter<'a, '_>) -> Parts<'a> {
        let (recorder, tail_delta) = interpreter.take_record();
        let findings_in_order = interpreter.findings.clone();
        let units = std::mem::take(&mut interpreter.units);
        let unit_names = std::mem::take(&mut interpreter.unit_names);
        let executed = interpreter.executed;
        // `finish` needs the main program only to say whether it has flow.
        interpreter.units = units.first().cloned().into_iter().collect();
        let execution = interpreter.finish();
        Parts {
            execution,
            findings_in_order,
            units,
            unit_names,
            recorder,
            tail_delta,
            executed,
        }
    }

    /// The run that ended by itself (`raw_passes` of the moves made before a resume).
    fn into_run(
        self,
        mut moves: Vec<ExecutedMove>,
        end: RunEnd,
        start: RunStart,
        context: &RunContext,
        macros: Arc<LibraryMacros>,
        raw_passes: Option<Vec<u32>>,
    ) -> RecordedRun {
        let raw_passes =
            raw_passes.unwrap_or_else(|| moves.iter().map(|movement| movement.pass).collect());
        hide_single_passes(
            &mut moves,
            &raw_passes,
            &self.execution.pass_totals,
            &self.units,
        );
        let moves = Arc::new(moves);
        RecordedRun {
            execution: self.execution,
            path_moves: Arc::clone(&moves),
            moves,
            start,
            raw_passes: Arc::new(raw_passes),
            findings_in_order: Arc::new(self.findings_in_order),
            units: self.units,
            unit_names: self.unit_names,
            checkpoints: self.recorder.checkpoints,
            tail_delta: self.tail_delta,
            first_run: self.recorder.first_run,
            last_run: self.recorder.last_run,
            interval: self.recorder.interval,
            resumable: end == RunEnd::Finished,
            kind: context.kind,
            options: context.options.clone(),
            setup: context.setup.clone(),
            macro_files: context.macro_files.clone(),
            macros,
        }
    }

    /// The run that reached the state of `earlier` at its checkpoint `index`: the rest is
    /// `earlier`'s, shifted by the difference in executed blocks.
    fn rejoin(
        mut self,
        earlier: &RecordedRun,
        index: usize,
        mut moves: Vec<ExecutedMove>,
        mut raw_passes: Vec<u32>,
        start: RunStart,
    ) -> RecordedRun {
        let joined = &earlier.checkpoints[index];
        raw_passes.extend(
            moves[raw_passes.len()..]
                .iter()
                .map(|movement| movement.pass),
        );
        moves.extend_from_slice(&earlier.moves[joined.moves..]);
        raw_passes.extend_from_slice(&earlier.raw_passes[joined.moves..]);
        let mut findings = self.findings_in_order;
        findings.extend_from_slice(&earlier.findings_in_order[joined.findings..]);
        let shift = |time: u64| time - joined.executed + self.executed;
        let move_shift = moves.len() - (earlier.moves.len() - joined.moves);
        let finding_shift = findings.len() - (earlier.findings_in_order.len() - joined.findings);

        // The checkpoint where the runs met, with how often each line ran since this run's last
        // checkpoint, then the earlier run's later checkpoints.
        let mut recorder = self.recorder;
        let mut checkpoints = std::mem::take(&mut recorder.checkpoints);
        let mut met = (**joined).clone();
        met.delta = self.tail_delta;
        met.executed = self.executed;
        met.moves = move_shift;
        met.findings = finding_shift;
        checkpoints.push(Arc::new(met));
        for later in &earlier.checkpoints[index + 1..] {
            let mut later = (**later).clone();
            later.executed = shift(later.executed);
            later.moves = later.moves - joined.moves + move_shift;
            later.findings = later.findings - joined.findings + finding_shift;
            checkpoints.push(Arc::new(later));
        }
        let mut first_run = recorder.first_run;
        let mut last_run = recorder.last_run;
        for line in 0..first_run.len() {
            if earlier.first_run[line] != NEVER && earlier.first_run[line] >= joined.executed {
                first_run[line] = shift(earlier.first_run[line]);
            }
            if earlier.last_run[line] != NEVER && earlier.last_run[line] >= joined.executed {
                last_run[line] = shift(earlier.last_run[line]);
            }
        }
        self.execution.findings = findings.clone();
        self.execution
            .findings
            .sort_by_key(|item| (item.line, item.diagnostic.span.start()));
        self.execution.executed_blocks = shift(earlier.execution.executed_blocks);
        self.execution.pass_totals = earlier.execution.pass_totals.clone();
        if let (Some(mine), Some(theirs)) = (
            self.execution.first_passes.take(),
            earlier.execution.first_passes.as_deref(),
        ) {
            let joined = mine.joined(theirs, &earlier.first_run, joined.executed);
            self.execution.first_passes = Some(Box::new(joined));
        }
        hide_single_passes(
            &mut moves,
            &raw_passes,
            &self.execution.pass_totals,
            &self.units,
        );
        let moves = Arc::new(moves);
        RecordedRun {
            execution: self.execution,
            path_moves: Arc::clone(&moves),
            moves,
            start,
            raw_passes: Arc::new(raw_passes),
            findings_in_order: Arc::new(findings),
            units: self.units,
            unit_names: self.unit_names,
            checkpoints,
            tail_delta: earlier.tail_delta.clone(),
            first_run,
            last_run,
            interval: recorder.interval.max(earlier.interval),
            resumable: earlier.resumable,
            kind: earlier.kind,
            options: earlier.options.clone(),
            setup: earlier.setup.clone(),
            macro_files: earlier.macro_files.clone(),
            macros: Arc::clone(&earlier.macros),
        }
    }
}

/// Gives every move the pass number it shows: 0 when its block ran once in the whole run.
fn hide_single_passes(
    moves: &mut [ExecutedMove],
    raw_passes: &[u32],
    totals: &[Vec<u32>],
    units: &[Arc<ProgramUnit>],
) {
    let paths = unit_paths(units);
    for (movement, &raw) in moves.iter_mut().zip(raw_passes) {
        let unit = match movement.path.as_deref() {
            None => 0,
            Some(path) => paths.get(path).copied().unwrap_or(0),
        };
        let total = totals
            .get(unit)
            .and_then(|lines| lines.get(movement.movement.line))
            .copied()
            .unwrap_or(1);
        movement.pass = if total <= 1 { 0 } else { raw };
    }
}
