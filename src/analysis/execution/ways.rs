//! The interpreter's main loop: one way runs block by block; ways that wait run in program order and
//! are joined where they meet; a way forks at a condition the program does not determine; when the
//! track is lost the rest is read in program order.

use crate::analysis::engine::engine_state::Engine;
use crate::analysis::execution::assumptions::{reset_assumptions, ASSUMED_GROUPS};
use crate::analysis::execution::block_run::Next;
use crate::analysis::execution::interpreter::Interpreter;
use crate::analysis::execution::outcome::{CallSite, ExecutedMove, Execution};
use crate::analysis::execution::paths::{Activation, Control, UnknownLoop, Way, MAX_FORKS};
use crate::analysis::execution::program::ProgramUnit;
use crate::analysis::program_kind::ProgramKind;
use crate::config::execution::EntryState;
use crate::diagnostics::{Code, Span};
use std::sync::Arc;

/// Undecided conditions in one run after which the rest is read in program order: a program whose
/// every way depends on data the analysis does not have is not worth following further.
const MAX_DECISIONS: u32 = 20_000;

impl<'a, 's> Interpreter<'a, 's> {
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
        let stack: Arc<[CallSite]> = Arc::from(Vec::new());
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

    /// Starts a subprogram from the call sites' state: their G functions replace the assumed reset
    /// ones, and a group they do not agree on is unknown (the control has one of their values).
    pub(super) fn enter_from_callers(&mut self, control: &mut Control, engine: &mut Engine<'a>) {
        let Some(entry) = self.setup.entry.clone() else {
            return;
        };
        self.assumed.clear();
        self.assumed.push(("source", entry.describe()));
        control.assumed_groups = 0;
        for &(group, name) in ASSUMED_GROUPS.iter() {
            let code = entry.groups.iter().find(|code| code.group() == group);
            engine.state.groups[group as usize] = code.copied();
            if let Some(code) = code {
                self.assumed.push((name, code.name().to_string()));
                control.assumed_groups |= 1 << group;
            }
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
