//! The state of a document's analysis: `DocumentAnalysis` (the findings, the line flags, the
//! checkpoints of the modal state) with its construction, its updates' entry point and what it
//! answers without reading the text. Reading the text is in `first_analysis.rs` (the whole document),
//! `incremental.rs` (after an edit) and `pass.rs` (one forward pass).

use crate::analysis::document::line_source::LineSource;
use crate::analysis::engine::snapshot::EngineSnapshot;
use crate::analysis::program_kind::ProgramKind;
use crate::config::MachineConfig;
use crate::diagnostics::LineDiagnostic;
use crate::syntax::structure::StructureChecker;
use crate::syntax::SyntaxContext;
use std::ops::Range;
use std::sync::Arc;

/// Lines between two checkpoints of the modal state. A hover replays at most this many blocks, and an
/// edit whose effect ends reads on to the next checkpoint; memory is one modal state per interval.
/// Against 512, 256 halves the instructions of a hover's block report and takes a third off those of
/// an edit, for 0.05 % more in the first analysis (`docs/performance.md`, "fourth pass").
pub const CHECKPOINT_INTERVAL: usize = 256;

// The sizes below are those of when checkpoints were every 512 lines: the interval was halved for
// hovers and edits, not to change how a document is first read or when an update may stop.

/// A document is analysed on two threads when each half has at least this many lines (8,192): below,
/// the second thread's start costs more than it saves.
pub(super) const PARALLEL_HALF_MIN_LINES: usize = 32 * CHECKPOINT_INTERVAL;
/// The blocks read for the guess of the state in the middle of a document: from its start, and
/// before the middle (1,024 each).
pub(super) const GUESS_HEAD_LINES: usize = 4 * CHECKPOINT_INTERVAL;
pub(super) const GUESS_TAIL_LINES: usize = 4 * CHECKPOINT_INTERVAL;

/// An update may be interrupted once it has read this many lines (32,768): shorter ones finish within
/// milliseconds, and stopping them would only add work.
pub const INTERRUPTIBLE_AFTER_LINES: usize = 128 * CHECKPOINT_INTERVAL;

/// The state before one line: where the analysis can start again.
#[derive(Debug, Clone)]
pub(super) struct Checkpoint {
    pub(super) line: usize,
    /// Shared, so that an edit that moves every later position carries the checkpoints after it
    /// over to the new list without copying each snapshot's vectors (a third of such an edit's time
    /// when they were copied).
    pub(super) engine: Arc<EngineSnapshot>,
    pub(super) structure: StructureChecker,
}

/// The analysis of a document.
pub struct DocumentAnalysis {
    pub(super) config: Arc<MachineConfig>,
    pub(super) kind: ProgramKind,
    /// The parser's view of the configuration, with the macros the document defines.
    pub(super) context: SyntaxContext,
    /// Whether the document starts from a caller's state (a subprogram, or a `PROC` header).
    pub(super) subprogram: bool,
    /// Per line: [`DEFINES_MACRO`], [`PROC_HEADER`].
    pub(super) line_flags: Vec<u8>,
    /// Sorted by line; the first is always line 0.
    pub(super) checkpoints: Vec<Checkpoint>,
    /// The findings of single lines (syntax, structure, semantics), sorted by line and column.
    pub(super) body: Vec<LineDiagnostic>,
    /// Per line: the axes its block reads absolutely (see [`position_reads_of`]).
    pub(super) position_reads: Vec<u8>,
    /// The findings made at the end of the program (structures never closed), at their lines.
    pub(super) tail: Vec<LineDiagnostic>,
    /// `body` and `tail` together, sorted as a from-scratch analysis sorts them, when `tail` is not
    /// empty.
    pub(super) combined: Option<Vec<LineDiagnostic>>,
    /// How many lines the last update or analysis read, for benchmarks and tests.
    pub(super) lines_read: usize,
    /// Lines an interrupted update left unread (the numbering of the text it read): from the first
    /// line it did not read to the end of what it had to read. Until the next update reads them, the
    /// findings and checkpoints from there on are those of before that update.
    pub(super) unread: Option<Range<usize>>,
}

impl DocumentAnalysis {
    /// An analysis of nothing yet, to be filled by one of the from-scratch readings.
    pub(super) fn empty(config: Arc<MachineConfig>, kind: ProgramKind) -> DocumentAnalysis {
        let context = SyntaxContext::new(&config);
        DocumentAnalysis {
            config,
            kind,
            context,
            subprogram: false,
            line_flags: Vec::new(),
            position_reads: Vec::new(),
            checkpoints: Vec::new(),
            body: Vec::new(),
            tail: Vec::new(),
            combined: None,
            lines_read: 0,
            unread: None,
        }
    }

    /// Analyses the whole document.
    pub fn new(
        source: &dyn LineSource,
        config: Arc<MachineConfig>,
        kind: ProgramKind,
    ) -> DocumentAnalysis {
        let mut analysis = DocumentAnalysis::empty(config, kind);
        analysis.recompute(source);
        analysis
    }

    /// Analyses the whole document like [`DocumentAnalysis::new`], reading the second half on another
    /// thread from `helper_source`, which must give the same lines as `source`.
    pub fn new_in_parallel(
        source: &dyn LineSource,
        helper_source: &mut (dyn LineSource + Send),
        config: Arc<MachineConfig>,
        kind: ProgramKind,
    ) -> DocumentAnalysis {
        let mut analysis = DocumentAnalysis::empty(config, kind);
        analysis.recompute_in_parallel(source, helper_source);
        analysis
    }

    /// The text changed: lines `first_line .. first_line + removed` of the old text were replaced by
    /// the `inserted` lines now at `first_line .. first_line + inserted` of `source`. A range that does
    /// not fit the old and new line counts makes the whole document be analysed again.
    pub fn update(
        &mut self,
        source: &dyn LineSource,
        first_line: usize,
        removed: usize,
        inserted: usize,
    ) {
        self.update_interruptible(source, first_line, removed, inserted, &|| false);
    }

    /// Whether the analysis describes the whole text it was last given: false after an interrupted
    /// update, until the next update.
    pub fn is_complete(&self) -> bool {
        self.unread.is_none()
    }

    /// How many lines the last update (or the first analysis) read: the cost of an edit.
    pub fn lines_read_by_last_update(&self) -> usize {
        self.lines_read
    }

    /// The configuration this document is analysed with.
    pub fn config(&self) -> &Arc<MachineConfig> {
        &self.config
    }

    /// Whether the document is a main program or a subprogram.
    pub fn kind(&self) -> ProgramKind {
        self.kind
    }

    /// Every diagnostic of the document, sorted by line and column, severities configured.
    pub fn diagnostics(&self) -> &[LineDiagnostic] {
        self.combined.as_deref().unwrap_or(&self.body)
    }

    /// The nearest checkpoint at or before `line`.
    pub(super) fn checkpoint_before(&self, line: usize) -> &Checkpoint {
        let index = self
            .checkpoints
            .partition_point(|checkpoint| checkpoint.line <= line);
        &self.checkpoints[index.saturating_sub(1)]
    }

    /// Joins the findings of single lines and those of the end of the program, in the order of a
    /// from-scratch analysis: by line and column, end-of-program findings after the others. Without
    /// end-of-program findings (the common case) nothing is copied.
    pub(super) fn combine(&mut self) {
        // S180 is reported once per axis and file, with the count of its blocks: a fact of the whole
        // document, worked out here from the findings of every line.
        let axes = crate::syntax::unconfigured_axes::any(&self.body);
        self.combined = (!self.tail.is_empty() || axes).then(|| {
            let mut combined = self.body.clone();
            combined.extend(self.tail.iter().cloned());
            combined.sort_by_key(|item| (item.line, item.diagnostic.span.start()));
            crate::syntax::unconfigured_axes::summarize(&mut combined);
            combined
        });
    }
}
