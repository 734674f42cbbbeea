//! The block numbers of a document (`N10`, `:10`), as the symbol table keeps them. A CAM program has
//! one on nearly every one of its million lines, and the workspace index holds the table of every
//! open document: at 32 bytes an entry that was the largest part of the server's memory after a
//! pause in editing. Entries are kept in 8 bytes: the value in 32 bits, and in 32 more the line, the
//! column the word starts at, how much longer the word is than its letter and the value's digits
//! (leading zeros), and the main-block flag. The rare entry that does not fit is kept whole in a
//! second list.

use crate::diagnostics::Span;

/// `N10` or `:10` at the start of a block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlockNumberEntry {
    pub value: u64,
    /// `:10`, a main block.
    pub main: bool,
    pub line: usize,
    /// The whole number word, `N` or `:` included.
    pub span: Span,
}

/// The fields of [`Compact::packed`], from the lowest bit on.
const LINE_BITS: u32 = 23;
const START_BITS: u32 = 5;
const EXTRA_BITS: u32 = 3;
const START_SHIFT: u32 = LINE_BITS;
const EXTRA_SHIFT: u32 = START_SHIFT + START_BITS;
const MAIN: u32 = 1 << (EXTRA_SHIFT + EXTRA_BITS);

#[derive(Debug, Clone, Copy, PartialEq)]
struct Compact {
    value: u32,
    /// The line, the span's start, the span's length beyond the letter and the value's digits, and
    /// the main-block flag.
    packed: u32,
}

/// The number of decimal digits of `value`.
fn digits(value: u32) -> usize {
    value.checked_ilog10().map_or(1, |log| log as usize + 1)
}

/// `value` when it fits in `bits` bits.
fn fitting(value: usize, bits: u32) -> Option<u32> {
    u32::try_from(value).ok().filter(|value| *value < 1 << bits)
}

impl Compact {
    fn of(entry: &BlockNumberEntry) -> Option<Compact> {
        let value = u32::try_from(entry.value).ok()?;
        let line = fitting(entry.line, LINE_BITS)?;
        let start = fitting(entry.span.start(), START_BITS)?;
        let length = entry.span.end().checked_sub(entry.span.start())?;
        let extra = fitting(length.checked_sub(1 + digits(value))?, EXTRA_BITS)?;
        let main = if entry.main { MAIN } else { 0 };
        Some(Compact {
            value,
            packed: line | start << START_SHIFT | extra << EXTRA_SHIFT | main,
        })
    }

    fn line(&self) -> usize {
        (self.packed & ((1 << LINE_BITS) - 1)) as usize
    }

    fn entry(&self) -> BlockNumberEntry {
        let field = |shift: u32, bits: u32| ((self.packed >> shift) & ((1 << bits) - 1)) as usize;
        let start = field(START_SHIFT, START_BITS);
        let end = start + 1 + digits(self.value) + field(EXTRA_SHIFT, EXTRA_BITS);
        BlockNumberEntry {
            value: u64::from(self.value),
            main: self.packed & MAIN != 0,
            line: self.line(),
            span: Span::new(start, end),
        }
    }
}

/// Block numbers in line order, at most one a line (a block has one number).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BlockNumbers {
    compact: Vec<Compact>,
    /// The entries that do not fit in 8 bytes (a value over 32 bits, a line past 8 million, a word
    /// far into its line or with many leading zeros), in line order too.
    wide: Vec<BlockNumberEntry>,
}

impl BlockNumbers {
    /// Adds `entry`, which is on a line after every entry so far.
    pub fn push(&mut self, entry: BlockNumberEntry) {
        match Compact::of(&entry) {
            Some(compact) => self.compact.push(compact),
            None => self.wide.push(entry),
        }
    }

    pub fn len(&self) -> usize {
        self.compact.len() + self.wide.len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Every entry, in line order.
    pub fn iter(&self) -> BlockNumberIter<'_> {
        BlockNumberIter {
            compact: &self.compact,
            wide: &self.wide,
        }
    }

    /// The entries on line `line`.
    pub fn on_line(&self, line: usize) -> BlockNumberIter<'_> {
        let compact_start = self.compact.partition_point(|entry| entry.line() < line);
        let compact_end = compact_start
            + self.compact[compact_start..].partition_point(|entry| entry.line() <= line);
        let wide_start = self.wide.partition_point(|entry| entry.line < line);
        let wide_end =
            wide_start + self.wide[wide_start..].partition_point(|entry| entry.line <= line);
        BlockNumberIter {
            compact: &self.compact[compact_start..compact_end],
            wide: &self.wide[wide_start..wide_end],
        }
    }
}

/// The entries of [`BlockNumbers`], the two lists merged by line.
pub struct BlockNumberIter<'a> {
    compact: &'a [Compact],
    wide: &'a [BlockNumberEntry],
}

impl Iterator for BlockNumberIter<'_> {
    type Item = BlockNumberEntry;

    fn next(&mut self) -> Option<BlockNumberEntry> {
        let take_wide = match (self.compact.first(), self.wide.first()) {
            (None, None) => return None,
            (Some(_), None) => false,
            (None, Some(_)) => true,
            (Some(compact), Some(wide)) => wide.line < compact.line(),
        };
        if take_wide {
            let (first, rest) = self.wide.split_first()?;
            self.wide = rest;
            Some(*first)
        } else {
            let (first, rest) = self.compact.split_first()?;
            self.compact = rest;
            Some(first.entry())
        }
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let length = self.compact.len() + self.wide.len();
        (length, Some(length))
    }
}

impl<'a> IntoIterator for &'a BlockNumbers {
    type Item = BlockNumberEntry;
    type IntoIter = BlockNumberIter<'a>;

    fn into_iter(self) -> BlockNumberIter<'a> {
        self.iter()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The entry of the word `N<value>` (or `:<value>`) at `column`, with `zeros` leading zeros.
    fn entry(value: u64, line: usize, main: bool, column: usize, zeros: usize) -> BlockNumberEntry {
        BlockNumberEntry {
            value,
            main,
            line,
            span: Span::new(column, column + 1 + zeros + value.to_string().len()),
        }
    }

    #[test]
    fn entries_come_back_whole_and_in_line_order_whatever_list_holds_them() {
        let entries = [
            entry(10, 0, false, 0, 0),
            entry(u64::from(u32::MAX) + 1, 1, false, 0, 0),
            entry(20, 2, true, 3, 2),
            entry(u64::MAX, 3, true, 0, 0),
            entry(u64::from(u32::MAX), 4, true, 31, 7),
            entry(0, 5, false, 0, 0),
            entry(9, 6, false, 32, 0),
            entry(99, 7, false, 0, 8),
            entry(30, (1 << 23) - 1, false, 1, 0),
            entry(40, 1 << 23, true, 0, 0),
            entry(50, (1 << 31) + 6, true, 0, 0),
        ];
        let mut numbers = BlockNumbers::default();
        for item in entries {
            numbers.push(item);
        }
        assert_eq!(numbers.len(), entries.len());
        assert_eq!(numbers.iter().collect::<Vec<_>>(), entries.to_vec());
        assert_eq!(numbers.on_line(1).collect::<Vec<_>>(), vec![entries[1]]);
        assert_eq!(numbers.on_line(2).collect::<Vec<_>>(), vec![entries[2]]);
        assert_eq!(numbers.on_line(8).count(), 0);
        assert_eq!(
            numbers.on_line((1 << 31) + 6).collect::<Vec<_>>(),
            vec![entries[10]]
        );
        // Too large a value, column, number of zeros or line: kept whole.
        assert_eq!(numbers.wide.len(), 6);
        assert_eq!(numbers.compact.len(), 5);
    }

    #[test]
    fn a_word_shorter_than_its_value_is_kept_whole() {
        let mut numbers = BlockNumbers::default();
        let odd = BlockNumberEntry {
            value: 12345,
            main: false,
            line: 3,
            span: Span::new(4, 6),
        };
        numbers.push(odd);
        assert_eq!(numbers.iter().collect::<Vec<_>>(), vec![odd]);
        assert_eq!(numbers.wide.len(), 1);
    }

    #[test]
    fn an_entry_takes_eight_bytes() {
        assert_eq!(std::mem::size_of::<Compact>(), 8);
    }
}
