//! Reading program files from disk: a size limit, and decoding bytes to text whatever they contain.
//!
//! Programs written on the control or on old Windows PCs are often Windows-1252 (German umlauts in
//! comments), newer ones UTF-8, so the decoder tries UTF-8 first and falls back to Windows-1252.

use std::io::{self, Read};
use std::path::Path;

/// The largest file `check` reads. Spans are `u32` byte offsets, and no real part program comes near
/// this size, so a larger file is almost certainly not a program (a disk image, a log) and is refused
/// rather than read into memory.
pub const MAX_SOURCE_FILE_SIZE: u64 = 256 * 1024 * 1024;

/// Which decoding produced the text, so a caller that writes the file back can keep its encoding.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SourceEncoding {
    /// Valid UTF-8, with or without a byte order mark.
    Utf8,
    /// A UTF-8 byte order mark followed by invalid UTF-8: the file claims to be UTF-8, so it is read as
    /// UTF-8 with each invalid sequence replaced by U+FFFD.
    Utf8Lossy,
    /// Not valid UTF-8 and no byte order mark: read as Windows-1252.
    Windows1252,
}

/// The decoded text of a program file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SourceText {
    /// The text without a byte order mark.
    pub text: String,
    pub encoding: SourceEncoding,
}

const UTF8_BOM: &[u8] = b"\xEF\xBB\xBF";

/// Decodes the bytes of a program file. Never fails and never panics: every byte sequence, binary
/// garbage and NUL bytes included, gives some text for the checker to report on.
pub fn decode_source(bytes: &[u8]) -> SourceText {
    let (without_bom, had_bom) = match bytes.strip_prefix(UTF8_BOM) {
        Some(rest) => (rest, true),
        None => (bytes, false),
    };
    match std::str::from_utf8(without_bom) {
        Ok(text) => SourceText {
            text: text.to_string(),
            encoding: SourceEncoding::Utf8,
        },
        Err(_) if had_bom => SourceText {
            text: String::from_utf8_lossy(without_bom).into_owned(),
            encoding: SourceEncoding::Utf8Lossy,
        },
        Err(_) => SourceText {
            text: decode_windows_1252(bytes),
            encoding: SourceEncoding::Windows1252,
        },
    }
}

/// Windows-1252: Latin-1 except for 0x80–0x9F, which hold typographic characters. The five bytes the
/// code page leaves undefined (0x81, 0x8D, 0x8F, 0x90, 0x9D) become the C1 control characters of the
/// same value, as in the WHATWG encoding standard that browsers follow: every byte maps to a different
/// character, so nothing is lost, and the checker reports the control character where it stands.
pub fn decode_windows_1252(bytes: &[u8]) -> String {
    const HIGH_CONTROL_RANGE: [char; 32] = [
        '\u{20AC}', '\u{0081}', '\u{201A}', '\u{0192}', '\u{201E}', '\u{2026}', '\u{2020}',
        '\u{2021}', '\u{02C6}', '\u{2030}', '\u{0160}', '\u{2039}', '\u{0152}', '\u{008D}',
        '\u{017D}', '\u{008F}', '\u{0090}', '\u{2018}', '\u{2019}', '\u{201C}', '\u{201D}',
        '\u{2022}', '\u{2013}', '\u{2014}', '\u{02DC}', '\u{2122}', '\u{0161}', '\u{203A}',
        '\u{0153}', '\u{009D}', '\u{017E}', '\u{0178}',
    ];
    bytes
        .iter()
        .map(|&byte| match byte {
            0x80..=0x9F => HIGH_CONTROL_RANGE[usize::from(byte - 0x80)],
            _ => char::from(byte),
        })
        .collect()
}

/// Reads and decodes a program file, refusing files larger than [`MAX_SOURCE_FILE_SIZE`].
pub fn read_source_file(path: &Path) -> io::Result<SourceText> {
    let file = std::fs::File::open(path)?;
    let size = file.metadata()?.len();
    if size > MAX_SOURCE_FILE_SIZE {
        return Err(too_large_error(size));
    }
    // The size is checked again while reading because the metadata can lie: a file may grow in the
    // meantime, and devices or pipes report a size of 0.
    let mut bytes = Vec::with_capacity(usize::try_from(size).unwrap_or(0));
    file.take(MAX_SOURCE_FILE_SIZE + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > MAX_SOURCE_FILE_SIZE {
        return Err(too_large_error(bytes.len() as u64));
    }
    Ok(decode_source(&bytes))
}

fn too_large_error(size: u64) -> io::Error {
    io::Error::other(format!(
        "the file is too large to be a part program ({} MiB, the limit is {} MiB); it was not checked",
        size.div_ceil(1024 * 1024),
        MAX_SOURCE_FILE_SIZE / (1024 * 1024)
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utf8_is_kept_and_its_bom_dropped() {
        let decoded = decode_source("N10 G0 X10 ; Änderung\r\n".as_bytes());
        assert_eq!(decoded.text, "N10 G0 X10 ; Änderung\r\n");
        assert_eq!(decoded.encoding, SourceEncoding::Utf8);

        let decoded = decode_source(b"\xEF\xBB\xBFN10 G0\n");
        assert_eq!(decoded.text, "N10 G0\n");
        assert_eq!(decoded.encoding, SourceEncoding::Utf8);

        assert_eq!(decode_source(b"").text, "");
        assert_eq!(decode_source(UTF8_BOM).text, "");
    }

    #[test]
    fn invalid_utf8_is_read_as_windows_1252() {
        let decoded = decode_source(b"N10 G0 X10 ; \xC4nderung\r\n");
        assert_eq!(decoded.text, "N10 G0 X10 ; Änderung\r\n");
        assert_eq!(decoded.encoding, SourceEncoding::Windows1252);

        let decoded = decode_source(b"; \x80 \x84\x93\x94 \x96 \x9F \xFF \xDF");
        assert_eq!(decoded.text, "; € „“” – Ÿ ÿ ß");
    }

    #[test]
    fn undefined_windows_1252_bytes_become_c1_controls() {
        let decoded = decode_windows_1252(b"\x81\x8D\x8F\x90\x9D");
        assert_eq!(decoded, "\u{81}\u{8D}\u{8F}\u{90}\u{9D}");
    }

    #[test]
    fn every_byte_decodes_to_exactly_one_character() {
        let all_bytes: Vec<u8> = (0..=255).collect();
        let decoded = decode_windows_1252(&all_bytes);
        let characters: Vec<char> = decoded.chars().collect();
        assert_eq!(characters.len(), 256);
        let distinct: std::collections::HashSet<char> = characters.iter().copied().collect();
        assert_eq!(distinct.len(), 256);
        assert_eq!(characters[0], '\0');
        assert_eq!(characters[0x41], 'A');
        assert_eq!(characters[0xA0], '\u{A0}');
    }

    #[test]
    fn a_bom_before_invalid_utf8_keeps_utf8() {
        let decoded = decode_source(b"\xEF\xBB\xBF; \xC3\xA4 \xC4\n");
        assert_eq!(decoded.text, "; ä \u{FFFD}\n");
        assert_eq!(decoded.encoding, SourceEncoding::Utf8Lossy);
    }

    #[test]
    fn binary_garbage_decodes() {
        // A fixed pseudo-random sequence (a linear congruential generator) keeps the test repeatable.
        let mut state: u32 = 12345;
        let bytes: Vec<u8> = (0..10_000)
            .map(|_| {
                state = state.wrapping_mul(1_103_515_245).wrapping_add(12345);
                (state >> 16) as u8
            })
            .collect();
        let decoded = decode_source(&bytes);
        assert_eq!(decoded.text.chars().count(), bytes.len());
    }
}
