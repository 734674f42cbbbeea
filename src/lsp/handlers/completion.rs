//! Completion: the protocol's form of `ide::completion` (G functions with their group, keywords,
//! axes, variables and labels in scope, subprograms and cycles with a parameter snippet). It reads
//! the document's index entry as it is, which may be a few edits old: completion is asked for on
//! every keystroke, and rebuilding the symbol table of a large program each time would cost more
//! than a label list that lags by 300 ms.

use crate::ide::completion::{completion, CompletionKind};
use crate::lsp::documents::Analysed;
use crate::lsp::handlers::navigation::line_at;
use crate::lsp::state::DocumentRequest;
use tower_lsp_server::ls_types::{
    CompletionItem, CompletionItemKind, CompletionItemLabelDetails, Documentation,
    InsertTextFormat, MarkupContent, MarkupKind, Position,
};

/// The characters after which the client asks for completion without a letter typed: `$` starts a
/// system variable.
pub const TRIGGER_CHARACTERS: [&str; 1] = ["$"];

fn item_kind(kind: CompletionKind) -> CompletionItemKind {
    match kind {
        CompletionKind::GCode | CompletionKind::Keyword => CompletionItemKind::KEYWORD,
        CompletionKind::Function => CompletionItemKind::FUNCTION,
        CompletionKind::Modifier => CompletionItemKind::OPERATOR,
        CompletionKind::SystemVariable => CompletionItemKind::CONSTANT,
        CompletionKind::Axis => CompletionItemKind::FIELD,
        CompletionKind::Variable | CompletionKind::Parameter => CompletionItemKind::VARIABLE,
        CompletionKind::Macro => CompletionItemKind::CONSTANT,
        CompletionKind::Label => CompletionItemKind::REFERENCE,
        CompletionKind::Subprogram | CompletionKind::Cycle => CompletionItemKind::MODULE,
    }
}

/// `textDocument/completion`; snippets only for clients that take them.
pub fn completion_items(
    request: &DocumentRequest,
    analysed: &Analysed,
    position: Position,
    snippets: bool,
) -> Vec<CompletionItem> {
    let shared = &request.shared;
    let id = shared.workspace.ensure_present(&request.uri, analysed);
    let Some((line, text, byte)) = line_at(analysed, position, request.encoding) else {
        return Vec::new();
    };
    let state = shared.workspace.read();
    completion(
        &state.index,
        &id,
        &text,
        line,
        byte,
        analysed.analysis.config(),
    )
    .into_iter()
    .map(|item| {
        let snippet = item.snippet.filter(|_| snippets);
        CompletionItem {
            kind: Some(item_kind(item.kind)),
            label_details: (!item.detail.is_empty()).then(|| CompletionItemLabelDetails {
                detail: None,
                description: Some(item.detail.clone()),
            }),
            detail: (!item.detail.is_empty()).then_some(item.detail),
            documentation: item.documentation.map(|text| {
                Documentation::MarkupContent(MarkupContent {
                    kind: MarkupKind::Markdown,
                    value: text,
                })
            }),
            insert_text_format: snippet.as_ref().map(|_| InsertTextFormat::SNIPPET),
            insert_text: snippet,
            label: item.label,
            ..CompletionItem::default()
        }
    })
    .collect()
}
