//! Go to definition (with the targets of jumps, direction-aware), find references and document
//! highlights.

use super::occurrences::occurrences;
use super::symbol::on_line;
use super::symbol::{symbol_at, Role, Symbol};
use crate::diagnostics::Span;
use crate::ide::jumps::{resolve_jump, JumpResolution};
use crate::ide::symbols::JumpDestination;
use crate::ide::workspace::WorkspaceIndex;
use crate::ide::Location;

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
pub(super) fn jump_target_at(
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
