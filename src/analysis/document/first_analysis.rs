//! The first analysis of a whole document: the whole-document facts, then one pass over every line;
//! for a large document on two threads (the second half from a guess of the state in the middle,
//! checked against the true state and read again where they differ).

use crate::analysis::document::document_state::{
    Checkpoint, DocumentAnalysis, CHECKPOINT_INTERVAL, GUESS_HEAD_LINES, GUESS_TAIL_LINES,
    PARALLEL_HALF_MIN_LINES,
};
use crate::analysis::document::facts::DocumentFacts;
use crate::analysis::document::incremental::MovedLines;
use crate::analysis::document::line_source::LineSource;
use crate::analysis::document::pass::{PassLimits, PositionReads};
use crate::analysis::engine::engine_state::Engine;
use crate::analysis::engine::snapshot::EngineSnapshot;
use crate::analysis::position_reads::READS_ALL;
use crate::analysis::program_kind::ProgramKind;
use crate::syntax::structure::StructureChecker;
use crate::syntax::{Block, LineParser, SyntaxContext};
use std::sync::Arc;

impl DocumentAnalysis {
    /// Analyses the whole document again.
    pub(super) fn recompute(&mut self, source: &dyn LineSource) {
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
    }

    /// Reads the whole-document facts (macros, `PROC` headers) and gives the state before line 0.
    pub(super) fn prepare_from_scratch(&mut self, source: &dyn LineSource) -> Checkpoint {
        let facts = DocumentFacts::read(source, 0, usize::MAX);
        self.start_from_facts(facts)
    }

    /// [`DocumentAnalysis::prepare_from_scratch`] with the lines from `middle` on read on a second
    /// thread from `helper_source` (the same text).
    pub(super) fn prepare_from_scratch_in_parallel(
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
    pub(super) fn start_from_facts(&mut self, facts: DocumentFacts) -> Checkpoint {
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
            engine: Arc::new(engine.snapshot()),
            structure: StructureChecker::default(),
        }
    }

    /// Analyses the whole document on two threads: this one reads the first half; `helper_source`
    /// (the same text) is read on a second thread from the middle on, starting from a guess of the
    /// state there. When the first half ends in exactly the guessed state, the second half's results
    /// stand as they are; otherwise the second half is read again from the true state the way an edit
    /// is, stopping where the states meet or carrying a shift of positions, so the result is always
    /// the one of [`DocumentAnalysis::recompute`].
    pub(super) fn recompute_in_parallel(
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
            && Engine::from_snapshot(&self.config, EngineSnapshot::clone(&end_of_first.engine))
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
    pub(super) fn guess_state_at(
        &self,
        source: &dyn LineSource,
        start: &Checkpoint,
        middle: usize,
    ) -> Checkpoint {
        let mut engine = Engine::from_snapshot(&self.config, EngineSnapshot::clone(&start.engine));
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
            engine: Arc::new(engine.snapshot()),
            structure,
        }
    }
}
