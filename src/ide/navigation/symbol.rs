//! What a name at the cursor stands for: the symbol under a cursor (`symbol_at`), and how a name or
//! a call resolves within one document of the workspace (`resolve_name`, `resolve_call`).

use crate::diagnostics::Span;
use crate::ide::symbols::{JumpDestination, SymbolTable};
use crate::ide::workspace::{DocumentId, IndexedDocument, WorkspaceIndex};
use crate::ide::Location;

/// What a name at the cursor stands for.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Symbol {
    /// A label of one program.
    Label {
        document: DocumentId,
        name: String,
    },
    /// A block number of one program.
    BlockNumber {
        document: DocumentId,
        value: u64,
    },
    /// A `DEF` variable or `PROC` parameter local to one program.
    Local {
        document: DocumentId,
        name: String,
    },
    /// Global user data: a `DEF` in a `.DEF` file or with `NCK`/`CHAN`.
    Global {
        name: String,
    },
    /// A macro of one program (`document`) or of a `.DEF` file (`None`).
    Macro {
        document: Option<DocumentId>,
        name: String,
    },
    /// A subprogram or cycle.
    Program {
        name: String,
    },
    RParameter {
        number: u32,
    },
    /// A name that nothing defines (in this program or the index).
    Unresolved {
        document: DocumentId,
        name: String,
    },
}

/// How an occurrence uses its symbol.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    Definition,
    Read,
    Write,
}

/// One place where a symbol occurs.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Occurrence {
    pub location: Location,
    pub role: Role,
}

/// The symbol at `line`/`byte` of a document and the span of the name there.
pub fn symbol_at(
    index: &WorkspaceIndex,
    document: &str,
    line: usize,
    byte: usize,
) -> Option<(Symbol, Span)> {
    let indexed = index.document(document)?;
    let table = &indexed.symbols;
    let id = &indexed.id;
    let hit = |span: Span| span.start() <= byte && byte <= span.end();
    for label in on_line(&table.labels, line, |entry| entry.line).iter() {
        if hit(label.span) {
            return Some((
                Symbol::Label {
                    document: id.clone(),
                    name: label.name.clone(),
                },
                label.span,
            ));
        }
    }
    for jump in on_line(&table.jumps, line, |entry| entry.line).iter() {
        match &jump.destination {
            JumpDestination::Label { name, span } if hit(*span) => {
                return Some((
                    Symbol::Label {
                        document: id.clone(),
                        name: name.clone(),
                    },
                    *span,
                ))
            }
            JumpDestination::BlockNumber { value, span } if hit(*span) => {
                return Some((
                    Symbol::BlockNumber {
                        document: id.clone(),
                        value: *value,
                    },
                    *span,
                ))
            }
            _ => {}
        }
    }
    for number in table.block_numbers.on_line(line) {
        if hit(number.span) {
            return Some((
                Symbol::BlockNumber {
                    document: id.clone(),
                    value: number.value,
                },
                number.span,
            ));
        }
    }
    if let Some(procedure) = table
        .procedure
        .as_ref()
        .filter(|procedure| procedure.line == line)
    {
        if hit(procedure.span) {
            return Some((
                Symbol::Program {
                    name: procedure.name.clone(),
                },
                procedure.span,
            ));
        }
        for parameter in &procedure.parameters {
            if hit(parameter.span) {
                return Some((
                    Symbol::Local {
                        document: id.clone(),
                        name: parameter.name.clone(),
                    },
                    parameter.span,
                ));
            }
        }
    }
    for variable in on_line(&table.variables, line, |entry| entry.line).iter() {
        if hit(variable.span) {
            return Some((resolve_name(index, indexed, &variable.name), variable.span));
        }
    }
    for definition in on_line(&table.macros, line, |entry| entry.line).iter() {
        if hit(definition.span) {
            return Some((
                resolve_name(index, indexed, &definition.name),
                definition.span,
            ));
        }
    }
    for declaration in on_line(&table.externs, line, |entry| entry.line).iter() {
        if hit(declaration.span) {
            return Some((
                Symbol::Program {
                    name: declaration.name.clone(),
                },
                declaration.span,
            ));
        }
    }
    for call in on_line(&table.calls, line, |entry| entry.line).iter() {
        if hit(call.span) {
            return Some((resolve_call(index, indexed, &call.name), call.span));
        }
    }
    for name_use in on_line(&table.name_uses, line, |entry| entry.line).iter() {
        if hit(name_use.span) {
            return Some((resolve_name(index, indexed, &name_use.name), name_use.span));
        }
    }
    for parameter in on_line(&table.r_parameters, line, |entry| entry.line).iter() {
        if let (true, Some(number)) = (hit(parameter.span), parameter.number) {
            return Some((Symbol::RParameter { number }, parameter.span));
        }
    }
    None
}

/// The entries of a list sorted by line that stand on `line`.
pub(crate) fn on_line<T>(entries: &[T], line: usize, line_of: impl Fn(&T) -> usize) -> &[T] {
    let start = entries.partition_point(|entry| line_of(entry) < line);
    let end = start + entries[start..].partition_point(|entry| line_of(entry) <= line);
    &entries[start..end]
}

pub(super) fn defines_locally(table: &SymbolTable, name: &str) -> bool {
    table.procedure.as_ref().is_some_and(|procedure| {
        procedure
            .parameters
            .iter()
            .any(|parameter| parameter.name == name)
    }) || table
        .variables
        .iter()
        .any(|variable| variable.name == name && variable.global_attribute.is_none())
}

/// What a variable-like name means in a document: a local definition wins over a macro of the
/// program, which wins over global data and macros of definition files (reference §8.9).
pub fn resolve_name(index: &WorkspaceIndex, document: &IndexedDocument, name: &str) -> Symbol {
    let table = &document.symbols;
    let in_definition_file = document.kind == crate::ide::workspace::FileKind::Definitions;
    if defines_locally(table, name) && !in_definition_file {
        return Symbol::Local {
            document: document.id.clone(),
            name: name.to_string(),
        };
    }
    if table
        .macros
        .iter()
        .any(|definition| definition.name == name)
        && !in_definition_file
    {
        return Symbol::Macro {
            document: Some(document.id.clone()),
            name: name.to_string(),
        };
    }
    if table.variables.iter().any(|variable| variable.name == name)
        || index.global_variables(name).next().is_some()
    {
        return Symbol::Global {
            name: name.to_string(),
        };
    }
    if in_definition_file
        && table
            .macros
            .iter()
            .any(|definition| definition.name == name)
        || index.global_macros(name).next().is_some()
    {
        return Symbol::Macro {
            document: None,
            name: name.to_string(),
        };
    }
    Symbol::Unresolved {
        document: document.id.clone(),
        name: name.to_string(),
    }
}

/// What a called name means: a macro reads like a call, so macros come first (reference §8.10).
pub fn resolve_call(index: &WorkspaceIndex, document: &IndexedDocument, name: &str) -> Symbol {
    match resolve_name(index, document, name) {
        symbol @ Symbol::Macro { .. } => symbol,
        _ => Symbol::Program {
            name: name.to_string(),
        },
    }
}
