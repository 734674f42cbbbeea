//! A whole program read in program order, in one pass over its blocks: its diagnostics (what `check`
//! and the language server need), and its moves when asked (what `preview` needs).

use crate::analysis::engine::engine_state::Engine;
use crate::analysis::engine::moves::Move;
use crate::analysis::execution::library_macros::LibraryMacros;
use crate::analysis::program_kind::{has_proc_header, ProgramKind};
use crate::config::MachineConfig;
use crate::diagnostics::LineDiagnostic;

/// Everything the analysis finds in a program.
#[derive(Debug, Clone, PartialEq)]
pub struct Analysis {
    pub moves: Vec<Move>,
    /// Syntax and semantic diagnostics, sorted by line and column, with the configured severities.
    pub diagnostics: Vec<LineDiagnostic>,
}

/// Parses and interprets a whole main program.
pub fn analyze(text: &str, config: &MachineConfig) -> Analysis {
    analyze_program(text, config, ProgramKind::Main)
}

/// Parses and interprets a whole program of the given kind, in one pass over its blocks.
pub fn analyze_program(text: &str, config: &MachineConfig, kind: ProgramKind) -> Analysis {
    let mut moves = Vec::new();
    let diagnostics = for_each_move(text, config, kind, |movement| moves.push(movement));
    Analysis { moves, diagnostics }
}

/// The diagnostics of a program, syntax and semantic, without building its moves: what `check` and the
/// language server need, at the cost of parsing and following the modal state only.
pub fn diagnose_program(
    text: &str,
    config: &MachineConfig,
    kind: ProgramKind,
) -> Vec<LineDiagnostic> {
    let mut engine = new_engine(text, config, kind);
    crate::syntax::visit_blocks(text, config, |_, line, block, findings| {
        engine.step(line, block, findings);
    })
}

/// Like [`diagnose_program`], with the macros of the library's definition files (`macros`): a block
/// that uses one is expanded instead of read as an unknown G function or call.
pub fn diagnose_program_with_macros(
    text: &str,
    config: &MachineConfig,
    kind: ProgramKind,
    macros: &LibraryMacros,
) -> Vec<LineDiagnostic> {
    let mut engine = new_engine(text, config, kind);
    engine.define_library_macros(&macros.definitions);
    let names: Vec<&str> = macros.names().collect();
    crate::syntax::visit_blocks_with_macros(text, config, &names, |_, line, block, findings| {
        engine.step(line, block, findings);
    })
}

/// Hands every move of a program to `visit`, in program order, and returns the diagnostics. The moves
/// are built one at a time and not kept, so a program of any length needs memory for one move only.
pub fn visit_moves(
    text: &str,
    config: &MachineConfig,
    kind: ProgramKind,
    mut visit: impl FnMut(&Move),
) -> Vec<LineDiagnostic> {
    for_each_move(text, config, kind, |movement| visit(&movement))
}

/// Like [`visit_moves`], also handing over the move of each dwell block (`G4`, see
/// [`Engine::describe_last_dwell`]), in program order: what the machining time of a program read in
/// program order needs.
pub fn visit_moves_and_dwells(
    text: &str,
    config: &MachineConfig,
    kind: ProgramKind,
    mut visit: impl FnMut(&Move),
) -> Vec<LineDiagnostic> {
    let mut engine = new_engine(text, config, kind);
    crate::syntax::visit_blocks(text, config, |line_index, line, block, findings| {
        if engine.step(line, block, findings) {
            visit(&engine.describe_last_move(line_index, line, block));
        } else if let Some(dwell) = engine.describe_last_dwell(line_index, line, block) {
            visit(&dwell);
        }
    })
}

/// Like [`visit_moves`], handing each move over by value, so that a caller that keeps them (as
/// [`analyze_program`] does) takes the move as built instead of a copy of it.
fn for_each_move(
    text: &str,
    config: &MachineConfig,
    kind: ProgramKind,
    mut visit: impl FnMut(Move),
) -> Vec<LineDiagnostic> {
    let mut engine = new_engine(text, config, kind);
    crate::syntax::visit_blocks(text, config, |line_index, line, block, findings| {
        if engine.step(line, block, findings) {
            visit(engine.describe_last_move(line_index, line, block));
        }
    })
}

/// An engine in the state a program of this kind starts with.
fn new_engine<'a>(text: &str, config: &'a MachineConfig, kind: ProgramKind) -> Engine<'a> {
    let mut engine = Engine::new(config);
    if kind == ProgramKind::Subprogram || has_proc_header(text) {
        // A subprogram starts with the caller's modal state and feed, unknown here.
        engine.assume_inherited_state();
    }
    engine
}
