//! Pieces of a statement's text for the symbol table: bracket groups, jump keywords, indirect program
//! names, PROC and EXTERN parameter types as written, and whether a block executes something.

use crate::diagnostics::Span;
use crate::ide::names::{is_type_name, text_of, upper};
use crate::syntax::ast::{Block, Statement};
use crate::syntax::lexer::{lex_line_into, Lexeme, Token};

/// The text of a `[...]` group starting at lexeme `index`, brackets included.
pub(crate) fn bracket_text(text: &str, lexemes: &[Lexeme], index: usize) -> Option<String> {
    let first = lexemes.get(index)?;
    if first.token != Some(Token::LeftBracket) {
        return None;
    }
    let mut depth = 0;
    for lexeme in &lexemes[index..] {
        match lexeme.token {
            Some(Token::LeftBracket) => depth += 1,
            Some(Token::RightBracket) => {
                depth -= 1;
                if depth == 0 {
                    let span = Span::new(first.span.start(), lexeme.span.end());
                    return Some(
                        text_of(text, span)
                            .chars()
                            .filter(|c| !c.is_whitespace())
                            .collect(),
                    );
                }
            }
            _ => {}
        }
    }
    None
}

/// The keyword of a jump statement (whose span may start at its `IF`): the word that ends right
/// before the target, which starts at `target_start`.
pub(crate) fn jump_keyword_before(line: &str, statement: Span, target_start: usize) -> Span {
    let bytes = line.as_bytes();
    let mut end = target_start.min(bytes.len());
    while end > statement.start() && bytes[end - 1].is_ascii_whitespace() {
        end -= 1;
    }
    let mut start = end;
    while start > statement.start()
        && (bytes[start - 1].is_ascii_alphanumeric() || bytes[start - 1] == b'_')
    {
        start -= 1;
    }
    Span::new(start, end)
}

/// For `CALL "NAME"`, `CALL "/_N_DIR/_N_NAME_SPF"` and `PCALL /_N_DIR/_N_NAME_SPF`: the program name
/// and its span inside the line. `None` for a call through a variable.
pub(crate) fn indirect_program_name(line: &str, span: Span) -> Option<(String, Span)> {
    let text = text_of(line, span);
    let (content, content_start) = match text.strip_prefix('"') {
        Some(rest) => (rest.strip_suffix('"')?, span.start() + 1),
        None if text.contains('/') => (text, span.start()),
        None => return None,
    };
    let segment_start = content.rfind('/').map_or(0, |position| position + 1);
    let segment = &content[segment_start..];
    let (name_offset, name) = match segment
        .strip_prefix("_N_")
        .or_else(|| segment.strip_prefix("_n_"))
    {
        Some(rest) => {
            let end = rest.rfind('_').filter(|position| *position > 0)?;
            (3, &rest[..end])
        }
        None => (0, segment),
    };
    if !crate::ide::names::is_identifier(name) {
        return None;
    }
    let start = content_start + segment_start + name_offset;
    Some((upper(name), Span::new(start, start + name.len())))
}

/// A parameter of a `PROC` header as read from its tokens: name span, type, `VAR`, dimensions.
type DescribedParameter = (Span, String, bool, Option<String>);

/// The parameters of a `PROC` header: (name span, type, VAR, dimensions) per parameter name the
/// parser found, and whether there is a parameter list.
pub(crate) fn describe_parameters(
    line: &str,
    span: Span,
    parameters: &[Span],
    lexemes: &mut Vec<Lexeme>,
) -> (Vec<DescribedParameter>, bool) {
    let statement = text_of(line, span);
    lex_line_into(statement, lexemes);
    let offset = span.start();
    let has_list = lexemes
        .iter()
        .any(|lexeme| lexeme.token == Some(Token::LeftParen));
    let mut described = Vec::new();
    for name_span in parameters {
        let relative_start = name_span.start().saturating_sub(offset);
        let Some(name_index) = lexemes
            .iter()
            .position(|lexeme| lexeme.span.start() == relative_start)
        else {
            continue;
        };
        // Walk back to the comma or parenthesis that starts this parameter.
        let mut type_name = String::new();
        let mut by_reference = false;
        for lexeme in lexemes[..name_index].iter().rev() {
            match lexeme.token {
                Some(Token::Comma) | Some(Token::LeftParen) => break,
                Some(Token::Identifier) => {
                    let word = upper(text_of(statement, lexeme.span));
                    if word == "VAR" {
                        by_reference = true;
                    } else if is_type_name(&word) && type_name.is_empty() {
                        type_name = word;
                    }
                }
                _ => {}
            }
        }
        let dimensions = bracket_text(statement, lexemes, name_index + 1);
        described.push((*name_span, type_name, by_reference, dimensions));
    }
    (described, has_list)
}

/// The parameter types of `EXTERN NAME(REAL, VAR INT)` between `name_end` and `end` of the line.
pub(crate) fn extern_parameter_types(
    line: &str,
    name_end: usize,
    end: usize,
) -> Option<Vec<String>> {
    let rest = line.get(name_end..end)?.trim_start();
    let inner = rest.strip_prefix('(')?;
    let close = inner.rfind(')').unwrap_or(inner.len());
    let inner = inner[..close].trim();
    if inner.is_empty() {
        return Some(Vec::new());
    }
    let mut types = Vec::new();
    let mut depth = 0i32;
    let mut current = String::new();
    for character in inner.chars() {
        match character {
            '[' | '(' => depth += 1,
            ']' | ')' => depth -= 1,
            ',' if depth == 0 => {
                types.push(normalise_spaces(&current));
                current.clear();
                continue;
            }
            _ => {}
        }
        current.push(character);
    }
    types.push(normalise_spaces(&current));
    Some(types)
}

pub(crate) fn normalise_spaces(text: &str) -> String {
    text.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .to_ascii_uppercase()
}

/// Whether a block executes something: declarations (`DEF`, `DEFINE`, `PROC`, `EXTERN`, access
/// levels, `REDEF`), labels, block numbers and comments alone do not (reference §8.1, alarm 14500).
pub fn is_executable(line: &str, block: &Block) -> bool {
    block.statements.iter().any(|statement| match statement {
        Statement::Definition { .. }
        | Statement::MacroDefinition { .. }
        | Statement::ProcedureHeader { .. }
        | Statement::ExternDeclaration { .. } => false,
        Statement::Instruction { name, .. } => !matches!(
            upper(text_of(line, *name)).as_str(),
            "REDEF" | "APR" | "APW" | "APRP" | "APWP" | "APRB" | "APWB"
        ),
        _ => true,
    })
}
