//! `RopeLines`: an open document's rope read as the analysis reads lines (without terminators,
//! counted as the core counts them), fast when read in order.

use crate::analysis::document::line_source::LineSource;
use ropey::Rope;
use std::borrow::Cow;
use std::cell::RefCell;

/// The core's line count of a rope: ropey counts an empty line after a final line terminator (and
/// one line in an empty text), the core does not.
pub fn core_line_count(rope: &Rope) -> usize {
    let rope_lines = rope.len_lines();
    if rope.line(rope_lines - 1).len_chars() == 0 {
        rope_lines - 1
    } else {
        rope_lines
    }
}

/// A rope snapshot read by the analysis: lines without terminators, counted as the core counts them.
/// The analysis mostly reads lines in order, so the last position is kept: the next line then comes
/// from ropey's line iterator instead of a lookup from the root for every line.
pub struct RopeLines<'a> {
    rope: &'a Rope,
    line_count: usize,
    cursor: RefCell<Option<(usize, ropey::iter::Lines<'a>)>>,
}

impl<'a> RopeLines<'a> {
    pub fn new(rope: &'a Rope) -> RopeLines<'a> {
        RopeLines {
            rope,
            line_count: core_line_count(rope),
            cursor: RefCell::new(None),
        }
    }
}

impl LineSource for RopeLines<'_> {
    fn line_count(&self) -> usize {
        self.line_count
    }

    fn line(&self, index: usize) -> Cow<'_, str> {
        if index >= self.line_count {
            return Cow::Borrowed("");
        }
        let mut cursor = self.cursor.borrow_mut();
        let line = match cursor.as_mut() {
            Some((next, lines)) if *next == index => {
                *next += 1;
                lines.next()
            }
            _ => {
                let mut lines = self.rope.lines_at(index);
                let line = lines.next();
                *cursor = Some((index + 1, lines));
                line
            }
        };
        let Some(line) = line else {
            return Cow::Borrowed("");
        };
        // Most lines lie within one chunk of the rope and are borrowed as they are.
        match line.as_str() {
            Some(text) => Cow::Borrowed(strip_terminator(text)),
            None => {
                let mut text = line.to_string();
                let length = strip_terminator(&text).len();
                text.truncate(length);
                Cow::Owned(text)
            }
        }
    }

    fn for_each_line(&self, start: usize, visit: &mut dyn FnMut(usize, &str) -> bool) {
        self.scan_lines(start, visit);
    }
}

impl RopeLines<'_> {
    /// Walks the lines from `start` on by scanning the rope's chunks for terminators, which is much
    /// faster than ropey's line iterator (that one searches the line breaks of each line anew). A
    /// line that spans chunks is gathered in a buffer; ropey never splits a CRLF between chunks, but
    /// a CR at a chunk's end is still checked against the next chunk's first byte.
    fn scan_lines(&self, start: usize, visit: &mut dyn FnMut(usize, &str) -> bool) {
        if start >= self.line_count {
            return;
        }
        let line_start = self.rope.line_to_byte(start);
        let (chunks, chunk_start, _, _) = self.rope.chunks_at_byte(line_start);
        let mut skip = line_start - chunk_start;
        let mut index = start;
        let mut carry = String::new();
        // The previous chunk ended in CR: a LF at the start of this one belongs to it.
        let mut after_cr = false;
        for chunk in chunks {
            let bytes = &chunk.as_bytes()[skip..];
            let text = &chunk[skip..];
            skip = 0;
            let mut position = 0;
            if after_cr && bytes.first() == Some(&b'\n') {
                position = 1;
            }
            after_cr = false;
            while let Some(offset) = memchr::memchr2(b'\n', b'\r', &bytes[position..]) {
                let end = position + offset;
                let line = if carry.is_empty() {
                    &text[position..end]
                } else {
                    carry.push_str(&text[position..end]);
                    carry.as_str()
                };
                if !visit(index, line) {
                    return;
                }
                carry.clear();
                index += 1;
                if index >= self.line_count {
                    return;
                }
                position = end + 1;
                if bytes[end] == b'\r' {
                    match bytes.get(position) {
                        Some(b'\n') => position += 1,
                        Some(_) => {}
                        None => after_cr = true,
                    }
                }
            }
            carry.push_str(&text[position..]);
        }
        // The last line, without a terminator after it.
        if !carry.is_empty() && index < self.line_count {
            visit(index, &carry);
        }
    }
}

/// A line's text without its LF, CRLF or CR.
fn strip_terminator(line: &str) -> &str {
    let line = line.strip_suffix('\n').unwrap_or(line);
    line.strip_suffix('\r').unwrap_or(line)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(text: &str) -> Vec<String> {
        let rope = Rope::from_str(text);
        let source = RopeLines::new(&rope);
        (0..source.line_count())
            .map(|index| source.line(index).into_owned())
            .collect()
    }

    fn scanned_lines(text: &str, start: usize) -> Vec<String> {
        let rope = Rope::from_str(text);
        let source = RopeLines::new(&rope);
        let mut lines = Vec::new();
        source.for_each_line(start, &mut |index, line| {
            assert_eq!(index, start + lines.len());
            lines.push(line.to_string());
            true
        });
        lines
    }

    #[test]
    fn scanning_chunks_gives_the_lines_of_the_core_also_across_chunk_borders() {
        // Long lines and many short ones, so that lines and CRLFs fall on the borders of ropey's
        // chunks (about 1 kB each), with every kind of terminator.
        let mut text = String::new();
        for index in 0..3000 {
            text.push_str(&"X".repeat(index % 1500));
            text.push_str(["\n", "\r\n", "\r", "\r\r\n"][index % 4]);
            if index % 7 == 0 {
                text.push_str("\u{e4}\u{1f600}");
            }
        }
        text.push_str("last line without terminator");
        let expected: Vec<String> = crate::syntax::lines::line_ranges(&text)
            .map(|(start, end)| text[start..end].to_string())
            .collect();
        for start in [0, 1, 17, 1499, expected.len() - 1, expected.len()] {
            assert_eq!(
                scanned_lines(&text, start),
                expected[start..],
                "from {start}"
            );
        }
        let mut seen = 0;
        let rope = Rope::from_str(&text);
        RopeLines::new(&rope).for_each_line(5, &mut |_, _| {
            seen += 1;
            seen < 3
        });
        assert_eq!(seen, 3, "the walk stops when the visitor says so");
    }

    #[test]
    fn lines_split_like_the_core() {
        for text in [
            "",
            "a",
            "a\n",
            "a\nb\r\nc\rd",
            "\r\r",
            "a\n\n",
            "x\u{c}y\u{2028}z",
        ] {
            let expected: Vec<String> = crate::syntax::lines::line_ranges(text)
                .map(|(start, end)| text[start..end].to_string())
                .collect();
            assert_eq!(lines(text), expected, "{text:?}");
            assert_eq!(scanned_lines(text, 0), expected, "{text:?}");
        }
    }
}
