//! What a document's lines say of the whole document, read before its blocks: per line whether it
//! defines a macro or is a `PROC` header, the macros defined, and whether the document is a
//! subprogram.

use crate::analysis::document::line_source::LineSource;
use crate::analysis::program_kind::is_proc_header;
use crate::syntax::macro_defined_by;

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
