//! The block numbers of a document (`N10`, `:10`), as the symbol table keeps them. A CAM program has
//! one on nearly every one of its million lines, and the workspace index holds the table of every
//! open document: at 32 bytes an entry that was the largest part of the server's memory after a
//! pause in editing. Entries are kept in 16 bytes (the value in 32 bits, the line and the main-block
//! flag in 32 more, the span); the rare one that does not fit is kept whole in a second list.

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

/// The flag of a main block in [`Compact::line_and_main`].
const MAIN: u32 = 1 << 31;

#[derive(Debug, Clone, Copy, PartialEq)]
struct Compact {
    value: u32,
    line_and_main: u32,
    span: Span,
}

impl Compact {
    fn of(entry: &BlockNumberEntry) -> Option<Compact> {
        let value = u32::try_from(entry.value).ok()?;
        let line = u32::try_from(entry.line)
            .ok()
            .filter(|line| line & MAIN == 0)?;
        Some(Compact {
            value,
            line_and_main: line | if entry.main { MAIN } else { 0 },
            span: entry.span,
        })
    }

    fn line(&self) -> usize {
        (self.line_and_main & !MAIN) as usize
    }

    fn entry(&self) -> BlockNumberEntry {
        BlockNumberEntry {
            value: u64::from(self.value),
            main: self.line_and_main & MAIN != 0,
            line: self.line(),
            span: self.span,
        }
    }
}

/// Block numbers in line order, at most one a line (a block has one number).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BlockNumbers {
    compact: Vec<Compact>,
    /// The entries whose value or line does not fit in 32 bits, in line order too.
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

    fn entry(value: u64, line: usize, main: bool) -> BlockNumberEntry {
        BlockNumberEntry {
            value,
            main,
            line,
            span: Span::new(line % 7, line % 7 + 4),
        }
    }

    #[test]
    fn entries_come_back_whole_and_in_line_order_whatever_list_holds_them() {
        let entries = [
            entry(10, 0, false),
            entry(u64::from(u32::MAX) + 1, 1, false),
            entry(20, 2, true),
            entry(u64::MAX, 3, true),
            entry(u64::from(u32::MAX), 4, true),
            entry(30, (1 << 31) + 5, false),
            entry(40, (1 << 31) + 6, true),
        ];
        let mut numbers = BlockNumbers::default();
        for item in entries {
            numbers.push(item);
        }
        assert_eq!(numbers.len(), entries.len());
        assert_eq!(numbers.iter().collect::<Vec<_>>(), entries.to_vec());
        assert_eq!(numbers.on_line(1).collect::<Vec<_>>(), vec![entries[1]]);
        assert_eq!(numbers.on_line(2).collect::<Vec<_>>(), vec![entries[2]]);
        assert_eq!(numbers.on_line(5).count(), 0);
        assert_eq!(
            numbers.on_line((1 << 31) + 6).collect::<Vec<_>>(),
            vec![entries[6]]
        );
        assert!(numbers.wide.len() == 4 && numbers.compact.len() == 3);
    }

    #[test]
    fn an_entry_takes_sixteen_bytes() {
        assert_eq!(std::mem::size_of::<Compact>(), 16);
    }
}
