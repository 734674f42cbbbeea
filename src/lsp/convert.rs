//! Conversions between the core's plain values and LSP types, in one place: positions in the
//! negotiated encoding, byte spans of a line to ranges, diagnostics and their fixes.
//!
//! The core counts columns as byte offsets within a line; LSP counts UTF-16 code units (or UTF-8
//! bytes when both sides agreed on it at initialize). Every conversion clamps: a position past the
//! end of a line is the end of the line, one inside a multi-byte character is that character's start.

use crate::diagnostics::{LineDiagnostic, Severity, Span};
use ropey::Rope;
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
    fn utf8_is_chosen_only_when_offered() {
        assert_eq!(PositionEncoding::negotiate(None), PositionEncoding::Utf16);
        let offered = [PositionEncodingKind::UTF16, PositionEncodingKind::UTF8];
        assert_eq!(
            PositionEncoding::negotiate(Some(&offered)),
            PositionEncoding::Utf8
        );
    }
}
