//! Language features for editors and the command line, over the core's types: symbols, a workspace
//! index with navigation and rename, completion, outline, semantic tokens, cross-file diagnostics,
//! hover and inlay hints, renumbering and formatting.
//!
//! Architecture Invariant: this module knows no protocol and does no IO. Every feature is one plain
//! function that speaks in 0-based lines, byte spans within a line ([`Span`]) and plain data; the
//! language server converts positions and types at its edge, and the CLI reads and writes the files.
//! Documents are read through [`LineSource`], which both the server's ropes and whole texts
//! ([`TextLines`]) implement.
//!
//! - `symbols.rs`: the symbol table of one document, collected from the parser's blocks.
//! - `workspace.rs`: the index over many documents; `navigation.rs`: definition, references, rename.
//! - `completion.rs`, `signature_help.rs`, `language_docs.rs` (the one table of descriptions shared
//!   with hover), `cycles.rs` (standard cycle parameter lists), `documentation.rs` (hover texts).
//! - `outline.rs` (document symbols, folding, highlights), `semantic_tokens.rs`.
//! - `cross_file_diagnostics.rs`: W3xx findings that need the symbol table or the workspace.
//! - `renumber.rs`, `format.rs`: whole-document rewrites returned as text.
//! - `hover/` (`hover_at`) and `inlay.rs` (`end_point_hints`): what a block does, over the analysis's
//!   block reports and the parser's words (`block_words.rs`), with the run where the program's flow
//!   decides (`program_run.rs`, `execution.rs`, `timing.rs`).
//! - `numbers.rs`: how numbers are written for people (hover, hints, the preview's outputs).

pub mod block_numbers;
pub mod block_words;
pub mod call_lookup;
mod comment_sections;
pub mod completion;
pub mod cross_file_diagnostics;
pub mod cycles;
pub mod documentation;
pub mod execution;
pub mod format;
pub mod hover;
pub mod inlay;
pub mod jumps;
pub mod language_docs;
pub mod navigation;
pub mod numbers;
pub mod outline;
pub mod program_run;
pub mod renumber;
pub mod semantic_tokens;
pub mod signature_help;
mod statement_text;
pub mod symbol_types;
pub mod symbols;
pub mod timing;
pub mod workspace;

mod names;

pub use crate::analysis::document::{LineSource, TextLines};
pub use crate::diagnostics::Span;
pub use symbols::SymbolTable;
pub use workspace::{DocumentId, WorkspaceIndex};

/// A place in a document: a 0-based line and a byte span inside it.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Location {
    pub document: DocumentId,
    pub line: usize,
    pub span: Span,
}

/// A replacement of a byte span of one line by new text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LineEdit {
    pub line: usize,
    pub span: Span,
    pub new_text: String,
}

/// Applies edits to a text: each edit replaces a byte span of one line (0-based). Edits may come in
/// any order but must not overlap; line terminators and everything outside the edits stay as they
/// are, byte for byte.
pub fn apply_edits(text: &str, edits: &[LineEdit]) -> String {
    let mut sorted: Vec<&LineEdit> = edits.iter().collect();
    sorted.sort_by_key(|edit| (edit.line, edit.span.start()));
    let mut out = String::with_capacity(text.len() + 16 * sorted.len());
    let mut copied = 0;
    let mut pending = sorted.into_iter().peekable();
    for (line_index, (start, end)) in crate::syntax::lines::line_ranges(text).enumerate() {
        while let Some(edit) = pending.next_if(|edit| edit.line == line_index) {
            let edit_start = start + edit.span.start().min(end - start);
            let edit_end = start + edit.span.end().min(end - start);
            if edit_start < copied {
                continue;
            }
            out.push_str(&text[copied..edit_start]);
            out.push_str(&edit.new_text);
            copied = edit_end;
        }
        if pending.peek().is_none() {
            break;
        }
    }
    out.push_str(&text[copied..]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edits_replace_spans_and_keep_line_ends() {
        let text = "N10 G0\r\nN20 G1\nX1";
        let edits = [
            LineEdit {
                line: 2,
                span: Span::new(0, 1),
                new_text: "Y".into(),
            },
            LineEdit {
                line: 0,
                span: Span::new(1, 3),
                new_text: "100".into(),
            },
            LineEdit {
                line: 1,
                span: Span::new(3, 3),
                new_text: " M3".into(),
            },
        ];
        assert_eq!(apply_edits(text, &edits), "N100 G0\r\nN20 M3 G1\nY1");
        assert_eq!(apply_edits(text, &[]), text);
    }
}
