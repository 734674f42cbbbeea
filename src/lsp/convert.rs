//! Conversions between the core's plain values and LSP types, in one place: positions in the
//! negotiated encoding, byte spans of a line to ranges, diagnostics and their fixes.
//!
//! The core counts columns as byte offsets within a line; LSP counts UTF-16 code units (or UTF-8
//! bytes when both sides agreed on it at initialize). Every conversion clamps: a position past the
//! end of a line is the end of the line, one inside a multi-byte character is that character's start.

use crate::diagnostics::{LineDiagnostic, Severity, Span};
use ropey::Rope;
use std::borrow::Cow;
use tower_lsp_server::ls_types::{
    self, DiagnosticSeverity, NumberOrString, Position, PositionEncodingKind, Range,
};

/// The unit of `Position::character`, negotiated once at initialize.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PositionEncoding {
    Utf8,
    Utf16,
}

impl PositionEncoding {
    /// UTF-8 when the client offers it (no conversion needed), else the protocol's default UTF-16.
    pub fn negotiate(offered: Option<&[PositionEncodingKind]>) -> PositionEncoding {
        match offered {
            Some(kinds) if kinds.contains(&PositionEncodingKind::UTF8) => PositionEncoding::Utf8,
            _ => PositionEncoding::Utf16,
        }
    }

    pub fn kind(self) -> PositionEncodingKind {
        match self {
            PositionEncoding::Utf8 => PositionEncodingKind::UTF8,
            PositionEncoding::Utf16 => PositionEncodingKind::UTF16,
        }
    }
}

/// The character index in the rope of an LSP position, clamped to the document and to its line
/// (the line terminator is not part of the line).
pub fn position_to_char(rope: &Rope, position: Position, encoding: PositionEncoding) -> usize {
    let line_idx = position.line as usize;
    if line_idx >= rope.len_lines() {
        return rope.len_chars();
    }
    let line_start = rope.line_to_char(line_idx);
    let line = line_without_terminator(rope, line_idx);
    let character = position.character as usize;
    let offset = match encoding {
        PositionEncoding::Utf8 => line.byte_to_char(character.min(line.len_bytes())),
        PositionEncoding::Utf16 => line.utf16_cu_to_char(character.min(line.len_utf16_cu())),
    };
    line_start + offset
}

/// The byte offset within `line` of an LSP character offset, clamped to the line and rounded down
/// to a character boundary.
pub fn character_to_byte(line: &str, character: u32, encoding: PositionEncoding) -> usize {
    let character = character as usize;
    match encoding {
        PositionEncoding::Utf8 => floor_char_boundary(line, character),
        PositionEncoding::Utf16 => {
            if line.is_ascii() {
                return character.min(line.len());
            }
            let mut units = 0;
            for (byte, ch) in line.char_indices() {
                let next = units + ch.len_utf16();
                if next > character {
                    return byte;
                }
                units = next;
            }
            line.len()
        }
    }
}

/// The LSP character offset of a byte offset within `line` (clamped, rounded down to a character).
pub fn byte_to_character(line: &str, byte: usize, encoding: PositionEncoding) -> u32 {
    let byte = floor_char_boundary(line, byte);
    let units = match encoding {
        PositionEncoding::Utf8 => byte,
        PositionEncoding::Utf16 if line.is_ascii() => byte,
        PositionEncoding::Utf16 => line[..byte].encode_utf16().count(),
    };
    u32::try_from(units).unwrap_or(u32::MAX)
}

fn floor_char_boundary(line: &str, byte: usize) -> usize {
    let mut byte = byte.min(line.len());
    while !line.is_char_boundary(byte) {
        byte -= 1;
    }
    byte
}

/// The range of a byte span of line `line_idx`, whose text is `line`.
pub fn span_to_range(line_idx: usize, line: &str, span: Span, encoding: PositionEncoding) -> Range {
    let line_number = u32::try_from(line_idx).unwrap_or(u32::MAX);
    let start = byte_to_character(line, span.start(), encoding);
    let end = byte_to_character(line, span.end().max(span.start()), encoding);
    Range::new(
        Position::new(line_number, start),
        Position::new(line_number, end),
    )
}

/// The position at the end of line `line_idx`, whose text is `line`.
pub fn end_of_line(line_idx: usize, line: &str, encoding: PositionEncoding) -> Position {
    Position::new(
        u32::try_from(line_idx).unwrap_or(u32::MAX),
        byte_to_character(line, line.len(), encoding),
    )
}

fn severity(severity: Severity) -> DiagnosticSeverity {
    match severity {
        Severity::Error => DiagnosticSeverity::ERROR,
        Severity::Warning => DiagnosticSeverity::WARNING,
        Severity::Information => DiagnosticSeverity::INFORMATION,
        Severity::Hint => DiagnosticSeverity::HINT,
    }
}

/// The JSON array of diagnostics sorted by line, reading each line's text once from `line_text` (not
/// at all when `all_ascii` says the document is ASCII, where byte offsets are the columns in both
/// encodings). Written directly as JSON text, in the shape of [`diagnostic_to_lsp`]: tens of
/// thousands of diagnostics are published after every edit of a large program, and building LSP
/// values first took several times as long.
pub fn diagnostics_json<'a>(
    diagnostics: &[LineDiagnostic],
    mut line_text: impl FnMut(usize) -> Cow<'a, str>,
    all_ascii: bool,
    encoding: PositionEncoding,
) -> Vec<u8> {
    let mut array = Vec::with_capacity(2 + diagnostics.len() * 200);
    array.push(b'[');
    let mut current: Option<(usize, Cow<'a, str>)> = None;
    for (index, item) in diagnostics.iter().enumerate() {
        let range = if all_ascii {
            ascii_range(item)
        } else {
            if current.as_ref().map(|(line_idx, _)| *line_idx) != Some(item.line) {
                current = Some((item.line, line_text(item.line)));
            }
            let line = current
                .as_ref()
                .map(|(_, text)| text.as_ref())
                .unwrap_or("");
            span_to_range(item.line, line, item.diagnostic.span, encoding)
        };
        if index > 0 {
            array.push(b',');
        }
        write_diagnostic_json(&mut array, range, item);
    }
    array.push(b']');
    array
}

/// The range of a diagnostic in an ASCII line, where byte offsets are the columns in either encoding.
pub fn ascii_range(item: &LineDiagnostic) -> Range {
    let line_number = u32::try_from(item.line).unwrap_or(u32::MAX);
    let span = item.diagnostic.span;
    let column = |byte: usize| u32::try_from(byte).unwrap_or(u32::MAX);
    Range::new(
        Position::new(line_number, column(span.start())),
        Position::new(line_number, column(span.end().max(span.start()))),
    )
}

/// How every diagnostic object starts; the start line's number follows.
pub const DIAGNOSTIC_JSON_START: &[u8] = br#"{"range":{"start":{"line":"#;
/// What comes before the end line's number within a diagnostic object.
pub const DIAGNOSTIC_JSON_END_LINE: &[u8] = br#""end":{"line":"#;

/// One diagnostic as a JSON object (starting with [`DIAGNOSTIC_JSON_START`]) at `range`.
pub fn write_diagnostic_json(out: &mut Vec<u8>, range: Range, item: &LineDiagnostic) {
    use std::io::Write;
    let severity = match item.diagnostic.severity {
        Severity::Error => 1,
        Severity::Warning => 2,
        Severity::Information => 3,
        Severity::Hint => 4,
    };
    out.extend_from_slice(DIAGNOSTIC_JSON_START);
    let _ = write!(
        out,
        r#"{},"character":{}}},"end":{{"line":{},"character":{}}}}},"severity":{severity},"code":"{}","source":"sinumerik","message":"#,
        range.start.line,
        range.start.character,
        range.end.line,
        range.end.character,
        item.diagnostic.code.as_str(),
    );
    let _ = serde_json::to_writer(&mut *out, &item.diagnostic.message);
    out.push(b'}');
}

/// The whole `textDocument/publishDiagnostics` message in one buffer, header included (the server
/// sends the pieces of [`publish_diagnostics_frame`] instead; tests read the message whole).
/// A line of a rope without its terminator.
pub fn line_without_terminator(rope: &Rope, line_idx: usize) -> ropey::RopeSlice<'_> {
    if line_idx >= rope.len_lines() {
        return rope.slice(0..0);
    }
    let line = rope.line(line_idx);
    line.slice(..line.len_chars() - terminator_chars(line))
}

/// The length in characters of a line's terminator (LF, CRLF, CR, or none on the last line).
pub fn terminator_chars(line: ropey::RopeSlice<'_>) -> usize {
    let length = line.len_chars();
    match (
        length.checked_sub(2).map(|index| line.char(index)),
        length.checked_sub(1).map(|index| line.char(index)),
    ) {
        (Some('\r'), Some('\n')) => 2,
        (_, Some('\n' | '\r')) => 1,
        _ => 0,
    }
}

#[cfg(test)]
pub fn publish_diagnostics_message(
    uri: &ls_types::Uri,
    version: Option<i32>,
    diagnostics_array: &[u8],
) -> Vec<u8> {
    let (head, tail) = publish_diagnostics_frame(uri, version, diagnostics_array.len());
    let mut message = Vec::with_capacity(head.len() + diagnostics_array.len() + tail.len());
    message.extend_from_slice(&head);
    message.extend_from_slice(diagnostics_array);
    message.extend_from_slice(&tail);
    message
}

/// What comes before (the header included) and after a diagnostics array of `array_length` bytes in
/// its `textDocument/publishDiagnostics` message: the array itself is sent as it is, without a copy.
pub fn publish_diagnostics_frame(
    uri: &ls_types::Uri,
    version: Option<i32>,
    array_length: usize,
) -> (Vec<u8>, Vec<u8>) {
    let mut prefix =
        br#"{"jsonrpc":"2.0","method":"textDocument/publishDiagnostics","params":{"uri":"#.to_vec();
    let _ = serde_json::to_writer(&mut prefix, uri.as_str());
    prefix.extend_from_slice(br#","diagnostics":"#);
    let suffix = match version {
        Some(version) => format!(r#","version":{version}}}}}"#),
        None => "}}".to_string(),
    };
    let length = prefix.len() + array_length + suffix.len();
    let mut head = format!("Content-Length: {length}\r\n\r\n").into_bytes();
    head.extend_from_slice(&prefix);
    (head, suffix.into_bytes())
}

/// One diagnostic, with `line` the text of its line.
pub fn diagnostic_to_lsp(
    item: &LineDiagnostic,
    line: &str,
    encoding: PositionEncoding,
) -> ls_types::Diagnostic {
    let diagnostic = &item.diagnostic;
    ls_types::Diagnostic {
        range: span_to_range(item.line, line, diagnostic.span, encoding),
        severity: Some(severity(diagnostic.severity)),
        code: Some(NumberOrString::String(diagnostic.code.as_str().to_string())),
        source: Some("sinumerik".to_string()),
        message: diagnostic.message.clone(),
        ..ls_types::Diagnostic::default()
    }
}

/// The edits of a diagnostic's fix, as LSP text edits on the diagnostic's line.
pub fn fix_edits(
    item: &LineDiagnostic,
    line: &str,
    encoding: PositionEncoding,
) -> Vec<ls_types::TextEdit> {
    item.diagnostic
        .fix
        .iter()
        .flat_map(|fix| fix.edits.iter())
        .map(|edit| ls_types::TextEdit {
            range: span_to_range(item.line, line, edit.span, encoding),
            new_text: edit.new_text.clone(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utf16_counts_surrogate_pairs_as_two() {
        let line = "; ä 😀 X1";
        let byte = line.find('X').unwrap();
        assert_eq!(byte_to_character(line, byte, PositionEncoding::Utf16), 7);
        assert_eq!(
            byte_to_character(line, byte, PositionEncoding::Utf8),
            byte as u32
        );
        assert_eq!(character_to_byte(line, 7, PositionEncoding::Utf16), byte);
        // Inside the surrogate pair: the start of the emoji.
        assert_eq!(
            character_to_byte(line, 5, PositionEncoding::Utf16),
            line.find('😀').unwrap()
        );
        assert_eq!(
            character_to_byte(line, 999, PositionEncoding::Utf16),
            line.len()
        );
    }

    #[test]
    fn positions_clamp_to_the_line_and_the_document() {
        let rope = Rope::from_str("ab\r\ncd😀e\n");
        let at = |line, character, encoding| {
            position_to_char(&rope, Position::new(line, character), encoding)
        };
        assert_eq!(at(0, 99, PositionEncoding::Utf16), 2);
        assert_eq!(at(1, 4, PositionEncoding::Utf16), 4 + 3);
        assert_eq!(at(1, 3, PositionEncoding::Utf16), 4 + 2);
        assert_eq!(at(1, 4, PositionEncoding::Utf8), 4 + 2);
        assert_eq!(at(1, 6, PositionEncoding::Utf8), 4 + 3);
        assert_eq!(at(1, 7, PositionEncoding::Utf8), 4 + 4);
        assert_eq!(at(7, 0, PositionEncoding::Utf16), rope.len_chars());
    }

    #[test]
    fn the_written_notification_equals_the_lsp_types_serialization() {
        use crate::diagnostics::{Code, Diagnostic};
        let lines = ["N10 G0 Z=AC17 ; \"quoted\" ä", "N20 😀 X\t1"];
        let diagnostics = vec![
            LineDiagnostic {
                line: 0,
                diagnostic: Diagnostic::new(
                    Code::ModifierWithoutParentheses,
                    Span::new(9, 13),
                    "write `AC(17)` \"now\"\n",
                ),
            },
            LineDiagnostic {
                line: 1,
                diagnostic: Diagnostic::new(
                    Code::UnexpectedCharacter,
                    Span::new(4, 8),
                    "ünexpected",
                ),
            },
        ];
        let uri: ls_types::Uri = "file:///a%20b/c.mpf".parse().unwrap();
        for encoding in [PositionEncoding::Utf8, PositionEncoding::Utf16] {
            let array = diagnostics_json(
                &diagnostics,
                |index| Cow::Borrowed(lines[index]),
                false,
                encoding,
            );
            let message = publish_diagnostics_message(&uri, Some(7), &array);
            let header_end = message
                .windows(4)
                .position(|window| window == b"\r\n\r\n")
                .unwrap()
                + 4;
            let body = &message[header_end..];
            let header = std::str::from_utf8(&message[..header_end]).unwrap();
            assert_eq!(header, format!("Content-Length: {}\r\n\r\n", body.len()));
            let written: serde_json::Value = serde_json::from_slice(body).unwrap();
            let expected = ls_types::PublishDiagnosticsParams {
                uri: uri.clone(),
                diagnostics: diagnostics
                    .iter()
                    .map(|item| diagnostic_to_lsp(item, lines[item.line], encoding))
                    .collect(),
                version: Some(7),
            };
            assert_eq!(written["params"], serde_json::to_value(&expected).unwrap());
            assert_eq!(written["method"], "textDocument/publishDiagnostics");
        }
        // An ASCII document needs no line text: the same ranges come from the spans alone.
        let ascii_lines = ["N10 G0 Z=AC17 ; x", "N20 ?? X1"];
        let from_text = diagnostics_json(
            &diagnostics,
            |index| Cow::Borrowed(ascii_lines[index]),
            false,
            PositionEncoding::Utf16,
        );
        let from_spans = diagnostics_json(
            &diagnostics,
            |_| unreachable!("no line is read"),
            true,
            PositionEncoding::Utf16,
        );
        assert_eq!(from_text, from_spans);
    }

    #[test]
    fn utf8_is_chosen_only_when_offered() {
        assert_eq!(PositionEncoding::negotiate(None), PositionEncoding::Utf16);
        let offered = [PositionEncodingKind::UTF16, PositionEncodingKind::UTF8];
        assert_eq!(
            PositionEncoding::negotiate(Some(&offered)),
            PositionEncoding::Utf8
        );
    }
}
