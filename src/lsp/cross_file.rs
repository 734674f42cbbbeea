//! The cross-file findings (W301–W307) of an open document, published in the same
//! `publishDiagnostics` as its analysis's diagnostics. They are computed off the async threads after
//! the document's index entry is rebuilt (debounced, see `workspace.rs`); between recomputations
//! every edit shifts their lines (an O(findings) loop, nothing proportional to the document), so they
//! stay on their blocks. A generation counter tells the publishing worker that they changed after it
//! wrote its message, so it writes again instead of publishing an outdated set.

use crate::diagnostics::LineDiagnostic;
use crate::lsp::locks::lock;
use crate::lsp::text_document::RopeLineChange;
use std::sync::Mutex;

/// The latest cross-file findings of one document.
#[derive(Debug, Default)]
pub struct ExtraDiagnostics {
    items: Vec<LineDiagnostic>,
    /// The revision of the last edit whose line change was applied to `items`: findings computed for
    /// an older text would land on the wrong lines.
    shifted_to: u64,
    /// Counts every change of `items`.
    generation: u64,
}

impl ExtraDiagnostics {
    /// Follows an edit that made the document's text revision `revision`: findings on lines after
    /// the edited range move with them, findings on removed lines go.
    pub fn on_edit(&mut self, change: Option<RopeLineChange>, revision: u64) {
        let Some(change) = change else {
            return;
        };
        self.shifted_to = revision;
        if self.items.is_empty() {
            return;
        }
        // Without clamping (unbounded line counts) the conversion gives the change's own numbers.
        let change = change.to_core(usize::MAX, usize::MAX);
        let old_end = change.first + change.removed;
        let new_end = change.first + change.inserted;
        self.items.retain_mut(|item| {
            if item.line < change.first {
                true
            } else if item.line >= old_end {
                item.line = item.line - old_end + new_end;
                true
            } else {
                // An edited line keeps its findings while it still exists.
                item.line < new_end
            }
        });
        self.generation += 1;
    }

    /// Replaces the findings with ones computed for text revision `computed_for`. Refused (false)
    /// when an edit came since, whose debounced update computes them again; false also when
    /// nothing changed.
    pub fn replace(&mut self, items: Vec<LineDiagnostic>, computed_for: u64) -> bool {
        if computed_for < self.shifted_to || items == self.items {
            return false;
        }
        self.items = items;
        self.generation += 1;
        true
    }

    pub fn generation(&self) -> u64 {
        self.generation
    }
}

/// The cross-file findings on the document's `line_count` lines, and their generation.
pub fn extra_findings(
    extra: &Mutex<ExtraDiagnostics>,
    line_count: usize,
) -> (Vec<LineDiagnostic>, u64) {
    let extra = lock(extra);
    let items = extra
        .items
        .iter()
        .filter(|item| item.line < line_count)
        .cloned()
        .collect();
    (items, extra.generation)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostics::{Code, Diagnostic, Span};

    fn finding(line: usize) -> LineDiagnostic {
        LineDiagnostic {
            line,
            diagnostic: Diagnostic::new(Code::UnexpectedCharacter, Span::new(0, 1), "x"),
        }
    }

    #[test]
    fn findings_follow_inserted_and_removed_lines() {
        let mut extra = ExtraDiagnostics::default();
        assert!(extra.replace(vec![finding(1), finding(5), finding(9)], 1));
        // Lines 4..=6 became one line: the finding on line 5 goes with its line, 9 moves up to 7.
        let rope_before = ropey::Rope::from_str("0\n1\n2\n3\n4\n5\n6\n7\n8\n9\n");
        let mut text = crate::lsp::text_document::DocumentText {
            rope: rope_before,
            version: 1,
        };
        let change = crate::lsp::text_document::apply_changes(
            &mut text,
            &[tower_lsp_server::ls_types::TextDocumentContentChangeEvent {
                range: Some(tower_lsp_server::ls_types::Range::new(
                    tower_lsp_server::ls_types::Position::new(4, 0),
                    tower_lsp_server::ls_types::Position::new(6, 1),
                )),
                range_length: None,
                text: "x".into(),
            }],
            2,
            crate::lsp::convert::PositionEncoding::Utf16,
        )
        .unwrap();
        extra.on_edit(change, 2);
        let lines: Vec<usize> = extra.items.iter().map(|item| item.line).collect();
        assert_eq!(lines, vec![1, 7]);
        // Findings computed for the text before the edit are refused.
        assert!(!extra.replace(vec![finding(3)], 1));
        assert!(extra.replace(vec![finding(3)], 2));
    }
}
