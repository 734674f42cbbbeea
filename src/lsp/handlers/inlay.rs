//! Inlay hints: `ide::inlay::end_point_hints` for the requested lines, placed at the end of each
//! line and wrapped in LSP types.

use crate::analysis::document::LineSource;
use crate::ide::inlay::{end_point_hints, HintScope};
use crate::lsp::convert::{end_of_line, PositionEncoding};
use crate::lsp::documents::Analysed;
use crate::lsp::settings::InlayHintMode;
use tower_lsp_server::ls_types::{InlayHint, InlayHintLabel, InlayHintTooltip, Range};

/// The hints for the lines of `range` (both ends included).
pub fn inlay_hints(
    analysed: &Analysed,
    library: &dyn crate::analysis::library::ProgramLibrary,
    range: Range,
    mode: InlayHintMode,
    encoding: PositionEncoding,
) -> Vec<InlayHint> {
    let scope = match mode {
        InlayHintMode::Off => return Vec::new(),
        InlayHintMode::NotPlain => HintScope::NotPlain,
        InlayHintMode::All => HintScope::All,
    };
    let lines = analysed.lines();
    let first = range.start.line as usize;
    let end = (range.end.line as usize).saturating_add(1);
    end_point_hints(
        &lines,
        &analysed.analysis,
        &analysed.program_run(library),
        first..end,
        scope,
    )
    .into_iter()
    .map(|hint| InlayHint {
        position: end_of_line(hint.line, &lines.line(hint.line), encoding),
        label: InlayHintLabel::String(hint.label),
        kind: None,
        text_edits: None,
        tooltip: Some(InlayHintTooltip::String(hint.tooltip.to_string())),
        padding_left: Some(true),
        padding_right: None,
        data: None,
    })
    .collect()
}
