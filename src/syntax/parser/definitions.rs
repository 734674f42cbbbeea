//! The first reading of `DEF` (the declared names, their type, attributes and the balance of brackets,
//! with the findings about them) and `DEFINE name AS body` (macros). The sizes and initial values of
//! `DEF` are read afterwards, in `declarations.rs`.

use crate::diagnostics::{Code, Span};
use crate::syntax::ast::{DataType, Statement};
use crate::syntax::lexer::Token;
use crate::syntax::parser::cursor::Parser;

impl Parser<'_> {
    /// `DEF [NCK|CHAN ...] TYPE name[=init], name2[dims]` — read leniently: only the declared names and
    /// the balance of brackets are checked here. Sizes and initial values are read afterwards
    /// (`declarations.rs`).
    pub(super) fn parse_definition(&mut self, keyword_span: Span) {
        let mut names = Vec::new();
        let mut data_type = None;
        let mut expect_name = false;
        let mut seen_type = false;
        let mut in_initializer = false;
        let mut invalid_name_reported = false;
        let mut depth: i32 = 0;
        let mut after_type_index = false;
        while !self.at_end() {
            let token = self.peek();
            let span = self.advance();
            match token {
                Some(Token::LeftParen) | Some(Token::LeftBracket) => depth += 1,
                Some(Token::RightParen) | Some(Token::RightBracket) => {
                    depth -= 1;
                    if depth == 0 && after_type_index {
                        after_type_index = false;
                        expect_name = true;
                    }
                }
                Some(Token::Comma) if depth == 0 => {
                    expect_name = true;
                    in_initializer = false;
                }
                Some(Token::Assign) if depth == 0 => {
                    expect_name = false;
                    in_initializer = true;
                }
                Some(Token::Identifier) | Some(Token::Letter) if depth == 0 && !in_initializer => {
                    let upper = self.upper_name(span);
                    if is_definition_attribute(&upper) {
                        // Attributes such as `LLI 0 ULI 4` or `APR 7` may stand before or after the
                        // type; their value is not a name.
                        if definition_attribute_takes_value(&upper) {
                            if matches!(self.peek(), Some(Token::Minus) | Some(Token::Plus)) {
                                self.advance();
                            }
                            if !self.at_end() {
                                self.advance();
                            }
                        }
                    } else if !seen_type && is_type_name(&upper) {
                        seen_type = true;
                        data_type = DataType::from_name(&upper);
                        expect_name = true;
                        if upper == "STRING" && self.is_at(Token::LeftBracket) {
                            expect_name = false;
                            after_type_index = true;
                        }
                    } else if expect_name {
                        expect_name = false;
                        self.check_definition_name(token, span);
                        names.push(span);
                    } else if seen_type {
                        let text = self.text(span).to_string();
                        self.report(
                            Code::UnexpectedToken,
                            span,
                            format!("`{text}` follows a name without a comma: separate the names of one DEF with `,`"),
                        );
                    }
                }
                Some(Token::SystemVariable) | Some(Token::Number) if expect_name && depth == 0 => {
                    expect_name = false;
                    invalid_name_reported = true;
                    // `1COUNT` lexes as a number and a name: report them as one name.
                    let mut span = span;
                    if token == Some(Token::Number)
                        && self.is_at(Token::Identifier)
                        && self.adjacent(self.position)
                    {
                        span = span.to(self.advance());
                    }
                    let text = self.text(span).to_string();
                    let message = if token == Some(Token::SystemVariable) {
                        format!("`{text}` is a system variable; DEF defines user variables only")
                    } else {
                        format!("`{text}` cannot be a variable name: names start with two letters")
                    };
                    self.report(Code::InvalidLabel, span, message);
                }
                Some(Token::UnterminatedString) => self.report_unterminated_string(span),
                _ => {}
            }
        }
        if depth > 0 {
            self.report(
                Code::UnbalancedBrackets,
                keyword_span,
                "this definition has an unclosed bracket or parenthesis",
            );
        }
        if names.is_empty() && !invalid_name_reported {
            let message = if seen_type {
                "DEF needs the name of the variable after its type"
            } else {
                "DEF needs a type (INT, REAL, BOOL, CHAR, STRING[n], AXIS, FRAME) and a name"
            };
            self.report(Code::ExpectedExpression, keyword_span, message);
        }
        let declarators = self.parse_declarators(&names);
        let span = self.span_since(keyword_span);
        self.block.statements.push(Statement::Definition {
            names,
            data_type,
            declarators,
            span,
        });
    }

    /// A defined name must not be an address letter (`DEF REAL A`) and should start with two letters.
    pub(super) fn check_definition_name(&mut self, token: Option<Token>, span: Span) {
        if token == Some(Token::Letter) {
            let text = self.text(span).to_string();
            if self.is_at(Token::Number) && self.adjacent(self.position) {
                // `V1AR` lexes as a letter, a number and a name: it is one name.
                let mut whole = span.to(self.advance());
                if self.is_at(Token::Identifier) && self.adjacent(self.position) {
                    whole = whole.to(self.advance());
                }
                let name = self.text(whole).to_string();
                self.report(
                    Code::LabelStyle,
                    whole,
                    format!(
                        "`{name}` starts with a single letter; names should start with two letters"
                    ),
                );
            } else {
                self.report(
                    Code::InvalidLabel,
                    span,
                    format!("`{text}` is an address letter and cannot be a variable name; names start with two letters"),
                );
            }
        } else {
            self.check_name_style(span, "variable");
        }
    }

    pub(super) fn parse_macro_definition(&mut self, keyword_span: Span) {
        let name = self.name_or_report(keyword_span, "DEFINE needs a name: `DEFINE NAME AS ...`");
        if self.is_at(Token::Identifier) && self.upper_name(self.current_span()) == "AS" {
            self.advance();
        } else if name.is_some() {
            self.report(
                Code::UnexpectedToken,
                self.current_span(),
                "DEFINE needs `AS` after the name: `DEFINE NAME AS ...`",
            );
        }
        let body_start = self.current_span().start();
        while !self.at_end() {
            let token = self.peek();
            let span = self.advance();
            if token == Some(Token::UnterminatedString) {
                self.report_unterminated_string(span);
            }
        }
        let body = Span::new(body_start.min(self.previous_end()), self.previous_end());
        let span = self.span_since(keyword_span);
        self.block
            .statements
            .push(Statement::MacroDefinition { name, body, span });
    }
}

/// Attributes of `DEF` in definition files (reference §8.1): storage, synchronisation, access levels,
/// limits, units and initialisation.
fn is_definition_attribute(upper: &str) -> bool {
    matches!(
        upper,
        "NCK"
            | "CHAN"
            | "SYNR"
            | "SYNW"
            | "SYNRW"
            | "APR"
            | "APW"
            | "APRP"
            | "APWP"
            | "APRB"
            | "APWB"
            | "PHY"
            | "LLI"
            | "ULI"
            | "INIPO"
            | "INIRE"
            | "INICF"
            | "PRLOC"
    )
}

fn definition_attribute_takes_value(upper: &str) -> bool {
    matches!(
        upper,
        "APR" | "APW" | "APRP" | "APWP" | "APRB" | "APWB" | "PHY" | "LLI" | "ULI"
    )
}

pub(super) fn is_type_name(upper: &str) -> bool {
    matches!(
        upper,
        "INT" | "REAL" | "BOOL" | "CHAR" | "STRING" | "AXIS" | "FRAME"
    )
}
