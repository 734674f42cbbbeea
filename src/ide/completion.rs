//! Completion at a cursor: G functions and keywords with their description and group (from the
//! shared [`language_docs`](crate::ide::language_docs) table), the machine's axes, the variables,
//! parameters and macros in scope, labels after a jump keyword (in the jump's direction), and
//! subprograms and cycles with a parameter snippet.

use crate::config::MachineConfig;
use crate::ide::cycles::CYCLES;
use crate::ide::language_docs::{all_entries, EntryKind};
use crate::ide::workspace::{FileKind, WorkspaceIndex};
use crate::syntax::lexer::{lex_line_into, Token};

/// What a completion item inserts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CompletionKind {
    GCode,
    Keyword,
    Function,
    Modifier,
    SystemVariable,
    Axis,
    Variable,
    Parameter,
    Macro,
    Label,
    Subprogram,
    Cycle,
}

/// One proposal.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CompletionItem {
    pub label: String,
    pub kind: CompletionKind,
    /// A short detail: the G group, a variable's type, a call signature.
    pub detail: String,
    pub documentation: Option<String>,
    /// A snippet in the common `${1:name}` syntax for calls with parameters; `None` inserts the label.
    pub snippet: Option<String>,
}

impl CompletionItem {
    fn plain(
        label: impl Into<String>,
        kind: CompletionKind,
        detail: impl Into<String>,
    ) -> CompletionItem {
        CompletionItem {
            label: label.into(),
            kind,
            detail: detail.into(),
            documentation: None,
            snippet: None,
        }
    }
}

/// The proposals at byte `byte` of `line_text` (line `line` of `document`), filtered by the word
/// already typed (in any case). Nothing inside comments and strings.
pub fn completion(
    index: &WorkspaceIndex,
    document: &str,
    line_text: &str,
    line: usize,
    byte: usize,
    config: &MachineConfig,
) -> Vec<CompletionItem> {
    let byte = floor_char_boundary(line_text, byte);
    let before = &line_text[..byte];
    let mut lexemes = Vec::new();
    lex_line_into(before, &mut lexemes);
    if lexemes.last().is_some_and(|lexeme| {
        matches!(
            lexeme.token,
            Some(Token::Comment) | Some(Token::UnterminatedString)
        )
    }) {
        return Vec::new();
    }
    let prefix_start = before
        .bytes()
        .rposition(|byte| !(byte.is_ascii_alphanumeric() || byte == b'_' || byte == b'$'))
        .map_or(0, |position| position + 1);
    let prefix = before[prefix_start..].to_ascii_uppercase();
    let previous_word = before[..prefix_start]
        .trim_end()
        .rsplit(|character: char| !(character.is_ascii_alphanumeric() || character == '_'))
        .next()
        .unwrap_or("")
        .to_ascii_uppercase();
    let matches = |label: &str| label.to_ascii_uppercase().starts_with(&prefix);
    let table = index
        .document(document)
        .map(|indexed| indexed.symbols.clone());

    if let Some(direction) = jump_direction(&previous_word) {
        let mut items = Vec::new();
        if let Some(table) = &table {
            for label in &table.labels {
                let reachable = match direction {
                    Direction::Forward => label.line > line,
                    Direction::Backward => label.line < line,
                    Direction::Both => true,
                };
                if reachable
                    && matches(&label.name)
                    && !items
                        .iter()
                        .any(|item: &CompletionItem| item.label == label.name)
                {
                    items.push(CompletionItem::plain(
                        label.name.clone(),
                        CompletionKind::Label,
                        format!("label, line {}", label.line + 1),
                    ));
                }
            }
        }
        return items;
    }

    let mut items: Vec<CompletionItem> = Vec::new();
    for entry in all_entries() {
        if !matches(&entry.name) {
            continue;
        }
        let kind = match entry.kind {
            EntryKind::GCode { .. } => CompletionKind::GCode,
            EntryKind::Keyword => CompletionKind::Keyword,
            EntryKind::Function | EntryKind::Instruction => CompletionKind::Function,
            EntryKind::Modifier => CompletionKind::Modifier,
            EntryKind::SystemVariable => CompletionKind::SystemVariable,
            // Cycles come below, with their snippets.
            EntryKind::Cycle => continue,
        };
        items.push(CompletionItem {
            label: entry.name,
            kind,
            detail: entry.detail,
            documentation: Some(entry.summary),
            snippet: None,
        });
    }
    for axis in &config.axes {
        if matches(&axis.name) {
            items.push(CompletionItem::plain(
                axis.name.clone(),
                CompletionKind::Axis,
                format!("{} axis", axis.kind.as_str()),
            ));
        }
    }
    if let Some(table) = &table {
        if let Some(procedure) = &table.procedure {
            for parameter in procedure
                .parameters
                .iter()
                .filter(|parameter| matches(&parameter.name))
            {
                let reference = if parameter.by_reference { "VAR " } else { "" };
                items.push(CompletionItem::plain(
                    parameter.name.clone(),
                    CompletionKind::Parameter,
                    format!("{reference}{} parameter", parameter.type_name),
                ));
            }
        }
        for variable in table
            .variables
            .iter()
            .filter(|variable| matches(&variable.name))
        {
            let dimensions = variable.dimensions.clone().unwrap_or_default();
            items.push(CompletionItem::plain(
                variable.name.clone(),
                CompletionKind::Variable,
                format!("DEF {}{dimensions}", variable.type_name),
            ));
        }
        for definition in table
            .macros
            .iter()
            .filter(|definition| matches(&definition.name))
        {
            items.push(CompletionItem::plain(
                definition.name.clone(),
                CompletionKind::Macro,
                format!("DEFINE AS {}", definition.body),
            ));
        }
    }
    for indexed in index.documents() {
        let symbols = &indexed.symbols;
        if indexed.kind == FileKind::Definitions {
            for variable in symbols
                .variables
                .iter()
                .filter(|variable| matches(&variable.name))
            {
                items.push(CompletionItem::plain(
                    variable.name.clone(),
                    CompletionKind::Variable,
                    format!("global DEF {} ({})", variable.type_name, indexed.id),
                ));
            }
            for definition in symbols
                .macros
                .iter()
                .filter(|definition| matches(&definition.name))
            {
                items.push(CompletionItem::plain(
                    definition.name.clone(),
                    CompletionKind::Macro,
                    format!("DEFINE AS {}", definition.body),
                ));
            }
            continue;
        }
        let name = symbols
            .procedure
            .as_ref()
            .map_or(&indexed.program_name, |procedure| &procedure.name);
        if !matches(name) || items.iter().any(|item| &item.label == name) {
            continue;
        }
        let parameters: Vec<String> = symbols
            .procedure
            .as_ref()
            .map(|procedure| {
                procedure
                    .parameters
                    .iter()
                    .map(|parameter| parameter.name.clone())
                    .collect()
            })
            .unwrap_or_default();
        let mut item = CompletionItem::plain(
            name.clone(),
            CompletionKind::Subprogram,
            format!("{name}({})", parameters.join(", ")),
        );
        item.snippet = (!parameters.is_empty()).then(|| snippet(name, &parameters));
        item.documentation = symbols
            .procedure
            .as_ref()
            .and_then(|procedure| procedure.documentation.clone());
        items.push(item);
    }
    for cycle in CYCLES.iter().filter(|cycle| matches(cycle.name)) {
        let parameters: Vec<String> = cycle
            .parameters
            .iter()
            .map(|name| name.to_string())
            .collect();
        items.push(CompletionItem {
            label: cycle.name.to_string(),
            kind: CompletionKind::Cycle,
            detail: format!("{}({})", cycle.name, parameters.join(", ")),
            documentation: Some(cycle.summary.to_string()),
            snippet: Some(snippet(cycle.name, &parameters)),
        });
    }
    items
}

/// `NAME(${1:A}, ${2:B})$0`.
fn snippet(name: &str, parameters: &[String]) -> String {
    let placeholders: Vec<String> = parameters
        .iter()
        .enumerate()
        .map(|(position, parameter)| format!("${{{}:{parameter}}}", position + 1))
        .collect();
    format!("{name}({})$0", placeholders.join(", "))
}

enum Direction {
    Forward,
    Backward,
    Both,
}

fn jump_direction(word: &str) -> Option<Direction> {
    match word {
        "GOTOF" => Some(Direction::Forward),
        "GOTOB" => Some(Direction::Backward),
        "GOTO" | "GOTOC" => Some(Direction::Both),
        _ => None,
    }
}

/// The largest character boundary at or before `byte`.
pub(crate) fn floor_char_boundary(text: &str, byte: usize) -> usize {
    let mut byte = byte.min(text.len());
    while !text.is_char_boundary(byte) {
        byte -= 1;
    }
    byte
}
