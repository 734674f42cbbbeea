//! What a document's analysis tells about its blocks on request, replaying from the nearest
//! checkpoint: the moves of a range of lines, and a block's report (the state before and after it in
//! words a person reads, its move, how its axis words resolve).

use crate::analysis::document::document_state::DocumentAnalysis;
use crate::analysis::document::line_source::LineSource;
use crate::analysis::engine::engine_state::Engine;
use crate::analysis::engine::moves::Move;
use crate::analysis::engine::snapshot::EngineSnapshot;
use crate::analysis::resolution::WordResolution;
use crate::analysis::state::{ModalState, Pole};
use crate::config::MachineConfig;
use crate::syntax::{Block, LineParser};
use std::ops::Range;

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

impl DocumentAnalysis {
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
    pub(super) fn for_each_move(
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
        let mut engine =
            Engine::from_snapshot(&self.config, EngineSnapshot::clone(&checkpoint.engine));
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

    /// Whether flow is uncertain before or after the block on `line` (`before.flow_uncertain ||
    /// after.flow_uncertain` of its [`Self::block_report`]), when the checkpoints tell it without
    /// replaying blocks: once a label, jump or structure has been passed, flow stays uncertain to the
    /// end, so the checkpoint before the line tells when it is uncertain there and the checkpoint
    /// after the line when it is certain through the block. `None` when neither tells (the line is in
    /// the last interval and flow is certain before it).
    pub fn flow_uncertain_by_checkpoints(&self, line: usize) -> Option<bool> {
        if self.checkpoint_before(line).engine.flow_uncertain() {
            return Some(true);
        }
        let after = self
            .checkpoints
            .partition_point(|checkpoint| checkpoint.line <= line);
        self.checkpoints
            .get(after)
            .filter(|checkpoint| !checkpoint.engine.flow_uncertain())
            .map(|_| false)
    }

    /// The state before and after the block on `line`, its move and how its axis words resolve. A
    /// line past the end reports the state at the end of the program.
    pub fn block_report(&self, source: &dyn LineSource, line: usize) -> BlockReport {
        let checkpoint = self.checkpoint_before(line);
        let mut engine =
            Engine::from_snapshot(&self.config, EngineSnapshot::clone(&checkpoint.engine));
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
