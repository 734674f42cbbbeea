//! A JSON string literal of megabytes: the text of a large `didOpen` (`open_in_place.rs`). Its end
//! is found by a search for quotes, then it is checked and unescaped in one pass that reads it eight
//! bytes at a time. serde_json checks such a literal a byte at a time, and the text of a program has
//! an escape on every line (its `\n`), where a search for the next backslash by a library call costs
//! more than the line; here a word without a backslash or a control character is moved in one step.

/// Eight copies of one byte, and the high bit of each byte of a word.
const ONES: u64 = 0x0101_0101_0101_0101;
const HIGH_BITS: u64 = 0x8080_8080_8080_8080;
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

/// Why a literal is not a string JSON allows (or one a Rust string cannot hold).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StringProblem {
    /// Not JSON: a raw control character or an escape JSON does not have.
    NotJson,
    /// A `\u` escape of half a surrogate pair: JSON (as serde_json reads it without making a
    /// string) lets it pass, but no string can hold it.
    LoneSurrogate,
}

/// The index of the quote that closes the string literal whose contents start at `start` (after its
/// opening quote): the first quote after an even number of backslashes. Whether what lies between is
/// a string JSON allows is for [`unescape_to_front`] to say.
pub fn closing_quote(bytes: &[u8], start: usize) -> Option<usize> {
    let mut from = start;
    loop {
        let quote = from + memchr::memchr(b'"', bytes.get(from..)?)?;
        let backslashes = bytes[start..quote]
            .iter()
            .rev()
            .take_while(|&&byte| byte == b'\\')
            .count();
        if backslashes % 2 == 0 {
            return Some(quote);
        }
        from = quote + 1;
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

/// Unescapes the contents of the string literal `bytes[start..end]` (between its quotes, see
/// [`closing_quote`]) to the front of `bytes`, checking them as serde_json checks a string it makes,
/// and returns the text's length and whether it had half a surrogate pair (written as U+FFFD: no
/// string can hold the half; the caller drops the message). Every escape is at least as long as
/// what it stands for, so the writing never overtakes the reading; what follows the text may be
/// overwritten. Bytes that are not UTF-8 are left for the caller to find in the text, which is UTF-8
/// exactly when the literal is (escapes give whole characters, and stand between characters): the
/// text is made into a string anyway.
pub fn unescape_to_front(
    bytes: &mut [u8],
    start: usize,
    end: usize,
) -> Result<Unescaped, StringProblem> {
    let end = end.min(bytes.len());
    let mut read = start.min(end);
    let mut write = 0;
    let mut lone_surrogate = false;
    while read < end {
        // A run without a backslash or a control character moves a word at a time. A word is
        // written whole only when all of it is moved: otherwise the write could reach bytes that
        // are still to be read.
        if let Some(word) = word_at(bytes, read) {
            let special = zero_bytes(word ^ BACKSLASHES) | bytes_below(word, 0x20);
            let run = if special == 0 {
                8
            } else {
                (special.trailing_zeros() / 8) as usize
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
        } else if bytes[read] != b'\\' && bytes[read] >= 0x20 {
            bytes[write] = bytes[read];
            read += 1;
            write += 1;
            continue;
        }
        if bytes[read] < 0x20 {
            return Err(StringProblem::NotJson);
        }
        let (character, consumed) = match escape(&bytes[read..end]) {
            Ok(escaped) => escaped,
            // Kept looking: anything that is not JSON after it decides.
            Err(StringProblem::LoneSurrogate) => {
                lone_surrogate = true;
                ('\u{fffd}', 6)
            }
            Err(StringProblem::NotJson) => return Err(StringProblem::NotJson),
        };
        let mut encoded = [0; 4];
        let encoded = character.encode_utf8(&mut encoded).as_bytes();
        bytes[write..write + encoded.len()].copy_from_slice(encoded);
        write += encoded.len();
        read += consumed;
    }
    Ok(Unescaped {
        length: write,
        lone_surrogate,
    })
}

/// What [`unescape_to_front`] made of a literal that has nothing that is not JSON but bytes that may
/// not be UTF-8.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Unescaped {
    pub length: usize,
    pub lone_surrogate: bool,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What the literal's end and the unescaping make of `literal` (with its quotes), in serde_json's
    /// terms: the string, or why there is none.
    fn ours(literal: &[u8]) -> Result<String, StringProblem> {
        let mut bytes = literal.to_vec();
        let end = closing_quote(&bytes, 1).ok_or(StringProblem::NotJson)?;
        if end + 1 != literal.len() {
            return Err(StringProblem::NotJson);
        }
        let unescaped = unescape_to_front(&mut bytes, 1, end)?;
        bytes.truncate(unescaped.length);
        let text = String::from_utf8(bytes).map_err(|_| StringProblem::NotJson)?;
        match unescaped.lone_surrogate {
            true => Err(StringProblem::LoneSurrogate),
            false => Ok(text),
        }
    }

    /// serde_json's reading: the string, or whether the literal is JSON at all.
    fn theirs(literal: &[u8]) -> Result<String, StringProblem> {
        serde_json::from_slice::<String>(literal).map_err(|_| {
            match std::str::from_utf8(literal).is_ok()
                && serde_json::from_slice::<serde::de::IgnoredAny>(literal).is_ok()
            {
                true => StringProblem::LoneSurrogate,
                false => StringProblem::NotJson,
            }
        })
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
                assert_eq!(ours(&literal), Ok(text.clone()));
                assert_eq!(theirs(&literal), Ok(text.clone()));
            }
        }
        // Escapes serde_json does not write itself: \/, \u of either letter case, a surrogate pair.
        let literal = br#""a\/b\u00e4\u00C4\ud83d\udee0 and the rest of a line""#;
        assert_eq!(ours(literal), Ok("a/bäÄ🛠 and the rest of a line".into()));
        assert_eq!(ours(literal), theirs(literal));
    }

    #[test]
    fn what_serde_json_refuses_is_refused_for_the_same_reason() {
        let refused: [&[u8]; 12] = [
            b"\"raw\ncontrol character in a long literal\"",
            b"\"\x01\"",
            b"\"an escape \\x JSON does not have\"",
            b"\"\\u12\"",
            b"\"\\uZZZZ and more to fill a word\"",
            b"\"not UTF-8: \xff\xfe in a long literal\"",
            b"\"cut UTF-8: \xe4\xb8\"",
            br#""\ud83d""#,
            br#""\udee0x""#,
            br#""\ud83d\u0041 and more""#,
            // Half a pair and then something that is not JSON, or not UTF-8: not JSON.
            b"\"\\ud83d and a raw \x02 later\"",
            b"\"\\udee0 and \xff later in the literal\"",
        ];
        for literal in refused {
            let theirs = theirs(literal);
            assert!(theirs.is_err(), "{}", String::from_utf8_lossy(literal));
            assert_eq!(
                ours(literal),
                theirs,
                "{}",
                String::from_utf8_lossy(literal)
            );
        }
    }

    #[test]
    fn the_closing_quote_is_the_first_after_an_even_number_of_backslashes() {
        let body = br#""N10 X1\nN20 \"quoted\" X2\\","version":7,"more":"ab""#;
        let end = closing_quote(body, 1).unwrap();
        assert_eq!(&body[end..end + 11], br#"","version""#);
        let mut bytes = body.to_vec();
        let unescaped = unescape_to_front(&mut bytes, 1, end).unwrap();
        assert_eq!(&bytes[..unescaped.length], b"N10 X1\nN20 \"quoted\" X2\\");
        assert_eq!(closing_quote(br#""no end\""#, 1), None);
    }
}
