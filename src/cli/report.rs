//! Printing diagnostics: the compiler-style human format, the JSON format, and the conversion of byte
//! spans to 1-based character columns that both share.

use crate::diagnostics::{LineDiagnostic, Severity, Span};
use serde::Serialize;
use std::cell::Cell;
use std::io::{self, Write};

/// The gutter of the human format is at least this wide, so short files line up like long ones.
const MIN_GUTTER_WIDTH: usize = 5;

/// Lines longer than this (in bytes) are shown as an excerpt around the span: a binary file can hold
/// one line of many megabytes, and printing it whole for every diagnostic would flood the terminal.
const MAX_SHOWN_LINE_BYTES: usize = 1000;

/// How much of a long line is shown before and after the span, in bytes.
const EXCERPT_CONTEXT_BYTES: usize = 120;

/// How many diagnostics of each severity were reported.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub(crate) struct SeverityCounts {
    pub errors: usize,
    pub warnings: usize,
    pub infos: usize,
    pub hints: usize,
}

impl SeverityCounts {
    pub fn add(&mut self, severity: Severity) {
        match severity {
            Severity::Error => self.errors += 1,
            Severity::Warning => self.warnings += 1,
            Severity::Information => self.infos += 1,
            Severity::Hint => self.hints += 1,
        }
    }
}

/// The last line of the human format, e.g. `checked 3 files: 2 errors, 1 warning, 0 infos`. Hints are
/// only mentioned when there are some, because by default no check reports a hint.
pub(crate) fn summary_line(n_files: usize, counts: SeverityCounts) -> String {
    let mut summary = format!(
        "checked {}: {}, {}, {}",
        plural(n_files, "file"),
        plural(counts.errors, "error"),
        plural(counts.warnings, "warning"),
        plural(counts.infos, "info")
    );
    if counts.hints > 0 {
        summary.push_str(&format!(", {}", plural(counts.hints, "hint")));
    }
    summary
}

fn plural(count: usize, noun: &str) -> String {
    if count == 1 {
        format!("{count} {noun}")
    } else {
        format!("{count} {noun}s")
    }
}

/// One program file's text and line index: the text of the line a diagnostic points into, and the
/// conversion of its byte spans to character columns.
pub(crate) struct ProgramLines<'text> {
    text: &'text str,
    line_ranges: Vec<(usize, usize)>,
    /// In an ASCII text, and most programs are, a byte offset already is a character index.
    is_ascii: bool,
    /// The last conversion: line, byte offset and character index. Diagnostics come sorted, so a
    /// long line with many of them is counted once from left to right instead of once per diagnostic
    /// (a 20 MB line of binary garbage took seconds before).
    last_conversion: Cell<(usize, usize, usize)>,
}

impl<'text> ProgramLines<'text> {
    pub fn new(text: &'text str) -> ProgramLines<'text> {
        ProgramLines {
            text,
            line_ranges: crate::syntax::lines::line_ranges(text).collect(),
            is_ascii: text.is_ascii(),
            last_conversion: Cell::new((usize::MAX, 0, 0)),
        }
    }

    /// The text of a 0-based line; a line past the end (a diagnostic at the end of the file) is empty.
    pub fn line(&self, line_idx: usize) -> &'text str {
        match self.line_ranges.get(line_idx) {
            Some(&(start, end)) => &self.text[start..end],
            None => "",
        }
    }

    /// The 1-based columns, in characters (Unicode scalar values), of a span in a line: the first
    /// character and the one after the last (end exclusive); an empty span gives the same column
    /// twice. Offsets past the end count as the end and offsets inside a multi-byte character widen
    /// the span to that character, so a bad span never panics.
    pub fn columns(&self, line_idx: usize, span: Span) -> (usize, usize) {
        let line = self.line(line_idx);
        let start = floor_char_boundary(line, span.start());
        let end = ceil_char_boundary(line, span.end().max(span.start()));
        if self.is_ascii {
            return (start + 1, end + 1);
        }
        let (cached_line_idx, cached_offset, cached_index) = self.last_conversion.get();
        let start_index = if cached_line_idx == line_idx && cached_offset <= start {
            cached_index + line[cached_offset..start].chars().count()
        } else {
            line[..start].chars().count()
        };
        self.last_conversion.set((line_idx, start, start_index));
        let end_index = start_index + line[start..end].chars().count();
        (start_index + 1, end_index + 1)
    }
}

fn floor_char_boundary(line: &str, byte_offset: usize) -> usize {
    let mut byte_offset = byte_offset.min(line.len());
    while !line.is_char_boundary(byte_offset) {
        byte_offset -= 1;
    }
    byte_offset
}

fn ceil_char_boundary(line: &str, byte_offset: usize) -> usize {
    let mut byte_offset = byte_offset.min(line.len());
    while !line.is_char_boundary(byte_offset) {
        byte_offset += 1;
    }
    byte_offset
}

/// Writes one diagnostic in the human format:
///
/// ```text
/// path/to/FILE.MPF:12:7: error[S101]: modifier AC needs its value in parentheses
///    12 | N20 X75 Z=AC17
///       |         ^^^^^^
///       = fix: write `Z=AC(17)`
/// ```
pub(crate) fn write_human(
    out: &mut dyn Write,
    path: &str,
    lines: &ProgramLines<'_>,
    line_diagnostic: &LineDiagnostic,
) -> io::Result<()> {
    let diagnostic = &line_diagnostic.diagnostic;
    let line = lines.line(line_diagnostic.line);
    let line_number = line_diagnostic.line + 1;
    let (start_column, _) = lines.columns(line_diagnostic.line, diagnostic.span);
    // Messages quote the program's text and paths can hold anything, so both are made safe too.
    writeln!(
        out,
        "{}:{line_number}:{start_column}: {}[{}]: {}",
        terminal_safe(path),
        diagnostic.severity,
        diagnostic.code,
        terminal_safe(&diagnostic.message)
    )?;

    let gutter_width = MIN_GUTTER_WIDTH.max(line_number.to_string().len());
    let excerpt = Excerpt::new(line, diagnostic.span);
    writeln!(out, "{line_number:>gutter_width$} | {}", excerpt.shown_text)?;
    writeln!(out, "{:>gutter_width$} | {}", "", excerpt.underline)?;
    if let Some(fix) = &diagnostic.fix {
        writeln!(
            out,
            "{:>gutter_width$} = fix: {}",
            "",
            terminal_safe(&fix.title)
        )?;
    }
    Ok(())
}

/// The part of a line that is printed, made safe for a terminal, with its caret underline.
struct Excerpt {
    shown_text: String,
    underline: String,
}

impl Excerpt {
    fn new(line: &str, span: Span) -> Excerpt {
        let span_start = floor_char_boundary(line, span.start());
        let span_end = ceil_char_boundary(line, span.end().max(span.start()));
        let (shown_start, shown_end) = if line.len() <= MAX_SHOWN_LINE_BYTES {
            (0, line.len())
        } else {
            let span_shown_end = span_end.min(span_start + MAX_SHOWN_LINE_BYTES / 2);
            (
                floor_char_boundary(line, span_start.saturating_sub(EXCERPT_CONTEXT_BYTES)),
                ceil_char_boundary(line, span_shown_end + EXCERPT_CONTEXT_BYTES),
            )
        };
        let span_end = span_end.min(shown_end);

        let mut shown_text = String::new();
        let mut underline = String::new();
        if shown_start > 0 {
            shown_text.push('…');
            underline.push(' ');
        }
        for (byte_offset, character) in line[shown_start..shown_end].char_indices() {
            let byte_offset = shown_start + byte_offset;
            shown_text.push(printable(character));
            if byte_offset < span_start {
                // A tab stays a tab under a tab, so the carets line up whatever the tab width.
                underline.push(if character == '\t' { '\t' } else { ' ' });
            } else if byte_offset < span_end {
                underline.push('^');
            }
        }
        if shown_end < line.len() {
            shown_text.push('…');
        }
        // An empty span (something missing at the end of the line) still gets one caret.
        if span_end <= span_start {
            underline.push('^');
        }
        Excerpt {
            shown_text,
            underline,
        }
    }
}

/// Control characters from binary files or stray escapes would move the cursor or recolour the
/// terminal, so they are shown as U+FFFD, one character for one, which keeps the carets aligned.
fn printable(character: char) -> char {
    if character.is_control() && character != '\t' {
        '\u{FFFD}'
    } else {
        character
    }
}

fn terminal_safe(text: &str) -> String {
    text.chars().map(printable).collect()
}

/// One diagnostic of the JSON format. Lines and columns are 1-based, columns count characters (Unicode
/// scalar values), and the end column is the one after the last character.
#[derive(Serialize)]
pub(crate) struct JsonDiagnostic<'a> {
    file: &'a str,
    line: usize,
    column: usize,
    end_line: usize,
    end_column: usize,
    severity: &'static str,
    code: &'static str,
    message: &'a str,
    fix: Option<JsonFix<'a>>,
}

#[derive(Serialize)]
struct JsonFix<'a> {
    title: &'a str,
    edits: Vec<JsonEdit<'a>>,
}

#[derive(Serialize)]
struct JsonEdit<'a> {
    line: usize,
    column: usize,
    end_line: usize,
    end_column: usize,
    new_text: &'a str,
}

impl<'a> JsonDiagnostic<'a> {
    pub fn new(
        path: &'a str,
        lines: &ProgramLines<'_>,
        line_diagnostic: &'a LineDiagnostic,
    ) -> JsonDiagnostic<'a> {
        let diagnostic = &line_diagnostic.diagnostic;
        let line_number = line_diagnostic.line + 1;
        let (column, end_column) = lines.columns(line_diagnostic.line, diagnostic.span);
        let fix = diagnostic.fix.as_ref().map(|fix| JsonFix {
            title: &fix.title,
            edits: fix
                .edits
                .iter()
                .map(|edit| {
                    // Edits are relative to the diagnostic's line, like its span.
                    let (column, end_column) = lines.columns(line_diagnostic.line, edit.span);
                    JsonEdit {
                        line: line_number,
                        column,
                        end_line: line_number,
                        end_column,
                        new_text: &edit.new_text,
                    }
                })
                .collect(),
        });
        JsonDiagnostic {
            file: path,
            line: line_number,
            column,
            end_line: line_number,
            end_column,
            severity: diagnostic.severity.as_str(),
            code: diagnostic.code.as_str(),
            message: &diagnostic.message,
            fix,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostics::{Code, Diagnostic, Fix};

    fn render_human(text: &str, line_diagnostic: &LineDiagnostic) -> String {
        let mut out = Vec::new();
        write_human(&mut out, "P.MPF", &ProgramLines::new(text), line_diagnostic).unwrap();
        String::from_utf8(out).unwrap()
    }

    fn s101(line: usize, start: usize, end: usize) -> LineDiagnostic {
        LineDiagnostic {
            line,
            diagnostic: Diagnostic::new(
                Code::ModifierWithoutParentheses,
                Span::new(start, end),
                "modifier AC needs its value in parentheses",
            ),
        }
    }

    fn columns(line: &str, span: Span) -> (usize, usize) {
        ProgramLines::new(line).columns(0, span)
    }

    #[test]
    fn byte_offsets_become_character_columns() {
        assert_eq!(columns("N10 X1", Span::new(4, 6)), (5, 7));
        assert_eq!(columns("; Ä X", Span::new(5, 6)), (5, 6));
        assert_eq!(columns("; Ä X", Span::new(2, 4)), (3, 4));
        assert_eq!(columns("; Ä X", Span::new(99, 99)), (6, 6));
        assert_eq!(columns("", Span::new(3, 4)), (1, 1));
        assert_eq!(columns("ÄÖ Z=AC17", Span::new(5, 12)), (4, 10));
        assert_eq!(columns("ab", Span::new(2, 2)), (3, 3));
        // An emoji is one character (one Unicode scalar value) although it is four bytes.
        assert_eq!(columns("😀X1", Span::new(4, 6)), (2, 4));
    }

    #[test]
    fn bad_spans_are_clamped_not_panicking() {
        // Offsets inside a character widen to the whole character; reversed or out-of-range spans
        // collapse to something printable.
        assert_eq!(columns("ÄB", Span::new(1, 1)), (1, 2));
        assert_eq!(columns("ÄB", Span::new(1, 3)), (1, 3));
        assert_eq!(columns("AB", Span::new(5, 1)), (3, 3));
        assert_eq!(columns("AB", Span::new(2, 0)), (3, 3));
    }

    #[test]
    fn remembered_conversions_give_the_same_columns() {
        let text = "; Ä\nÄÖ X1 Ü Y2 é Z3 😀 A4\nB5 Ä";
        let lines = ProgramLines::new(text);
        // Forwards, backwards, and across lines, against a fresh conversion each time.
        let spans = [
            (1, 0, 2),
            (1, 5, 7),
            (1, 10, 12),
            (1, 5, 6),
            (2, 0, 2),
            (1, 16, 18),
            (1, 2, 4),
            (0, 2, 4),
        ];
        for (line_idx, start, end) in spans {
            let span = Span::new(start, end);
            let fresh = ProgramLines::new(lines.line(line_idx)).columns(0, span);
            assert_eq!(
                lines.columns(line_idx, span),
                fresh,
                "line {line_idx} {span:?}"
            );
        }
        assert_eq!(lines.columns(1, Span::new(5, 7)), (4, 6));
    }

    #[test]
    fn human_format_matches_the_compiler_style() {
        let text = "N10 G0\nN20 X75 Z=AC17\n";
        let mut line_diagnostic = s101(1, 8, 14);
        line_diagnostic.diagnostic = line_diagnostic.diagnostic.with_fix(Fix::replace(
            "write `Z=AC(17)`",
            Span::new(8, 14),
            "Z=AC(17)",
        ));
        assert_eq!(
            render_human(text, &line_diagnostic),
            "P.MPF:2:9: error[S101]: modifier AC needs its value in parentheses\n\
             \x20   2 | N20 X75 Z=AC17\n\
             \x20     |         ^^^^^^\n\
             \x20     = fix: write `Z=AC(17)`\n"
        );
    }

    #[test]
    fn human_format_counts_characters_and_keeps_tabs() {
        let rendered = render_human("N1\tÄ Z=AC1", &s101(0, 6, 11));
        assert!(rendered.starts_with("P.MPF:1:6: error[S101]"), "{rendered}");
        assert!(rendered.contains("\n      |   \t  ^^^^^\n"), "{rendered:?}");
    }

    #[test]
    fn empty_span_and_missing_line_get_one_caret() {
        let rendered = render_human("N10 X", &s101(0, 5, 5));
        assert!(rendered.ends_with("      |      ^\n"), "{rendered:?}");
        let rendered = render_human("N10 X", &s101(3, 0, 0));
        assert!(rendered.starts_with("P.MPF:4:1: "), "{rendered}");
        assert!(rendered.contains("    4 | \n      | ^\n"), "{rendered:?}");
    }

    #[test]
    fn control_characters_are_not_echoed() {
        let rendered = render_human("N1 \u{1b}[31m\0X", &s101(0, 4, 5));
        assert!(!rendered.contains('\u{1b}'), "{rendered:?}");
        assert!(!rendered.contains('\0'), "{rendered:?}");
        assert!(
            rendered.contains("N1 \u{FFFD}[31m\u{FFFD}X"),
            "{rendered:?}"
        );

        let mut line_diagnostic = s101(0, 0, 1);
        line_diagnostic.diagnostic.message = "`\u{1b}[2J` cannot stand here".to_string();
        line_diagnostic.diagnostic.fix = Some(Fix::replace("remove `\u{7}`", Span::new(0, 1), ""));
        let rendered = render_human("X", &line_diagnostic);
        assert!(!rendered.contains(['\u{1b}', '\u{7}']), "{rendered:?}");
    }

    #[test]
    fn long_lines_are_shown_as_an_excerpt() {
        let line = format!("{}Z=AC17{}", "X".repeat(5000), "Y".repeat(5000));
        let rendered = render_human(&line, &s101(0, 5000, 5006));
        assert!(rendered.starts_with("P.MPF:1:5001: "), "{rendered}");
        assert!(rendered.len() < 1000, "{} bytes", rendered.len());
        let shown_lines: Vec<&str> = rendered.lines().collect();
        let text_line = shown_lines[1];
        let caret_line = shown_lines[2];
        let caret_column = caret_line
            .chars()
            .position(|character| character == '^')
            .unwrap();
        let text_from_caret: String = text_line.chars().skip(caret_column).take(6).collect();
        assert_eq!(text_from_caret, "Z=AC17");
    }

    #[test]
    fn summary_is_pluralised() {
        let counts = SeverityCounts {
            errors: 2,
            warnings: 1,
            infos: 0,
            hints: 0,
        };
        assert_eq!(
            summary_line(3, counts),
            "checked 3 files: 2 errors, 1 warning, 0 infos"
        );
        let counts = SeverityCounts {
            errors: 1,
            warnings: 0,
            infos: 1,
            hints: 2,
        };
        assert_eq!(
            summary_line(1, counts),
            "checked 1 file: 1 error, 0 warnings, 1 info, 2 hints"
        );
    }

    #[test]
    fn json_has_character_columns_and_fix_edits() {
        let text = "; Ä\nÄ Z=AC17";
        let mut line_diagnostic = s101(1, 3, 9);
        line_diagnostic.diagnostic = line_diagnostic.diagnostic.with_fix(Fix::replace(
            "write `Z=AC(17)`",
            Span::new(3, 9),
            "Z=AC(17)",
        ));
        let lines = ProgramLines::new(text);
        let value =
            serde_json::to_value(JsonDiagnostic::new("P.MPF", &lines, &line_diagnostic)).unwrap();
        assert_eq!(
            value,
            serde_json::json!({
                "file": "P.MPF", "line": 2, "column": 3, "end_line": 2, "end_column": 9,
                "severity": "error", "code": "S101",
                "message": "modifier AC needs its value in parentheses",
                "fix": {"title": "write `Z=AC(17)`", "edits": [
                    {"line": 2, "column": 3, "end_line": 2, "end_column": 9, "new_text": "Z=AC(17)"}
                ]}
            })
        );
    }
}
