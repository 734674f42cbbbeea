//! The text of a JSON string literal, turned into a rope. A `didOpen` of a 1,000,000-line program
//! carries 33 MB of text with an escaped line break every 33 bytes or so: serde_json took about 50 ms
//! to unescape it into a `String`, and building the rope from that took 40 ms more, all of which the
//! user waits for before the first diagnostics. [`LiteralReader`] unescapes the content segment by
//! segment (a search eight bytes at a time for the next quote, backslash or control character) into
//! pieces of [`PIECE_BYTES`] that go straight into a rope builder, as the bytes arrive
//! (`arriving_open.rs`); a literal that is already whole is read as two halves on two threads, whose
//! ropes are joined at the end.

use ropey::{Rope, RopeBuilder};

/// The unescaped text is handed to the rope builder in pieces of about this size: small enough to
/// stay in the cache, large enough for the builder to cut most leaves straight from them.
const PIECE_BYTES: usize = 64 * 1024;

/// Literals shorter than this are unescaped on one thread: a second one costs more than it saves.
const PARALLEL_MIN_BYTES: usize = 1 << 20;

/// The rope of the string `literal` (the JSON text of a string, quotes included), or `None` when it
/// is not a valid JSON string: a bad escape, a `\u` escape that is a lone surrogate, a control
/// character or a quote inside.
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
fn rope_of(content: &[u8]) -> Option<Rope> {
    let mut reader = LiteralReader::new();
    match reader.read(content, true) {
        Read::More(used) if used == content.len() => reader.finish(),
        _ => None,
    }
}

/// What [`LiteralReader::read`] did with the bytes it was given.
#[derive(Debug, PartialEq, Eq)]
pub enum Read {
    /// This many bytes were used; the rest (an escape cut off at the end) waits for more.
    More(usize),
    /// The closing quote was found: this many bytes were used, the quote included.
    End(usize),
    /// The bytes are not the content of a JSON string: a bad escape, a lone surrogate, a control
    /// character or bytes that are not UTF-8.
    Invalid,
}

/// Unescapes the content of a JSON string literal (after its opening quote) piece by piece, as the
/// bytes arrive, into a rope. The content is checked as JSON asks: escapes, no control characters,
/// UTF-8; so a message need not be parsed before its text is read.
pub struct LiteralReader {
    builder: RopeBuilder,
    piece: Vec<u8>,
}

impl LiteralReader {
    pub fn new() -> LiteralReader {
        LiteralReader {
            builder: RopeBuilder::new(),
            piece: Vec::with_capacity(PIECE_BYTES + 4096),
        }
    }

    /// Reads `bytes`, the next bytes of the content. With `complete`, no more bytes follow: an escape
    /// cut off at the end is invalid instead of waiting.
    pub fn read(&mut self, bytes: &[u8], complete: bool) -> Read {
        let mut at = 0;
        loop {
            let special = at + plain_run(&bytes[at..]);
            self.piece.extend_from_slice(&bytes[at..special]);
            let Some(&byte) = bytes.get(special) else {
                return Read::More(bytes.len());
            };
            match byte {
                b'"' => {
                    return match self.hand_on_piece() {
                        true => Read::End(special + 1),
                        false => Read::Invalid,
                    }
                }
                b'\\' => {}
                _ => return Read::Invalid,
            }
            let rest = &bytes[special + 1..];
            let Some(&escape) = rest.first() else {
                return self.cut_off(special, complete);
            };
            let plain = match escape {
                b'"' => b'"',
                b'\\' => b'\\',
                b'/' => b'/',
                b'b' => 0x08,
                b'f' => 0x0c,
                b'n' => b'\n',
                b'r' => b'\r',
                b't' => b'\t',
                b'u' => match unicode_escape(&rest[1..]) {
                    Escape::Character(character, used) => {
                        let mut buffer = [0u8; 4];
                        self.piece
                            .extend_from_slice(character.encode_utf8(&mut buffer).as_bytes());
                        at = special + 2 + used;
                        continue;
                    }
                    Escape::CutOff => return self.cut_off(special, complete),
                    Escape::Invalid => return Read::Invalid,
                },
                _ => return Read::Invalid,
            };
            self.piece.push(plain);
            at = special + 2;
            // A piece ends after an escape, so at a character boundary, and not between CR and LF.
            if self.piece.len() >= PIECE_BYTES && plain != b'\r' && !self.hand_on_piece() {
                return Read::Invalid;
            }
        }
    }

    /// An escape starts at `at` but its end has not arrived.
    fn cut_off(&self, at: usize, complete: bool) -> Read {
        match complete {
            true => Read::Invalid,
            false => Read::More(at),
        }
    }

    /// Hands the piece to the rope builder; false when it is not UTF-8.
    fn hand_on_piece(&mut self) -> bool {
        let Ok(text) = std::str::from_utf8(&self.piece) else {
            return false;
        };
        self.builder.append(text);
        self.piece.clear();
        true
    }

    /// The rope of everything read; `None` when the last piece is not UTF-8.
    pub fn finish(mut self) -> Option<Rope> {
        self.hand_on_piece().then(|| self.builder.finish())
    }
}

/// How many bytes at the start of `bytes` are plain content: not a quote, a backslash or a control
/// character. Eight bytes are tested at a time: a line of a program is some 30 bytes between two
/// escaped line breaks, and a test byte by byte was most of the time of reading a large text.
fn plain_run(bytes: &[u8]) -> usize {
    const ONES: u64 = 0x0101_0101_0101_0101;
    const HIGH: u64 = 0x8080_8080_8080_8080;
    let mut at = 0;
    while let Some(word) = bytes.get(at..at + 8) {
        let word = u64::from_le_bytes(word.try_into().expect("eight bytes"));
        // The high bit of a byte is set in `found` where that byte is special; a byte above a
        // special one may be marked too (a borrow), but the lowest mark is always exact.
        let quote = word ^ (ONES * u64::from(b'"'));
        let backslash = word ^ (ONES * u64::from(b'\\'));
        let found = (quote.wrapping_sub(ONES) & !quote
            | backslash.wrapping_sub(ONES) & !backslash
            | word.wrapping_sub(ONES * 0x20) & !word)
            & HIGH;
        if found != 0 {
            return at + (found.trailing_zeros() / 8) as usize;
        }
        at += 8;
    }
    at + bytes[at..]
        .iter()
        .position(|&byte| byte == b'"' || byte == b'\\' || byte < 0x20)
        .unwrap_or(bytes.len() - at)
}

/// What the four hex digits (and for a surrogate pair, the second `\uXXXX`) after a `\u` are.
enum Escape {
    /// The character and the bytes used after the `\u`.
    Character(char, usize),
    /// The escape goes on beyond the bytes there are.
    CutOff,
    Invalid,
}

/// The character of a `\u` escape whose four hex digits start `rest`, with a second `\uXXXX` for
/// a surrogate pair.
fn unicode_escape(rest: &[u8]) -> Escape {
    let Some(first) = rest.get(..4) else {
        return Escape::CutOff;
    };
    let Some(first) = hex4(first) else {
        return Escape::Invalid;
    };
    match first {
        0xD800..=0xDBFF => {
            let Some(second) = rest.get(4..10) else {
                return Escape::CutOff;
            };
            let second = match (&second[..2], hex4(&second[2..])) {
                (b"\\u", Some(second)) if (0xDC00..=0xDFFF).contains(&second) => second,
                _ => return Escape::Invalid,
            };
            let code = 0x10000 + ((first - 0xD800) << 10) + (second - 0xDC00);
            char::from_u32(code).map_or(Escape::Invalid, |character| {
                Escape::Character(character, 10)
            })
        }
        0xDC00..=0xDFFF => Escape::Invalid,
        _ => char::from_u32(first)
            .map_or(Escape::Invalid, |character| Escape::Character(character, 4)),
    }
}

fn hex4(bytes: &[u8]) -> Option<u32> {
    let digits = std::str::from_utf8(bytes).ok()?;
    if digits.len() != 4 || !digits.bytes().all(|byte| byte.is_ascii_hexdigit()) {
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

    /// The content of `literal` read in pieces of `piece` bytes, handing on each time only what the
    /// reader left and the next piece, as the arriving message does.
    fn read_in_pieces(content: &[u8], piece: usize) -> (Read, Option<Rope>) {
        let mut reader = LiteralReader::new();
        let mut left: Vec<u8> = Vec::new();
        let mut used_before = 0;
        for bytes in content.chunks(piece) {
            left.extend_from_slice(bytes);
            match reader.read(&left, false) {
                Read::More(used) => {
                    used_before += used;
                    left.drain(..used);
                }
                Read::End(used) => return (Read::End(used_before + used), reader.finish()),
                Read::Invalid => return (Read::Invalid, None),
            }
        }
        match reader.read(&left, true) {
            Read::More(used) => (Read::More(used_before + used), reader.finish()),
            Read::End(used) => (Read::End(used_before + used), reader.finish()),
            Read::Invalid => (Read::Invalid, None),
        }
    }

    #[test]
    fn a_literal_read_in_pieces_of_any_size_is_the_same_text() {
        let text = "N10 \"a\" \\ /\t\u{e4}\u{1F600}\r\nN20\u{7f}\u{1}\n".repeat(40);
        let mut content = literal(&text).into_bytes();
        // What follows the closing quote is not read.
        content.extend_from_slice(b",\"version\":1}");
        let quote_end = literal(&text).len() - 1;
        for piece in 1..=40 {
            let (read, rope) = read_in_pieces(&content[1..], piece);
            assert_eq!(read, Read::End(quote_end), "pieces of {piece}");
            assert_eq!(rope.map(|rope| rope.to_string()), Some(text.clone()));
        }
        // Escapes serde_json does not write, cut at every place.
        let escapes = br#"\u00e4\/\b\f\ud83d\ude00""#;
        for piece in 1..=escapes.len() {
            let (read, rope) = read_in_pieces(escapes, piece);
            assert_eq!(read, Read::End(escapes.len()));
            assert_eq!(
                rope.map(|rope| rope.to_string()).as_deref(),
                Some("\u{e4}/\u{8}\u{c}\u{1F600}")
            );
        }
    }

    #[test]
    fn control_characters_bad_escapes_and_bytes_that_are_not_utf8_are_invalid() {
        for content in [
            &b"N10\nX1\""[..],
            b"tab\tinside\"",
            b"bad \\x\"",
            b"lone \\ud800 x\"",
            b"lone \\ud800\\u0041\"",
            b"low \\udc00\"",
            b"\xff\xfe not UTF-8\"",
            b"cut \\u12",
            b"cut \\",
        ] {
            for piece in [1, 2, 3, content.len()] {
                assert_eq!(
                    read_in_pieces(content, piece).0,
                    Read::Invalid,
                    "{content:?}"
                );
            }
        }
        // Without the closing quote the text goes on: all of it was used.
        assert_eq!(read_in_pieces(b"N10 X1", 2).0, Read::More(6));
        // The eight-byte test finds specials at every place in a word, after plain bytes of any kind.
        for at in 0..20 {
            for special in [b'"', b'\\', b'\n', 0x1f, 0] {
                let mut bytes = "\u{e4}".repeat(10).into_bytes();
                bytes.extend_from_slice(&b"abcdefghijklmnopqrstuvwxyz"[..at]);
                let position = bytes.len();
                bytes.push(special);
                bytes.extend_from_slice(b"xyz \x7f");
                assert_eq!(plain_run(&bytes), position, "{special} after {at}");
            }
        }
        assert_eq!(plain_run(b"\x20\x7f\x80\xff!#[]~ plain"), 15);
    }
}
