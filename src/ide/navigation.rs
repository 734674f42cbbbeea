//! Go to definition, find references, rename and document highlights, across the documents of a
//! [`WorkspaceIndex`]: labels and block numbers used as jump targets (per program, direction-aware),
//! `DEF` variables and `PROC` parameters (per program), global `DEF`s of `.DEF` files, R parameters
//! (channel-wide), `DEFINE` macros and programs (`PROC` names, file names, calls, `EXTERN`).

use crate::config::MachineConfig;
use crate::diagnostics::Span;
use crate::ide::jumps::{resolve_jump, JumpResolution};
use crate::ide::names::{is_identifier, reserved_reason, upper};
use crate::ide::symbols::{CallStyle, JumpDestination, SymbolTable};
use crate::ide::workspace::{DocumentId, IndexedDocument, WorkspaceIndex};
use crate::ide::{LineEdit, Location};
use crate::syntax::ast::JumpKind;
use std::sync::Arc;

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

fn defines_locally(table: &SymbolTable, name: &str) -> bool {
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
fn name_occurrences(table: &SymbolTable, name: &str, with_calls: bool) -> Vec<(usize, Span, Role)> {
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

/// Go to definition: where the symbol at the cursor is defined. A jump goes to the label or block it
/// reaches (in its direction); a call to the `PROC` header, or to the start of the file named so.
pub fn definition(
    index: &WorkspaceIndex,
    document: &str,
    line: usize,
    byte: usize,
) -> Vec<Location> {
    let Some((symbol, _)) = symbol_at(index, document, line, byte) else {
        return Vec::new();
    };
    if let Some(target) = jump_target_at(index, document, line, byte) {
        return vec![target];
    }
    if let Symbol::Program { name } = &symbol {
        let mut out: Vec<Location> = Vec::new();
        for indexed in index.programs_named(name) {
            match indexed
                .symbols
                .procedure
                .as_ref()
                .filter(|procedure| &procedure.name == name)
            {
                Some(procedure) => out.push(Location {
                    document: indexed.id.clone(),
                    line: procedure.line,
                    span: procedure.span,
                }),
                None => out.push(Location {
                    document: indexed.id.clone(),
                    line: 0,
                    span: Span::new(0, 0),
                }),
            }
        }
        return out;
    }
    occurrences(index, &symbol)
        .into_iter()
        .filter(|occurrence| occurrence.role == Role::Definition)
        .map(|occurrence| occurrence.location)
        .collect()
}

/// For the target of a jump at the cursor: the label or block number it reaches, if it reaches one.
fn jump_target_at(
    index: &WorkspaceIndex,
    document: &str,
    line: usize,
    byte: usize,
) -> Option<Location> {
    let indexed = index.document(document)?;
    let table = &indexed.symbols;
    let jump = on_line(&table.jumps, line, |entry| entry.line)
        .iter()
        .find(|jump| match &jump.destination {
            JumpDestination::Label { span, .. } | JumpDestination::BlockNumber { span, .. } => {
                span.start() <= byte && byte <= span.end()
            }
            _ => false,
        })?;
    let (lines, spans): (Vec<usize>, Vec<Span>) = match &jump.destination {
        JumpDestination::Label { name, .. } => table
            .labels
            .iter()
            .filter(|label| &label.name == name)
            .map(|label| (label.line, label.span))
            .unzip(),
        JumpDestination::BlockNumber { value, .. } => table
            .block_numbers
            .iter()
            .filter(|number| number.value == *value)
            .map(|number| (number.line, number.span))
            .unzip(),
        _ => return None,
    };
    match resolve_jump(jump.kind, line, &lines) {
        JumpResolution::Found(target) | JumpResolution::WrongDirection(target) => {
            let position = lines.iter().position(|candidate| *candidate == target)?;
            Some(Location {
                document: indexed.id.clone(),
                line: target,
                span: spans[position],
            })
        }
        JumpResolution::Missing => None,
    }
}

/// Find references: every occurrence of the symbol at the cursor, the definitions included when
/// `include_declaration` is set.
pub fn references(
    index: &WorkspaceIndex,
    document: &str,
    line: usize,
    byte: usize,
    include_declaration: bool,
) -> Vec<Location> {
    let Some((symbol, _)) = symbol_at(index, document, line, byte) else {
        return Vec::new();
    };
    occurrences(index, &symbol)
        .into_iter()
        .filter(|occurrence| include_declaration || occurrence.role != Role::Definition)
        .map(|occurrence| occurrence.location)
        .collect()
}

/// Document highlights: the occurrences of the symbol at the cursor in the same document (a label
/// and the jumps to it, a variable and its reads and writes).
pub fn highlights(
    index: &WorkspaceIndex,
    document: &str,
    line: usize,
    byte: usize,
) -> Vec<(usize, Span, Role)> {
    let Some((symbol, _)) = symbol_at(index, document, line, byte) else {
        return Vec::new();
    };
    occurrences(index, &symbol)
        .into_iter()
        .filter(|occurrence| &*occurrence.location.document == document)
        .map(|occurrence| {
            (
                occurrence.location.line,
                occurrence.location.span,
                occurrence.role,
            )
        })
        .collect()
}

/// The edits of a rename, per document, and the programs whose file should be renamed with them.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct WorkspaceEdit {
    pub changes: Vec<(DocumentId, Vec<LineEdit>)>,
    /// Documents named after the renamed program (`PART2.SPF`), with the new program name: the
    /// file must be renamed too, or the control no longer finds it.
    pub renamed_programs: Vec<(DocumentId, String)>,
}

/// Why a rename cannot be done.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum RenameError {
    /// There is no renamable symbol at the cursor.
    NothingToRename,
    /// The new name is not allowed, with the reason.
    Refused(String),
}

/// Prepare rename: the span of the renamable name at the cursor and its current text.
pub fn prepare_rename(
    index: &WorkspaceIndex,
    document: &str,
    line: usize,
    byte: usize,
) -> Option<(Span, Symbol)> {
    let (symbol, span) = symbol_at(index, document, line, byte)?;
    (!matches!(symbol, Symbol::Unresolved { .. })).then_some((span, symbol))
}

/// Renames the symbol at the cursor everywhere it occurs. Refuses keywords, G functions, axis names,
/// address words and names that another symbol of the affected programs already has.
pub fn rename(
    index: &WorkspaceIndex,
    config: &MachineConfig,
    document: &str,
    line: usize,
    byte: usize,
    new_name: &str,
) -> Result<WorkspaceEdit, RenameError> {
    let (_, symbol) =
        prepare_rename(index, document, line, byte).ok_or(RenameError::NothingToRename)?;
    if let Symbol::Program { name } = &symbol {
        // A program that no indexed file defines lives on the control (a cycle, a program not in
        // the workspace): renaming its calls alone would break them.
        if index.programs_named(name).next().is_none() {
            return Err(RenameError::Refused(format!(
                "no file of the workspace defines `{name}`, so its calls cannot be renamed"
            )));
        }
    }
    let new_upper = upper(new_name.trim());
    let new_text = match &symbol {
        Symbol::RParameter { .. } => {
            let digits = new_upper.strip_prefix('R').unwrap_or("");
            if digits.is_empty() || !digits.bytes().all(|byte| byte.is_ascii_digit()) {
                return Err(RenameError::Refused(format!(
                    "`{new_name}` is not an R parameter (R followed by its number)"
                )));
            }
            let number: u32 = digits
                .parse()
                .map_err(|_| RenameError::Refused(format!("`{new_name}` is out of range")))?;
            if number >= config.r_parameter_count {
                return Err(RenameError::Refused(format!(
                    "R{number} does not exist: the machine has {} R parameters (MD28050)",
                    config.r_parameter_count
                )));
            }
            format!("R{number}")
        }
        Symbol::BlockNumber { document, value } => {
            let digits = new_upper.strip_prefix('N').unwrap_or(&new_upper);
            let number: u64 = digits
                .parse()
                .map_err(|_| RenameError::Refused(format!("`{new_name}` is not a block number")))?;
            let table = &index
                .document(document)
                .ok_or(RenameError::NothingToRename)?
                .symbols;
            if number != *value
                && table
                    .block_numbers
                    .iter()
                    .any(|entry| entry.value == number)
            {
                return Err(RenameError::Refused(format!(
                    "block number {number} is already used in this program"
                )));
            }
            number.to_string()
        }
        _ => {
            if !is_identifier(&new_upper) {
                return Err(RenameError::Refused(format!(
                    "`{new_name}` is not a name: names are letters, digits and `_`, starting with a letter or `_`"
                )));
            }
            if let Some(reason) = reserved_reason(&new_upper, config) {
                return Err(RenameError::Refused(reason));
            }
            if let Some(reason) = collision(index, &symbol, &new_upper) {
                return Err(RenameError::Refused(reason));
            }
            new_upper.clone()
        }
    };
    let mut edit = WorkspaceEdit::default();
    for occurrence in occurrences(index, &symbol) {
        let replacement = match &symbol {
            // Only the digits of `N10`/`:10` change, so `N` or `:` stays as written.
            Symbol::BlockNumber { .. } => {
                let span = occurrence.location.span;
                let edit_span = Span::new(span.start() + 1, span.end());
                (edit_span, new_text.clone())
            }
            _ => (occurrence.location.span, new_text.clone()),
        };
        let line_edit = LineEdit {
            line: occurrence.location.line,
            span: replacement.0,
            new_text: replacement.1,
        };
        match edit
            .changes
            .iter_mut()
            .find(|(id, _)| *id == occurrence.location.document)
        {
            Some((_, edits)) => edits.push(line_edit),
            None => edit
                .changes
                .push((occurrence.location.document.clone(), vec![line_edit])),
        }
    }
    if let Symbol::Program { name } = &symbol {
        for indexed in index.programs_named(name) {
            if &indexed.program_name == name {
                edit.renamed_programs
                    .push((Arc::clone(&indexed.id), new_text.clone()));
            }
        }
    }
    Ok(edit)
}

/// Why `new_name` would collide with another symbol where `symbol` is visible, if it would.
fn collision(index: &WorkspaceIndex, symbol: &Symbol, new_name: &str) -> Option<String> {
    let in_table = |table: &SymbolTable| -> Option<&'static str> {
        if table.labels.iter().any(|label| label.name == new_name) {
            return Some("a label");
        }
        if table
            .variables
            .iter()
            .any(|variable| variable.name == new_name)
        {
            return Some("a variable");
        }
        if table.procedure.as_ref().is_some_and(|procedure| {
            procedure.name == new_name
                || procedure
                    .parameters
                    .iter()
                    .any(|parameter| parameter.name == new_name)
        }) {
            return Some("the program or one of its parameters");
        }
        if table
            .macros
            .iter()
            .any(|definition| definition.name == new_name)
        {
            return Some("a macro");
        }
        None
    };
    let affected: Vec<&IndexedDocument> = match symbol {
        Symbol::Label { document, .. }
        | Symbol::BlockNumber { document, .. }
        | Symbol::Local { document, .. }
        | Symbol::Unresolved { document, .. }
        | Symbol::Macro {
            document: Some(document),
            ..
        } => index.document(document).into_iter().collect(),
        _ => index.documents().collect(),
    };
    for indexed in affected {
        if let Some(what) = in_table(&indexed.symbols) {
            return Some(format!("`{new_name}` is already {what} in {}", indexed.id));
        }
    }
    if index.programs_named(new_name).next().is_some()
        || crate::ide::cycles::cycle(new_name).is_some()
    {
        return Some(format!("`{new_name}` is already the name of a program"));
    }
    if index.global_variables(new_name).next().is_some()
        || index.global_macros(new_name).next().is_some()
    {
        return Some(format!(
            "`{new_name}` is already defined in a definition file"
        ));
    }
    None
}

/// The jump kind of `GOTOF`/`GOTOB`/... written as text, for messages.
pub fn jump_keyword(kind: JumpKind) -> &'static str {
    match kind {
        JumpKind::Gotof => "GOTOF",
        JumpKind::Gotob => "GOTOB",
        JumpKind::Goto => "GOTO",
        JumpKind::Gotoc => "GOTOC",
        JumpKind::Gotos => "GOTOS",
    }
}

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
