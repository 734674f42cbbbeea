//! The text of one open document: a rope, its version, and `apply_changes`, which applies the
//! client's edits in order and says which lines they touched, so the analysis can update just those.

use crate::analysis::document::core_line_count;
use crate::lsp::convert::{position_to_char, PositionEncoding};
use ropey::Rope;
use std::fmt;
use tower_lsp_server::ls_types::TextDocumentContentChangeEvent;

/// The text and version of a document as the client last sent it.
#[derive(Debug, Clone)]
pub struct DocumentText {
    pub rope: Rope,
    pub version: i32,
}

/// Lines `first .. first + removed` of the old text became lines `first .. first + inserted` of the
/// new one; every other line is unchanged (lines after the range only moved). Counted in the core's
/// lines: a text that ends with a line terminator has no empty line after it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LineChange {
    pub first: usize,
    pub removed: usize,
    pub inserted: usize,
}

/// The same in ropey's lines, which do count the empty line after a final terminator. Changes are
/// merged in these terms and converted to [`LineChange`] once, when the analysis takes them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RopeLineChange {
    first: usize,
    removed: usize,
    inserted: usize,
}

impl RopeLineChange {
    /// `self` followed by `next` (whose lines are counted in the text after `self`), as one change of
    /// the text before `self`.
    pub fn then(self, next: RopeLineChange) -> RopeLineChange {
        let first = self.first.min(next.first);
        // The end of the union of both ranges, in the lines of the text between the two changes.
        let middle_end = (self.first + self.inserted).max(next.first + next.removed);
        RopeLineChange {
            first,
            removed: middle_end + self.removed - self.inserted - first,
            inserted: middle_end + next.inserted - next.removed - first,
        }
    }

    /// The change in the core's lines, given the core's line counts of the old and the new text.
    pub fn to_core(self, old_line_count: usize, new_line_count: usize) -> LineChange {
        let first = self.first.min(old_line_count).min(new_line_count);
        LineChange {
            first,
            removed: (self.first + self.removed).min(old_line_count) - first,
            inserted: (self.first + self.inserted).min(new_line_count) - first,
        }
    }
}

/// Why a set of changes was not applied.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ChangeError {
    /// The version is not newer than the document's: the edit is old or repeated.
    StaleVersion { current: i32, received: i32 },
    /// A range whose end comes before its start: the document cannot be kept in step with the client.
    ReversedRange { index: usize },
}

impl fmt::Display for ChangeError {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ChangeError::StaleVersion { current, received } => write!(
                formatter,
                "version {received} is not newer than the document's version {current}; the edit is ignored"
            ),
            ChangeError::ReversedRange { index } => write!(
                formatter,
                "change {index} has a range whose end is before its start"
            ),
        }
    }
}

impl DocumentText {
    pub fn new(text: &str, version: i32) -> DocumentText {
        DocumentText::from_rope(Rope::from_str(text), version)
    }

    pub fn from_rope(rope: Rope, version: i32) -> DocumentText {
        DocumentText { rope, version }
    }

    /// The number of lines as the core counts them.
    pub fn line_count(&self) -> usize {
        core_line_count(&self.rope)
    }
}

/// Applies the changes of one `didChange` in order, with positions in `encoding`, and returns the
/// lines they touched (merged into one range). Positions past the end of a line or of the document
/// are clamped. A version that is not newer than the document's is rejected before anything is
/// changed; a reversed range stops the application and leaves the document out of step, so the
/// caller must drop it.
pub fn apply_changes(
    document: &mut DocumentText,
    changes: &[TextDocumentContentChangeEvent],
    version: i32,
    encoding: PositionEncoding,
) -> Result<Option<RopeLineChange>, ChangeError> {
    if version <= document.version {
        return Err(ChangeError::StaleVersion {
            current: document.version,
            received: version,
        });
    }
    let mut merged: Option<RopeLineChange> = None;
    for (index, change) in changes.iter().enumerate() {
        let line_change = match change.range {
            None => {
                let removed = document.rope.len_lines();
                document.rope = Rope::from_str(&change.text);
                RopeLineChange {
                    first: 0,
                    removed,
                    inserted: document.rope.len_lines(),
                }
            }
            Some(range) => {
                let start = position_to_char(&document.rope, range.start, encoding);
                let end = position_to_char(&document.rope, range.end, encoding);
                if end < start {
                    return Err(ChangeError::ReversedRange { index });
                }
                replace(&mut document.rope, start, end, &change.text)
            }
        };
        merged = Some(match merged {
            Some(earlier) => earlier.then(line_change),
            None => line_change,
        });
    }
    document.version = version;
    Ok(merged)
}

/// Replaces the characters `start..end` by `text` and returns the ropey lines that changed.
fn replace(rope: &mut Rope, start: usize, end: usize, text: &str) -> RopeLineChange {
    let first = rope.char_to_line(start);
    let old_last = rope.char_to_line(end);
    rope.remove(start..end);
    rope.insert(start, text);
    // The line of the last inserted character's end, found in the new text: CR and LF that meet at
    // the edges of the edit may have joined into one CRLF, or a CRLF may have been split.
    let new_last = rope.char_to_line(start + text.chars().count());
    RopeLineChange {
        first,
        removed: old_last - first + 1,
        inserted: new_last - first + 1,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::document::{LineSource, RopeLines};
    use tower_lsp_server::ls_types::{Position, Range};

    fn change(start: (u32, u32), end: (u32, u32), text: &str) -> TextDocumentContentChangeEvent {
        TextDocumentContentChangeEvent {
            range: Some(Range::new(
                Position::new(start.0, start.1),
                Position::new(end.0, end.1),
            )),
            range_length: None,
            text: text.to_string(),
        }
    }

    #[test]
    fn edits_apply_in_order_and_report_their_lines() {
        let mut document = DocumentText::new("N10 X1\nN20 X2\nN30 X3\n", 1);
        let changed = apply_changes(
            &mut document,
            &[
                change((1, 4), (1, 6), "Y7\nN25 Y8"),
                change((0, 0), (0, 0), ";"),
            ],
            2,
            PositionEncoding::Utf16,
        )
        .unwrap()
        .unwrap();
        assert_eq!(
            document.rope.to_string(),
            ";N10 X1\nN20 Y7\nN25 Y8\nN30 X3\n"
        );
        assert_eq!(
            changed.to_core(3, 4),
            LineChange {
                first: 0,
                removed: 2,
                inserted: 3
            }
        );
    }

    #[test]
    fn stale_versions_are_rejected_unchanged() {
        let mut document = DocumentText::new("N10\n", 5);
        let error = apply_changes(
            &mut document,
            &[change((0, 0), (0, 0), "x")],
            5,
            PositionEncoding::Utf16,
        )
        .unwrap_err();
        assert_eq!(
            error,
            ChangeError::StaleVersion {
                current: 5,
                received: 5
            }
        );
        assert_eq!(document.rope.to_string(), "N10\n");
    }

    #[test]
    fn a_cr_joined_with_a_following_lf_counts_as_one_break() {
        let mut document = DocumentText::new("a\rb", 1);
        let changed = apply_changes(
            &mut document,
            &[change((1, 0), (1, 0), "\n")],
            2,
            PositionEncoding::Utf16,
        )
        .unwrap()
        .unwrap();
        assert_eq!(document.rope.to_string(), "a\r\nb");
        // "a\r" and the new "\n" joined into one CRLF: still two lines, and line 0 is untouched.
        let lines = RopeLines::new(&document.rope);
        assert_eq!(lines.line_count(), 2);
        assert_eq!((lines.line(0), lines.line(1)), ("a".into(), "b".into()));
        assert_eq!(
            changed.to_core(2, 2),
            LineChange {
                first: 1,
                removed: 1,
                inserted: 1
            }
        );
    }
}
