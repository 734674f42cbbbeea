//! One forward pass of a document's analysis: blocks read from a checkpoint, new checkpoints taken,
//! until the state meets an old checkpoint's (convergence), a shift of positions is carried across
//! the intervals that read the shifted axes only incrementally, or the document ends.

use crate::analysis::document::document_state::{
    Checkpoint, DocumentAnalysis, CHECKPOINT_INTERVAL, INTERRUPTIBLE_AFTER_LINES,
};
use crate::analysis::document::line_source::LineSource;
use crate::analysis::engine::engine_state::Engine;
use crate::analysis::engine::snapshot::EngineSnapshot;
use crate::analysis::position_reads::{
    position_reads as position_reads_of, shifted_axes, READS_ALL,
};
use crate::diagnostics::{Diagnostic, LineDiagnostic};
use crate::syntax::{Block, LineParser};
use std::ops::Range;
use std::sync::Arc;

/// What one forward pass found.
pub(super) struct Pass {
    pub(super) lines_read: usize,
    pub(super) checkpoints: Vec<Checkpoint>,
    pub(super) diagnostics: Vec<LineDiagnostic>,
    /// Line ranges (new numbering) whose old findings stay, because a shift was carried across them.
    pub(super) kept: Vec<Range<usize>>,
    /// The line at which the pass met an old checkpoint with the same state (new numbering), or
    /// `None` when it ran to the end of the document.
    pub(super) converged_at: Option<usize>,
    /// The end-of-program findings, when the pass ran to the end.
    pub(super) tail: Vec<LineDiagnostic>,
    /// The state at the pass's `stop_at` line, when it stopped there.
    pub(super) stopped: Option<Checkpoint>,
    /// The line (new numbering) at which the pass was interrupted, a checkpoint of its own.
    pub(super) interrupted_at: Option<usize>,
}

/// Where a pass stops besides convergence and the end: at `stop_at`, and at a checkpoint when
/// `interrupted` says so (see [`DocumentAnalysis::update_interruptible`]).
pub(super) struct PassLimits<'a> {
    pub(super) stop_at: usize,
    pub(super) interrupted: &'a dyn Fn() -> bool,
}

impl PassLimits<'_> {
    pub(super) const NONE: PassLimits<'static> = PassLimits {
        stop_at: usize::MAX,
        interrupted: &|| false,
    };
}

/// The per-line position reads of the lines from `base` on, which a pass fills in: a pass over part of
/// the document gets the part of the vector it owns.
pub(super) struct PositionReads<'a> {
    pub(super) base: usize,
    pub(super) reads: &'a mut [u8],
}

impl PositionReads<'_> {
    pub(super) fn get_mut(&mut self, line: usize) -> Option<&mut u8> {
        self.reads.get_mut(line.checked_sub(self.base)?)
    }

    /// Whether the lines `range` all read none of `axes` absolutely (lines outside count as reading
    /// everything).
    pub(super) fn none_read(&self, range: Range<usize>, axes: u8) -> bool {
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
    /// Reads the document forward from `start`, taking new checkpoints, until it meets one of
    /// `old_checkpoints` (all at or after `changed_end`, the first line the edit did not touch) with
    /// the same state, or the end. At an old checkpoint whose state differs only by a shift of
    /// positions, the intervals after it whose blocks read the shifted axes only incrementally are not
    /// read again: their findings stay and their checkpoints are moved by the shift.
    pub(super) fn run_pass(
        &self,
        source: &dyn LineSource,
        start: Checkpoint,
        changed_end: usize,
        old_checkpoints: &mut [Checkpoint],
        mut position_reads: PositionReads<'_>,
        limits: PassLimits<'_>,
    ) -> Pass {
        let line_count = source.line_count();
        let mut engine = Engine::from_snapshot(&self.config, Arc::unwrap_or_clone(start.engine));
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
                            engine: Arc::new(engine.snapshot()),
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
                            engine: Arc::new(engine.snapshot()),
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
                engine: Arc::new(engine.snapshot()),
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
                Arc::make_mut(&mut old_checkpoints[current].engine).shift_positions(&shift);
                let checkpoint = old_checkpoints[current].clone();
                last_checkpoint = checkpoint.line;
                pass.checkpoints.push(checkpoint);
            }
            if pass.converged_at.is_some() {
                break;
            }
            if current > next_old {
                let checkpoint = &old_checkpoints[current];
                engine =
                    Engine::from_snapshot(&self.config, EngineSnapshot::clone(&checkpoint.engine));
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
}

/// Moves the findings of the block on `line` to the document's. Most blocks have none, and the
/// extension of the document's findings costs more than asking first.
pub(super) fn move_findings(
    findings: &mut Vec<Diagnostic>,
    line: usize,
    into: &mut Vec<LineDiagnostic>,
) {
    if findings.is_empty() {
        return;
    }
    into.extend(
        findings
            .drain(..)
            .map(|diagnostic| LineDiagnostic { line, diagnostic }),
    );
}
