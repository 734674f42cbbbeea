//! The interpreter's state: the `Interpreter` struct (the programs it runs, the ways that wait, the
//! passes counted, the findings, the sink of its moves), its construction and options, and the
//! result of a run. The main loop is in `ways.rs`, one block in `block_run.rs`, the decisions of
//! single statements in `control.rs`, calls and returns in `calls.rs`.

use crate::analysis::engine::engine_state::Engine;
use crate::analysis::engine::snapshot::EngineSnapshot;
use crate::analysis::execution::cycles::cycle_state::CycleState;
use crate::analysis::execution::entry::RunSetup;
use crate::analysis::execution::first_pass::FirstPasses;
use crate::analysis::execution::library_macros::LibraryMacros;
use crate::analysis::execution::outcome::{ExecutedMove, Execution};
use crate::analysis::execution::paths::Way;
use crate::analysis::execution::program::ProgramUnit;
use crate::analysis::execution::resume::Recorder;
use crate::analysis::library::ProgramLibrary;
use crate::config::execution::ExecutionOptions;
use crate::config::MachineConfig;
use crate::diagnostics::{Code, Diagnostic, LineDiagnostic};
use crate::syntax::ast::Block;
use crate::syntax::LineParser;
use std::collections::{HashMap, HashSet};
use std::sync::Arc;

/// Runs a program block by block in the order the control runs them (see `execution/ways.rs` for
/// the loop, `execution/block_run.rs` for one block).
pub struct Interpreter<'a, 's> {
    pub(super) config: &'a MachineConfig,
    pub(super) library: &'a dyn ProgramLibrary,
    pub(super) options: &'a ExecutionOptions,
    pub(super) units: Vec<Arc<ProgramUnit>>,
    /// Lookups of programs by name, misses included.
    pub(super) unit_names: HashMap<String, Option<usize>>,
    /// Per program, per line: how often the line was executed.
    pub(super) passes: Vec<Vec<u32>>,
    pub(super) parser: LineParser,
    pub(super) block: Block,
    /// Where the moves go, in the order the control executes them.
    pub(super) sink: &'s mut dyn FnMut(ExecutedMove),
    /// How often each line of each program runs in the whole run (from a first run that only
    /// counts), so that a move says its pass only when its block runs more than once; `None`: every
    /// block runs once (a program without any flow).
    pub(super) pass_totals: Option<Vec<Vec<u32>>>,
    /// The run only counts passes: no move is built.
    pub(super) counting: bool,
    pub(super) findings: Vec<LineDiagnostic>,
    pub(super) reported: HashSet<(usize, Code)>,
    pub(super) executed: u64,
    /// The ways that wait, in no particular order.
    pub(super) pending: Vec<Way>,
    pub(super) next_fork: u32,
    /// Decisions taken on a way that ended because its loop's state no longer changed: that way goes
    /// on as an earlier pass did, so a way that took such a decision the other way does not depend
    /// on it.
    pub(super) covered: HashSet<(u32, bool)>,
    pub(super) assumed: Vec<(&'static str, String)>,
    /// Checkpoints, pass records and the place to rejoin an earlier run, when the run is recorded
    /// for running again after an edit (`resume.rs`).
    pub(super) recorder: Option<Recorder<'a>>,
    /// States seen at the heads of long concrete loops, to find loops whose state never changes.
    pub(super) loop_heads: HashMap<(usize, usize, usize), EngineSnapshot>,
    pub(super) scratch: Vec<Diagnostic>,
    /// The macros of the library's definition files, read when the run starts.
    pub(super) library_macros: Option<Arc<LibraryMacros>>,
    /// The entry state from the call sites and whether first passes are recorded.
    pub(super) setup: RunSetup,
    /// The first passes of the analysed program's lines, when they are recorded.
    pub(super) first_passes: Option<FirstPasses>,
    /// The built-in models of the standard cycles (`cycles/`).
    pub(super) cycles: CycleState,
    /// Set when a block that moves asks for a rounding, chamfer or angle at its corner, for a
    /// counting run that must know whether the corner stage has anything to do.
    pub(super) corner_flag: Option<&'s std::cell::Cell<bool>>,
}

impl<'a, 's> Interpreter<'a, 's> {
    pub fn new(
        config: &'a MachineConfig,
        library: &'a dyn ProgramLibrary,
        options: &'a ExecutionOptions,
        sink: &'s mut dyn FnMut(ExecutedMove),
    ) -> Interpreter<'a, 's> {
        Interpreter {
            config,
            library,
            options,
            units: Vec::new(),
            unit_names: HashMap::new(),
            passes: Vec::new(),
            parser: LineParser::new(),
            block: Block::default(),
            sink,
            pass_totals: None,
            counting: false,
            findings: Vec::new(),
            reported: HashSet::new(),
            executed: 0,
            pending: Vec::new(),
            next_fork: 0,
            covered: HashSet::new(),
            assumed: Vec::new(),
            recorder: None,
            loop_heads: HashMap::new(),
            scratch: Vec::new(),
            library_macros: None,
            setup: RunSetup::default(),
            first_passes: None,
            cycles: CycleState::default(),
            corner_flag: None,
        }
    }

    pub(super) fn add_unit(&mut self, unit: ProgramUnit) -> usize {
        self.passes.push(vec![0; unit.line_count()]);
        self.units.push(Arc::new(unit));
        self.units.len() - 1
    }

    pub(super) fn engine_from(&self, snapshot: EngineSnapshot) -> Engine<'a> {
        let mut engine = Engine::from_snapshot(self.config, snapshot);
        engine.set_executing(true);
        engine
    }

    /// The pass number of the execution of `line` of `unit` just counted: 0 when the block runs once
    /// in the whole run.
    pub(super) fn pass_of(&self, unit: usize, line: usize) -> u32 {
        // A recorded run keeps every pass number: whether a block runs more than once is known only
        // at its end (`resume.rs` hides the pass of a block that ran once).
        if self.recorder.is_some() {
            return self.passes[unit][line];
        }
        let total = self
            .pass_totals
            .as_ref()
            .and_then(|totals| totals.get(unit)?.get(line).copied())
            .unwrap_or(1);
        if total <= 1 {
            0
        } else {
            self.passes[unit][line]
        }
    }

    /// Makes this run one that only counts how often each block runs.
    /// Sets `flag` when a block that moves asks for a rounding, chamfer or angle at its corner.
    pub fn watching_corners(mut self, flag: &'s std::cell::Cell<bool>) -> Self {
        self.corner_flag = Some(flag);
        self
    }

    pub fn counting_only(mut self) -> Self {
        self.counting = true;
        self
    }

    /// Runs with the entry state from the call sites, recording first passes when asked.
    pub fn with_setup(mut self, setup: RunSetup) -> Self {
        if setup.record_first_passes && !self.counting {
            self.first_passes = Some(FirstPasses::default());
        }
        self.setup = setup;
        self
    }

    /// How often line `pc` of the analysed program has run so far.
    pub(super) fn passes_so_far(&self, pc: usize) -> u32 {
        self.passes
            .first()
            .and_then(|lines| lines.get(pc).copied())
            .unwrap_or(0)
    }

    /// Gives this run the pass counts of an earlier counting run of the same program.
    pub fn with_pass_totals(mut self, totals: Vec<Vec<u32>>) -> Self {
        self.pass_totals = Some(totals);
        self
    }

    pub(super) fn finish(mut self) -> Execution {
        self.findings
            .sort_by_key(|item| (item.line, item.diagnostic.span.start()));
        Execution {
            findings: self.findings,
            assumed: self.assumed,
            executed_blocks: self.executed,
            pass_totals: self.passes,
            has_flow: self.units.first().is_some_and(|unit| unit.flow.has_flow),
            first_passes: self.first_passes.take().map(Box::new),
        }
    }

    /// Runs with macros already read (one execution reads them once for all its runs).
    pub fn with_library_macros(mut self, macros: Arc<LibraryMacros>) -> Self {
        self.library_macros = Some(macros);
        self
    }

    /// The macros of the library's definition files, read on first use.
    pub(super) fn library_macros(&mut self) -> Arc<LibraryMacros> {
        let (library, config) = (self.library, self.config);
        Arc::clone(
            self.library_macros
                .get_or_insert_with(|| Arc::new(LibraryMacros::read(library, config))),
        )
    }
}
