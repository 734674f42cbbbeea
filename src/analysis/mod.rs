//! The analysis layer: the modal state of every block and the resolved end points of every move, with
//! semantic diagnostics. No IO and no protocol types: text and configuration in, plain values out.
//!
//! What is followed today: G groups, G90/G91 with `=AC`/`=IC`, inch/metric (G70/G71/G700/G710),
//! diameter programming (DIAMOF/DIAMON/DIAM90 and DAC/DIC/RAC/RIC), R parameters and DEF variables,
//! feed, circles (I/J/K, CR, AR, CIP, CT, TURN), polar coordinates, macros of the program, and for
//! machine coordinates the programmable frame, the configured settable offsets with `$P_UIFR` writes
//! and G53/G153/SUPA. What is not followed turns values into "unknown" (spatial rotations, basic and
//! system frames, calls of subprograms and cycles, transformations) or "uncertain" (everything after a
//! jump or control structure, because the engine evaluates in program order).

pub mod axis_lookup;
pub mod circle;
pub mod document;
pub mod engine;
pub mod eval;
pub mod execution;
pub mod four_decimals;
pub mod frame;
pub mod library;
pub mod machine;
pub mod offsets;
pub mod position_reads;
pub mod resolution;
pub mod simulation;
pub mod state;

pub use engine::{Engine, Move};

use crate::config::MachineConfig;
use crate::diagnostics::LineDiagnostic;

/// Everything the analysis finds in a program.
#[derive(Debug, Clone, PartialEq)]
pub struct Analysis {
    pub moves: Vec<Move>,
    /// Syntax and semantic diagnostics, sorted by line and column, with the configured severities.
    pub diagnostics: Vec<LineDiagnostic>,
}

/// Whether a program runs on its own (a main program, `.MPF`) or is called (a subprogram, `.SPF`): a
/// subprogram inherits the caller's modal state, feed included.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProgramKind {
    Main,
    Subprogram,
}

impl ProgramKind {
    /// The kind by file extension: only `mpf` is known to be a main program. Anything else (`spf`,
    /// contour files such as `drs`, text files) may be called with the caller's modal state, so it is
    /// treated as a subprogram: findings that need the reset state are not reported there.
    pub fn from_extension(extension: Option<&str>) -> ProgramKind {
        match extension {
            Some(extension) if extension.eq_ignore_ascii_case("mpf") => ProgramKind::Main,
            _ => ProgramKind::Subprogram,
        }
    }

    /// The kind by file name or path: the control's own names say it (`_N_PART1_MPF` is a main
    /// program, `_N_PART1_SPF` a subprogram, with or without an extension after them, as archives
    /// and transfers add one); any other name goes by its extension as in
    /// [`ProgramKind::from_extension`]. A path's folders are ignored, whether written with `/` or `\`.
    pub fn from_file_name(name: &str) -> ProgramKind {
        let base = name.rsplit(['/', '\\']).next().unwrap_or(name);
        let (stem, extension) = match base.rfind('.') {
            Some(dot) if dot > 0 => (&base[..dot], Some(&base[dot + 1..])),
            _ => (base, None),
        };
        // Compared as bytes: a name may hold any characters, and slicing a `str` inside one panics.
        let stem = stem.as_bytes();
        let is_control_name = |suffix: &[u8]| {
            stem.len() > 3 + suffix.len()
                && stem[..3].eq_ignore_ascii_case(b"_N_")
                && stem[stem.len() - suffix.len()..].eq_ignore_ascii_case(suffix)
        };
        if is_control_name(b"_MPF") {
            ProgramKind::Main
        } else if is_control_name(b"_SPF") {
            ProgramKind::Subprogram
        } else {
            ProgramKind::from_extension(extension)
        }
    }
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
    macros: &crate::analysis::execution::library_macros::LibraryMacros,
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

/// Whether a line of the program starts with `PROC`: such a program is a subprogram whatever its
/// file is called.
pub fn has_proc_header(text: &str) -> bool {
    crate::syntax::lines_containing(text, b"PROC").any(is_proc_header)
}

/// Whether a line starts with `PROC`, the header of a subprogram.
pub fn is_proc_header(line: &str) -> bool {
    line.trim_start()
        .get(..4)
        .is_some_and(|word| word.eq_ignore_ascii_case("PROC"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_kind_comes_from_the_control_s_file_names_and_from_extensions() {
        for (name, kind) in [
            ("_N_PART1_MPF", ProgramKind::Main),
            ("_n_part1_mpf", ProgramKind::Main),
            ("_N_PART1_SPF", ProgramKind::Subprogram),
            ("_N_PART1_MPF.txt", ProgramKind::Main),
            ("_N_PART1_MPF.SPF", ProgramKind::Main),
            ("_N_PART1_SPF.MPF", ProgramKind::Subprogram),
            ("/nc/_N_WKS_DIR/_N_A_WPD/_N_MAIN_MPF", ProgramKind::Main),
            ("C:\\nc\\_N_MAIN_MPF", ProgramKind::Main),
            ("PART1.MPF", ProgramKind::Main),
            ("part1.mpf", ProgramKind::Main),
            ("a/b/PART1.SPF", ProgramKind::Subprogram),
            ("CONTOUR.DRS", ProgramKind::Subprogram),
            ("MPF", ProgramKind::Subprogram),
            // The name between `_N_` and the type must not be empty.
            ("_N_MPF", ProgramKind::Subprogram),
            ("_N__MPF", ProgramKind::Subprogram),
            ("_N_X_MPF", ProgramKind::Main),
            ("_N_ÄÖ_MPF", ProgramKind::Main),
            ("ÄÖÜ", ProgramKind::Subprogram),
            ("PART1_MPF", ProgramKind::Subprogram),
            ("", ProgramKind::Subprogram),
        ] {
            assert_eq!(ProgramKind::from_file_name(name), kind, "{name}");
        }
    }
}
