//! Rename: which names may be renamed, the edits across the workspace, and the collisions that
//! refuse a new name.

use super::occurrences::occurrences;
use super::symbol::{symbol_at, Symbol};
use crate::config::MachineConfig;
use crate::diagnostics::Span;
use crate::ide::names::{is_identifier, reserved_reason, upper};
use crate::ide::symbols::SymbolTable;
use crate::ide::workspace::{DocumentId, IndexedDocument, WorkspaceIndex};
use crate::ide::LineEdit;
use crate::syntax::ast::JumpKind;
use std::sync::Arc;

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
pub(super) fn collision(index: &WorkspaceIndex, symbol: &Symbol, new_name: &str) -> Option<String> {
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
