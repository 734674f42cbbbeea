//! Running a program the way the control runs it: loops for as many passes as the control makes,
//! jumps to labels and block numbers, `IF`/`CASE` decisions, subprogram calls with their parameters,
//! repetitions and returns. Every executed block goes through the [`Engine`](crate::analysis::Engine),
//! so each execution of a block has the modal state the control has there.
//!
//! Where a decision depends on what the program does not contain (main-run variables, machine data),
//! every way is followed and the ways are joined where they meet: what is equal on every way stays
//! known, what differs becomes unknown. A loop whose number of passes is not known is run until its
//! state no longer changes (each pass forgets what differs), so that only what its body changes
//! becomes unknown. A budget of executed blocks bounds the work; past it the rest of the program is
//! read in program order, as values that are uncertain.

mod assumptions;
mod calls;
mod control;
mod cycles;
pub mod entry;
pub mod first_pass;
mod interpreter;
mod jump_targets;
pub mod library_macros;
mod paths;
pub mod program;
mod recorded;
mod repeats;
mod resume;
mod tables;

use crate::analysis::library::ProgramLibrary;
use crate::analysis::{Move, ProgramKind};
use crate::config::MachineConfig;
use crate::diagnostics::LineDiagnostic;
use crate::syntax::ast::{AddressKind, AddressWord, ValueExpr};
use std::sync::Arc;

pub use crate::config::execution::{EntryState, ExecutionOptions};
pub use recorded::{resume_run, run_recorded, RecordedRun, RunStart};

/// Where a called program was called from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CallSite {
    /// The file of the calling program; `None` for the analysed program.
    pub path: Option<Arc<str>>,
    /// The 0-based line of the call in that file.
    pub line: usize,
}

/// One execution of a block that moves axes.
#[derive(Debug, Clone, PartialEq)]
pub struct ExecutedMove {
    /// The move; its `line` is the line in `path` (in the analysed program when `path` is `None`).
    pub movement: Move,
    /// The file of the called program that made the move; `None` for the analysed program.
    pub path: Option<Arc<str>>,
    /// The calls that led to the move, outermost first.
    pub stack: Arc<[CallSite]>,
    /// Which execution of its block this is (1, 2, ...), 0 when the block runs once only.
    pub pass: u32,
    /// The move lies on a way whose condition the analysis could not decide.
    pub conditional: bool,
    /// The axes whose value rests on the assumed entry state.
    pub assumed: Vec<Arc<str>>,
}

impl ExecutedMove {
    /// The line of the analysed program that caused the move: the outermost call, or its own line.
    pub fn outer_line(&self) -> usize {
        self.stack
            .first()
            .map_or(self.movement.line, |site| site.line)
    }
}

/// What running a program gave besides its moves.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Execution {
    /// Findings of the run, at lines of the analysed program (a finding inside a called program is
    /// reported at the call).
    pub findings: Vec<LineDiagnostic>,
    /// What was assumed about the entry state: (`"units"`, `"G71"`), (`"distance"`, `"G90"`), ...
    pub assumed: Vec<(&'static str, String)>,
    /// How many blocks were executed.
    pub executed_blocks: u64,
    /// Per program (the analysed one first, then the called ones in the order they were first
    /// called), per line: how often it was executed.
    pub pass_totals: Vec<Vec<u32>>,
    /// Whether the analysed program has labels, jumps, control structures or calls: without them it
    /// runs in program order, every block once.
    pub has_flow: bool,
    /// The first pass of each line of the analysed program, when the run was asked to record them
    /// ([`entry::RunSetup`]).
    pub first_passes: Option<Box<first_pass::FirstPasses>>,
}

impl Execution {
    /// How often line `line` of the analysed program was executed.
    pub fn passes_of_line(&self, line: usize) -> u32 {
        self.pass_totals
            .first()
            .and_then(|lines| lines.get(line).copied())
            .unwrap_or(0)
    }
}

/// How a block ends a program level, if it does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProgramEnd {
    /// `M17` or `RET`: the end of a subprogram.
    Return,
    /// `M2` or `M30`: the end of the main program.
    End,
}

/// Whether the address word `word` is M2, M30 or M17 (written as a constant).
pub fn ends_program(word: &AddressWord) -> Option<ProgramEnd> {
    if word.kind != AddressKind::MFunction || word.extension.is_some() {
        return None;
    }
    let value = match word.value.expr {
        ValueExpr::Constant { value, .. } => value,
        _ => return None,
    };
    if value == 17.0 {
        Some(ProgramEnd::Return)
    } else if value == 2.0 || value == 30.0 {
        Some(ProgramEnd::End)
    } else {
        None
    }
}

/// Runs the program `text` (of `kind`) on `config`, calling programs `library` finds, and hands every
/// executed move to `visit` in the order the control executes them. A program with loops, jumps or
/// calls is run twice: first only counting how often each block runs (so that each move can say
/// its pass), then for its moves; a program without them runs once.
pub fn execute(
    text: &str,
    config: &MachineConfig,
    kind: ProgramKind,
    library: &dyn ProgramLibrary,
    options: &ExecutionOptions,
    visit: &mut dyn FnMut(ExecutedMove),
) -> Execution {
    execute_with(
        text,
        config,
        kind,
        library,
        options,
        &entry::RunSetup::default(),
        visit,
    )
}

/// Runs a program like [`execute`], with the entry state from its call sites and the first passes
/// recorded as `setup` asks.
pub fn execute_with(
    text: &str,
    config: &MachineConfig,
    kind: ProgramKind,
    library: &dyn ProgramLibrary,
    options: &ExecutionOptions,
    setup: &entry::RunSetup,
    visit: &mut dyn FnMut(ExecutedMove),
) -> Execution {
    // The corner stage inserts roundings and chamfers between the moves (reference §14); moves of
    // programs without them pass straight through.
    let mut stage = crate::analysis::simulation::CornerStage::new(config, text);
    let mut execution = {
        let mut staged = |movement: ExecutedMove| stage.push(movement, visit);
        execute_programmed(text, config, kind, library, options, setup, &mut staged)
    };
    let findings = stage.finish(visit);
    add_stage_findings(&mut execution.findings, findings);
    execution
}

/// Adds the corner stage's findings to a run's, in the run's order (by line and column).
pub(crate) fn add_stage_findings(findings: &mut Vec<LineDiagnostic>, stage: Vec<LineDiagnostic>) {
    if stage.is_empty() {
        return;
    }
    findings.extend(stage);
    findings.sort_by_key(|item| (item.line, item.diagnostic.span.start()));
}

/// The run of [`execute_with`] without the corner stage: the moves of the blocks as they program
/// them, with sharp corners.
pub fn execute_programmed(
    text: &str,
    config: &MachineConfig,
    kind: ProgramKind,
    library: &dyn ProgramLibrary,
    options: &ExecutionOptions,
    setup: &entry::RunSetup,
    visit: &mut dyn FnMut(ExecutedMove),
) -> Execution {
    let macros = Arc::new(library_macros::LibraryMacros::read(library, config));
    let main = Arc::new(program::ProgramUnit::with_macro_names(
        String::new(),
        None,
        Arc::from(text),
        config,
        macros.names(),
    ));
    if !main.flow.has_flow {
        return interpreter::Interpreter::new(config, library, options, visit)
            .with_library_macros(macros)
            .with_setup(setup.clone())
            .run_unit(main, kind);
    }
    let mut ignore = |_: ExecutedMove| {};
    let counted = interpreter::Interpreter::new(config, library, options, &mut ignore)
        .with_library_macros(Arc::clone(&macros))
        .counting_only()
        .with_setup(setup.clone())
        .run_unit(Arc::clone(&main), kind);
    interpreter::Interpreter::new(config, library, options, visit)
        .with_library_macros(macros)
        .with_setup(setup.clone())
        .with_pass_totals(counted.pass_totals)
        .run_unit(main, kind)
}

/// What the run of `text` assumes about its entry state: for a subprogram analysed on its own with
/// [`EntryState::Reset`], the reset values of the groups that decide how its values read.
pub fn entry_assumptions(
    text: &str,
    config: &MachineConfig,
    kind: ProgramKind,
    options: &ExecutionOptions,
) -> Vec<(&'static str, String)> {
    let subprogram = kind == ProgramKind::Subprogram || crate::analysis::has_proc_header(text);
    if !subprogram || options.entry != EntryState::Reset {
        return Vec::new();
    }
    // The first entry says which state is assumed; the groups follow.
    std::iter::once(("source", RESET_SOURCE.to_string()))
        .chain(
            assumptions::reset_assumptions(config)
                .into_iter()
                .map(|(_, name, value)| (name, value)),
        )
        .collect()
}

/// How the preview and the hover name the assumed reset state (`"source"` of `"assumed"`).
pub const RESET_SOURCE: &str = "assumed: reset state";

/// The findings of running `text`, without building any move: what `check` adds to the findings of
/// reading the program block by block.
pub fn execution_findings(
    text: &str,
    config: &MachineConfig,
    kind: ProgramKind,
    library: &dyn ProgramLibrary,
    options: &ExecutionOptions,
) -> Vec<LineDiagnostic> {
    let mut ignore = |_: ExecutedMove| {};
    let corners = std::cell::Cell::new(false);
    let findings = interpreter::Interpreter::new(config, library, options, &mut ignore)
        .counting_only()
        .watching_corners(&corners)
        .run(Arc::from(text), kind)
        .findings;
    if !corners.get() {
        return findings;
    }
    // The corner stage needs the moves: the program is run again with them, which also gives the
    // run's own findings.
    execute(text, config, kind, library, options, &mut ignore).findings
}

/// Runs a program like [`execute`] and keeps its moves.
pub fn execute_collecting(
    text: &str,
    config: &MachineConfig,
    kind: ProgramKind,
    library: &dyn ProgramLibrary,
    options: &ExecutionOptions,
) -> (Execution, Vec<ExecutedMove>) {
    let mut moves = Vec::new();
    let execution = execute(text, config, kind, library, options, &mut |movement| {
        moves.push(movement)
    });
    (execution, moves)
}
