//! The update of a document's analysis after an edit: the changed lines and the checkpoints after them
//! are moved, a pass reads from the checkpoint before the edit until it meets an old checkpoint with
//! the same state, and the old findings from there on are kept, moved by the lines inserted or
//! removed.

use crate::analysis::document::document_state::{Checkpoint, DocumentAnalysis};
use crate::analysis::document::facts::line_flags_of;
use crate::analysis::document::line_source::LineSource;
use crate::analysis::document::pass::{PassLimits, PositionReads};
use crate::analysis::position_reads::READS_ALL;
use crate::diagnostics::LineDiagnostic;
use std::ops::Range;

/// What a reading from a checkpoint on did: whether it read all it had to (see
/// [`DocumentAnalysis::update_interruptible`]).
pub(super) struct Reread {
    finished: bool,
}

/// The old findings at lines from `from` on (old numbering) are `by` lines further in the new text.
pub(super) struct MovedLines {
    pub(super) from: usize,
    pub(super) by: isize,
}

impl DocumentAnalysis {
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
        reread.finished
    }

    /// Reads the document again from `start` (the last of `self.checkpoints[..later_from]`), where
    /// `self.checkpoints[later_from..]` are the old checkpoints after the changed lines (already
    /// moved to the new numbering), `changed_end` the first line (new numbering) the change did not
    /// touch, and the old findings at lines from `old_region_end` on move by `delta` lines (those
    /// before it were replaced).
    pub(super) fn read_again_from(
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
            return Reread { finished: false };
        }
        self.combine();
        Reread { finished: true }
    }

    /// Replaces the old findings from `prefix_end` on by the `fresh` ones of a pass, keeping the old
    /// ones of the line ranges `kept` (a shift was carried across them) and those from `converged_at`
    /// on, all moved as `moved` says.
    pub(super) fn merge_old_findings(
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
}

/// Appends to `body` the items of `fresh` and `kept`, both sorted by line and about disjoint lines, in
/// line order.
pub(super) fn merge_by_line(
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
