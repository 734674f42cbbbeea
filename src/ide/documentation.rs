//! Hover documentation of the word at a cursor, from the shared table of
//! [`language_docs`](crate::ide::language_docs) and the workspace: what a G function, keyword, cycle
//! or system variable does; a called `PROC` with its parameters and the comment above its header; a
//! variable with its `DEF`; a macro with its expansion. Plain text, the server adds the markup.

use crate::diagnostics::Span;
use crate::ide::completion::floor_char_boundary;
use crate::ide::language_docs::describe;
use crate::ide::navigation::{symbol_at, Symbol};
use crate::ide::workspace::WorkspaceIndex;
use crate::syntax::lexer::{lex_line_into, Token};

/// The documentation of one word.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Documentation {
    /// The word the documentation is about, in the line.
    pub span: Span,
    /// `G1 — group 1 (motion), modal`, `PROC PART2(REAL A)`, `DEF REAL DEPTH`.
    pub title: String,
    pub text: String,
}

/// The documentation at byte `byte` of `line_text` (line `line` of `document`), `None` on words the
/// table and the workspace do not describe, in comments and in strings.
pub fn documentation_at(
    index: &WorkspaceIndex,
    document: &str,
    line_text: &str,
    line: usize,
    byte: usize,
) -> Option<Documentation> {
    let byte = floor_char_boundary(line_text, byte);
    let mut lexemes = Vec::new();
    lex_line_into(line_text, &mut lexemes);
    let position = lexemes.iter().position(|lexeme| {
        lexeme.span.start() <= byte && byte <= lexeme.span.end() && lexeme.token.is_some()
    })?;
    let lexeme = lexemes[position];
    let mut span = lexeme.span;
    match lexeme.token {
        Some(Token::Comment) | Some(Token::String) | Some(Token::UnterminatedString) => {
            return None
        }
        // `G1`: the letter and its number form the word.
        Some(Token::Letter) | Some(Token::Number) => {
            let (letter, number) = match lexeme.token {
                Some(Token::Letter) => (Some(lexeme), lexemes.get(position + 1).copied()),
                _ => (
                    position.checked_sub(1).map(|previous| lexemes[previous]),
                    Some(lexeme),
                ),
            };
            if let (Some(letter), Some(number)) = (letter, number) {
                if letter.token == Some(Token::Letter)
                    && number.token == Some(Token::Number)
                    && letter.span.end() == number.span.start()
                {
                    span = letter.span.to(number.span);
                }
            }
        }
        _ => {}
    }
    if let Some((symbol, _)) = symbol_at(index, document, line, span.start()) {
        if let Some(documentation) = symbol_documentation(index, document, &symbol, span) {
            return Some(documentation);
        }
    }
    let word = &line_text[span.start()..span.end()];
    let doc = describe(word).or_else(|| {
        // `$TC_DP1`, `$TC_DP12`: the family `$TC_DP`.
        word.starts_with('$')
            .then(|| describe(word.trim_end_matches(|c: char| c.is_ascii_digit())))
            .flatten()
    })?;
    let title = if doc.detail.is_empty() {
        doc.name
    } else {
        format!("{} — {}", doc.name, doc.detail)
    };
    Some(Documentation {
        span,
        title,
        text: doc.summary,
    })
}

fn symbol_documentation(
    index: &WorkspaceIndex,
    document: &str,
    symbol: &Symbol,
    span: Span,
) -> Option<Documentation> {
    match symbol {
        Symbol::Program { name } => {
            let (_, procedure) = index.procedure(name)?;
            let parameters: Vec<String> = procedure
                .parameters
                .iter()
                .map(|parameter| {
                    let reference = if parameter.by_reference { "VAR " } else { "" };
                    format!(
                        "{reference}{} {}{}",
                        parameter.type_name,
                        parameter.name,
                        parameter.dimensions.as_deref().unwrap_or("")
                    )
                })
                .collect();
            Some(Documentation {
                span,
                title: format!("PROC {}({})", procedure.name, parameters.join(", ")),
                text: procedure.documentation.clone().unwrap_or_default(),
            })
        }
        Symbol::Local { name, .. } | Symbol::Global { name } => {
            let indexed = index.document(document)?;
            let local = indexed
                .symbols
                .variables
                .iter()
                .find(|variable| &variable.name == name);
            let global = || {
                index
                    .global_variables(name)
                    .next()
                    .map(|(_, variable)| variable)
            };
            if let Some(variable) = local.or_else(global) {
                let scope = variable
                    .global_attribute
                    .as_deref()
                    .map(|attribute| format!("{attribute} "))
                    .unwrap_or_default();
                return Some(Documentation {
                    span,
                    title: format!(
                        "DEF {scope}{} {}{}",
                        variable.type_name,
                        variable.name,
                        variable.dimensions.as_deref().unwrap_or("")
                    ),
                    text: String::new(),
                });
            }
            let parameter = indexed
                .symbols
                .procedure
                .as_ref()?
                .parameters
                .iter()
                .find(|parameter| &parameter.name == name)?;
            Some(Documentation {
                span,
                title: format!(
                    "{}{} {} (parameter)",
                    if parameter.by_reference { "VAR " } else { "" },
                    parameter.type_name,
                    parameter.name
                ),
                text: String::new(),
            })
        }
        Symbol::Macro {
            document: scope,
            name,
        } => {
            let local = scope
                .as_ref()
                .and_then(|id| index.document(id))
                .and_then(|indexed| {
                    indexed
                        .symbols
                        .macros
                        .iter()
                        .find(|definition| &definition.name == name)
                        .cloned()
                });
            let definition = local.or_else(|| {
                index
                    .global_macros(name)
                    .next()
                    .map(|(_, definition)| definition.clone())
            })?;
            Some(Documentation {
                span,
                title: format!("DEFINE {} AS {}", definition.name, definition.body),
                text: String::new(),
            })
        }
        _ => None,
    }
}
