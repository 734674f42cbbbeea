//! The token set of one NC block, generated with logos. Keywords are not tokens: every name is an
//! `Identifier` and is classified later with a `match`, which keeps the automaton small and fast.
//!
//! Why a single letter is its own token: SINUMERIK lets words run together (`G0X10Y5`, `T0D0`), and
//! the rule of the control is that after a one-letter address the value ends the word. A name, on the
//! other hand, starts with two letters (or an underscore), so `XR1` and `CR10` are single identifiers.

use crate::diagnostics::Span;
use logos::Logos;

#[derive(Logos, Debug, Clone, Copy, PartialEq, Eq)]
#[logos(skip r"[ \t\x0B\x0C\r&\x00-\x08\x0E-\x1F\x7F]+")]
pub enum Token {
    /// A comment from `;` to the end of the line.
    #[regex(r";[^\r\n]*", allow_greedy = true)]
    Comment,

    /// A string with its closing quote. Strings have no escapes: a backslash is an ordinary character.
    #[regex(r#""[^"\r\n]*""#)]
    String,

    /// A string whose closing quote is missing before the end of the line.
    #[regex(r#""[^"\r\n]*"#, allow_greedy = true)]
    UnterminatedString,

    /// Hexadecimal `'H1F'` or binary `'B101'` literal. Anything else in single quotes is `BadQuoted`.
    #[regex(r"'[Hh][0-9A-Fa-f]+'")]
    HexNumber,
    #[regex(r"'[Bb][01]+'")]
    BinaryNumber,
    #[regex(r"'[^'\r\n]*'?", priority = 1)]
    BadQuoted,

    /// A decimal number: `10`, `10.`, `.5`, `1.5EX-3`. The sign is an operator token.
    #[regex(r"[0-9]+(\.[0-9]*)?([Ee][Xx][+-]?[0-9]+)?")]
    #[regex(r"\.[0-9]+([Ee][Xx][+-]?[0-9]+)?")]
    Number,

    /// A run of digits and points that is not one number, e.g. `1.2.3`.
    #[regex(r"[0-9]*\.[0-9]*\.[0-9.]*", priority = 1)]
    BadNumber,

    /// A single letter: an address (`X`, `G`, `N`, `R`) or a one-letter name.
    #[regex(r"[A-Za-z]")]
    Letter,

    /// A name of two or more characters that starts with two letters/underscores, or an underscore.
    #[regex(r"[A-Za-z_][A-Za-z_][A-Za-z0-9_]*")]
    #[regex(r"_[A-Za-z0-9_]*")]
    Identifier,

    /// A system variable: `$P_GG`, `$AA_IW`, `$TC_DP1`, `$$SA_...`, and `$R1` written in synchronized actions.
    #[regex(r"\$+[A-Za-z_][A-Za-z0-9_]*")]
    SystemVariable,

    #[token("=")]
    Assign,
    #[token("==")]
    Equal,
    #[token("<>")]
    NotEqual,
    #[token("<")]
    Less,
    #[token(">")]
    Greater,
    #[token("<=")]
    LessEqual,
    #[token(">=")]
    GreaterEqual,
    #[token("<<")]
    Concat,
    #[token("+")]
    Plus,
    #[token("-")]
    Minus,
    #[token("*")]
    Star,
    #[token("/")]
    Slash,
    #[token("(")]
    LeftParen,
    #[token(")")]
    RightParen,
    #[token("[")]
    LeftBracket,
    #[token("]")]
    RightBracket,
    #[token(",")]
    Comma,
    #[token(":")]
    Colon,
    /// `%` starts a program header line in punched-tape format (`%_N_NAME_MPF`).
    #[token("%")]
    Percent,
}

/// A token with its byte span inside the line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Lexeme {
    /// `None` for bytes that form no token (an unexpected character).
    pub token: Option<Token>,
    pub span: Span,
}

/// Lexes one line into `out` (cleared first), reusing its allocation.
pub fn lex_line_into(line: &str, out: &mut Vec<Lexeme>) {
    out.clear();
    let mut lexer = Token::lexer(line);
    while let Some(result) = lexer.next() {
        let range = lexer.span();
        out.push(Lexeme {
            token: result.ok(),
            span: Span::new(range.start, range.end),
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tokens(line: &str) -> Vec<(Option<Token>, &str)> {
        let mut out = Vec::new();
        lex_line_into(line, &mut out);
        out.iter()
            .map(|lexeme| (lexeme.token, &line[lexeme.span.start()..lexeme.span.end()]))
            .collect()
    }

    #[test]
    fn words_run_together() {
        let got = tokens("G0X10.5Y-5");
        let texts: Vec<&str> = got.iter().map(|(_, text)| *text).collect();
        assert_eq!(texts, vec!["G", "0", "X", "10.5", "Y", "-", "5"]);
    }

    #[test]
    fn names_start_with_two_letters() {
        assert_eq!(tokens("XR1"), vec![(Some(Token::Identifier), "XR1")]);
        assert_eq!(tokens("CR10"), vec![(Some(Token::Identifier), "CR10")]);
        assert_eq!(tokens("_LOOP"), vec![(Some(Token::Identifier), "_LOOP")]);
    }

    #[test]
    fn strings_come_before_comments() {
        assert_eq!(
            tokens(r#"MSG("A;B") ; note"#),
            vec![
                (Some(Token::Identifier), "MSG"),
                (Some(Token::LeftParen), "("),
                (Some(Token::String), r#""A;B""#),
                (Some(Token::RightParen), ")"),
                (Some(Token::Comment), "; note"),
            ]
        );
        assert_eq!(tokens(r#""\""#), vec![(Some(Token::String), r#""\""#)]);
        assert_eq!(
            tokens(r#"MSG("open"#)[2],
            (Some(Token::UnterminatedString), r#""open"#)
        );
    }

    #[test]
    fn numbers_and_literals() {
        assert_eq!(tokens(".5"), vec![(Some(Token::Number), ".5")]);
        assert_eq!(tokens("1.5EX-3"), vec![(Some(Token::Number), "1.5EX-3")]);
        assert_eq!(tokens("'H1F'"), vec![(Some(Token::HexNumber), "'H1F'")]);
        assert_eq!(
            tokens("'B101'"),
            vec![(Some(Token::BinaryNumber), "'B101'")]
        );
        assert_eq!(tokens("'HXZ'"), vec![(Some(Token::BadQuoted), "'HXZ'")]);
        assert_eq!(tokens("1.2.3"), vec![(Some(Token::BadNumber), "1.2.3")]);
    }

    #[test]
    fn operators_and_unknown_bytes() {
        let got = tokens("<<<=<>==@");
        let kinds: Vec<Option<Token>> = got.iter().map(|(token, _)| *token).collect();
        assert_eq!(
            kinds,
            vec![
                Some(Token::Concat),
                Some(Token::LessEqual),
                Some(Token::NotEqual),
                Some(Token::Equal),
                None
            ]
        );
    }

    #[test]
    fn control_bytes_are_blanks() {
        assert_eq!(
            tokens("X1\u{0}\r"),
            vec![(Some(Token::Letter), "X"), (Some(Token::Number), "1")]
        );
    }
}
