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
//!
//! This file only declares the layer's modules and re-exports what the rest of the crate uses; the
//! files of the layer import each other by their own paths, never through this file.

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
pub mod program_kind;
pub mod resolution;
pub mod simulation;
pub mod state;
pub mod whole_program;

pub use engine::{Engine, Move};
pub use program_kind::{has_proc_header, is_proc_header, ProgramKind};
pub use whole_program::{
    analyze, analyze_program, diagnose_program, diagnose_program_with_macros, visit_moves,
    visit_moves_and_dwells, Analysis,
};
