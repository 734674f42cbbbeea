//! The hover at a place of a document: on an axis word, how its value resolves; on a G function,
//! what it does, its group and the function of that group in effect before the block; on other
//! words their documentation (given by the caller); and everywhere in a block the modal state in
//! effect and the block's end point, with what the run adds (passes, calls, assumptions) and the
//! block's machining time. The values come from the analysis's `BlockReport` only.

use crate::analysis::document::{DocumentAnalysis, LineSource};
use crate::analysis::ProgramKind;
use crate::diagnostics::Span;
use crate::ide::block_words::{BlockWords, WordAt};
use crate::ide::documentation::Documentation;
use crate::ide::hover::axis::axis_hover;
use crate::ide::hover::block::block_hover;
use crate::ide::hover::gcode::gcode_hover;
use crate::ide::program_run::{ProgramRun, TIMES_MADE_UP_TO_LINES};

/// A hover's text and the span of the word it is about (`None`: the block as a whole).
#[derive(Debug, Clone, PartialEq)]
pub struct HoverText {
    pub markdown: String,
    pub span: Option<Span>,
}

/// The hover at byte `offset` of line `line` of the document `lines` analysed by `analysis`; `None`
/// on a line without words. On a word that is neither an axis word nor a G function,
/// `documentation` (called with the line's text, its index and the byte offset) gives the word's
/// documentation, shown above the block's state. `run` is asked for the program's run only when
/// program order does not tell what the block does.
pub fn hover_at(
    lines: &dyn LineSource,
    analysis: &DocumentAnalysis,
    run: &dyn ProgramRun,
    line: usize,
    offset: usize,
    documentation: impl FnOnce(&str, usize, usize) -> Option<Documentation>,
) -> Option<HoverText> {
    if line >= lines.line_count() {
        return None;
    }
    let text = lines.line(line);
    let config = analysis.config();
    let words = BlockWords::parse(&text, config);
    if words.is_empty() {
        return None;
    }
    let report = analysis.block_report(lines, line);
    let special = match words.at(offset, config) {
        Some(WordAt::Axis(word)) => {
            Some((axis_hover(&word, &words, &report, config), Some(word.span)))
        }
        Some(WordAt::GCode { code, span }) => Some((gcode_hover(code, &report), Some(span))),
        Some(WordAt::Other) | None => None,
    };
    // The run of the program adds what program order cannot show: passes, calls, assumptions. A
    // program that runs in order (the large CAM programs) is not run for a hover.
    let needs_run = report.before.flow_uncertain
        || report.after.flow_uncertain
        || analysis.kind() == ProgramKind::Subprogram
        || words.calls_a_program();
    let run_summary = needs_run
        .then(|| crate::ide::execution::execution_summary(&run.execution(), line))
        .flatten();
    let (markdown, span) = match special {
        Some(found) => found,
        None => match documentation(&text, line, offset) {
            Some(doc) => (
                format!(
                    "**{}**\n\n{}\n\n---\n\n{}",
                    doc.title,
                    doc.text,
                    block_hover(&report, config)
                ),
                Some(doc.span),
            ),
            None => (block_hover(&report, config), None),
        },
    };
    let markdown = match run_summary {
        Some(summary) => format!("{summary}\n\n---\n\n{markdown}"),
        None => markdown,
    };
    // The machining time of the block over its passes and the time before its first pass. A large
    // program shows them once the status bar or the toolpath made this revision's times: a hover
    // does not read it again after every edit.
    let times = if lines.line_count() <= TIMES_MADE_UP_TO_LINES {
        Some(run.times())
    } else {
        run.cached_times()
    };
    let time = times.and_then(|times| crate::ide::timing::time_summary(&times, line));
    let markdown = match time {
        Some(time) => format!("{markdown}\n\n---\n\n{time}"),
        None => markdown,
    };
    Some(HoverText { markdown, span })
}
