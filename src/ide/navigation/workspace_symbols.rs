//! Workspace symbols: programs, labels, global variables and macros matching a query.

use crate::diagnostics::Span;
use crate::ide::names::upper;
use crate::ide::workspace::WorkspaceIndex;
use crate::ide::Location;

/// What a workspace symbol is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WorkspaceSymbolKind {
    Program,
    Label,
    GlobalVariable,
    Macro,
}

/// Workspace symbols: programs (their `PROC` header or file), labels, global variables and macros of
/// definition files whose name contains `query` (any case; an empty query matches everything).
pub fn workspace_symbols(
    index: &WorkspaceIndex,
    query: &str,
) -> Vec<(String, WorkspaceSymbolKind, Location)> {
    let query = upper(query);
    let wanted = |name: &str| name.contains(&query);
    let mut out = Vec::new();
    for indexed in index.documents() {
        let table = &indexed.symbols;
        let definitions = indexed.kind == crate::ide::workspace::FileKind::Definitions;
        let at = |line: usize, span: Span| Location {
            document: indexed.id.clone(),
            line,
            span,
        };
        match &table.procedure {
            Some(procedure) if wanted(&procedure.name) => out.push((
                procedure.name.clone(),
                WorkspaceSymbolKind::Program,
                at(procedure.line, procedure.span),
            )),
            None if !definitions && wanted(&indexed.program_name) => out.push((
                indexed.program_name.clone(),
                WorkspaceSymbolKind::Program,
                at(0, Span::new(0, 0)),
            )),
            _ => {}
        }
        for label in table.labels.iter().filter(|label| wanted(&label.name)) {
            out.push((
                label.name.clone(),
                WorkspaceSymbolKind::Label,
                at(label.line, label.span),
            ));
        }
        for variable in table.variables.iter().filter(|variable| {
            (definitions || variable.global_attribute.is_some()) && wanted(&variable.name)
        }) {
            out.push((
                variable.name.clone(),
                WorkspaceSymbolKind::GlobalVariable,
                at(variable.line, variable.span),
            ));
        }
        for definition in table
            .macros
            .iter()
            .filter(|definition| definitions && wanted(&definition.name))
        {
            out.push((
                definition.name.clone(),
                WorkspaceSymbolKind::Macro,
                at(definition.line, definition.span),
            ));
        }
    }
    out
}
