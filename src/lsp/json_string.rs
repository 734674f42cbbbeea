//! The text of a JSON string literal, turned into a rope on two threads. A `didOpen` of a
//! 1,000,000-line program carries 33 MB of text with an escaped line break every 33 bytes or so:
//! serde_json took about 50 ms to unescape it into a `String`, and building the rope from that took
//! 40 ms more, all of which the user waits for before the first diagnostics. Unescaped here segment by
//! segment (a SIMD search for the next backslash) into pieces of [`PIECE_BYTES`] that go straight into
//! a rope builder, two ropes at once, joined at the end.

use ropey::{Rope, RopeBuilder};

/// The unescaped text is handed to the rope builder in pieces of about this size: small enough to
/// stay in the cache, large enough for the builder to cut most leaves straight from them.
const PIECE_BYTES: usize = 64 * 1024;

/// Literals shorter than this are unescaped on one thread: a second one costs more than it saves.
const PARALLEL_MIN_BYTES: usize = 1 << 20;

/// The rope of the string `literal` (the JSON text of a string, quotes included), or `None` when it
/// is not a valid JSON string: a bad escape, or a `\u` escape that is a lone surrogate.
pub fn rope_from_literal(literal: &str) -> Option<Rope> {
    let content = literal.strip_prefix('"')?.strip_suffix('"')?.as_bytes();
    if content.len() < PARALLEL_MIN_BYTES {
        return rope_of(content);
    }
    let middle = split_point(content);
    let (first, second) = content.split_at(middle);
    let (first, second) = std::thread::scope(|scope| {
        let second = scope.spawn(|| rope_of(second));
        (rope_of(first), second.join().ok().flatten())
    });
    let mut rope = first?;
    rope.append(second?);
    Some(rope)
}

/// A byte index near the middle of `content` where an escape of a line feed starts, so that both
/// halves are whole escapes and whole lines (a CR LF pair is not split either). A backslash after
/// a character other than a backslash always starts an escape. Without such a place: the end.
fn split_point(content: &[u8]) -> usize {
    let middle = content.len() / 2;
    memchr::memmem::find_iter(&content[middle..], b"\\n")
        .map(|offset| middle + offset)
        .find(|&index| content[index - 1] != b'\\')
        .unwrap_or(content.len())
}

/// The rope of the JSON string content `content` (between the quotes), `None` when it is not valid.
/// `content` comes from a message that was checked to be UTF-8 and JSON, so only the escapes are
/// looked at; each piece handed on is checked to be text.
fn rope_of(content: &[u8]) -> Option<Rope> {
    let mut builder = RopeBuilder::new();
    let mut piece = Vec::with_capacity(PIECE_BYTES + 4096);
    let mut rest = content;
    while let Some(backslash) = memchr::memchr(b'\\', rest) {
        piece.extend_from_slice(&rest[..backslash]);
        let escape = *rest.get(backslash + 1)?;
        rest = &rest[backslash + 2..];
        let plain = match escape {
            b'"' => b'"',
            b'\\' => b'\\',
            b'/' => b'/',
            b'b' => 0x08,
            b'f' => 0x0c,
            b'n' => b'\n',
            b'r' => b'\r',
            b't' => b'\t',
            b'u' => {
                let (character, used) = unicode_escape(rest)?;
                rest = &rest[used..];
                let mut buffer = [0u8; 4];
                piece.extend_from_slice(character.encode_utf8(&mut buffer).as_bytes());
                continue;
            }
            _ => return None,
        };
        piece.push(plain);
        // A piece ends after an escape, so at a character boundary, and not between CR and LF.
        if piece.len() >= PIECE_BYTES && plain != b'\r' {
            builder.append(std::str::from_utf8(&piece).ok()?);
            piece.clear();
        }
    }
    piece.extend_from_slice(rest);
    builder.append(std::str::from_utf8(&piece).ok()?);
    Some(builder.finish())
}

/// The character of a `\u` escape whose four hex digits start `rest`, with a second `\uXXXX` for
/// a surrogate pair; returns the character and the bytes used after the first `\u`.
fn unicode_escape(rest: &[u8]) -> Option<(char, usize)> {
    let first = hex4(rest)?;
    match first {
        0xD800..=0xDBFF => {
            if rest.get(4..6)? != b"\\u" {
                return None;
            }
            let second = hex4(&rest[6..])?;
            if !(0xDC00..=0xDFFF).contains(&second) {
                return None;
            }
            let code = 0x10000 + ((first - 0xD800) << 10) + (second - 0xDC00);
            Some((char::from_u32(code)?, 10))
        }
        0xDC00..=0xDFFF => None,
        _ => Some((char::from_u32(first)?, 4)),
    }
}

fn hex4(bytes: &[u8]) -> Option<u32> {
    let digits = std::str::from_utf8(bytes.get(..4)?).ok()?;
    if !digits.bytes().all(|byte| byte.is_ascii_hexdigit()) {
        return None;
    }
    u32::from_str_radix(digits, 16).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn literal(text: &str) -> String {
        serde_json::to_string(text).unwrap()
    }

    #[test]
    fn texts_come_back_as_serde_json_reads_them() {
        let samples = [
            String::new(),
            "N10 G0 X1\r\nN20 ; \"quoted\" \\ back/slash\tand tab\n".to_string(),
            "Umlaut \u{e4}, emoji \u{1F600}, control \u{1} and \u{7f}".to_string(),
            "N10 X1\nN20 X2\n".repeat(100_000),
            "\\n".repeat(300_000) + "\r\n" + &"\u{1F600}\n".repeat(200_000),
            // Pieces end near every CR LF pair, on one thread and on two.
            "N10 X1\r\n".repeat(50_000),
            "G1 X\u{e4}1\r\n\r".repeat(200_000),
        ];
        for text in samples {
            let rope = rope_from_literal(&literal(&text)).expect("a valid literal");
            assert_eq!(rope.to_string(), text);
            // Lines as ropey counts them in a rope built at once (a CR LF pair is one break).
            assert_eq!(rope.len_lines(), Rope::from_str(&text).len_lines());
        }
        // Escapes serde_json does not write itself.
        let rope = rope_from_literal(r#""\u00e4\/\b\f\ud83d\ude00""#).unwrap();
        assert_eq!(rope.to_string(), "\u{e4}/\u{8}\u{c}\u{1F600}");
    }

    #[test]
    fn the_halves_meet_at_a_line_feed_escape_and_not_inside_an_escaped_backslash() {
        assert_eq!(split_point(br"abc\\ndef\nghi"), 9);
        // The `\n` at 2 is a backslash (escaped) followed by an `n`.
        assert_eq!(split_point(br"a\\n"), 4, "no line feed escape: the end");
        assert_eq!(split_point(br"\\n\\n\\n"), 9);
    }

    #[test]
    fn invalid_literals_give_none() {
        for literal in [
            r#""abc"#,
            r#"abc""#,
            r#""bad \x escape""#,
            r#""lone \ud800 surrogate""#,
            r#""lone \udc00 low""#,
            r#""short \u12""#,
            r#""ends with \"#,
        ] {
            assert!(rope_from_literal(literal).is_none(), "{literal}");
        }
        let long_and_bad = format!("\"{}\\x\"", "N10\\n".repeat(400_000));
        assert!(rope_from_literal(&long_and_bad).is_none());
    }
}
