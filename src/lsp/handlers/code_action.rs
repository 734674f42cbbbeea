//! Code actions: the quick fixes carried by the diagnostics of the requested range.

use crate::analysis::document::LineSource;
use crate::lsp::convert::{diagnostic_to_lsp, fix_edits, PositionEncoding};
use crate::lsp::documents::Analysed;
use std::collections::HashMap;
use tower_lsp_server::ls_types::{
    CodeAction, CodeActionKind, CodeActionOrCommand, Position, Range, Uri, WorkspaceEdit,
};

fn overlaps(left: Range, right: Range) -> bool {
    let before = |a: Position, b: Position| (a.line, a.character) <= (b.line, b.character);
    before(left.start, right.end) && before(right.start, left.end)
}

/// One quick fix per diagnostic with a fix whose range meets `range`.
pub fn code_actions(
    analysed: &Analysed,
    uri: &Uri,
    range: Range,
    encoding: PositionEncoding,
) -> Vec<CodeActionOrCommand> {
    let lines = analysed.lines();
    let diagnostics = analysed.analysis.diagnostics();
    let first_line = range.start.line as usize;
    let last_line = range.end.line as usize;
    let start = diagnostics.partition_point(|item| item.line < first_line);
    diagnostics[start..]
        .iter()
        .take_while(|item| item.line <= last_line)
        .filter(|item| item.diagnostic.fix.is_some())
        .filter_map(|item| {
            let line = lines.line(item.line);
            let diagnostic = diagnostic_to_lsp(item, &line, encoding);
            if !overlaps(diagnostic.range, range) {
                return None;
            }
            let fix = item.diagnostic.fix.as_ref()?;
            let edits = fix_edits(item, &line, encoding);
            Some(CodeActionOrCommand::CodeAction(CodeAction {
                title: fix.title.clone(),
                kind: Some(CodeActionKind::QUICKFIX),
                diagnostics: Some(vec![diagnostic]),
                edit: Some(WorkspaceEdit {
                    changes: Some(HashMap::from([(uri.clone(), edits)])),
                    ..WorkspaceEdit::default()
                }),
                is_preferred: Some(true),
                ..CodeAction::default()
            }))
        })
        .collect()
}
