//! The analysis of one open document, kept up to date as the text changes: what the language server
//! asks of the core. The text itself stays with the caller (a rope in the server, a string in tests)
//! and is read through [`LineSource`]; this type keeps only what it derived from it.
//!
//! This first version recomputes the whole analysis on every update; the interface is the one the
//! incremental version keeps (edits by line range, lazy replay for a block's report).

use crate::analysis::engine::Engine;
use crate::analysis::state::{ModalState, Pole};
use crate::analysis::{analyze_program, Move, ProgramKind};
use crate::config::MachineConfig;
use crate::diagnostics::LineDiagnostic;
use crate::syntax::lines;
use std::borrow::Cow;
use std::ops::Range;
use std::sync::Arc;

/// Read access to the lines of a document. Line `index` is returned without its line terminator.
pub trait LineSource {
    fn line_count(&self) -> usize;
    fn line(&self, index: usize) -> Cow<'_, str>;
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

/// How the value of an axis word is read (reference §3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ResolutionMode {
    /// Modal G90: the value is the end point.
    Absolute,
    /// Modal G91: the value is added to the last position.
    Incremental,
    /// A non-modal override written on the word: `AC`, `IC`, `DC`, `ACP`, `ACN`, `DAC`, `DIC`, `RAC`,
    /// `RIC`, `CAC`, `CIC`, `CACP`, `CACN`, `CDC`.
    Override(crate::syntax::ast::Modifier),
    /// G53, G153 or SUPA in the block: the value is a machine position.
    Machine,
    /// The mode is inherited from an unseen caller (a subprogram that has not programmed G90/G91).
    Unknown,
}

/// The resolution of one axis word, with the steps a person needs to follow it.
#[derive(Debug, Clone, PartialEq)]
pub struct WordResolution {
    /// The word's byte span within the line.
    pub span: crate::diagnostics::Span,
    /// The axis name in upper case (`X`, `Z1`).
    pub axis: String,
    /// The value as written (after evaluating an expression), in the program's units; `None` when it
    /// depends on something unknown.
    pub programmed: Option<f64>,
    pub mode: ResolutionMode,
    /// The factor from program units to the basic system (25.4 under G70 on a metric machine).
    pub unit_factor: Option<f64>,
    /// Whether the value was read as a diameter (DIAMON, DIAM90 absolute, DAC, DIC).
    pub read_as_diameter: bool,
    /// The axis position before the block, as the program shows it (a diameter under DIAMON).
    pub start: Option<f64>,
    /// The resolved end point, as the program shows it.
    pub end: Option<f64>,
    /// The end point after the programmable frame (machine coordinates, a radius on transverse axes).
    pub machine: Option<f64>,
    /// Why the end point is unknown, when it is.
    pub unknown_reason: Option<String>,
}

/// The analysis of a document.
pub struct DocumentAnalysis {
    config: Arc<MachineConfig>,
    kind: ProgramKind,
    diagnostics: Vec<LineDiagnostic>,
    moves: Vec<Move>,
}

impl DocumentAnalysis {
    /// Analyses the whole document.
    pub fn new(
        source: &dyn LineSource,
        config: Arc<MachineConfig>,
        kind: ProgramKind,
    ) -> DocumentAnalysis {
        let mut analysis = DocumentAnalysis {
            config,
            kind,
            diagnostics: Vec::new(),
            moves: Vec::new(),
        };
        analysis.recompute(source);
        analysis
    }

    /// The text changed: lines `first_line .. first_line + removed` of the old text were replaced by
    /// the `inserted` lines now at `first_line .. first_line + inserted` of `source`.
    pub fn update(
        &mut self,
        source: &dyn LineSource,
        first_line: usize,
        removed: usize,
        inserted: usize,
    ) {
        let _ = (first_line, removed, inserted);
        self.recompute(source);
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
        &self.diagnostics
    }

    /// The moves of the blocks in `lines` (0-based, end exclusive), in program order.
    pub fn moves(&self, _source: &dyn LineSource, lines: Range<usize>) -> Vec<Move> {
        self.moves
            .iter()
            .filter(|movement| lines.contains(&movement.line))
            .cloned()
            .collect()
    }

    /// The state before and after the block on `line`, and its move. A line past the end reports the
    /// state at the end of the program.
    pub fn block_report(&self, source: &dyn LineSource, line: usize) -> BlockReport {
        let mut engine = Engine::new(&self.config);
        let text = joined_text(source, 0..line.saturating_add(1).min(source.line_count()));
        if is_subprogram(self.kind, &text) {
            engine.assume_inherited_state();
        }
        let mut before = None;
        let mut movement = None;
        crate::syntax::visit_blocks(&text, &self.config, |index, line_text, block, found| {
            if index == line {
                before = Some(summarize(
                    &self.config,
                    &engine.state,
                    engine.flow_uncertain(),
                ));
            }
            let result = engine.apply(index, line_text, block, found);
            if index == line {
                movement = result;
            }
        });
        let after = summarize(&self.config, &engine.state, engine.flow_uncertain());
        BlockReport {
            line,
            before: before.unwrap_or_else(|| after.clone()),
            after,
            movement,
            words: Vec::new(),
        }
    }

    fn recompute(&mut self, source: &dyn LineSource) {
        let text = joined_text(source, 0..source.line_count());
        let analysis = analyze_program(&text, &self.config, self.kind);
        self.diagnostics = analysis.diagnostics;
        self.moves = analysis.moves;
    }
}

fn is_subprogram(kind: ProgramKind, text: &str) -> bool {
    kind == ProgramKind::Subprogram
        || lines::line_ranges(text).any(|(start, end)| {
            text[start..end]
                .trim_start()
                .get(..4)
                .is_some_and(|word| word.eq_ignore_ascii_case("PROC"))
        })
}

fn joined_text(source: &dyn LineSource, lines: Range<usize>) -> String {
    let mut text = String::new();
    for index in lines {
        text.push_str(&source.line(index));
        text.push('\n');
    }
    text
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
            let value = state.positions[index].and_then(|value| {
                if axis.kind == crate::config::AxisKind::Transverse {
                    shows_diameter.map(|diameter| if diameter { value * 2.0 } else { value })
                } else {
                    Some(value)
                }
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
}
