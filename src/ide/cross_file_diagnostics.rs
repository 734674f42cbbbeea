//! Findings that need the symbol table of a program or the workspace index (codes `W3xx`): unknown
//! subprograms, wrong argument counts, undefined jump targets and jumps in the wrong direction,
//! undefined variables, and `DEF` after the first executable block. What depends on files the index
//! may not hold (unknown programs and variables) is reported only when the index says it is complete:
//! unknown is not wrong.

use crate::config::MachineConfig;
use crate::diagnostics::{Code, Diagnostic, Fix, LineDiagnostic, Span};
use crate::ide::cycles::is_control_cycle;
use crate::ide::jumps::{resolve_jump, JumpResolution};
use crate::ide::names::reserved_reason;
use crate::ide::navigation::{jump_keyword, resolve_call, resolve_name, Symbol};
use crate::ide::symbols::{JumpDestination, ProcedureDefinition, SymbolTable};
use crate::ide::workspace::{FileKind, IndexedDocument, WorkspaceIndex};
use crate::syntax::ast::JumpKind;
use std::collections::{HashMap, HashSet};

/// The W3xx findings of one indexed document, with the configured severities, sorted by line.
pub fn cross_file_diagnostics(
    index: &WorkspaceIndex,
    document: &str,
    config: &MachineConfig,
) -> Vec<LineDiagnostic> {
    let Some(indexed) = index.document(document) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    jump_findings(&indexed.symbols, &mut out);
    definition_order_findings(&indexed.symbols, &mut out);
    call_findings(index, indexed, &mut out);
    if index.is_complete() {
        undefined_variable_findings(index, indexed, config, &mut out);
    }
    for item in &mut out {
        item.diagnostic.severity = config.severity_of(item.diagnostic.code);
    }
    out.sort_by_key(|item| (item.line, item.diagnostic.span.start()));
    out
}

fn push(out: &mut Vec<LineDiagnostic>, line: usize, diagnostic: Diagnostic) {
    out.push(LineDiagnostic { line, diagnostic });
}

/// W304 and W305: every jump to a label or block number must reach it in its direction.
fn jump_findings(table: &SymbolTable, out: &mut Vec<LineDiagnostic>) {
    let label_lines = table.label_lines();
    // A CAM program has a number on every block and rarely a jump: the map is built only when needed.
    let any_block_number_jump = table
        .jumps
        .iter()
        .any(|jump| matches!(jump.destination, JumpDestination::BlockNumber { .. }));
    let block_number_lines = if any_block_number_jump {
        table.block_number_lines()
    } else {
        HashMap::new()
    };
    for jump in &table.jumps {
        let (lines, span, shown): (&[usize], Span, String) = match &jump.destination {
            JumpDestination::Label { name, span } => (
                label_lines.get(name.as_str()).map_or(&[], Vec::as_slice),
                *span,
                format!("label `{name}`"),
            ),
            JumpDestination::BlockNumber { value, span } => (
                block_number_lines.get(value).map_or(&[], Vec::as_slice),
                *span,
                format!("block number N{value}"),
            ),
            JumpDestination::Computed | JumpDestination::None => continue,
        };
        let keyword = jump_keyword(jump.kind);
        match resolve_jump(jump.kind, jump.line, lines) {
            JumpResolution::Found(_) => {}
            JumpResolution::Missing if jump.kind == JumpKind::Gotoc => {}
            JumpResolution::Missing => push(
                out,
                jump.line,
                Diagnostic::new(
                    Code::UndefinedJumpTarget,
                    span,
                    format!("{keyword} jumps to {shown}, which this program does not contain (alarm 14080)"),
                ),
            ),
            JumpResolution::WrongDirection(_) => {
                let (where_it_is, right) = if jump.kind == JumpKind::Gotof {
                    ("above", "GOTOB")
                } else {
                    ("below", "GOTOF")
                };
                let fix = Fix::replace(format!("Write `{right}`"), jump.keyword_span, right);
                push(
                    out,
                    jump.line,
                    Diagnostic::new(
                        Code::JumpWrongDirection,
                        span,
                        format!(
                            "{keyword} searches {} only, but {shown} stands {where_it_is} this block (alarm 14080); use {right}, or GOTO to search both ways",
                            if jump.kind == JumpKind::Gotof { "forward" } else { "backward" }
                        ),
                    )
                    .with_fix(fix),
                );
            }
        }
    }
}

/// W307: `DEF` and `PROC` belong before the first executable block.
fn definition_order_findings(table: &SymbolTable, out: &mut Vec<LineDiagnostic>) {
    let Some(first_executable) = table.first_executable_line else {
        return;
    };
    let mut reported_lines = HashSet::new();
    for variable in table
        .variables
        .iter()
        .filter(|variable| variable.line > first_executable)
    {
        if reported_lines.insert(variable.line) {
            push(
                out,
                variable.line,
                Diagnostic::new(
                    Code::DefinitionAfterExecutable,
                    variable.span,
                    format!(
                        "DEF of `{}` after the first executable block: definitions must come before the program's statements (alarm 14500)",
                        variable.name
                    ),
                ),
            );
        }
    }
    if let Some(procedure) = table
        .procedure
        .as_ref()
        .filter(|procedure| procedure.line > first_executable)
    {
        push(
            out,
            procedure.line,
            Diagnostic::new(
                Code::DefinitionAfterExecutable,
                procedure.span,
                "PROC must be the first block of a subprogram (alarm 14500)",
            ),
        );
    }
}

/// W301, W302, W303: calls of programs the index does not know, and argument counts that do not fit
/// the `PROC` header (or the `EXTERN` declaration when the header is not indexed).
fn call_findings(
    index: &WorkspaceIndex,
    document: &IndexedDocument,
    out: &mut Vec<LineDiagnostic>,
) {
    let table = &document.symbols;
    // What each called name resolves to, looked up once per name: (macro, PROC header, a program).
    type Resolution<'a> = (bool, Option<&'a ProcedureDefinition>, bool);
    let mut resolutions: HashMap<&str, Resolution<'_>> = HashMap::new();
    for call in &table.calls {
        let (is_macro, procedure, known_program) =
            *resolutions.entry(call.name.as_str()).or_insert_with(|| {
                (
                    matches!(
                        resolve_call(index, document, &call.name),
                        Symbol::Macro { .. }
                    ),
                    index.procedure(&call.name).map(|(_, procedure)| procedure),
                    index.programs_named(&call.name).next().is_some(),
                )
            });
        if is_macro {
            continue;
        }
        if !known_program
            && !call.reads_as_address_word
            && index.is_complete()
            && !is_control_cycle(&call.name)
        {
            push(
                out,
                call.line,
                Diagnostic::new(
                    Code::UnknownSubprogram,
                    call.span,
                    format!(
                        "no program of the workspace is called `{}` and it is not a cycle of the control",
                        call.name
                    ),
                ),
            );
        }
        let Some(count) = call.argument_count else {
            continue;
        };
        // (parameter count, by-reference flags) from the header, else from an EXTERN declaration.
        let signature: Option<Vec<bool>> = match procedure {
            Some(procedure) if procedure.has_parameter_list || procedure.parameters.is_empty() => {
                Some(
                    procedure
                        .parameters
                        .iter()
                        .map(|parameter| parameter.by_reference)
                        .collect(),
                )
            }
            Some(_) => None,
            None => table
                .externs
                .iter()
                .find(|declaration| declaration.name == call.name)
                .and_then(|declaration| declaration.parameter_types.as_ref())
                .map(|types| {
                    types
                        .iter()
                        .map(|written| written.starts_with("VAR "))
                        .collect()
                }),
        };
        let Some(by_reference) = signature else {
            continue;
        };
        if count > by_reference.len() {
            push(
                out,
                call.line,
                Diagnostic::new(
                    Code::TooManyArguments,
                    call.span,
                    format!(
                        "`{}` takes {} parameter{}, but the call passes {count} arguments",
                        call.name,
                        by_reference.len(),
                        if by_reference.len() == 1 { "" } else { "s" }
                    ),
                ),
            );
        } else if let Some(missing) = by_reference
            .iter()
            .skip(count)
            .position(|reference| *reference)
        {
            let parameter_name = procedure
                .and_then(|procedure| procedure.parameters.get(count + missing))
                .map(|parameter| format!(" `{}`", parameter.name))
                .unwrap_or_default();
            push(
                out,
                call.line,
                Diagnostic::new(
                    Code::MissingReferenceArgument,
                    call.span,
                    format!(
                        "the call leaves out parameter {}{parameter_name} of `{}`, which is passed by reference (VAR) and needs a variable",
                        count + missing + 1,
                        call.name
                    ),
                ),
            );
        }
    }
}

/// W306: names used as variables that nothing defines. Single letters and letters with digits are
/// address words or axes; names a main program defines may be program-global data of the caller.
fn undefined_variable_findings(
    index: &WorkspaceIndex,
    document: &IndexedDocument,
    config: &MachineConfig,
    out: &mut Vec<LineDiagnostic>,
) {
    if document.kind == FileKind::Definitions {
        return;
    }
    let table = &document.symbols;
    let labels: HashSet<&str> = table
        .labels
        .iter()
        .map(|label| label.name.as_str())
        .collect();
    // Each name is checked once: the first use of an undefined name is reported.
    let mut checked: HashSet<&str> = HashSet::new();
    for name_use in &table.name_uses {
        let name = name_use.name.as_str();
        let looks_like_address = name.len() <= 1
            || (name.as_bytes()[0].is_ascii_alphabetic()
                && name.as_bytes()[1..].iter().all(u8::is_ascii_digit));
        if looks_like_address || !checked.insert(name) {
            continue;
        }
        if !matches!(
            resolve_name(index, document, name),
            Symbol::Unresolved { .. }
        ) {
            continue;
        }
        if reserved_reason(name, config).is_some()
            || labels.contains(name)
            || index.main_program_defines(name)
        {
            continue;
        }
        push(
            out,
            name_use.line,
            Diagnostic::new(
                Code::UndefinedVariable,
                name_use.span,
                format!(
                    "`{name}` is not defined: no DEF, PROC parameter, definition file or macro of the workspace defines it (alarm 12550)"
                ),
            ),
        );
    }
}
