//! Running a whole program: once for its moves, or first counting passes when it has loops, jumps
//! or calls; with the corner stage of the simulation, or without it; or only for its findings.

use crate::analysis::execution::assumptions::reset_assumptions;
use crate::analysis::execution::entry::RunSetup;
use crate::analysis::execution::interpreter::Interpreter;
use crate::analysis::execution::library_macros::LibraryMacros;
use crate::analysis::execution::outcome::{ExecutedMove, Execution};
use crate::analysis::execution::program::ProgramUnit;
use crate::analysis::library::ProgramLibrary;
use crate::analysis::program_kind::{has_proc_header, ProgramKind};
use crate::config::execution::{EntryState, ExecutionOptions};
use crate::config::MachineConfig;
use crate::diagnostics::LineDiagnostic;
use std::sync::Arc;

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
        &RunSetup::default(),
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
    setup: &RunSetup,
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
    setup: &RunSetup,
    visit: &mut dyn FnMut(ExecutedMove),
) -> Execution {
    let macros = Arc::new(LibraryMacros::read(library, config));
    let main = Arc::new(ProgramUnit::with_macro_names(
        String::new(),
        None,
        Arc::from(text),
        config,
        macros.names(),
    ));
    if !main.flow.has_flow {
        return Interpreter::new(config, library, options, visit)
            .with_library_macros(macros)
            .with_setup(setup.clone())
            .run_unit(main, kind);
    }
    let mut ignore = |_: ExecutedMove| {};
    let counted = Interpreter::new(config, library, options, &mut ignore)
        .with_library_macros(Arc::clone(&macros))
        .counting_only()
        .with_setup(setup.clone())
        .run_unit(Arc::clone(&main), kind);
    Interpreter::new(config, library, options, visit)
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
    let subprogram = kind == ProgramKind::Subprogram || has_proc_header(text);
    if !subprogram || options.entry != EntryState::Reset {
        return Vec::new();
    }
    // The first entry says which state is assumed; the groups follow.
    std::iter::once(("source", RESET_SOURCE.to_string()))
        .chain(
            reset_assumptions(config)
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
    let findings = Interpreter::new(config, library, options, &mut ignore)
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
