//! The hover: `ide::hover::hover_at` on the analysed document, with positions converted and the
//! answer wrapped in LSP types.

use crate::analysis::document::LineSource;
use crate::diagnostics::Span;
use crate::ide::documentation::Documentation;
use crate::ide::hover::hover_at;
use crate::lsp::convert::{character_to_byte, span_to_range, PositionEncoding};
use crate::lsp::documents::Analysed;
use tower_lsp_server::ls_types::{Hover, HoverContents, MarkupContent, MarkupKind, Position};

/// The hover at `position` of the analysed text, `None` on a line without words. `documentation`
/// (called with the line's text, its index and the byte offset) gives the documentation of a word
/// that is neither an axis word nor a G function.
pub fn hover(
    analysed: &Analysed,
    library: &dyn crate::analysis::library::ProgramLibrary,
    position: Position,
    encoding: PositionEncoding,
    documentation: impl FnOnce(&str, usize, usize) -> Option<Documentation>,
) -> Option<Hover> {
    let lines = analysed.lines();
    let line_index = position.line as usize;
    if line_index >= lines.line_count() {
        return None;
    }
    let line = lines.line(line_index);
    let offset = character_to_byte(&line, position.character, encoding);
    let found = hover_at(
        &lines,
        &analysed.analysis,
        &analysed.program_run(library),
        line_index,
        offset,
        documentation,
    )?;
    Some(Hover {
        contents: HoverContents::Markup(MarkupContent {
            kind: MarkupKind::Markdown,
            value: found.markdown,
        }),
        range: found
            .span
            .map(|span: Span| span_to_range(line_index, &line, span, encoding)),
    })
}
