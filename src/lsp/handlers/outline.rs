//! Document symbols (the outline) and folding ranges: the protocol's form of `ide::outline`, which
//! finds the PROC, the comment sections, labels, tool changes and control structures.

use crate::analysis::document::LineSource;
use crate::ide::outline::{self, FoldingKind, OutlineItem, OutlineKind};
use crate::ide::symbols::SymbolTable;
use crate::lsp::convert::{end_of_line, span_to_range, PositionEncoding};
use crate::lsp::documents::Analysed;
use tower_lsp_server::ls_types::{
    DocumentSymbol, FoldingRange, FoldingRangeKind, Position, Range, SymbolKind,
};

/// The outline of a document as nested document symbols.
pub fn document_symbols(analysed: &Analysed, encoding: PositionEncoding) -> Vec<DocumentSymbol> {
    let lines = analysed.lines();
    let table = SymbolTable::build(&lines, analysed.analysis.config());
    outline::document_symbols(&table)
        .iter()
        .map(|item| to_symbol(item, &lines, encoding))
        .collect()
}

/// The lines that can be folded: control structures and comment sections.
pub fn folding_ranges(analysed: &Analysed) -> Vec<FoldingRange> {
    let lines = analysed.lines();
    let table = SymbolTable::build(&lines, analysed.analysis.config());
    outline::folding_ranges(&table)
        .into_iter()
        .map(|range| FoldingRange {
            start_line: line_number(range.start_line),
            end_line: line_number(range.end_line),
            kind: Some(match range.kind {
                FoldingKind::Structure => FoldingRangeKind::Region,
                FoldingKind::Section => FoldingRangeKind::Comment,
            }),
            ..FoldingRange::default()
        })
        .collect()
}

fn to_symbol(
    item: &OutlineItem,
    lines: &dyn LineSource,
    encoding: PositionEncoding,
) -> DocumentSymbol {
    let selection_text = lines.line(item.selection_line);
    let selection_range = span_to_range(
        item.selection_line,
        &selection_text,
        item.selection_span,
        encoding,
    );
    let (first, last) = item.lines;
    let last_text = lines.line(last);
    // The whole range must contain the selection range, as the protocol requires.
    let mut range = Range::new(
        Position::new(line_number(first), 0),
        end_of_line(last, &last_text, encoding),
    );
    if range.end < selection_range.end {
        range.end = selection_range.end;
    }
    if selection_range.start < range.start {
        range.start = selection_range.start;
    }
    #[allow(deprecated)]
    DocumentSymbol {
        name: if item.name.is_empty() {
            "(unnamed)".to_string()
        } else {
            item.name.clone()
        },
        detail: (!item.detail.is_empty()).then(|| item.detail.clone()),
        kind: match item.kind {
            OutlineKind::Procedure => SymbolKind::FUNCTION,
            OutlineKind::Section => SymbolKind::NAMESPACE,
            OutlineKind::Label => SymbolKind::KEY,
            OutlineKind::ToolChange => SymbolKind::EVENT,
        },
        tags: None,
        deprecated: None,
        range,
        selection_range,
        children: (!item.children.is_empty()).then(|| {
            item.children
                .iter()
                .map(|child| to_symbol(child, lines, encoding))
                .collect()
        }),
    }
}

fn line_number(line: usize) -> u32 {
    u32::try_from(line).unwrap_or(u32::MAX)
}
