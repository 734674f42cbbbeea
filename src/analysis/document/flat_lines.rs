//! `FlatLines`: a whole text in memory read as lines without an index of every line. The server's
//! first analysis of a just-opened document reads its string through it, before the document's rope
//! is built (`docs/performance.md`).

use crate::analysis::document::line_source::LineSource;
use crate::syntax::lines::line_ranges;
use std::borrow::Cow;
use std::cell::RefCell;

/// Bytes per stretch of whole lines whose lines are counted at once.
const STRETCH_BYTES: usize = 64 * 1024;

/// The lines of a whole text in memory, split as the control splits blocks (LF, CRLF, lone CR), as
/// the rope's lines are. Unlike `TextLines` it does not keep every line's range (16 MB for a million
/// lines, and a walk over every line before the analysis starts): it counts the lines of stretches
/// of about 64 KB with SIMD, keeps where each stretch starts, and the place of the last line read,
/// for reading in order.
#[derive(Clone)]
pub struct FlatLines<'a> {
    text: &'a str,
    line_count: usize,
    /// For each stretch of whole lines, the index of its first line and the byte where it starts.
    stretches: Vec<(usize, usize)>,
    /// The next line's index and where it starts.
    cursor: RefCell<(usize, usize)>,
}

impl<'a> FlatLines<'a> {
    pub fn new(text: &'a str) -> FlatLines<'a> {
        let bytes = text.as_bytes();
        let mut stretches = Vec::with_capacity(bytes.len() / STRETCH_BYTES + 1);
        let (mut line, mut start) = (0, 0);
        while start < bytes.len() {
            // A stretch ends after a line feed, so a CRLF is never split.
            let target = (start + STRETCH_BYTES).min(bytes.len());
            let end = memchr::memchr(b'\n', &bytes[target..])
                .map_or(bytes.len(), |offset| target + offset + 1);
            let stretch = &bytes[start..end];
            stretches.push((line, start));
            line += if memchr::memchr(b'\r', stretch).is_none() {
                memchr::memchr_iter(b'\n', stretch).count() + usize::from(!stretch.ends_with(b"\n"))
            } else {
                line_ranges(&text[start..end]).count()
            };
            start = end;
        }
        FlatLines {
            text,
            line_count: line,
            stretches,
            cursor: RefCell::new((0, 0)),
        }
    }

    /// The start of line `index` (below the line count), from the cursor when it is at or before
    /// the line in the same stretch, else from the start of the line's stretch.
    fn start_of(&self, index: usize) -> usize {
        let (cursor_line, cursor_start) = *self.cursor.borrow();
        let stretch = self
            .stretches
            .partition_point(|&(first_line, _)| first_line <= index)
            .saturating_sub(1);
        let (first_line, first_start) = self.stretches.get(stretch).copied().unwrap_or((0, 0));
        let (mut line, mut start) = if first_line <= cursor_line && cursor_line <= index {
            (cursor_line, cursor_start)
        } else {
            (first_line, first_start)
        };
        let bytes = self.text.as_bytes();
        while line < index {
            start = match memchr::memchr2(b'\n', b'\r', &bytes[start..]) {
                Some(offset) => start + offset + terminator_length(&bytes[start + offset..]),
                None => bytes.len(),
            };
            line += 1;
        }
        start
    }
}

fn terminator_length(rest: &[u8]) -> usize {
    match rest {
        [b'\r', b'\n', ..] => 2,
        [b'\r' | b'\n', ..] => 1,
        _ => 0,
    }
}

impl LineSource for FlatLines<'_> {
    fn line_count(&self) -> usize {
        self.line_count
    }

    fn line(&self, index: usize) -> Cow<'_, str> {
        if index >= self.line_count {
            return Cow::Borrowed("");
        }
        let start = self.start_of(index);
        let (_, end) = line_ranges(&self.text[start..]).next().unwrap_or((0, 0));
        let after = start + end;
        *self.cursor.borrow_mut() = (
            index + 1,
            after + terminator_length(&self.text.as_bytes()[after..]),
        );
        Cow::Borrowed(&self.text[start..after])
    }

    fn for_each_line(&self, start: usize, visit: &mut dyn FnMut(usize, &str) -> bool) {
        if start >= self.line_count {
            return;
        }
        let from = self.start_of(start);
        for (index, (line_start, line_end)) in (start..).zip(line_ranges(&self.text[from..])) {
            if !visit(index, &self.text[from + line_start..from + line_end]) {
                return;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::document::line_source::TextLines;
    use crate::analysis::document::rope_lines::RopeLines;
    use crate::analysis::document::test_texts::{long_text, TEXTS};

    fn same_lines(text: &str) {
        let flat = FlatLines::new(text);
        let expected = TextLines::new(text);
        assert_eq!(flat.line_count(), expected.line_count(), "{text:?}");
        let mut walked = Vec::new();
        flat.for_each_line(0, &mut |index, line| {
            walked.push((index, line.to_string()));
            true
        });
        let wanted: Vec<(usize, String)> = (0..expected.line_count())
            .map(|index| (index, expected.line(index).into_owned()))
            .collect();
        assert_eq!(walked, wanted);
        // In order, backwards, and from every start.
        for index in (0..expected.line_count()).chain((0..expected.line_count()).rev()) {
            assert_eq!(flat.line(index), expected.line(index), "line {index}");
        }
        for start in [0, 1, 255, 256, 257, 700, 5000, expected.line_count()] {
            let mut first = None;
            flat.for_each_line(start, &mut |index, line| {
                first = Some((index, line.to_string()));
                false
            });
            let wanted =
                (start < expected.line_count()).then(|| (start, expected.line(start).into_owned()));
            assert_eq!(first, wanted, "from {start}");
        }
        // The same lines as the rope's, which the analysis reads after the first one.
        let rope = ropey::Rope::from_str(text);
        assert_eq!(flat.line_count(), RopeLines::new(&rope).line_count());
    }

    #[test]
    fn flat_lines_are_the_lines_of_the_text() {
        for text in TEXTS {
            same_lines(text);
        }
        same_lines(&long_text(1000));
        // Over many stretches, with and without carriage returns.
        same_lines(&long_text(40_000));
        same_lines(&long_text(40_000).replace('\r', ""));
    }
}
