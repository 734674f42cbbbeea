//! The interpreter's main loop: one way runs block by block; ways that wait run in program order and
//! are joined where they meet. The decisions of single statements are in `control.rs`, calls and
//! returns in `calls.rs`.

use crate::analysis::engine::{Engine, EngineSnapshot};
use crate::analysis::execution::assumptions::reset_assumptions;
use crate::analysis::execution::cycles::CycleState;
use crate::analysis::execution::entry::RunSetup;
use crate::analysis::execution::first_pass::FirstPasses;
use crate::analysis::execution::library_macros::LibraryMacros;
use crate::analysis::execution::paths::{Activation, Control, UnknownLoop, Way, MAX_FORKS};
use crate::analysis::execution::program::ProgramUnit;
use crate::analysis::execution::resume::Recorder;
use crate::analysis::execution::tables::table_mark;
use crate::analysis::execution::{
    EntryState, ExecutedMove, Execution, ExecutionOptions, ProgramEnd,
};
use crate::analysis::library::ProgramLibrary;
use crate::analysis::ProgramKind;
use crate::config::MachineConfig;
use crate::diagnostics::{Code, Diagnostic, LineDiagnostic, Span};
use crate::syntax::ast::Block;
use crate::syntax::LineParser;
use std::collections::{HashMap, HashSet};
use std::sync::Arc;

/// Undecided conditions in one run after which the rest is read in program order: a program whose
/// every way depends on data the analysis does not have is not worth following further.
const MAX_DECISIONS: u32 = 20_000;

/// Where a way goes after a block.
pub(super) enum Next {
    /// The next line of the same level (a transfer within the level is made by the statement).
    Line(usize),
    /// The way has been moved already (a call or a return).
    Moved,
    /// The way ends here (program end, an endless loop, an alarm).
    Stop,
    /// The rest of the program is read in program order from here.
    LoseTrack,
}

pub struct Interpreter<'a, 's> {
    pub(super) config: &'a MachineConfig,
    pub(super) library: &'a dyn ProgramLibrary,
    pub(super) options: &'a ExecutionOptions,
    pub(super) units: Vec<Arc<ProgramUnit>>,
    /// Lookups of programs by name, misses included.
    pub(super) unit_names: HashMap<String, Option<usize>>,
    /// Per program, per line: how often the line was executed.
    pub(super) passes: Vec<Vec<u32>>,
    parser: LineParser,
    block: Block,
    /// Where the moves go, in the order the control executes them.
    sink: &'s mut dyn FnMut(ExecutedMove),
    /// How often each line of each program runs in the whole run (from a first run that only
    /// counts), so that a move says its pass only when its block runs more than once; `None`: every
    /// block runs once (a program without any flow).
    pass_totals: Option<Vec<Vec<u32>>>,
    /// The run only counts passes: no move is built.
    pub(super) counting: bool,
    pub(super) findings: Vec<LineDiagnostic>,
    pub(super) reported: HashSet<(usize, Code)>,
    pub(super) executed: u64,
    /// The ways that wait, in no particular order.
    pending: Vec<Way>,
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
    scratch: Vec<Diagnostic>,
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
    corner_flag: Option<&'s std::cell::Cell<bool>>,
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

    /// Runs the program `text` from its first block to its end.
    pub fn run(mut self, text: Arc<str>, kind: ProgramKind) -> Execution {
        let macros = self.library_macros();
        let main = Arc::new(ProgramUnit::with_macro_names(
            String::new(),
            None,
            text,
            self.config,
            macros.names(),
        ));
        self.run_unit(main, kind)
    }

    /// Runs the program `main` (read once, shared by the runs of one execution).
    pub fn run_unit(mut self, main: Arc<ProgramUnit>, kind: ProgramKind) -> Execution {
        let start = self.start(main, kind);
        self.run_from(start);
        self.finish()
    }

    /// Makes `main` the analysed program and gives the way at its first block, with the assumed
    /// entry state of a subprogram.
    pub(super) fn start(
        &mut self,
        main: Arc<ProgramUnit>,
        kind: ProgramKind,
    ) -> (Control, Engine<'a>) {
        let subprogram = kind == ProgramKind::Subprogram || main.has_proc_header();
        self.passes.push(vec![0; main.line_count()]);
        self.units.push(main);
        let mut engine = Engine::new(self.config);
        engine.set_executing(true);
        engine.define_library_macros(&self.library_macros().definitions);
        let mut control = Control {
            levels: vec![Activation::main(0)],
            forks: Vec::new(),
            unknown_loops: Vec::new(),
            assumed_groups: 0,
            assumed_axes: 0,
        };
        if subprogram {
            match self.options.entry {
                EntryState::Reset => {
                    engine.assume_reset_entry();
                    for (group, name, value) in reset_assumptions(self.config) {
                        self.assumed.push((name, value));
                        control.assumed_groups |= 1 << group;
                    }
                }
                EntryState::Unknown => engine.assume_inherited_state(),
            }
            self.enter_from_callers(&mut control, &mut engine);
        }
        (control, engine)
    }

    /// Runs the way `start` and every way it forks until all have ended, the track is lost, or a
    /// resumed run rejoins its earlier run.
    pub(super) fn run_from(&mut self, start: (Control, Engine<'a>)) -> RunEnd {
        let mut current = Some(start);
        loop {
            let (mut control, mut engine) = match current.take() {
                Some(way) => way,
                None => match self.take_first_pending() {
                    Some(way) => {
                        let engine = self.engine_from(way.engine);
                        (way.control, engine)
                    }
                    None => return RunEnd::Finished,
                },
            };
            match self.run_way(&mut control, &mut engine) {
                WayEnd::Stopped => {}
                WayEnd::LostTrack => {
                    self.read_rest_in_order(&control, engine);
                    self.pending.clear();
                    return RunEnd::LostTrack;
                }
                WayEnd::Rejoined(checkpoint) => return RunEnd::Rejoined(checkpoint),
            }
        }
    }

    fn take_first_pending(&mut self) -> Option<Way> {
        let first = (0..self.pending.len())
            .min_by(|&a, &b| self.pending[a].control.order(&self.pending[b].control))?;
        Some(self.pending.swap_remove(first))
    }

    /// Runs one way until it ends; switches to a waiting way that comes first and joins the ways
    /// that meet on the way.
    fn run_way(&mut self, control: &mut Control, engine: &mut Engine<'a>) -> WayEnd {
        loop {
            if !self.pending.is_empty() {
                self.meet_waiting_ways(control, engine);
            }
            if self.executed >= self.options.max_blocks {
                let line = self.outer_line(control);
                self.report_at(
                    line,
                    Code::ExecutionBudgetUsed,
                    Span::default(),
                    format!(
                        "{} blocks were executed, the configured budget (`max_blocks`): from here on the program is read in program order and its values are uncertain",
                        self.executed
                    ),
                );
                return WayEnd::LostTrack;
            }
            if self.next_fork >= MAX_DECISIONS {
                let line = self.outer_line(control);
                self.report_at(
                    line,
                    Code::FlowNotFollowed,
                    Span::default(),
                    format!(
                        "{MAX_DECISIONS} conditions that the program does not determine were met: from here on the program is read in program order and its values are uncertain"
                    ),
                );
                return WayEnd::LostTrack;
            }
            if self.recorder.is_some() && self.pending.is_empty() && control.is_simple() {
                if let Some(checkpoint) = self.at_simple_point(control, engine) {
                    return WayEnd::Rejoined(checkpoint);
                }
            }
            match self.step(control, engine) {
                Next::Line(line) => control.level_mut().pc = line,
                Next::Moved => {}
                Next::Stop => return WayEnd::Stopped,
                Next::LoseTrack => return WayEnd::LostTrack,
            }
            control.leave_loops();
        }
    }

    /// Joins the waiting ways that are where `control` is, and switches to one that comes first.
    fn meet_waiting_ways(&mut self, control: &mut Control, engine: &mut Engine<'a>) {
        let mut index = 0;
        while index < self.pending.len() {
            if self.pending[index].control.meets(control) {
                let way = self.pending.swap_remove(index);
                let mut snapshot = engine.snapshot();
                snapshot.join(&way.engine);
                *engine = self.engine_from(snapshot);
                control.join(&way.control);
            } else {
                index += 1;
            }
        }
        let first = (0..self.pending.len())
            .min_by(|&a, &b| self.pending[a].control.order(&self.pending[b].control));
        if let Some(first) = first {
            if self.pending[first].control.order(control) == std::cmp::Ordering::Less {
                let way = self.pending.swap_remove(first);
                let waiting = Way {
                    control: std::mem::replace(control, way.control),
                    engine: engine.snapshot(),
                };
                *engine = self.engine_from(way.engine);
                self.pending.push(waiting);
            }
        }
    }

    /// Lets a second way wait at `line` of the current level: the way the program takes when the
    /// undecided condition goes the other way. Both ways depend on the decision from now on.
    pub(super) fn fork(&mut self, control: &mut Control, engine: &Engine<'a>, line: usize) {
        let decision = self.next_fork;
        self.next_fork += 1;
        let mut other = control.clone();
        // A way that depends on many decisions is conditional already: the list keeps the newest,
        // which the loops' pass marks compare with.
        if control.forks.len() >= MAX_FORKS {
            control.forks.remove(0);
            other.forks.remove(0);
        }
        other.forks.push((decision, false));
        control.forks.push((decision, true));
        other.level_mut().pc = line;
        // Loops the other way leaves are loops whose passes are not known on this way.
        let depth = control.levels.len() - 1;
        let leaving: Vec<(usize, usize)> = control
            .level()
            .loops
            .iter()
            .filter(|frame| !(frame.head..=frame.end).contains(&line))
            .map(|frame| (frame.back_to, frame.end))
            .collect();
        for (head, end) in leaving {
            mark_unknown_loop(control, depth, head, end);
        }
        let level = other.level_mut();
        while level
            .loops
            .last()
            .is_some_and(|frame| !(frame.head..=frame.end).contains(&line))
        {
            level.loops.pop();
        }
        other.leave_loops();
        let way = Way {
            control: other,
            engine: engine.snapshot(),
        };
        if let Some(waiting) = self
            .pending
            .iter_mut()
            .find(|waiting| waiting.control.meets(&way.control))
        {
            waiting.engine.join(&way.engine);
            waiting.control.join(&way.control);
        } else {
            self.pending.push(way);
        }
    }

    /// Runs the block at the current line of `control`'s innermost level.
    fn step(&mut self, control: &mut Control, engine: &mut Engine<'a>) -> Next {
        let unit_index = control.level().unit;
        let unit = Arc::clone(&self.units[unit_index]);
        let pc = control.level().pc;
        if pc >= unit.line_count() {
            // A program that ends without M17/RET/M30 ends at its last block.
            return self.end_level(control, engine, ProgramEnd::Return);
        }
        let mut block = std::mem::take(&mut self.block);
        unit.parse(&mut self.parser, pc, &mut block);
        if let Some(recorder) = self.recorder.as_mut() {
            recorder.executing(
                unit_index,
                pc,
                unit.line_count(),
                self.executed,
                self.passes[unit_index][pc],
            );
        }
        self.executed += 1;
        self.passes[unit_index][pc] += 1;
        let line = unit.line(pc);
        if block.label.is_some() {
            let mark = self.next_fork;
            let marks = &mut control.level_mut().label_marks;
            // Sorted by line (see `transfer`).
            match marks.binary_search_by_key(&pc, |&(labelled, _)| labelled) {
                Ok(index) => marks[index].1 = mark,
                Err(index) => marks.insert(index, (pc, mark)),
            }
        }
        self.first_pass_before(control, engine, unit_index);
        let retest = control.level().retest_for == Some(pc);
        let next = if retest {
            control.level_mut().retest_for = None;
            self.control_statements(control, engine, &unit, pc, &block, true)
        } else {
            let call = self.prepare_call(control, engine, &unit, pc, &block);
            let builtin = match call {
                None => self.builtin_call(control, engine, &block, line),
                Some(_) => None,
            };
            if call.is_some() || builtin.is_some() {
                engine.follow_call_of_next_block();
            }
            let table = table_mark(&block, line);
            if let Some(mark) = table {
                self.table_start(control, engine, mark);
            }
            self.scratch.clear();
            let moved = engine.step(line, &block, &mut self.scratch)
                && control.level().curve_table.is_none();
            if let Some(flag) = self.corner_flag.filter(|_| moved) {
                flag.set(flag.get() || engine.has_contour_request());
            }
            self.update_assumptions(control, engine, line, &block);
            if moved && !self.counting && !control.widening() {
                self.record_move(control, engine, unit_index, pc, line, &block);
            } else if self.options.dwell_moves
                && !self.counting
                && !control.widening()
                && control.level().curve_table.is_none()
            {
                self.record_dwell(control, engine, unit_index, pc, line, &block);
            }
            if let Some(mark) = table {
                self.table_end(control, engine, mark);
            }
            if let Some(builtin) = builtin {
                self.run_builtin(control, engine, pc, line, &block, builtin);
            }
            let modal = self.modal_call_after(control, engine, &block, pc, moved);
            let callee = call.as_ref().or(modal.as_ref()).map(|call| call.unit());
            self.first_pass_after(control, engine, unit_index, pc, callee);
            match (call, modal) {
                (Some(call), _) | (None, Some(call)) => {
                    control.level_mut().pc = pc + 1;
                    self.enter(control, engine, call)
                }
                (None, None) => self.control_statements(control, engine, &unit, pc, &block, false),
            }
        };
        self.block = block;
        match next {
            Next::Line(next) if next == pc + 1 => Next::Line(self.after_section_line(control, pc)),
            other => other,
        }
    }

    /// Hands out the dwell of a `G4` block as a move of no axis, when the run is asked for them.
    pub(super) fn record_dwell(
        &mut self,
        control: &Control,
        engine: &Engine<'a>,
        unit_index: usize,
        pc: usize,
        line: &str,
        block: &Block,
    ) {
        if let Some(dwell) = engine.describe_last_dwell(pc, line, block) {
            self.hand_out(control, unit_index, pc, dwell);
        }
    }

    pub(super) fn record_move(
        &mut self,
        control: &Control,
        engine: &Engine<'a>,
        unit_index: usize,
        pc: usize,
        line: &str,
        block: &Block,
    ) {
        let movement = engine.describe_last_move(pc, line, block);
        self.hand_out(control, unit_index, pc, movement);
    }

    /// Hands a move of the current way to the sink, named after the cycle whose model makes it.
    fn hand_out(
        &mut self,
        control: &Control,
        unit_index: usize,
        pc: usize,
        mut movement: crate::analysis::Move,
    ) {
        movement.cycle = self.cycles.current.clone();
        let assumed = if control.assumed_axes == 0 {
            Vec::new()
        } else {
            let names = &self.config.axes;
            movement
                .end
                .iter()
                .filter(|(name, _)| {
                    names
                        .iter()
                        .position(|axis| axis.name.as_str() == name.as_ref())
                        .is_some_and(|index| index < 64 && control.assumed_axes & 1 << index != 0)
                })
                .map(|(name, _)| name.clone())
                .collect()
        };
        let level = control.level();
        let pass = self.pass_of(unit_index, pc);
        (self.sink)(ExecutedMove {
            movement,
            path: self.units[unit_index].path.clone(),
            stack: Arc::clone(&level.stack),
            pass,
            conditional: { control.open_decisions(&self.covered).next().is_some() },
            assumed,
        });
        if let Some(recorder) = self.recorder.as_mut() {
            recorder.emitted += 1;
        }
    }

    /// The line of the analysed program where the way is: its own line, or the outermost call.
    pub(super) fn outer_line(&self, control: &Control) -> usize {
        control.levels[0]
            .pc
            .min(self.units[0].line_count().saturating_sub(1))
    }

    /// A finding at `line` of `unit` on the current way: at that line in the analysed program, else
    /// at the outermost call, naming the program and line where it happened.
    pub(super) fn report(
        &mut self,
        control: &Control,
        pc: usize,
        code: Code,
        span: Span,
        message: String,
    ) {
        if control.levels.len() == 1 {
            self.report_at(pc, code, span, message);
            return;
        }
        let level = control.level();
        let call_line = level.stack.first().map_or(pc, |site| site.line);
        let name = &self.units[level.unit].name;
        let message = format!("in {name} (line {}): {message}", pc + 1);
        let length = self.units[0].line(call_line).len();
        self.report_at(call_line, code, Span::new(0, length), message);
    }

    pub(super) fn report_at(&mut self, line: usize, code: Code, span: Span, message: String) {
        if !self.reported.insert((line, code)) {
            return;
        }
        let span = if span.is_empty() {
            Span::new(0, self.units[0].line(line).len())
        } else {
            span
        };
        let mut diagnostic = Diagnostic::new(code, span, message);
        diagnostic.severity = self.config.severity_of(code);
        self.findings.push(LineDiagnostic { line, diagnostic });
    }

    /// Reads the rest of the analysed program in program order, after the way was lost: values that
    /// depend on the program's flow are uncertain from here on.
    fn read_rest_in_order(&mut self, control: &Control, mut engine: Engine<'a>) {
        engine.set_executing(false);
        engine.mark_flow_uncertain();
        if control.levels.len() > 1 {
            engine.forget_after_unknown_call();
        }
        let unit = Arc::clone(&self.units[0]);
        // The main level's counter is the next line to run: the line it was at has run (or, when the
        // budget ran out, has not started yet).
        let start = control.levels[0].pc;
        let mut block = std::mem::take(&mut self.block);
        let stack: Arc<[crate::analysis::execution::CallSite]> = Arc::from(Vec::new());
        for pc in start..unit.line_count() {
            unit.parse(&mut self.parser, pc, &mut block);
            self.passes[0][pc] += 1;
            self.scratch.clear();
            let line = unit.line(pc);
            let moved = engine.step(line, &block, &mut self.scratch);
            if let Some(flag) = self.corner_flag.filter(|_| moved) {
                flag.set(flag.get() || engine.has_contour_request());
            }
            let dwell = (!moved && self.options.dwell_moves)
                .then(|| engine.describe_last_dwell(pc, line, &block))
                .flatten();
            if (moved || dwell.is_some()) && !self.counting {
                let pass = self.pass_of(0, pc);
                (self.sink)(ExecutedMove {
                    movement: dwell.unwrap_or_else(|| engine.describe_last_move(pc, line, &block)),
                    path: None,
                    stack: Arc::clone(&stack),
                    pass,
                    conditional: false,
                    assumed: Vec::new(),
                });
                if let Some(recorder) = self.recorder.as_mut() {
                    recorder.emitted += 1;
                }
            }
        }
        self.block = block;
    }

    /// The pass number of the execution of `line` of `unit` just counted: 0 when the block runs once
    /// in the whole run.
    fn pass_of(&self, unit: usize, line: usize) -> u32 {
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
}

enum WayEnd {
    Stopped,
    LostTrack,
    /// A resumed run reached the state of its earlier run at that run's checkpoint (its index).
    Rejoined(usize),
}

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum RunEnd {
    Finished,
    /// The rest of the program was read in program order (a budget ran out).
    LostTrack,
    /// A resumed run reached the state of its earlier run at that run's checkpoint (its index): the
    /// rest is the earlier run's.
    Rejoined(usize),
}

/// Marks the loop `head..=end` of level `depth` as one whose number of passes is not known.
pub(super) fn mark_unknown_loop(control: &mut Control, depth: usize, head: usize, end: usize) {
    if !control
        .unknown_loops
        .iter()
        .any(|unknown| unknown.depth == depth && unknown.head == head)
    {
        control.unknown_loops.push(UnknownLoop {
            depth,
            head,
            end,
            state: None,
        });
    }
}
