//! The text of a `didOpen` becomes its rope after the first diagnostics are on their way: the first
//! analysis reads the string itself (`analysis::document::FlatLines`), and the rope of 33 MB, which
//! takes 15-30 ms to build, is built afterwards ([`rope_from_string`]), from the end of the string
//! while the string shrinks, so the text is never held twice (`docs/performance.md`).

use ropey::Rope;

/// Bytes of the string a rope is built from at a time: the rope grows by this much while the string
/// shrinks by as much.
const PIECE_BYTES: usize = 4 << 20;

/// The rope of `text`, built from its end in pieces that end after a line feed, the string's memory
/// given back after each piece. The result is the rope `Rope::from_str` gives.
pub fn rope_from_string(mut text: String) -> Rope {
    let mut rope = Rope::new();
    while !text.is_empty() {
        let cut = piece_start(&text);
        let mut piece = Rope::from_str(&text[cut..]);
        piece.append(rope);
        rope = piece;
        text.truncate(cut);
        text.shrink_to_fit();
    }
    rope
}

/// Where the last piece of `text` starts: after the last line feed at least [`PIECE_BYTES`] from the
/// end (a CRLF is never split), or at the start.
fn piece_start(text: &str) -> usize {
    let Some(target) = text.len().checked_sub(PIECE_BYTES) else {
        return 0;
    };
    memchr::memrchr(b'\n', &text.as_bytes()[..=target]).map_or(0, |line_feed| line_feed + 1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::document::test_texts::{long_text, TEXTS};

    #[test]
    fn the_rope_built_from_the_end_is_the_rope_of_the_text() {
        for text in TEXTS {
            assert_eq!(rope_from_string(text.to_string()), Rope::from_str(text));
        }
        // Over several pieces, with a CRLF right at a piece's edge somewhere.
        let text = long_text(900_000);
        assert!(text.len() > 2 * PIECE_BYTES);
        let rope = rope_from_string(text.clone());
        assert_eq!(rope, Rope::from_str(&text));
        assert_eq!(rope.len_lines(), Rope::from_str(&text).len_lines());
        // One long line without a line feed is one piece.
        let line = "X1 ".repeat(PIECE_BYTES);
        assert_eq!(rope_from_string(line.clone()), Rope::from_str(&line));
    }
}
