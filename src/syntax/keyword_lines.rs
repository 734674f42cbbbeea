//! Finding macro definitions (`DEFINE name AS ...`) and other keyword lines in a program text without
//! parsing it: a fast byte search, since every line of a large program is asked when it is opened.

/// The names defined with `DEFINE name AS ...` anywhere in `text`: a macro may be used before the line
/// that defines it is reached when it comes from a definition file, so they are collected up front.
pub fn macro_names(text: &str) -> impl Iterator<Item = &str> {
    lines_containing(text, b"DEFINE").filter_map(macro_defined_by)
}

/// The lines of `text` that contain `word` (upper case ASCII), in any letter case, each once. The
/// search jumps from one occurrence of the word's first letter to the next, so that a program without
/// the word costs a fast byte scan instead of a walk over its lines.
pub fn lines_containing<'a>(text: &'a str, word: &'static [u8]) -> impl Iterator<Item = &'a str> {
    let bytes = text.as_bytes();
    let first = word[0];
    let mut position = 0;
    std::iter::from_fn(move || {
        while position < bytes.len() {
            let offset = memchr::memchr2(first, first.to_ascii_lowercase(), &bytes[position..])?;
            let found = position + offset;
            position = found + 1;
            let matches = bytes
                .get(found..found + word.len())
                .is_some_and(|candidate| candidate.eq_ignore_ascii_case(word));
            if !matches {
                continue;
            }
            let line_start =
                memchr::memrchr2(b'\n', b'\r', &bytes[..found]).map_or(0, |end| end + 1);
            let line_end = memchr::memchr2(b'\n', b'\r', &bytes[found..])
                .map_or(bytes.len(), |offset| found + offset);
            position = line_end;
            // Both ends are ASCII line breaks or the ends of the text: character boundaries.
            return Some(&text[line_start..line_end]);
        }
        None
    })
}

/// The name a line defines with `DEFINE name AS ...`, if it defines one.
#[inline]
pub fn macro_defined_by(line: &str) -> Option<&str> {
    // Every line is asked when a document is opened, and almost none holds a `D` at all: ruling
    // those out eight bytes at a time costs less than starting the search below on each line. The
    // search is a function of its own so that this test needs none of the registers it saves.
    if !contains_letter_in_any_case(line.as_bytes(), b'd') {
        return None;
    }
    definition_in(line)
}

/// The name `line` defines, searched for in full.
#[inline(never)]
fn definition_in(line: &str) -> Option<&str> {
    let upper_position = find_ascii_case_insensitive(line, "DEFINE")?;
    let rest = line[upper_position + "DEFINE".len()..].trim_start();
    let name_end = rest
        .find(|character: char| !(character.is_ascii_alphanumeric() || character == '_'))
        .unwrap_or(rest.len());
    let name = &rest[..name_end];
    let after = rest[name_end..].trim_start();
    (!name.is_empty() && after.len() >= 2 && after.as_bytes()[..2].eq_ignore_ascii_case(b"AS"))
        .then_some(name)
}

/// Whether `bytes` hold the ASCII letter `lower` (given in lower case) in either case. Setting bit 5
/// of every byte maps exactly the upper- and the lower-case letter to `lower`, and a word of eight
/// such bytes holds `lower` when its difference from eight copies of `lower` has a zero byte.
fn contains_letter_in_any_case(bytes: &[u8], lower: u8) -> bool {
    const ONES: u64 = u64::from_ne_bytes([0x01; 8]);
    const HIGH_BITS: u64 = u64::from_ne_bytes([0x80; 8]);
    const CASE_BITS: u64 = u64::from_ne_bytes([0x20; 8]);
    let pattern = ONES * u64::from(lower);
    let holds_letter = |chunk: &[u8]| {
        let mut word = [0u8; 8];
        word.copy_from_slice(chunk);
        let difference = (u64::from_ne_bytes(word) | CASE_BITS) ^ pattern;
        difference.wrapping_sub(ONES) & !difference & HIGH_BITS != 0
    };
    if bytes.len() < 8 {
        return bytes.iter().any(|&byte| byte | 0x20 == lower);
    }
    // The last eight bytes are read as one more word, overlapping the one before, so that the rest
    // of a line needs no loop over single bytes.
    bytes.chunks_exact(8).any(holds_letter) || holds_letter(&bytes[bytes.len() - 8..])
}

/// Where `needle` (a word without `;`) first occurs in `haystack` before its comment, in any case.
fn find_ascii_case_insensitive(haystack: &str, needle: &str) -> Option<usize> {
    let code = haystack.as_bytes();
    let needle = needle.as_bytes();
    debug_assert!(!needle.contains(&b';'));
    let first = *needle.first()?;
    // Every line is searched when a document is opened, so the search jumps between the places
    // where the needle's first letter occurs instead of comparing at every byte. The same search
    // stops at the comment: most lines hold neither, and one pass over them costs half of finding
    // the comment first. A needle without `;` cannot match across the comment's start, so the
    // window may reach into the comment.
    let mut from = 0;
    while let Some(offset) = memchr::memchr3(
        b';',
        first.to_ascii_uppercase(),
        first.to_ascii_lowercase(),
        &code[from..],
    ) {
        let at = from + offset;
        if code[at] == b';' {
            return None;
        }
        if code
            .get(at..at + needle.len())
            .is_some_and(|window| window.eq_ignore_ascii_case(needle))
        {
            return Some(at);
        }
        from = at + 1;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_containing_finds_each_line_once_in_any_case_and_line_end() {
        let text = "G0 X1\r\ndefine A AS G1 ; DEFINE\rN10 Define B AS G2\nX2";
        let found: Vec<&str> = lines_containing(text, b"DEFINE").collect();
        assert_eq!(found, ["define A AS G1 ; DEFINE", "N10 Define B AS G2"]);
        assert_eq!(macro_names(text).collect::<Vec<_>>(), ["A", "B"]);
        assert_eq!(lines_containing("DEFIN", b"DEFINE").count(), 0);
    }

    #[test]
    fn the_letter_search_finds_d_in_either_case_at_every_position_only() {
        for length in 0..20 {
            for at in 0..length {
                for letter in [b'D', b'd'] {
                    let mut bytes = vec![b'X'; length];
                    bytes[at] = letter;
                    assert!(contains_letter_in_any_case(&bytes, b'd'), "{bytes:?}");
                }
            }
            // Every other pair of byte values, the neighbours of `D` and `d` and bytes above 0x7F
            // included, so that a borrow from one byte into the next cannot pass for the letter.
            let others = || (0..=255u8).filter(|byte| !matches!(byte, b'D' | b'd'));
            for first in others() {
                for second in others() {
                    let bytes: Vec<u8> = (0..length)
                        .map(|index| if index % 2 == 0 { first } else { second })
                        .collect();
                    assert!(!contains_letter_in_any_case(&bytes, b'd'), "{bytes:?}");
                }
            }
        }
    }

    #[test]
    fn a_definition_counts_only_before_the_comment() {
        assert_eq!(macro_defined_by("N5 dEfInE LIFT AS G0 Z50"), Some("LIFT"));
        assert_eq!(
            macro_defined_by("D1 DEFINE LIFT AS G0 ; DEFINE B AS"),
            Some("LIFT")
        );
        assert_eq!(macro_defined_by("G0 X1 ; DEFINE LIFT AS G0 Z50"), None);
        assert_eq!(macro_defined_by("DEFI;NE LIFT AS G0"), None);
        assert_eq!(macro_defined_by("DEFINE;"), None);
        assert_eq!(macro_defined_by("N10 D2 X5"), None);
    }
}
