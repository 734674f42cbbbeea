//! Every occurrence of a symbol across the documents of the workspace index, with its role.

use super::symbol::{defines_locally, resolve_name, Occurrence, Role, Symbol};
use crate::diagnostics::Span;
use crate::ide::symbols::{CallStyle, JumpDestination, SymbolTable};
use crate::ide::workspace::{DocumentId, WorkspaceIndex};
use crate::ide::Location;

/// Every occurrence of a symbol in the index, in document and line order.
pub fn occurrences(index: &WorkspaceIndex, symbol: &Symbol) -> Vec<Occurrence> {
    let mut out = Vec::new();
    let mut push = |document: &DocumentId, line: usize, span: Span, role: Role| {
        out.push(Occurrence {
            location: Location {
                document: document.clone(),
                line,
                span,
            },
            role,
        })
    };
    match symbol {
        Symbol::Label { document, name } => {
            if let Some(indexed) = index.document(document) {
                let table = &indexed.symbols;
                let mut items: Vec<(usize, Span, Role)> = table
                    .labels
                    .iter()
                    .filter(|label| &label.name == name)
                    .map(|label| (label.line, label.span, Role::Definition))
                    .collect();
                for jump in &table.jumps {
                    if let JumpDestination::Label { name: target, span } = &jump.destination {
                        if target == name {
                            items.push((jump.line, *span, Role::Read));
                        }
                    }
                }
                items.sort_by_key(|(line, span, _)| (*line, span.start()));
                for (line, span, role) in items {
                    push(document, line, span, role);
                }
            }
        }
        Symbol::BlockNumber { document, value } => {
            if let Some(indexed) = index.document(document) {
                let table = &indexed.symbols;
                let mut items: Vec<(usize, Span, Role)> = table
                    .block_numbers
                    .iter()
                    .filter(|number| number.value == *value)
                    .map(|number| (number.line, number.span, Role::Definition))
                    .collect();
                for jump in &table.jumps {
                    if let JumpDestination::BlockNumber {
                        value: target,
                        span,
                    } = &jump.destination
                    {
                        if target == value {
                            items.push((jump.line, *span, Role::Read));
                        }
                    }
                }
                items.sort_by_key(|(line, span, _)| (*line, span.start()));
                for (line, span, role) in items {
                    push(document, line, span, role);
                }
            }
        }
        Symbol::Local { document, name } | Symbol::Unresolved { document, name } => {
            if let Some(indexed) = index.document(document) {
                for (line, span, role) in name_occurrences(&indexed.symbols, name, false) {
                    push(document, line, span, role);
                }
            }
        }
        Symbol::Global { name } => {
            for indexed in index.documents() {
                let local = defines_locally(&indexed.symbols, name)
                    && indexed.kind != crate::ide::workspace::FileKind::Definitions;
                if !local {
                    for (line, span, role) in name_occurrences(&indexed.symbols, name, false) {
                        push(&indexed.id, line, span, role);
                    }
                }
            }
        }
        Symbol::Macro { document, name } => {
            for indexed in index.documents() {
                let matches = match document {
                    Some(document) => &indexed.id == document,
                    None => matches!(
                        resolve_name(index, indexed, name),
                        Symbol::Macro { document: None, .. }
                    ),
                };
                if matches {
                    for (line, span, role) in name_occurrences(&indexed.symbols, name, true) {
                        push(&indexed.id, line, span, role);
                    }
                }
            }
        }
        Symbol::Program { name } => {
            for indexed in index.documents() {
                let table = &indexed.symbols;
                let mut items: Vec<(usize, Span, Role)> = Vec::new();
                if let Some(procedure) = table
                    .procedure
                    .as_ref()
                    .filter(|procedure| &procedure.name == name)
                {
                    items.push((procedure.line, procedure.span, Role::Definition));
                }
                for declaration in table
                    .externs
                    .iter()
                    .filter(|declaration| &declaration.name == name)
                {
                    items.push((declaration.line, declaration.span, Role::Read));
                }
                let is_macro_here =
                    matches!(resolve_name(index, indexed, name), Symbol::Macro { .. });
                if !is_macro_here {
                    for call in table.calls.iter().filter(|call| &call.name == name) {
                        items.push((call.line, call.span, Role::Read));
                    }
                }
                items.sort_by_key(|(line, span, _)| (*line, span.start()));
                for (line, span, role) in items {
                    push(&indexed.id, line, span, role);
                }
            }
        }
        Symbol::RParameter { number } => {
            for indexed in index.documents() {
                for parameter in indexed
                    .symbols
                    .r_parameters
                    .iter()
                    .filter(|parameter| parameter.number == Some(*number))
                {
                    let role = if parameter.write {
                        Role::Write
                    } else {
                        Role::Read
                    };
                    push(&indexed.id, parameter.line, parameter.span, role);
                }
            }
        }
    }
    out
}

/// Definitions, reads and writes of a variable-like name in one table, in line order. With
/// `with_calls`, calls of the name count too (a macro used alone in a block reads like a call).
pub(super) fn name_occurrences(
    table: &SymbolTable,
    name: &str,
    with_calls: bool,
) -> Vec<(usize, Span, Role)> {
    let mut items: Vec<(usize, Span, Role)> = Vec::new();
    if let Some(procedure) = &table.procedure {
        for parameter in procedure
            .parameters
            .iter()
            .filter(|parameter| parameter.name == name)
        {
            items.push((parameter.line, parameter.span, Role::Definition));
        }
    }
    for variable in table
        .variables
        .iter()
        .filter(|variable| variable.name == name)
    {
        items.push((variable.line, variable.span, Role::Definition));
    }
    for definition in table
        .macros
        .iter()
        .filter(|definition| definition.name == name)
    {
        items.push((definition.line, definition.span, Role::Definition));
    }
    for name_use in table
        .name_uses
        .iter()
        .filter(|name_use| name_use.name == name)
    {
        items.push((
            name_use.line,
            name_use.span,
            if name_use.write {
                Role::Write
            } else {
                Role::Read
            },
        ));
    }
    if with_calls {
        for call in table
            .calls
            .iter()
            .filter(|call| call.name == name && call.style == CallStyle::Named)
        {
            items.push((call.line, call.span, Role::Read));
        }
    }
    items.sort_by_key(|(line, span, _)| (*line, span.start()));
    items
}
