//! What a document's lines say of the whole document, read before its blocks: per line whether it
//! defines a macro or is a `PROC` header, the macros defined, and whether the document is a
//! subprogram.

use crate::analysis::document::line_source::LineSource;
use crate::analysis::program_kind::is_proc_header;
use crate::syntax::{lines, macro_defined_by};

/// A line defines a macro: every line may read differently, so the whole document is analysed again.
pub(super) const DEFINES_MACRO: u8 = 1;
/// A line is a `PROC` header: the document is a subprogram, and starts from another state.
pub(super) const PROC_HEADER: u8 = 2;

/// What a document's lines say of the whole document: the flags of each line, the macros defined
/// and whether a `PROC` header makes it a subprogram.
pub(super) struct DocumentFacts {
    pub(super) line_flags: Vec<u8>,
    pub(super) macros: Vec<String>,
    pub(super) has_proc_header: bool,
}

impl DocumentFacts {
    /// The facts of all lines of `source`: searched in its whole text when it has one, else read
    /// line by line.
    pub(super) fn of_all_lines(source: &dyn LineSource) -> DocumentFacts {
        match source.whole_text() {
            Some(text) => DocumentFacts::search(text, source.line_count()),
            None => DocumentFacts::read(source, 0, usize::MAX),
        }
    }

    /// The facts of the lines `start..end` (as far as there are lines).
    pub(super) fn read(source: &dyn LineSource, start: usize, end: usize) -> DocumentFacts {
        let mut facts = DocumentFacts {
            line_flags: Vec::with_capacity(source.line_count().min(end).saturating_sub(start)),
            macros: Vec::new(),
            has_proc_header: false,
        };
        source.for_each_line(start, &mut |index, line| {
            if index >= end {
                return false;
            }
            let flags = line_flags_of(line);
            if flags & DEFINES_MACRO != 0 {
                if let Some(name) = macro_defined_by(line) {
                    facts.macros.push(name.to_string());
                }
            }
            facts.has_proc_header |= flags & PROC_HEADER != 0;
            facts.line_flags.push(flags);
            true
        });
        facts
    }

    /// Adds the facts of the lines that follow.
    pub(super) fn extend(&mut self, later: DocumentFacts) {
        self.line_flags.extend(later.line_flags);
        self.macros.extend(later.macros);
        self.has_proc_header |= later.has_proc_header;
    }
}

impl DocumentFacts {
    /// The facts of `text`, split into `line_count` lines as [`lines::line_ranges`] splits it,
    /// found by searching it whole: a line that defines a macro holds a `D` and a `PROC` header a
    /// `P` (in either case), and almost no line of a program holds either, so only the lines around
    /// those letters are read (a search of the whole text costs a fraction of a reading by lines).
    fn search(text: &str, line_count: usize) -> DocumentFacts {
        let bytes = text.as_bytes();
        // The lines that hold one of the letters, by their start: each is read once.
        let mut flagged: Vec<(usize, u8)> = Vec::new();
        for (upper, lower) in [(b'D', b'd'), (b'P', b'p')] {
            let mut line_end = 0;
            for found in memchr::memchr2_iter(upper, lower, bytes) {
                if found < line_end {
                    continue;
                }
                let start = memchr::memrchr2(b'\n', b'\r', &bytes[..found]).map_or(0, |at| at + 1);
                line_end = memchr::memchr2(b'\n', b'\r', &bytes[found..])
                    .map_or(bytes.len(), |offset| found + offset);
                let flags = line_flags_of(&text[start..line_end]);
                if flags != 0 {
                    flagged.push((start, flags));
                }
            }
        }
        flagged.sort_unstable_by_key(|&(start, _)| start);
        flagged.dedup_by_key(|&mut (start, _)| start);
        let mut facts = DocumentFacts {
            line_flags: vec![0; line_count],
            macros: Vec::new(),
            has_proc_header: false,
        };
        let (mut counted_to, mut line) = (0, 0);
        for (start, flags) in flagged {
            line += line_breaks(bytes, counted_to, start);
            counted_to = start;
            let line_text = lines::line_ranges(&text[start..])
                .next()
                .map_or("", |(from, to)| &text[start + from..start + to]);
            if flags & DEFINES_MACRO != 0 {
                if let Some(name) = macro_defined_by(line_text) {
                    facts.macros.push(name.to_string());
                }
            }
            facts.has_proc_header |= flags & PROC_HEADER != 0;
            if let Some(slot) = facts.line_flags.get_mut(line) {
                *slot = flags;
            }
        }
        facts
    }
}

/// How many line ends (LF, CRLF, a lone CR) are in `bytes[from..to]`, where both are starts of lines.
fn line_breaks(bytes: &[u8], from: usize, to: usize) -> usize {
    memchr::memchr2_iter(b'\n', b'\r', &bytes[from..to])
        .filter(|&offset| {
            // A CR followed by an LF ends its line together with it.
            bytes[from + offset] == b'\n' || bytes.get(from + offset + 1) != Some(&b'\n')
        })
        .count()
}

/// The flags of one line ([`DEFINES_MACRO`], [`PROC_HEADER`]).
pub(super) fn line_flags_of(line: &str) -> u8 {
    let mut flags = 0;
    if macro_defined_by(line).is_some() {
        flags |= DEFINES_MACRO;
    }
    if is_proc_header(line) {
        flags |= PROC_HEADER;
    }
    flags
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::document::line_source::TextLines;

    /// The facts read line by line, which the search of the whole text must give.
    fn by_lines(text: &str) -> (Vec<u8>, Vec<String>, bool) {
        let facts = DocumentFacts::read(&TextLines::new(text), 0, usize::MAX);
        (facts.line_flags, facts.macros, facts.has_proc_header)
    }

    fn searched(text: &str) -> (Vec<u8>, Vec<String>, bool) {
        let facts = DocumentFacts::of_all_lines(&TextLines::new(text));
        (facts.line_flags, facts.macros, facts.has_proc_header)
    }

    #[test]
    fn the_search_of_the_whole_text_gives_the_facts_of_its_lines() {
        let pieces = [
            "N10 G0 X1",
            "DEFINE ABC AS G1 X2",
            "define low as m3",
            "N20 D1 T1 DEFINE LATE AS G0 DEFINE SECOND AS G1",
            "DEFINE AS",
            "DIAMON D2",
            "PROC SUB(REAL A) SAVE",
            "  proc indented",
            "\u{3000}PROC after a wide space",
            "N30 PROC not first",
            "SUPA Z0 AP=90 RP=5",
            "",
            "Grüße D",
        ];
        let breaks = ["\n", "\r\n", "\r"];
        // Every piece after every other, with every line end, and the text's end with and without one.
        let mut texts = vec![String::new(), "DEFINE A AS G0".to_string(), "\r\n\r".into()];
        for (index, first) in pieces.iter().enumerate() {
            for (other, second) in pieces.iter().enumerate() {
                let end = breaks[(index + other) % 3];
                let last = breaks[index % 3];
                texts.push(format!("{first}{end}{second}{last}{first}"));
                texts.push(format!("{second}{last}{first}{end}"));
            }
        }
        texts.push(pieces.join("\n"));
        texts.push(pieces.join("\r"));
        texts.push(pieces.join("\r\n") + "\r\n");
        for text in &texts {
            assert_eq!(searched(text), by_lines(text), "{text:?}");
        }
        let all = searched(&pieces.join("\r\n"));
        assert_eq!(all.1, ["ABC", "low", "LATE"]);
        assert!(all.2);
        assert_eq!(
            all.0.iter().filter(|flags| **flags != 0).count(),
            6,
            "{:?}",
            all.0
        );
    }
}
