//! Signature help inside the parentheses of a call: the parameters of a `PROC` header in the
//! workspace, of an `EXTERN` declaration, or of a standard cycle (reference §8.7), with the parameter
//! the cursor is on.

use crate::ide::completion::floor_char_boundary;
use crate::ide::cycles::{cycle, parameter_meaning};
use crate::ide::workspace::WorkspaceIndex;
use crate::syntax::lexer::{lex_line_into, Token};

/// The signature of the call around the cursor.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SignatureHelp {
    /// `CYCLE81(RTP, RFP, SDIS, DP, DPR)`.
    pub label: String,
    /// The byte range of each parameter inside `label`.
    pub parameters: Vec<(usize, usize)>,
    /// What each parameter means, where known.
    pub parameter_documentation: Vec<Option<String>>,
    /// The parameter the cursor is on (0-based); may be past the last one.
    pub active_parameter: usize,
    pub documentation: Option<String>,
}

/// The signature help at byte `byte` of `line_text` in `document`, `None` outside a known call.
pub fn signature_help(
    index: &WorkspaceIndex,
    document: &str,
    line_text: &str,
    byte: usize,
) -> Option<SignatureHelp> {
    let before = &line_text[..floor_char_boundary(line_text, byte)];
    let mut lexemes = Vec::new();
    lex_line_into(before, &mut lexemes);
    // (called name, commas so far) for each open parenthesis.
    let mut open: Vec<(Option<String>, usize)> = Vec::new();
    for (position, lexeme) in lexemes.iter().enumerate() {
        match lexeme.token {
            Some(Token::LeftParen) => {
                let name = position
                    .checked_sub(1)
                    .map(|previous| &lexemes[previous])
                    .filter(|previous| {
                        previous.token == Some(Token::Identifier)
                            && previous.span.end() == lexeme.span.start()
                    })
                    .map(|previous| {
                        before[previous.span.start()..previous.span.end()].to_ascii_uppercase()
                    });
                open.push((name, 0));
            }
            Some(Token::RightParen) => {
                open.pop();
            }
            Some(Token::Comma) => {
                if let Some(top) = open.last_mut() {
                    top.1 += 1;
                }
            }
            Some(Token::Comment) | Some(Token::UnterminatedString) => return None,
            _ => {}
        }
    }
    // The innermost call with a known signature: inside `CYCLE82(10, SIN(30|))` that is CYCLE82.
    let (name, active_parameter, (parameters, documentation)) = open
        .into_iter()
        .rev()
        .filter_map(|(name, commas)| name.map(|name| (name, commas)))
        .find_map(|(name, commas)| {
            known_signature(index, document, &name).map(|signature| (name, commas, signature))
        })?;
    let mut label = format!("{name}(");
    let mut ranges = Vec::new();
    let mut parameter_documentation = Vec::new();
    for (position, (text, meaning)) in parameters.into_iter().enumerate() {
        if position > 0 {
            label.push_str(", ");
        }
        ranges.push((label.len(), label.len() + text.len()));
        label.push_str(&text);
        parameter_documentation.push(meaning);
    }
    label.push(')');
    Some(SignatureHelp {
        label,
        parameters: ranges,
        parameter_documentation,
        active_parameter,
        documentation,
    })
}

/// The parameters (text, meaning) and documentation of a called name: a `PROC` of the workspace, an
/// `EXTERN` declaration of the document, or a standard cycle.
type Signature = (Vec<(String, Option<String>)>, Option<String>);

fn known_signature(index: &WorkspaceIndex, document: &str, name: &str) -> Option<Signature> {
    if let Some((_, procedure)) = index.procedure(name) {
        let parameters = procedure
            .parameters
            .iter()
            .map(|parameter| {
                let reference = if parameter.by_reference { "VAR " } else { "" };
                let dimensions = parameter.dimensions.clone().unwrap_or_default();
                (
                    format!(
                        "{reference}{} {}{dimensions}",
                        parameter.type_name, parameter.name
                    )
                    .trim()
                    .to_string(),
                    None,
                )
            })
            .collect();
        return Some((parameters, procedure.documentation.clone()));
    }
    let declaration = index.document(document).and_then(|indexed| {
        indexed
            .symbols
            .externs
            .iter()
            .find(|declaration| declaration.name == name)
    });
    if let Some(types) = declaration.and_then(|declaration| declaration.parameter_types.clone()) {
        return Some((
            types.into_iter().map(|written| (written, None)).collect(),
            None,
        ));
    }
    let cycle = cycle(name)?;
    let parameters = cycle
        .parameters
        .iter()
        .map(|parameter| {
            (
                parameter.to_string(),
                parameter_meaning(parameter).map(str::to_string),
            )
        })
        .collect();
    Some((parameters, Some(cycle.summary.to_string())))
}
