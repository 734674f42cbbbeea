//! How the document analysis reads a text it does not own: `LineSource` (a rope in the server, a
//! string in tests) and `TextLines`, a whole text in memory split as the control splits blocks.

use crate::syntax::lines;
use std::borrow::Cow;

/// Read access to the lines of a document. Line `index` is returned without its line terminator.
pub trait LineSource {
    fn line_count(&self) -> usize;
    fn line(&self, index: usize) -> Cow<'_, str>;

    /// Hands the lines from `start` on to `visit`, in order, until it returns false or the lines end.
    /// A source that can walk its lines faster than by index (a rope) overrides this.
    fn for_each_line(&self, start: usize, visit: &mut dyn FnMut(usize, &str) -> bool) {
        for index in start..self.line_count() {
            if !visit(index, &self.line(index)) {
                return;
            }
        }
    }
}

/// A whole text in memory, split as the control splits blocks (LF, CRLF, lone CR).
pub struct TextLines<'a> {
    text: &'a str,
    ranges: Vec<(usize, usize)>,
}

impl<'a> TextLines<'a> {
    pub fn new(text: &'a str) -> TextLines<'a> {
        TextLines {
            text,
            ranges: lines::line_ranges(text).collect(),
        }
    }
}

impl LineSource for TextLines<'_> {
    fn line_count(&self) -> usize {
        self.ranges.len()
    }

    fn line(&self, index: usize) -> Cow<'_, str> {
        match self.ranges.get(index) {
            Some(&(start, end)) => Cow::Borrowed(&self.text[start..end]),
            None => Cow::Borrowed(""),
        }
    }

    /// Walks the line ranges directly: a full analysis reads every line twice, and a call of
    /// [`LineSource::line`] per line cost more than the slicing itself.
    fn for_each_line(&self, start: usize, visit: &mut dyn FnMut(usize, &str) -> bool) {
        let ranges = self.ranges.get(start..).unwrap_or_default();
        for (index, &(line_start, line_end)) in (start..).zip(ranges) {
            if !visit(index, &self.text[line_start..line_end]) {
                return;
            }
        }
    }
}
