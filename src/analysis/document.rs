//! The analysis of one open document, kept up to date as the text changes: what the language server
//! asks of the core. The text itself stays with the caller (a rope in the server, a string in tests)
//! and is read through [`LineSource`]; this type keeps only what it derived from it: the diagnostics,
//! a few flags per line, and checkpoints of the modal state every [`CHECKPOINT_INTERVAL`] lines.
//!
//! An edit re-reads the lines from the checkpoint before it and stops at the first later checkpoint
//! whose state the new pass reproduces exactly: from there on every block resolves as before, so the
//! old diagnostics are kept, moved by the number of lines inserted or removed. A block's report (for a
//! hover) replays at most one interval from the nearest checkpoint. The result is always the one a
//! from-scratch analysis of the same text gives (tested on random edits).
//!
//! A long update (an edit that changes how the whole rest of a program reads) can be interrupted by
//! a newer edit: it keeps what it read and leaves the rest to the next update, which reads it with
//! the new edit's lines. The first analysis of a large document reads its two halves on two threads
//! (see [`DocumentAnalysis::new_in_parallel`]).

use crate::analysis::engine::{Engine, EngineSnapshot};
use crate::analysis::position_reads::{
    position_reads as position_reads_of, shifted_axes, READS_ALL,
};
pub use crate::analysis::resolution::{ResolutionMode, WordResolution};
use crate::analysis::state::{ModalState, Pole};
use crate::analysis::{is_proc_header, Move, ProgramKind};
use crate::config::MachineConfig;
use crate::diagnostics::{Diagnostic, LineDiagnostic};
use crate::syntax::structure::StructureChecker;
use crate::syntax::{lines, macro_defined_by, Block, LineParser, SyntaxContext};
use std::borrow::Cow;
use std::ops::Range;
use std::sync::Arc;

/// Lines between two checkpoints of the modal state. A hover replays at most this many blocks (about
/// 0.1 ms); memory is one modal state per interval.
pub const CHECKPOINT_INTERVAL: usize = 512;

/// A document is analysed on two threads when each half has at least this many lines: below, the
/// second thread's start costs more than it saves.
const PARALLEL_HALF_MIN_LINES: usize = 16 * CHECKPOINT_INTERVAL;
/// The blocks read for the guess of the state in the middle of a document: from its start, and
/// before the middle.
const GUESS_HEAD_LINES: usize = 2 * CHECKPOINT_INTERVAL;
const GUESS_TAIL_LINES: usize = 2 * CHECKPOINT_INTERVAL;

/// An update may be interrupted once it has read this many lines: shorter ones finish within
/// milliseconds, and stopping them would only add work.
pub const INTERRUPTIBLE_AFTER_LINES: usize = 64 * CHECKPOINT_INTERVAL;

/// A line defines a macro: every line may read differently, so the whole document is analysed again.
const DEFINES_MACRO: u8 = 1;
/// A line is a `PROC` header: the document is a subprogram, and starts from another state.
const PROC_HEADER: u8 = 2;

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

/// The modal state in effect at one point of the program, in words a person reads. `None` fields are
/// unknown (inherited from an unseen caller, or lost after a call).
#[derive(Debug, Clone, PartialEq)]
pub struct StateSummary {
    /// Motion group: `G0`, `G1`, `G2`, ...
    pub motion: Option<String>,
    /// `G17`, `G18` or `G19`.
    pub plane: Option<String>,
    /// `G70`, `G71`, `G700` or `G710`.
    pub units: Option<String>,
    /// `G90` or `G91`.
    pub distance: Option<String>,
    /// `DIAMOF`, `DIAMON` or `DIAM90`.
    pub diameter: Option<String>,
    /// The settable offset: `G500`, `G54`, ...
    pub settable_offset: Option<String>,
    /// The pole of the active plane: `Some(None)` when no pole is defined (the WCS zero is used),
    /// `Some(Some((first, second)))` when known, `None` when unknown.
    pub pole: Option<Option<(f64, f64)>>,
    /// The programmable frame: `Some(true)` when it is the identity, `Some(false)` when a known frame
    /// is active, `None` when it cannot be followed.
    pub frame_is_identity: Option<bool>,
    /// The modal feed in the basic unit system.
    pub feed: Option<f64>,
    /// Every configured axis that the program has touched so far, with its last programmed position
    /// as the program shows it (a diameter under DIAMON), `None` when unknown.
    pub positions: Vec<(String, Option<f64>)>,
    /// Whether the program's flow (a label, jump or loop before this point) may differ from program
    /// order, so that the values shown may not be the control's.
    pub flow_uncertain: bool,
}

/// What the analysis knows about one block: the state before and after it and its move.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockReport {
    /// 0-based line of the block.
    pub line: usize,
    pub before: StateSummary,
    pub after: StateSummary,
    /// The block's move, when it moves axes.
    pub movement: Option<Move>,
    /// How each axis word of the block resolves, in the order written.
    pub words: Vec<WordResolution>,
}

/// The state before one line: where the analysis can start again.
#[derive(Debug, Clone)]
struct Checkpoint {
    line: usize,
    engine: EngineSnapshot,
    structure: StructureChecker,
}

/// The analysis of a document.
pub struct DocumentAnalysis {
    config: Arc<MachineConfig>,
    kind: ProgramKind,
    /// The parser's view of the configuration, with the macros the document defines.
    context: SyntaxContext,
    /// Whether the document starts from a caller's state (a subprogram, or a `PROC` header).
    subprogram: bool,
    /// Per line: [`DEFINES_MACRO`], [`PROC_HEADER`].
    line_flags: Vec<u8>,
    /// Sorted by line; the first is always line 0.
    checkpoints: Vec<Checkpoint>,
    /// The findings of single lines (syntax, structure, semantics), sorted by line and column.
    body: Vec<LineDiagnostic>,
    /// Per line: the axes its block reads absolutely (see [`position_reads_of`]).
    position_reads: Vec<u8>,
    /// The findings made at the end of the program (structures never closed), at their lines.
    tail: Vec<LineDiagnostic>,
    /// `body` and `tail` together, sorted as a from-scratch analysis sorts them, when `tail` is not
    /// empty.
    combined: Option<Vec<LineDiagnostic>>,
    /// How many lines the last update or analysis read, for benchmarks and tests.
    lines_read: usize,
    /// Lines an interrupted update left unread (the numbering of the text it read): from the first
    /// line it did not read to the end of what it had to read. Until the next update reads them, the
    /// findings and checkpoints from there on are those of before that update.
    unread: Option<Range<usize>>,
    /// The number of the findings as they are now, and how the last update changed them.
    findings_history: FindingsHistory,
}

/// How one update changed the list of findings ([`DocumentAnalysis::diagnostics`]): the first `start`
/// are as they were; the old ones from `old_end` on are the new ones from `new_end` on, each
/// `line_delta` lines further; the old ones between were replaced by the new ones between. It lets
/// a consumer that keeps something per finding (the server's JSON) redo only the replaced part.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FindingsChange {
    pub start: usize,
    pub old_end: usize,
    pub new_end: usize,
    pub line_delta: isize,
}

impl FindingsChange {
    /// The change of a list of `count` findings that did not change.
    pub fn none(count: usize) -> FindingsChange {
        FindingsChange {
            start: count,
            old_end: count,
            new_end: count,
            line_delta: 0,
        }
    }
}

/// Numbers for the states of the findings, unique across every analysis of the process: a number
/// remembered from another analysis (one replaced after a change of configuration) never matches.
static NEXT_FINDINGS_REVISION: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);

#[derive(Debug, Clone, Copy)]
struct FindingsHistory {
    revision: u64,
    /// The revision before the last update, and how that update changed the findings (`None` when
    /// it is not known).
    previous: u64,
    change: Option<FindingsChange>,
}

impl FindingsHistory {
    fn new() -> FindingsHistory {
        FindingsHistory {
            revision: next_findings_revision(),
            previous: 0,
            change: None,
        }
    }
}

fn next_findings_revision() -> u64 {
    NEXT_FINDINGS_REVISION.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
}

/// What a reading from a checkpoint on did: whether it read all it had to (see
/// [`DocumentAnalysis::update_interruptible`]), and how it changed `body`, when that is simple to say.
struct Reread {
    finished: bool,
    body_change: Option<FindingsChange>,
}

/// What one forward pass found.
struct Pass {
    lines_read: usize,
    checkpoints: Vec<Checkpoint>,
    diagnostics: Vec<LineDiagnostic>,
    /// Line ranges (new numbering) whose old findings stay, because a shift was carried across them.
    kept: Vec<Range<usize>>,
    /// The line at which the pass met an old checkpoint with the same state (new numbering), or
    /// `None` when it ran to the end of the document.
    converged_at: Option<usize>,
    /// The end-of-program findings, when the pass ran to the end.
    tail: Vec<LineDiagnostic>,
    /// The state at the pass's `stop_at` line, when it stopped there.
    stopped: Option<Checkpoint>,
    /// The line (new numbering) at which the pass was interrupted, a checkpoint of its own.
    interrupted_at: Option<usize>,
}

/// The old findings at lines from `from` on (old numbering) are `by` lines further in the new text.
struct MovedLines {
    from: usize,
    by: isize,
}

/// Where a pass stops besides convergence and the end: at `stop_at`, and at a checkpoint when
/// `interrupted` says so (see [`DocumentAnalysis::update_interruptible`]).
struct PassLimits<'a> {
    stop_at: usize,
    interrupted: &'a dyn Fn() -> bool,
}

impl PassLimits<'_> {
    const NONE: PassLimits<'static> = PassLimits {
        stop_at: usize::MAX,
        interrupted: &|| false,
    };
}

/// The per-line position reads of the lines from `base` on, which a pass fills in: a pass over part of
/// the document gets the part of the vector it owns.
struct PositionReads<'a> {
    base: usize,
    reads: &'a mut [u8],
}

impl PositionReads<'_> {
    fn get_mut(&mut self, line: usize) -> Option<&mut u8> {
        self.reads.get_mut(line.checked_sub(self.base)?)
    }

    /// Whether the lines `range` all read none of `axes` absolutely (lines outside count as reading
    /// everything).
    fn none_read(&self, range: Range<usize>, axes: u8) -> bool {
        let (Some(start), Some(end)) = (
            range.start.checked_sub(self.base),
            range.end.checked_sub(self.base),
        ) else {
            return false;
        };
        self.reads.get(start..end).is_some_and(|reads| {
            reads
                .iter()
                .all(|reads| reads & READS_ALL == 0 && reads & axes == 0)
        })
    }
}

impl DocumentAnalysis {
    /// An analysis of nothing yet, to be filled by one of the from-scratch readings.
    fn empty(config: Arc<MachineConfig>, kind: ProgramKind) -> DocumentAnalysis {
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
            findings_history: FindingsHistory::new(),
        }
    }

    /// The number of the findings as they are now; it changes with every update and is never that of
    /// another analysis.
    pub fn findings_revision(&self) -> u64 {
        self.findings_history.revision
    }

    /// How the findings changed since they had the revision `earlier`, when that is known: they were
    /// the same, or exactly one update came since and it says how it changed them.
    pub fn findings_change_since(&self, earlier: u64) -> Option<FindingsChange> {
        let history = &self.findings_history;
        if earlier == history.revision {
            return Some(FindingsChange::none(self.diagnostics().len()));
        }
        history.change.filter(|_| earlier == history.previous)
    }

    /// Gives the findings a new revision after a change described by `change` (`None`: not known).
    fn note_findings_change(&mut self, change: Option<FindingsChange>) {
        self.findings_history = FindingsHistory {
            revision: next_findings_revision(),
            previous: self.findings_history.revision,
            change,
        };
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
        analysis.note_findings_change(None);
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

    /// Like [`DocumentAnalysis::update`], but a long reading asks `interrupted` now and then (every
    /// checkpoint, once it has read [`INTERRUPTIBLE_AFTER_LINES`] lines) whether to stop: a newer
    /// edit has come, and reading on for this text would be wasted. Returns false when it stopped:
    /// the analysis must then be updated again (with the next change of the text it was given)
    /// before it is used, and that update reads the lines this one left.
    pub fn update_interruptible(
        &mut self,
        source: &dyn LineSource,
        first_line: usize,
        removed: usize,
        inserted: usize,
        interrupted: &dyn Fn() -> bool,
    ) -> bool {
        // The findings are `body` itself when there are no end-of-program findings; only then does
        // a change of `body` say how the findings changed.
        let body_only_before = self.combined.is_none();
        let old_count = self.line_flags.len();
        let new_count = source.line_count();
        let fits = first_line
            .checked_add(removed)
            .is_some_and(|end| end <= old_count)
            && old_count - removed + inserted == new_count;
        if !fits {
            self.recompute(source);
            return true;
        }
        // Lines an interrupted update did not read count as changed, with the lines between.
        let (first_line, removed, inserted) = match self.unread.take() {
            None => (first_line, removed, inserted),
            Some(unread) => {
                let start = first_line.min(unread.start);
                let end = (first_line + removed).max(unread.end).min(old_count);
                let start = start.min(end);
                let new_end = end + inserted - removed;
                (start, end - start, new_end - start)
            }
        };
        let removed_flags = self.line_flags[first_line..first_line + removed]
            .iter()
            .any(|flags| *flags != 0);
        let inserted_flags: Vec<u8> = (first_line..first_line + inserted)
            .map(|index| line_flags_of(&source.line(index)))
            .collect();
        if removed_flags || inserted_flags.iter().any(|flags| *flags != 0) {
            // A macro or a PROC header appeared or went: every line may read differently.
            self.recompute(source);
            return true;
        }
        self.line_flags
            .splice(first_line..first_line + removed, inserted_flags);
        let delta = inserted as isize - removed as isize;
        let old_region_end = first_line + removed;
        // Checkpoints at or before the first changed line stay valid; those after the changed lines
        // move with their lines and are what the new pass compares with; those inside are dropped.
        // They stay where they are in the vector: there are thousands of them in a large program,
        // and moving them out and back in cost more than the rest of a keystroke's update.
        let keep = self
            .checkpoints
            .partition_point(|checkpoint| checkpoint.line <= first_line);
        let inside_end = keep
            + self.checkpoints[keep..]
                .partition_point(|checkpoint| checkpoint.line < old_region_end);
        if inside_end > keep {
            self.checkpoints.drain(keep..inside_end);
        }
        if delta != 0 {
            for checkpoint in &mut self.checkpoints[keep..] {
                checkpoint.line = checkpoint.line.saturating_add_signed(delta);
                checkpoint.structure.shift_lines(old_region_end, delta);
            }
        }
        // Lines the edit inserted are read by the pass; until then they count as reading everything.
        self.position_reads.splice(
            first_line..first_line + removed,
            std::iter::repeat_n(READS_ALL, inserted),
        );
        let start = self.checkpoints[keep - 1].clone();
        self.lines_read = 0;
        let reread = self.read_again_from(
            source,
            start,
            first_line + inserted,
            keep,
            MovedLines {
                from: old_region_end,
                by: delta,
            },
            interrupted,
        );
        let body_only_after = self.tail.is_empty() && self.combined.is_none();
        self.note_findings_change(
            reread
                .body_change
                .filter(|_| body_only_before && body_only_after),
        );
        reread.finished
    }

    /// Reads the document again from `start` (the last of `self.checkpoints[..later_from]`), where
    /// `self.checkpoints[later_from..]` are the old checkpoints after the changed lines (already
    /// moved to the new numbering), `changed_end` the first line (new numbering) the change did not
    /// touch, and the old findings at lines from `old_region_end` on move by `delta` lines (those
    /// before it were replaced).
    fn read_again_from(
        &mut self,
        source: &dyn LineSource,
        start: Checkpoint,
        changed_end: usize,
        later_from: usize,
        moved: MovedLines,
        interrupted: &dyn Fn() -> bool,
    ) -> Reread {
        let (old_region_end, delta) = (moved.from, moved.by);
        let mut position_reads = std::mem::take(&mut self.position_reads);
        // Taken out for the pass, which reads (and may update) the later ones, and put back below.
        let mut checkpoints = std::mem::take(&mut self.checkpoints);
        let pass = self.run_pass(
            source,
            start.clone(),
            changed_end,
            &mut checkpoints[later_from..],
            PositionReads {
                base: 0,
                reads: &mut position_reads,
            },
            PassLimits {
                stop_at: usize::MAX,
                interrupted,
            },
        );
        self.position_reads = position_reads;
        // Diagnostics: those before the pass's start stay; the pass's replace what it re-read; the
        // old ones of the intervals it carried a shift across, and of everything after the point of
        // convergence, stay with their lines moved.
        let prefix_end = self.body.partition_point(|item| item.line < start.line);
        // From an interruption on, everything stays as it was, like after a convergence.
        let converged_at = pass.converged_at.or(pass.interrupted_at);
        let mut body_change = None;
        match converged_at {
            // The common case, an edit whose effect ends at a checkpoint: the old findings from the
            // point of convergence on stay (all of them, moved), the pass's replace those before, and
            // the rest of the list is moved once instead of item by item.
            Some(converged_line) if pass.kept.is_empty() => {
                let kept_from = prefix_end
                    + self.body[prefix_end..].partition_point(|item| {
                        item.line < old_region_end
                            || item.line.saturating_add_signed(delta) < converged_line
                    });
                let fresh = pass.diagnostics.len();
                body_change = Some(FindingsChange {
                    start: prefix_end,
                    old_end: kept_from,
                    new_end: prefix_end + fresh,
                    line_delta: delta,
                });
                self.body.splice(prefix_end..kept_from, pass.diagnostics);
                if delta != 0 {
                    for item in &mut self.body[prefix_end + fresh..] {
                        item.line = item.line.saturating_add_signed(delta);
                    }
                }
            }
            _ => self.merge_old_findings(
                prefix_end,
                pass.diagnostics,
                &pass.kept,
                converged_at,
                moved,
            ),
        }
        match converged_at {
            Some(converged_line) => {
                for item in &mut self.tail {
                    if item.line >= old_region_end {
                        item.line = item.line.saturating_add_signed(delta);
                    }
                }
                // An interrupted pass has a checkpoint of its own at the line it stopped at.
                let later = &checkpoints[later_from..];
                let index = match pass.interrupted_at {
                    Some(_) => {
                        later.partition_point(|checkpoint| checkpoint.line <= converged_line)
                    }
                    None => later.partition_point(|checkpoint| checkpoint.line < converged_line),
                };
                // Usually the pass met the first later checkpoint and made none: nothing moves.
                if index > 0 || !pass.checkpoints.is_empty() {
                    checkpoints.splice(later_from..later_from + index, pass.checkpoints);
                }
            }
            None => {
                self.tail = pass.tail;
                checkpoints.truncate(later_from);
                checkpoints.extend(pass.checkpoints);
            }
        }
        self.checkpoints = checkpoints;
        self.lines_read += pass.lines_read;
        if let (None, Some(line)) = (pass.converged_at, pass.interrupted_at) {
            self.unread = Some(line..changed_end.max(line + 1));
            return Reread {
                finished: false,
                body_change,
            };
        }
        self.combine();
        Reread {
            finished: true,
            body_change,
        }
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

    /// The moves of the blocks in `lines` (0-based, end exclusive), in program order.
    pub fn moves(&self, source: &dyn LineSource, lines: Range<usize>) -> Vec<Move> {
        let mut moves = Vec::new();
        self.for_each_move(source, lines, &mut |movement| moves.push(movement));
        moves
    }

    /// Hands the moves of the blocks in `lines` to `visit` one at a time, in program order, without
    /// keeping them: the preview of a program of any length needs memory for one move.
    pub fn visit_moves(
        &self,
        source: &dyn LineSource,
        lines: Range<usize>,
        visit: &mut dyn FnMut(&Move),
    ) {
        self.for_each_move(source, lines, &mut |movement| visit(&movement));
    }

    /// Like [`DocumentAnalysis::visit_moves`], handing each move over by value, so that
    /// [`DocumentAnalysis::moves`] keeps the move as built instead of a copy of it.
    fn for_each_move(
        &self,
        source: &dyn LineSource,
        lines: Range<usize>,
        visit: &mut dyn FnMut(Move),
    ) {
        let end = lines.end.min(source.line_count());
        if lines.start >= end {
            return;
        }
        let checkpoint = self.checkpoint_before(lines.start);
        let mut engine = Engine::from_snapshot(&self.config, checkpoint.engine.clone());
        let mut parser = LineParser::new();
        let mut block = Block::default();
        let mut findings = Vec::new();
        source.for_each_line(checkpoint.line, &mut |index, line| {
            if index >= end {
                return false;
            }
            findings.clear();
            parser.parse(line, &self.context, &mut block, &mut findings);
            findings.clear();
            if engine.step(line, &block, &mut findings) && index >= lines.start {
                visit(engine.describe_last_move(index, line, &block));
            }
            true
        });
    }

    /// The state before and after the block on `line`, its move and how its axis words resolve. A
    /// line past the end reports the state at the end of the program.
    pub fn block_report(&self, source: &dyn LineSource, line: usize) -> BlockReport {
        let checkpoint = self.checkpoint_before(line);
        let mut engine = Engine::from_snapshot(&self.config, checkpoint.engine.clone());
        let mut parser = LineParser::new();
        let mut block = Block::default();
        let mut findings = Vec::new();
        let mut report = None;
        source.for_each_line(checkpoint.line, &mut |index, line_text| {
            findings.clear();
            parser.parse(line_text, &self.context, &mut block, &mut findings);
            findings.clear();
            if index < line {
                engine.step(line_text, &block, &mut findings);
                return true;
            }
            let before_state = engine.state.clone();
            let before = summarize(&self.config, &before_state, engine.flow_uncertain());
            let movement = engine
                .step(line_text, &block, &mut findings)
                .then(|| engine.describe_last_move(index, line_text, &block));
            let words = crate::analysis::resolution::resolve_words(
                &self.config,
                &before_state,
                &engine.state,
                line_text,
                &block,
                movement
                    .as_ref()
                    .and_then(|movement| movement.machine.as_deref()),
            );
            report = Some(BlockReport {
                line,
                before,
                after: summarize(&self.config, &engine.state, engine.flow_uncertain()),
                movement,
                words,
            });
            false
        });
        report.unwrap_or_else(|| {
            let after = summarize(&self.config, &engine.state, engine.flow_uncertain());
            BlockReport {
                line,
                before: after.clone(),
                after,
                movement: None,
                words: Vec::new(),
            }
        })
    }

    /// The nearest checkpoint at or before `line`.
    fn checkpoint_before(&self, line: usize) -> &Checkpoint {
        let index = self
            .checkpoints
            .partition_point(|checkpoint| checkpoint.line <= line);
        &self.checkpoints[index.saturating_sub(1)]
    }

    /// Analyses the whole document again.
    fn recompute(&mut self, source: &dyn LineSource) {
        let start = self.prepare_from_scratch(source);
        let line_count = source.line_count();
        let mut position_reads = vec![READS_ALL; line_count];
        let pass = self.run_pass(
            source,
            start.clone(),
            line_count,
            &mut [],
            PositionReads {
                base: 0,
                reads: &mut position_reads,
            },
            PassLimits::NONE,
        );
        self.position_reads = position_reads;
        self.checkpoints = vec![start];
        self.checkpoints.extend(pass.checkpoints);
        self.body = pass.diagnostics;
        self.tail = pass.tail;
        self.lines_read = pass.lines_read;
        self.combine();
        self.note_findings_change(None);
    }

    /// Reads the whole-document facts (macros, `PROC` headers) and gives the state before line 0.
    fn prepare_from_scratch(&mut self, source: &dyn LineSource) -> Checkpoint {
        let facts = DocumentFacts::read(source, 0, usize::MAX);
        self.start_from_facts(facts)
    }

    /// [`DocumentAnalysis::prepare_from_scratch`] with the lines from `middle` on read on a second
    /// thread from `helper_source` (the same text).
    fn prepare_from_scratch_in_parallel(
        &mut self,
        source: &dyn LineSource,
        helper_source: &mut (dyn LineSource + Send),
        middle: usize,
    ) -> Checkpoint {
        let (mut facts, second) = std::thread::scope(|scope| {
            let second =
                scope.spawn(move || DocumentFacts::read(&*helper_source, middle, usize::MAX));
            (DocumentFacts::read(source, 0, middle), second.join())
        });
        match second {
            Ok(second) => facts.extend(second),
            // The thread failed (a bug): the rest is read here instead.
            Err(_) => facts.extend(DocumentFacts::read(source, middle, usize::MAX)),
        }
        self.start_from_facts(facts)
    }

    /// Takes the facts of the whole document and gives the state before line 0.
    fn start_from_facts(&mut self, facts: DocumentFacts) -> Checkpoint {
        self.unread = None;
        self.line_flags = facts.line_flags;
        self.context = SyntaxContext::new(&self.config);
        for name in &facts.macros {
            self.context.add_macro(name);
        }
        self.subprogram = self.kind == ProgramKind::Subprogram || facts.has_proc_header;
        let mut engine = Engine::new(&self.config);
        if self.subprogram {
            engine.assume_inherited_state();
        }
        Checkpoint {
            line: 0,
            engine: engine.snapshot(),
            structure: StructureChecker::default(),
        }
    }

    /// Analyses the whole document on two threads: this one reads the first half; `helper_source`
    /// (the same text) is read on a second thread from the middle on, starting from a guess of the
    /// state there. When the first half ends in exactly the guessed state, the second half's results
    /// stand as they are; otherwise the second half is read again from the true state the way an edit
    /// is, stopping where the states meet or carrying a shift of positions, so the result is always
    /// the one of [`DocumentAnalysis::recompute`].
    fn recompute_in_parallel(
        &mut self,
        source: &dyn LineSource,
        helper_source: &mut (dyn LineSource + Send),
    ) {
        let line_count = source.line_count();
        let middle = line_count / 2 / CHECKPOINT_INTERVAL * CHECKPOINT_INTERVAL;
        if middle < PARALLEL_HALF_MIN_LINES || helper_source.line_count() != line_count {
            self.recompute(source);
            return;
        }
        let start = self.prepare_from_scratch_in_parallel(source, &mut *helper_source, middle);
        let mut position_reads = vec![READS_ALL; line_count];
        let (first_reads, second_reads) = position_reads.split_at_mut(middle);
        let this = &*self;
        let (first, helper) = std::thread::scope(|scope| {
            let start_of_program = &start;
            let helper = scope.spawn(move || {
                let guess = this.guess_state_at(&*helper_source, start_of_program, middle);
                let second = this.run_pass(
                    &*helper_source,
                    guess.clone(),
                    line_count,
                    &mut [],
                    PositionReads {
                        base: middle,
                        reads: second_reads,
                    },
                    PassLimits::NONE,
                );
                (guess, second)
            });
            let first = this.run_pass(
                source,
                start.clone(),
                0,
                &mut [],
                PositionReads {
                    base: 0,
                    reads: first_reads,
                },
                PassLimits {
                    stop_at: middle,
                    interrupted: &|| false,
                },
            );
            (first, helper.join())
        });
        self.position_reads = position_reads;
        self.lines_read = first.lines_read;
        self.checkpoints = vec![start];
        self.checkpoints.extend(first.checkpoints);
        self.body = first.diagnostics;
        self.tail = Vec::new();
        let Some(end_of_first) = first.stopped else {
            // The first half always stops at the middle; should it not, nothing of it is lost.
            self.recompute(source);
            return;
        };
        self.checkpoints.push(end_of_first.clone());
        let (guess, second) = match helper {
            Ok(result) => result,
            Err(_) => {
                // The helper thread failed (a bug): the second half is read here instead.
                let later_from = self.checkpoints.len();
                self.read_again_from(
                    source,
                    end_of_first,
                    middle + 1,
                    later_from,
                    MovedLines {
                        from: line_count,
                        by: 0,
                    },
                    &|| false,
                );
                return;
            }
        };
        self.lines_read += second.lines_read;
        self.body.extend(second.diagnostics);
        self.tail = second.tail;
        let guessed_right = end_of_first.structure == guess.structure
            && Engine::from_snapshot(&self.config, end_of_first.engine.clone())
                .matches(&guess.engine);
        if guessed_right {
            self.checkpoints.extend(second.checkpoints);
            self.combine();
        } else {
            // The second half's results are an old analysis of those lines, as after an edit of the
            // first half: read again from the true state until they agree.
            let later_from = self.checkpoints.len();
            self.checkpoints.extend(second.checkpoints);
            self.read_again_from(
                source,
                end_of_first,
                middle + 1,
                later_from,
                MovedLines {
                    from: middle + 1,
                    by: 0,
                },
                &|| false,
            );
        }
    }

    /// A guess of the state before line `middle`: the blocks of the program's start (where its
    /// settings usually are) followed by those just before `middle` (where the last positions are).
    /// Only a guess: [`DocumentAnalysis::recompute_in_parallel`] checks it against the true state.
    fn guess_state_at(
        &self,
        source: &dyn LineSource,
        start: &Checkpoint,
        middle: usize,
    ) -> Checkpoint {
        let mut engine = Engine::from_snapshot(&self.config, start.engine.clone());
        let mut structure = start.structure.clone();
        let mut parser = LineParser::new();
        let mut block = Block::default();
        let mut findings = Vec::new();
        let mut structure_findings = Vec::new();
        let head_end = GUESS_HEAD_LINES.min(middle);
        let tail_start = middle.saturating_sub(GUESS_TAIL_LINES).max(head_end);
        for range in [0..head_end, tail_start..middle] {
            source.for_each_line(range.start, &mut |index, line| {
                if index >= range.end {
                    return false;
                }
                parser.parse(line, &self.context, &mut block, &mut findings);
                structure.feed(index, &block, &mut structure_findings);
                engine.step(line, &block, &mut findings);
                findings.clear();
                structure_findings.clear();
                true
            });
        }
        Checkpoint {
            line: middle,
            engine: engine.snapshot(),
            structure,
        }
    }

    /// Reads the document forward from `start`, taking new checkpoints, until it meets one of
    /// `old_checkpoints` (all at or after `changed_end`, the first line the edit did not touch) with
    /// the same state, or the end. At an old checkpoint whose state differs only by a shift of
    /// positions, the intervals after it whose blocks read the shifted axes only incrementally are not
    /// read again: their findings stay and their checkpoints are moved by the shift.
    fn run_pass(
        &self,
        source: &dyn LineSource,
        start: Checkpoint,
        changed_end: usize,
        old_checkpoints: &mut [Checkpoint],
        mut position_reads: PositionReads<'_>,
        limits: PassLimits<'_>,
    ) -> Pass {
        let line_count = source.line_count();
        let mut engine = Engine::from_snapshot(&self.config, start.engine);
        let mut structure = start.structure;
        let mut parser = LineParser::new();
        let mut block = Block::default();
        let mut line_findings = Vec::new();
        let mut engine_findings = Vec::new();
        let mut pass = Pass {
            lines_read: 0,
            checkpoints: Vec::new(),
            diagnostics: Vec::new(),
            kept: Vec::new(),
            converged_at: None,
            tail: Vec::new(),
            stopped: None,
            interrupted_at: None,
        };
        let first_old = old_checkpoints.partition_point(|checkpoint| checkpoint.line < changed_end);
        let mut next_old = first_old;
        let mut resume_at = start.line;
        let mut last_checkpoint = start.line;
        loop {
            // Why the reading below stopped: at an old checkpoint whose state differs by a shift.
            let mut shift = None;
            source.for_each_line(resume_at, &mut |index, line| {
                // The line the reading starts at was checked (or is the pass's start) already.
                if index > resume_at {
                    while old_checkpoints
                        .get(next_old)
                        .is_some_and(|checkpoint| checkpoint.line < index)
                    {
                        next_old += 1;
                    }
                    let old = old_checkpoints
                        .get(next_old)
                        .filter(|old| old.line == index && old.structure == structure);
                    if old.is_some_and(|old| engine.matches(&old.engine)) {
                        pass.converged_at = Some(index);
                        return false;
                    }
                    if index >= limits.stop_at {
                        pass.stopped = Some(Checkpoint {
                            line: index,
                            engine: engine.snapshot(),
                            structure: structure.clone(),
                        });
                        return false;
                    }
                    if let Some(found) = old.and_then(|old| engine.position_shift_from(&old.engine))
                    {
                        shift = Some(found);
                        return false;
                    }
                    if index - last_checkpoint >= CHECKPOINT_INTERVAL {
                        last_checkpoint = index;
                        pass.checkpoints.push(Checkpoint {
                            line: index,
                            engine: engine.snapshot(),
                            structure: structure.clone(),
                        });
                        if pass.lines_read >= INTERRUPTIBLE_AFTER_LINES && (limits.interrupted)() {
                            pass.interrupted_at = Some(index);
                            return false;
                        }
                    }
                }
                pass.lines_read += 1;
                let first_of_line = pass.diagnostics.len();
                parser.parse(line, &self.context, &mut block, &mut line_findings);
                move_findings(&mut line_findings, index, &mut pass.diagnostics);
                structure.feed(index, &block, &mut pass.diagnostics);
                engine.step(line, &block, &mut engine_findings);
                move_findings(&mut engine_findings, index, &mut pass.diagnostics);
                let of_line = &mut pass.diagnostics[first_of_line..];
                for item in of_line.iter_mut() {
                    item.diagnostic.severity = self.config.severity_of(item.diagnostic.code);
                }
                of_line.sort_by_key(|item| item.diagnostic.span.start());
                if let Some(reads) = position_reads.get_mut(index) {
                    *reads = position_reads_of(
                        &self.config,
                        engine.axis_lookup(),
                        line,
                        &block,
                        &engine.state,
                    );
                }
                true
            });
            let Some(shift) = shift else {
                break;
            };
            // Carry the shift across every following interval that reads the shifted axes only
            // incrementally; read again from the first one that does not.
            let Some(axes) = shifted_axes(&self.config, &shift) else {
                resume_at = old_checkpoints[next_old].line;
                continue;
            };
            let here = old_checkpoints[next_old].line;
            pass.checkpoints.push(Checkpoint {
                line: here,
                engine: engine.snapshot(),
                structure: structure.clone(),
            });
            last_checkpoint = here;
            let mut current = next_old;
            loop {
                let interval_start = old_checkpoints[current].line;
                let interval_end = old_checkpoints
                    .get(current + 1)
                    .map_or(line_count, |checkpoint| checkpoint.line);
                if !position_reads.none_read(interval_start..interval_end, axes) {
                    break;
                }
                pass.kept.push(interval_start..interval_end);
                current += 1;
                if current == old_checkpoints.len() {
                    // Shifted to the end: the structures open at the end are those of before.
                    pass.converged_at = Some(line_count);
                    break;
                }
                old_checkpoints[current].engine.shift_positions(&shift);
                let checkpoint = old_checkpoints[current].clone();
                last_checkpoint = checkpoint.line;
                pass.checkpoints.push(checkpoint);
            }
            if pass.converged_at.is_some() {
                break;
            }
            if current > next_old {
                let checkpoint = &old_checkpoints[current];
                engine = Engine::from_snapshot(&self.config, checkpoint.engine.clone());
                structure = checkpoint.structure.clone();
                // The checkpoint at `current` was pushed above; the old ones before it are replaced.
                next_old = current + 1;
            } else {
                next_old = current + 1;
            }
            resume_at = old_checkpoints[current].line;
        }
        if pass.converged_at.is_none() && pass.stopped.is_none() && pass.interrupted_at.is_none() {
            structure.finish(&mut pass.tail);
            for item in &mut pass.tail {
                item.diagnostic.severity = self.config.severity_of(item.diagnostic.code);
            }
        }
        pass
    }

    /// Replaces the old findings from `prefix_end` on by the `fresh` ones of a pass, keeping the old
    /// ones of the line ranges `kept` (a shift was carried across them) and those from `converged_at`
    /// on, all moved as `moved` says.
    fn merge_old_findings(
        &mut self,
        prefix_end: usize,
        fresh: Vec<LineDiagnostic>,
        kept: &[Range<usize>],
        converged_at: Option<usize>,
        moved: MovedLines,
    ) {
        let MovedLines {
            from: old_region_end,
            by: delta,
        } = moved;
        let old_rest: Vec<LineDiagnostic> = self.body.drain(prefix_end..).collect();
        let mut kept_ranges = kept.iter().peekable();
        let kept = old_rest.into_iter().filter_map(|mut item| {
            if item.line < old_region_end {
                return None;
            }
            item.line = item.line.saturating_add_signed(delta);
            if converged_at.is_some_and(|line| item.line >= line) {
                return Some(item);
            }
            while kept_ranges
                .next_if(|range| range.end <= item.line)
                .is_some()
            {}
            kept_ranges
                .peek()
                .is_some_and(|range| range.contains(&item.line))
                .then_some(item)
        });
        merge_by_line(&mut self.body, fresh, kept);
    }

    /// Joins the findings of single lines and those of the end of the program, in the order of a
    /// from-scratch analysis: by line and column, end-of-program findings after the others. Without
    /// end-of-program findings (the common case) nothing is copied.
    fn combine(&mut self) {
        // S180 is reported once per axis and file, with the count of its blocks: a fact of the whole
        // document, worked out here from the findings of every line (the update then says no
        // FindingsChange, and the server compares the published findings instead).
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

/// Appends to `body` the items of `fresh` and `kept`, both sorted by line and about disjoint lines, in
/// line order.
fn merge_by_line(
    body: &mut Vec<LineDiagnostic>,
    fresh: Vec<LineDiagnostic>,
    kept: impl Iterator<Item = LineDiagnostic>,
) {
    let mut fresh = fresh.into_iter().peekable();
    for item in kept {
        while let Some(earlier) = fresh.next_if(|candidate| candidate.line < item.line) {
            body.push(earlier);
        }
        body.push(item);
    }
    body.extend(fresh);
}

/// The whole-document facts a line carries.
/// Moves the findings of the block on `line` to the document's. Most blocks have none, and the
/// extension of the document's findings costs more than asking first.
fn move_findings(findings: &mut Vec<Diagnostic>, line: usize, into: &mut Vec<LineDiagnostic>) {
    if findings.is_empty() {
        return;
    }
    into.extend(
        findings
            .drain(..)
            .map(|diagnostic| LineDiagnostic { line, diagnostic }),
    );
}

/// What a document's lines say of the whole document: the flags of each line, the macros defined
/// and whether a `PROC` header makes it a subprogram.
struct DocumentFacts {
    line_flags: Vec<u8>,
    macros: Vec<String>,
    has_proc_header: bool,
}

impl DocumentFacts {
    /// The facts of the lines `start..end` (as far as there are lines).
    fn read(source: &dyn LineSource, start: usize, end: usize) -> DocumentFacts {
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
    fn extend(&mut self, later: DocumentFacts) {
        self.line_flags.extend(later.line_flags);
        self.macros.extend(later.macros);
        self.has_proc_header |= later.has_proc_header;
    }
}

fn line_flags_of(line: &str) -> u8 {
    let mut flags = 0;
    if macro_defined_by(line).is_some() {
        flags |= DEFINES_MACRO;
    }
    if is_proc_header(line) {
        flags |= PROC_HEADER;
    }
    flags
}

/// The readable form of a modal state.
pub fn summarize(config: &MachineConfig, state: &ModalState, flow_uncertain: bool) -> StateSummary {
    let group = |number: usize| state.groups[number].map(|code| code.name().into_owned());
    let shows_diameter = state.shows_diameter();
    let positions = config
        .axes
        .iter()
        .enumerate()
        .filter(|(index, _)| state.touched[*index])
        .map(|(index, axis)| {
            let transverse = axis.kind == crate::config::AxisKind::Transverse;
            let value = state.positions[index].and_then(|value| {
                crate::analysis::state::shown_value(transverse, shows_diameter, value)
            });
            (axis.name.clone(), value)
        })
        .collect();
    StateSummary {
        motion: group(1),
        plane: group(6),
        units: group(13),
        distance: group(14),
        diameter: group(29),
        settable_offset: group(8),
        pole: state
            .plane_index()
            .and_then(|plane| match state.poles[plane] {
                Pole::Undefined => Some(None),
                Pole::At(first, second) => Some(Some((first, second))),
                Pole::Unknown => None,
            }),
        frame_is_identity: state.frame.map(|frame| frame.is_identity()),
        feed: state.feed,
        positions,
        flow_uncertain,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SEED: &str = "N10 G18 G90 G0 X20 Z90\nN20 G1 X75 Z=IC(-32) F100\nN30 X=IC(5)\n";

    #[test]
    fn a_block_report_gives_the_state_before_and_the_end_point() {
        let config = Arc::new(MachineConfig::mill());
        let source = TextLines::new(SEED);
        let analysis = DocumentAnalysis::new(&source, config, ProgramKind::Main);
        let report = analysis.block_report(&source, 1);
        assert_eq!(report.before.motion.as_deref(), Some("G0"));
        assert_eq!(report.after.motion.as_deref(), Some("G1"));
        let movement = report.movement.expect("N20 moves");
        let z = movement
            .end
            .iter()
            .find(|(name, _)| &**name == "Z")
            .unwrap();
        assert_eq!(z.1, 58.0);
        type Row<'a> = (&'a str, ResolutionMode, Option<f64>, Option<f64>, bool);
        let words: Vec<Row> = report
            .words
            .iter()
            .map(|word| {
                (
                    word.axis.as_str(),
                    word.mode,
                    word.start,
                    word.end,
                    word.explained,
                )
            })
            .collect();
        assert_eq!(
            words,
            [
                ("X", ResolutionMode::Absolute, Some(20.0), Some(75.0), true),
                (
                    "Z",
                    ResolutionMode::Override(crate::syntax::ast::Modifier::Ic),
                    Some(90.0),
                    Some(58.0),
                    true
                ),
            ]
        );
    }

    #[test]
    fn unknown_words_say_why() {
        let config = Arc::new(MachineConfig::mill());
        let text = "N10 G91 X5\nN20 X=R7\n";
        let source = TextLines::new(text);
        let analysis = DocumentAnalysis::new(&source, config, ProgramKind::Main);
        let first = &analysis.block_report(&source, 0).words[0];
        assert_eq!(first.end, None);
        assert!(first
            .unknown_reason
            .as_deref()
            .unwrap()
            .contains("incremental move from a position"));
        let second = &analysis.block_report(&source, 1).words[0];
        assert_eq!(second.programmed, None);
        assert!(second
            .unknown_reason
            .as_deref()
            .unwrap()
            .contains("variable"));
    }

    #[test]
    fn an_update_sees_the_new_text() {
        let config = Arc::new(MachineConfig::mill());
        let mut analysis = DocumentAnalysis::new(&TextLines::new(SEED), config, ProgramKind::Main);
        assert!(analysis.diagnostics().is_empty());
        let changed = SEED.replace("Z=IC(-32)", "Z=IC(-32");
        analysis.update(&TextLines::new(&changed), 1, 1, 1);
        assert_eq!(analysis.diagnostics().len(), 1);
        assert_eq!(analysis.diagnostics()[0].line, 1);
    }

    /// Whether `change` turns `old` into `new`.
    fn change_holds(
        old: &[LineDiagnostic],
        new: &[LineDiagnostic],
        change: FindingsChange,
    ) -> bool {
        let moved = |item: &LineDiagnostic| LineDiagnostic {
            line: item.line.saturating_add_signed(change.line_delta),
            diagnostic: item.diagnostic.clone(),
        };
        change.start <= change.old_end
            && change.start <= change.new_end
            && change.old_end <= old.len()
            && change.new_end <= new.len()
            && old.len() - change.old_end == new.len() - change.new_end
            && old[..change.start] == new[..change.start]
            && old[change.old_end..]
                .iter()
                .map(moved)
                .eq(new[change.new_end..].iter().cloned())
    }

    #[test]
    fn the_findings_change_an_update_reports_turns_the_old_findings_into_the_new() {
        let config = Arc::new(MachineConfig::mill());
        let mut lines: Vec<String> = (0..3000)
            .map(|index| match index % 5 {
                0 => format!("N{index} G1 X=AC{index} F100"),
                _ => format!("N{index} G1 X{index} Y=IC(1) F100"),
            })
            .collect();
        let text = |lines: &[String]| lines.join("\n") + "\n";
        let mut analysis =
            DocumentAnalysis::new(&TextLines::new(&text(&lines)), config, ProgramKind::Main);
        let mut random = 0x9E37_79B9_7F4A_7C15_u64;
        let mut next = |bound: usize| {
            random ^= random << 13;
            random ^= random >> 7;
            random ^= random << 17;
            (random % bound as u64) as usize
        };
        let mut known = 0;
        for step in 0..300 {
            let old = analysis.diagnostics().to_vec();
            let revision = analysis.findings_revision();
            let line = next(lines.len() - 1);
            let (removed, inserted) = match step % 4 {
                0 => {
                    lines[line].insert(0, ' ');
                    (1, 1)
                }
                1 => {
                    lines.insert(line, format!("N9 X=AC{step}"));
                    (0, 1)
                }
                2 => {
                    lines.remove(line);
                    (1, 0)
                }
                _ => {
                    lines[line] = format!("N{step} G1 X{step}");
                    (1, 1)
                }
            };
            let current = text(&lines);
            analysis.update(&TextLines::new(&current), line, removed, inserted);
            assert_eq!(
                analysis.findings_change_since(analysis.findings_revision()),
                Some(FindingsChange::none(analysis.diagnostics().len()))
            );
            if let Some(change) = analysis.findings_change_since(revision) {
                known += 1;
                assert!(
                    change_holds(&old, analysis.diagnostics(), change),
                    "step {step}: {change:?}"
                );
            }
            assert_eq!(
                analysis.findings_change_since(revision.wrapping_sub(1)),
                None
            );
        }
        assert!(
            known > 200,
            "most edits say how they changed the findings: {known}"
        );
    }

    #[test]
    fn an_update_of_a_program_with_end_of_program_findings_does_not_say_how_they_changed() {
        let config = Arc::new(MachineConfig::mill());
        let text = "IF R1 == 1\nN10 G1 X=AC1 F100\nN20 X2\n";
        let mut analysis = DocumentAnalysis::new(&TextLines::new(text), config, ProgramKind::Main);
        assert!(analysis.diagnostics().iter().any(|item| item.line == 0));
        let revision = analysis.findings_revision();
        analysis.update(&TextLines::new(&text.replace("X2", " X2")), 2, 1, 1);
        assert_eq!(analysis.findings_change_since(revision), None);
    }
}
