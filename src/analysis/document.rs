//! The analysis of one open document, kept up to date as the text changes: what the language server
//! asks of the core. The text itself stays with the caller (a rope in the server, a string in tests)
//! and is read through [`LineSource`](line_source::LineSource); this type keeps only what it derived from it: the diagnostics,
//! a few flags per line, and checkpoints of the modal state every [`CHECKPOINT_INTERVAL`](document_state::CHECKPOINT_INTERVAL) lines.
//!
//! An edit re-reads the lines from the checkpoint before it and stops at the first later checkpoint
//! whose state the new pass reproduces exactly: from there on every block resolves as before, so the
//! old diagnostics are kept, moved by the number of lines inserted or removed. A block's report (for a
//! hover) replays at most one interval from the nearest checkpoint. The result is always the one a
//! from-scratch analysis of the same text gives (tested on random edits).
//!
//! A long update (an edit that changes how the whole rest of a program reads) can be interrupted by
//! a newer edit: it keeps what it read and leaves the rest to the next update, which reads it with
//! the new edit's lines. The first analysis of a large document reads its two halves on two threads
//! (see [`DocumentAnalysis::new_in_parallel`](document_state::DocumentAnalysis::new_in_parallel)).
//!
//! This file only declares the document analysis's files and re-exports what the rest of the crate
//! uses: the lines it reads (`line_source.rs`), its state (`document_state.rs`), the first analysis
//! (`first_analysis.rs`), the update after an edit (`incremental.rs`), one forward pass (`pass.rs`)
//! and what it reports about a block (`report.rs`).

pub(crate) mod document_state;
pub(crate) mod facts;
mod first_analysis;
mod flat_lines;
mod incremental;
pub(crate) mod line_source;
mod pass;
pub(crate) mod report;
mod rope_lines;
#[cfg(test)]
pub(crate) mod test_texts;
#[cfg(test)]
mod tests;

pub use crate::analysis::resolution::{ResolutionMode, WordResolution};
pub use document_state::{DocumentAnalysis, CHECKPOINT_INTERVAL, INTERRUPTIBLE_AFTER_LINES};
pub use flat_lines::FlatLines;
pub use line_source::{LineSource, TextLines};
pub use report::{summarize, BlockReport, StateSummary};
pub use rope_lines::{core_line_count, RopeLines};
