//! Small helpers about names shared by the features: the name part of a parsed span, which names
//! the language reserves (keywords, G functions, addresses) so that rename can refuse them, and which
//! parts of a parsed block the features read.

use crate::config::MachineConfig;
use crate::diagnostics::Span;
use crate::syntax::ast::{Block, Expr, Statement};
use crate::syntax::gcodes::GCode;
use crate::syntax::keywords;
use crate::syntax::lexer::{Lexeme, Token};

/// The expression nodes of a block that the features read as uses of names, numbers and functions:
/// all but the initial values, array sizes and defaults of `DEF` and `PROC`. The features take what
/// a declaration declares from the statement itself; its values are kept for running the program.
pub fn expressions_outside_declarations(block: &Block) -> impl Iterator<Item = &Expr> {
    // A declaration reads the rest of its block, so a block has at most one, and only a block with
    // one pays for the comparison.
    let declaration = block
        .statements
        .iter()
        .rev()
        .find_map(|statement| match statement {
            Statement::Definition { span, .. } | Statement::ProcedureHeader { span, .. } => {
                Some(*span)
            }
            _ => None,
        });
    block.exprs.iter().filter(move |expr| {
        declaration.is_none_or(|declaration| {
            expr.span.start() < declaration.start() || expr.span.start() >= declaration.end()
        })
    })
}

/// The address letter `P` of the count of a `REPEAT` or `REPEATB` statement with this span, when the
/// statement has a `P` word: the first one-letter token after the keyword (the labels are names).
pub fn repeat_count_letter(lexemes: &[Lexeme], statement_span: Span) -> Option<Span> {
    let first = lexemes.partition_point(|lexeme| lexeme.span.start() <= statement_span.start());
    lexemes[first..]
        .iter()
        .take_while(|lexeme| lexeme.span.end() <= statement_span.end())
        .find(|lexeme| lexeme.token == Some(Token::Letter))
        .map(|lexeme| lexeme.span)
}

/// The span of the identifier that starts `span` in `line`: a `Name` node's span also covers its
/// `[...]` indexes, and features want the name alone.
pub fn identifier_prefix(line: &str, span: Span) -> Span {
    let bytes = line.as_bytes();
    let start = span.start().min(bytes.len());
    let mut end = start;
    while end < span.end().min(bytes.len())
        && (bytes[end].is_ascii_alphanumeric()
            || bytes[end] == b'_'
            || (end == start && bytes[end] == b'$'))
    {
        end += 1;
    }
    Span::new(start, end)
}

/// The text of `span` in `line`, or "" when the span does not fit the line.
pub fn text_of(line: &str, span: Span) -> &str {
    line.get(span.start()..span.end()).unwrap_or("")
}

/// Upper-case ASCII copy of a name.
pub fn upper(text: &str) -> String {
    text.to_ascii_uppercase()
}

/// Whether `text` is a name the language accepts for a label, variable or program: letters, digits
/// and `_`, starting with a letter or `_` (reference §1.4).
pub fn is_identifier(text: &str) -> bool {
    let mut bytes = text.bytes();
    matches!(bytes.next(), Some(first) if first.is_ascii_alphabetic() || first == b'_')
        && bytes.all(|byte| byte.is_ascii_alphanumeric() || byte == b'_')
}

/// The data types of `DEF` and `PROC` parameters.
pub fn is_type_name(upper: &str) -> bool {
    matches!(
        upper,
        "INT" | "REAL" | "BOOL" | "CHAR" | "STRING" | "AXIS" | "FRAME"
    )
}

/// Why a name cannot be given to a user symbol, or `None` when it can.
pub fn reserved_reason(upper: &str, config: &MachineConfig) -> Option<String> {
    if keywords::statement_keyword(upper).is_some()
        || keywords::word_operator(upper).is_some()
        || is_type_name(upper)
        || matches!(
            upper,
            "TO" | "OF" | "DO" | "AS" | "VAR" | "DEFAULT" | "NOT" | "B_NOT" | "TRUE" | "FALSE"
        )
    {
        return Some(format!("`{upper}` is a keyword of the NC language"));
    }
    if GCode::from_name(upper).is_some() || is_g_word(upper) {
        return Some(format!("`{upper}` is a G function"));
    }
    if keywords::is_modifier_name(upper) {
        return Some(format!("`{upper}` is a position modifier"));
    }
    if keywords::named_address(upper).is_some() {
        return Some(format!("`{upper}` is an address"));
    }
    if keywords::is_function(upper) || keywords::is_instruction(upper) {
        return Some(format!("`{upper}` is a predefined function or instruction"));
    }
    if config.axis(upper).is_some() {
        return Some(format!("`{upper}` is an axis of the machine"));
    }
    if is_address_word(upper) {
        return Some(format!(
            "`{upper}` reads as an address word (a letter followed by digits)"
        ));
    }
    None
}

/// `G1`, `G500`: the letter G with digits.
fn is_g_word(upper: &str) -> bool {
    upper.len() > 1
        && upper.starts_with('G')
        && upper[1..].bytes().all(|byte| byte.is_ascii_digit())
}

/// A single letter, or a letter followed by digits only (`X`, `R10`, `N5`, `L1`): the control reads
/// it as an address word, not as a name.
fn is_address_word(upper: &str) -> bool {
    let bytes = upper.as_bytes();
    !bytes.is_empty() && bytes[0].is_ascii_alphabetic() && bytes[1..].iter().all(u8::is_ascii_digit)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reserved_names_are_refused_and_others_accepted() {
        let config = MachineConfig::default();
        for name in [
            "GOTOF", "G1", "DIAMON", "X", "R10", "AC", "CR", "SIN", "REAL", "AND",
        ] {
            assert!(reserved_reason(name, &config).is_some(), "{name}");
        }
        for name in ["MARK1", "_LOOP", "PART2", "COUNTER"] {
            assert_eq!(reserved_reason(name, &config), None, "{name}");
        }
        assert_eq!(
            identifier_prefix("ARR[1]=2", Span::new(0, 6)),
            Span::new(0, 3)
        );
        assert_eq!(
            identifier_prefix("$P_GG[13]", Span::new(0, 9)),
            Span::new(0, 5)
        );
        assert!(is_identifier("_N1") && !is_identifier("1A") && !is_identifier(""));
    }
}
