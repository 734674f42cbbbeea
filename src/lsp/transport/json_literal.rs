//! A JSON string literal of megabytes, checked and unescaped in two passes that read it eight bytes at
//! a time: the text of a large `didOpen` (`open_in_place.rs`). serde_json checks such a literal a
//! byte at a time, and the text of a program has an escape on every line (its `\n`), where a search
//! for the next backslash by a library call costs more than the line; here a word without anything
//! special in it is passed (checking) or moved (unescaping) in one step.

/// Eight copies of one byte, and the high bit of each byte of a word.
const ONES: u64 = 0x0101_0101_0101_0101;
const HIGH_BITS: u64 = 0x8080_8080_8080_8080;
const QUOTES: u64 = ONES * b'"' as u64;
const BACKSLASHES: u64 = ONES * b'\\' as u64;

/// The high bit of each byte of `word` that is below `limit` (at most 128). A byte that is below
/// borrows from the one above it, which may then be marked too, so only the lowest mark is exact:
/// the callers use only the lowest.
fn bytes_below(word: u64, limit: u8) -> u64 {
    word.wrapping_sub(ONES * limit as u64) & !word & HIGH_BITS
}

/// The high bit of each byte of `word` that is zero (the lowest mark exact, as above).
fn zero_bytes(word: u64) -> u64 {
    bytes_below(word, 1)
}

/// The eight bytes at `index` as a word, the first in its lowest byte; `None` near the end.
fn word_at(bytes: &[u8], index: usize) -> Option<u64> {
    let eight = bytes.get(index..index.checked_add(8)?)?;
    Some(u64::from_le_bytes(eight.try_into().ok()?))
}

/// A literal that JSON allows, as [`check_string`] found it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CheckedString {
    /// The index of the closing quote.
    pub end: usize,
}

/// Why a literal is not a string JSON allows (or one a Rust string cannot hold).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StringProblem {
    /// Not JSON: a raw control character, an escape JSON does not have, bytes that are not UTF-8, or
    /// no closing quote.
    NotJson,
    /// A `\u` escape of half a surrogate pair: JSON (as serde_json reads it without making a string)
    /// lets it pass, but no string can hold it.
    LoneSurrogate,
}

/// Checks the string literal whose contents start at `start` (after its opening quote) the way
/// serde_json checks a string it makes, and finds its closing quote.
pub fn check_string(bytes: &[u8], start: usize) -> Result<CheckedString, StringProblem> {
    let mut index = start;
    // The high bits of every word read: whether anything but ASCII may be in the literal.
    let mut seen = 0u64;
    loop {
        while let Some(word) = word_at(bytes, index) {
            let special = zero_bytes(word ^ QUOTES)
                | zero_bytes(word ^ BACKSLASHES)
                | bytes_below(word, 0x20);
            seen |= word;
            if special != 0 {
                index += (special.trailing_zeros() / 8) as usize;
                break;
            }
            index += 8;
        }
        let Some(&byte) = bytes.get(index) else {
            return Err(StringProblem::NotJson);
        };
        seen |= u64::from(byte);
        match byte {
            b'"' => {
                // The words may have read past the quote: only then is the literal read again.
                let contents = bytes.get(start..index).unwrap_or_default();
                if seen & HIGH_BITS != 0 && std::str::from_utf8(contents).is_err() {
                    return Err(StringProblem::NotJson);
                }
                return Ok(CheckedString { end: index });
            }
            b'\\' => index += escape(bytes.get(index..).unwrap_or_default())?.1,
            0..=0x1f => return Err(StringProblem::NotJson),
            _ => index += 1,
        }
    }
}

/// The character of the escape at the start of `bytes` (a backslash) and how many bytes it takes.
fn escape(bytes: &[u8]) -> Result<(char, usize), StringProblem> {
    let character = match bytes.get(1) {
        Some(b'"') => '"',
        Some(b'\\') => '\\',
        Some(b'/') => '/',
        Some(b'b') => '\u{8}',
        Some(b'f') => '\u{c}',
        Some(b'n') => '\n',
        Some(b'r') => '\r',
        Some(b't') => '\t',
        Some(b'u') => return unicode_escape(bytes),
        _ => return Err(StringProblem::NotJson),
    };
    Ok((character, 2))
}

/// The character of the `\uXXXX` escape at the start of `bytes` (with its low half when it is the
/// high half of a surrogate pair) and how many bytes it takes.
fn unicode_escape(bytes: &[u8]) -> Result<(char, usize), StringProblem> {
    let first = hex4(bytes.get(2..6))?;
    match first {
        0xD800..=0xDBFF => {
            if bytes.get(6..8) != Some(b"\\u") {
                return Err(StringProblem::LoneSurrogate);
            }
            let second = hex4(bytes.get(8..12))?;
            if !(0xDC00..=0xDFFF).contains(&second) {
                return Err(StringProblem::LoneSurrogate);
            }
            let code = 0x10000 + ((first - 0xD800) << 10) + (second - 0xDC00);
            char::from_u32(code)
                .map(|character| (character, 12))
                .ok_or(StringProblem::NotJson)
        }
        0xDC00..=0xDFFF => Err(StringProblem::LoneSurrogate),
        _ => char::from_u32(first)
            .map(|character| (character, 6))
            .ok_or(StringProblem::NotJson),
    }
}

fn hex4(digits: Option<&[u8]>) -> Result<u32, StringProblem> {
    digits
        .ok_or(StringProblem::NotJson)?
        .iter()
        .try_fold(0u32, |value, &digit| {
            let nibble = (digit as char).to_digit(16)?;
            Some(value * 16 + nibble)
        })
        .ok_or(StringProblem::NotJson)
}

/// Unescapes the contents of the literal `bytes[start..end]`, which [`check_string`] accepted, to
/// the front of `bytes`, and returns their length. Every escape is at least as long as what it stands
/// for, so the writing never overtakes the reading; the bytes after the literal may be overwritten.
/// Given contents it did not accept, it stops at the first escape it cannot read.
pub fn unescape_checked_to_front(bytes: &mut [u8], start: usize, end: usize) -> usize {
    let end = end.min(bytes.len());
    let mut read = start.min(end);
    let mut write = 0;
    while read < end {
        // A run without a backslash moves a word at a time. A word is written whole only when all
        // of it is moved: otherwise the write could reach bytes that are still to be read.
        if let Some(word) = word_at(bytes, read) {
            let backslashes = zero_bytes(word ^ BACKSLASHES);
            let run = if backslashes == 0 {
                8
            } else {
                (backslashes.trailing_zeros() / 8) as usize
            }
            .min(end - read);
            if run == 8 {
                bytes[write..write + 8].copy_from_slice(&word.to_le_bytes());
            } else {
                bytes[write..write + run].copy_from_slice(&word.to_le_bytes()[..run]);
            }
            read += run;
            write += run;
            if run == 8 || read == end {
                continue;
            }
        } else if bytes[read] != b'\\' {
            bytes[write] = bytes[read];
            read += 1;
            write += 1;
            continue;
        }
        let Ok((character, consumed)) = escape(&bytes[read..end]) else {
            break;
        };
        let mut encoded = [0; 4];
        let encoded = character.encode_utf8(&mut encoded).as_bytes();
        bytes[write..write + encoded.len()].copy_from_slice(encoded);
        write += encoded.len();
        read += consumed;
    }
    write
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What the two passes make of `literal` (with its quotes), and serde_json's reading of it.
    fn both(literal: &[u8]) -> (Result<String, StringProblem>, Option<String>) {
        let theirs = serde_json::from_slice::<String>(literal).ok();
        let mut bytes = literal.to_vec();
        let ours = check_string(&bytes, 1).and_then(|checked| {
            if checked.end + 1 != literal.len() {
                return Err(StringProblem::NotJson);
            }
            let length = unescape_checked_to_front(&mut bytes, 1, checked.end);
            bytes.truncate(length);
            String::from_utf8(bytes).map_err(|_| StringProblem::NotJson)
        });
        (ours, theirs)
    }

    #[test]
    fn every_text_reads_as_serde_json_reads_it() {
        let texts = [
            "N10 G0 X1\nN20 G1 Z=IC(-32)\r\n",
            "quote \" backslash \\ slash / tab \t bell \u{8} feed \u{c} nul \u{0}",
            "Grüße, 中文, 🛠 and \u{1f} control",
            "",
            "\\\\\\\"\"\"\n\n\n\n\n\n\n\n\n\n",
            "12345678\n12345678\\12345678\"1234567",
        ];
        for text in texts {
            // Every offset of the literal against the words: the text after 0 to 8 letters.
            for pad in 0..9 {
                let text = format!("{}{text}", "x".repeat(pad));
                let literal = serde_json::to_vec(&text).unwrap();
                assert_eq!(both(&literal), (Ok(text.clone()), Some(text.clone())));
            }
        }
        // Escapes serde_json does not write itself: \/, \u of either letter case, a surrogate pair.
        let literal = br#""a\/b\u00e4\u00C4\ud83d\udee0 and the rest of a line""#;
        assert_eq!(both(literal).0, Ok("a/bäÄ🛠 and the rest of a line".into()));
        assert_eq!(
            both(literal).1.as_deref(),
            Some("a/bäÄ🛠 and the rest of a line")
        );
    }

    #[test]
    fn what_serde_json_refuses_is_refused() {
        let refused: [&[u8]; 9] = [
            b"\"no closing quote",
            b"\"raw\ncontrol character in a long literal\"",
            b"\"\x01\"",
            b"\"an escape \\x JSON does not have\"",
            b"\"\\u12\"",
            b"\"\\uZZZZ and more to fill a word\"",
            b"\"not UTF-8: \xff\xfe in a long literal\"",
            b"\"cut UTF-8: \xe4\xb8\"",
            b"\"ends in a backslash\\",
        ];
        for literal in refused {
            let (ours, theirs) = both(literal);
            assert_eq!(theirs, None, "{}", String::from_utf8_lossy(literal));
            assert_eq!(
                ours,
                Err(StringProblem::NotJson),
                "{}",
                String::from_utf8_lossy(literal)
            );
        }
    }

    #[test]
    fn half_a_surrogate_pair_is_told_apart() {
        for literal in [r#""\ud83d""#, r#""\udee0x""#, r#""\ud83d\u0041 and more""#] {
            assert_eq!(
                check_string(literal.as_bytes(), 1),
                Err(StringProblem::LoneSurrogate)
            );
        }
    }

    #[test]
    fn the_closing_quote_is_found_before_what_follows() {
        let body = br#""N10 X1\nN20 \"quoted\" X2\n","version":7,"more":"ab""#;
        let checked = check_string(body, 1).unwrap();
        assert_eq!(&body[checked.end..checked.end + 11], br#"","version""#);
        let mut bytes = body.to_vec();
        let length = unescape_checked_to_front(&mut bytes, 1, checked.end);
        assert_eq!(&bytes[..length], b"N10 X1\nN20 \"quoted\" X2\n");
    }
}
