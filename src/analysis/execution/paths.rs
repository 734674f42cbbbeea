//! The ways through a program the interpreter follows: where each way is (a program counter per
//! program level), the loops it is in, and the decisions it depends on. Ways wait in program order
//! and are joined when they reach the same place.

use crate::analysis::engine::snapshot::EngineSnapshot;
use crate::analysis::eval::Locals;
use crate::analysis::execution::outcome::CallSite;
use crate::analysis::frame::Frame;
use crate::analysis::state::GROUP_COUNT;
use crate::syntax::gcodes::GCode;
use std::collections::HashSet;
use std::sync::Arc;

/// The decisions a way remembers, both ways of a joined decision included (it is conditional as long
/// as it remembers one that only one of its ways took).
pub const MAX_FORKS: usize = 128;

/// A loop of a control structure that a way is in.
#[derive(Debug, Clone, PartialEq)]
pub struct LoopFrame {
    /// The line of the opener (`WHILE`, `FOR`, `REPEAT`, `LOOP`) and of its closer.
    pub head: usize,
    pub end: usize,
    /// Where the closer sends the next pass: the opener for WHILE and FOR (which test again), the
    /// line after it for REPEAT and LOOP.
    pub back_to: usize,
    /// Passes started so far.
    pub passes: u32,
    /// The number of the first undecided condition met in the current pass: a way that still
    /// depends on one of them at the next pass has a number of passes that is not known.
    pub fork_mark: u32,
}

/// A section repetition in progress (`REPEAT LAB1 [LAB2] P=n`, `REPEATB LAB1 P=n`): the lines it
/// repeats, the repetitions still to start after the current one, and where the program goes on.
#[derive(Debug, Clone, PartialEq)]
pub struct RepeatFrame {
    pub start: usize,
    pub end: usize,
    pub remaining: u32,
    pub return_to: usize,
}

/// What a `SAVE` subprogram restores on its return (reference §8.3).
#[derive(Debug, Clone, PartialEq)]
pub struct SavedModal {
    pub groups: [Option<GCode>; GROUP_COUNT],
    pub frame: Option<Frame>,
}

/// A call in progress: what the return needs.
#[derive(Debug, Clone, PartialEq)]
pub struct CallFrame {
    /// Passes of the subprogram still to run after this one (`P`).
    pub repetitions_left: u32,
    pub saved: Option<SavedModal>,
    /// The caller's own variables, put aside while the subprogram runs.
    pub caller_locals: Locals,
    /// By-reference parameters: the subprogram's name and the caller's variable (upper case; an R
    /// parameter as `R<n>`).
    pub references: Vec<(String, String)>,
}

/// One program level of a way.
#[derive(Debug, Clone, PartialEq)]
pub struct Activation {
    /// The program it runs (index into the interpreter's programs).
    pub unit: usize,
    /// The line to run next.
    pub pc: usize,
    pub loops: Vec<LoopFrame>,
    /// The call that started this level; `None` for the main level.
    pub call: Option<Box<CallFrame>>,
    /// The next arrival at this FOR line comes from its ENDFOR: the counter is counted up and tested,
    /// the start value is not assigned again.
    pub retest_for: Option<usize>,
    /// The modal call (`MCALL NAME(..)`) active on this level.
    pub modal_call: Option<ModalCall>,
    /// Backward jumps taken to each target line (for the pass limit of loops made of jumps), sorted
    /// by line.
    pub jump_passes: Vec<(usize, u32)>,
    /// Per labelled line, the number of the next undecided condition when the way last ran it: the
    /// start of a pass of a loop made of a backward jump to that label. Sorted by line.
    pub label_marks: Vec<(usize, u32)>,
    /// Section repetitions in progress, the innermost last.
    pub repeats: Vec<RepeatFrame>,
    /// The calls that led here, outermost first (shared by every move of the level).
    pub stack: Arc<[CallSite]>,
    /// Inside a curve table definition (`CTABDEF` … `CTABEND`): the state before it, which its end
    /// restores. Its blocks move no axis.
    pub curve_table: Option<Box<EngineSnapshot>>,
}

impl Activation {
    pub fn main(unit: usize) -> Activation {
        Activation {
            unit,
            pc: 0,
            loops: Vec::new(),
            call: None,
            retest_for: None,
            modal_call: None,
            jump_passes: Vec::new(),
            label_marks: Vec::new(),
            repeats: Vec::new(),
            stack: Arc::from(Vec::new()),
            curve_table: None,
        }
    }
}

/// An argument of a call: left out (`SUB(1,,3)`, or missing at the end), or given (its value, `None`
/// when unknown).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Argument {
    Omitted,
    Given(Option<f64>),
}

/// A modal call: the program and the arguments, evaluated when `MCALL` was programmed.
#[derive(Debug, Clone, PartialEq)]
pub struct ModalCall {
    pub name: String,
    pub arguments: Vec<Argument>,
}

/// A loop whose number of passes is not known, on one level: its lines, and the state at its head
/// joined over the passes seen so far.
#[derive(Debug, Clone, PartialEq)]
pub struct UnknownLoop {
    pub depth: usize,
    pub head: usize,
    pub end: usize,
    pub state: Option<EngineSnapshot>,
}

/// Everything about a way except the engine's state.
#[derive(Debug, Clone, PartialEq)]
pub struct Control {
    pub levels: Vec<Activation>,
    /// The undecided conditions this way took, ordered: (decision, which way). A decision taken both
    /// ways is one of joined ways, which no longer depends on it.
    pub forks: Vec<(u32, bool)>,
    pub unknown_loops: Vec<UnknownLoop>,
    /// The G groups (bits by group number) whose value is still the assumed entry state.
    pub assumed_groups: u64,
    /// The axes (bits by configured index) whose value rests on the assumed entry state.
    pub assumed_axes: u64,
}

impl Control {
    pub fn level(&self) -> &Activation {
        self.levels
            .last()
            .expect("a way has at least its main level")
    }

    pub fn level_mut(&mut self) -> &mut Activation {
        self.levels
            .last_mut()
            .expect("a way has at least its main level")
    }

    /// Whether the way is on the main level, depends on no undecided condition and is in no loop
    /// of unknown passes: a state from which a run can be resumed (`resume.rs`).
    pub fn is_simple(&self) -> bool {
        self.levels.len() == 1 && self.forks.is_empty() && self.unknown_loops.is_empty()
    }

    /// Forgets the undecided-condition numbers kept at labels and loops of a simple way. They only
    /// tell whether a later condition was met during a pass, and every later condition has a higher
    /// number than all of them, so forgetting them changes no decision; it keeps the states that a
    /// resumed run compares small and equal.
    pub fn forget_condition_marks(&mut self) {
        for level in &mut self.levels {
            level.label_marks.clear();
            for frame in &mut level.loops {
                frame.fork_mark = 0;
            }
        }
    }

    /// Whether the way lies inside a loop whose passes are not known, where moves are not shown
    /// again (its first pass was shown).
    pub fn widening(&self) -> bool {
        let depth = self.levels.len() - 1;
        let pc = self.level().pc;
        self.unknown_loops.iter().any(|unknown| {
            unknown.state.is_some()
                && (unknown.depth < depth || (unknown.head..=unknown.end).contains(&pc))
        })
    }

    /// The undecided conditions the way depends on: those of its decisions whose other way has not
    /// joined it and does not go on as an earlier pass of a loop (`covered`). The list is in the
    /// order of the decisions.
    pub fn open_decisions<'c>(
        &'c self,
        covered: &'c HashSet<(u32, bool)>,
    ) -> impl Iterator<Item = u32> + 'c {
        self.forks
            .iter()
            .filter(|&&(decision, way)| {
                self.forks.binary_search(&(decision, !way)).is_err()
                    && !covered.contains(&(decision, !way))
            })
            .map(|(decision, _)| *decision)
    }

    /// Drops the unknown loops that the way has left.
    pub fn leave_loops(&mut self) {
        let depth = self.levels.len() - 1;
        let pc = self.level().pc;
        self.unknown_loops.retain(|unknown| {
            unknown.depth < depth
                || (unknown.depth == depth && (unknown.head..=unknown.end).contains(&pc))
        });
    }

    /// Which of two ways comes first in the program: the one whose program counters are smaller,
    /// level by level from the main level down; a way still inside a call comes before a way at the
    /// line the call returns to.
    pub fn order(&self, other: &Control) -> std::cmp::Ordering {
        for (mine, theirs) in self.levels.iter().zip(&other.levels) {
            let order = (mine.pc, mine.unit).cmp(&(theirs.pc, theirs.unit));
            if order != std::cmp::Ordering::Equal {
                return order;
            }
        }
        other.levels.len().cmp(&self.levels.len())
    }

    /// Whether two ways can continue as one: the same place, in the same loops and calls.
    pub fn meets(&self, other: &Control) -> bool {
        self.levels.len() == other.levels.len()
            && self.levels.iter().zip(&other.levels).all(|(mine, theirs)| {
                mine.unit == theirs.unit
                    && mine.pc == theirs.pc
                    && mine.loops == theirs.loops
                    && mine.retest_for == theirs.retest_for
                    && mine.modal_call == theirs.modal_call
                    && mine.repeats == theirs.repeats
                    && mine.curve_table.is_some() == theirs.curve_table.is_some()
                    && mine
                        .loops
                        .iter()
                        .map(|frame| frame.passes)
                        .eq(theirs.loops.iter().map(|frame| frame.passes))
                    && mine.call.as_ref().map(|call| call.repetitions_left)
                        == theirs.call.as_ref().map(|call| call.repetitions_left)
            })
    }

    /// Joins what the two ways know about their decisions: a decision the two ways took differently
    /// is no longer one the joined way depends on (both ways stay in the list, so that a way joined
    /// later that took one of them does not make it one again). A decision only one of them depends
    /// on stays: the joined way is reached on that way only when the decision goes its way (a way
    /// that jumped at one undecided condition meeting a way that jumped at another is still
    /// conditional, and still depends on conditions met in the current pass of a loop).
    pub fn join(&mut self, other: &Control) {
        let mut forks: Vec<(u32, bool)> = self.forks.iter().chain(&other.forks).copied().collect();
        forks.sort_unstable();
        forks.dedup();
        // The list keeps the newest decisions, which the loops' pass marks compare with.
        let excess = forks.len().saturating_sub(MAX_FORKS);
        forks.drain(..excess);
        self.forks = forks;
        self.assumed_groups |= other.assumed_groups;
        self.assumed_axes |= other.assumed_axes;
        for unknown in &other.unknown_loops {
            if !self.unknown_loops.iter().any(|mine| {
                mine.depth == unknown.depth && mine.head == unknown.head && mine.end == unknown.end
            }) {
                self.unknown_loops.push(unknown.clone());
            }
        }
        for (mine, theirs) in self.levels.iter_mut().zip(&other.levels) {
            if let (Some(table), Some(other_table)) = (&mut mine.curve_table, &theirs.curve_table) {
                table.join(other_table);
            }
            if let (Some(mine), Some(theirs)) = (mine.call.as_mut(), theirs.call.as_ref()) {
                mine.caller_locals.join(&theirs.caller_locals);
                if let (Some(saved), Some(other_saved)) = (mine.saved.as_mut(), &theirs.saved) {
                    for (group, other_group) in saved.groups.iter_mut().zip(&other_saved.groups) {
                        if group != other_group {
                            *group = None;
                        }
                    }
                    if saved.frame != other_saved.frame {
                        saved.frame = None;
                    }
                }
            }
        }
    }
}

/// A way waiting to run: its control and its engine state.
#[derive(Debug, Clone)]
pub struct Way {
    pub control: Control,
    pub engine: EngineSnapshot,
}
