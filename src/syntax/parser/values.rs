//! The value of an address word: a constant (`X10`, `X-5.5`), the value after `=` (see
//! `modifiers.rs`), and the forms written without the `=` they need (`Z(5+1)`, `X R1`, `Z AC(17)`,
//! `T"DRILL"`), reported with a fix. Also decides whether what follows an address without a value is
//! its value or the next word of the block.

use crate::diagnostics::{Code, Fix, Span};
use crate::syntax::ast::{AddressKind, ExprKind, UnaryOp, Value, ValueExpr};
use crate::syntax::gcodes::GCode;
use crate::syntax::keywords;
use crate::syntax::lexer::Token;
use crate::syntax::parser::cursor::Parser;

impl Parser<'_> {
    /// The value of an address word: a constant (`X10`, `X-5.5`), or `=` and an expression or modifier.
    pub(super) fn parse_word_value(
        &mut self,
        kind: AddressKind,
        name_span: Span,
        has_extension: bool,
    ) -> Value {
        if self.is_at(Token::Assign) {
            return self.parse_value_after_equals(kind, name_span);
        }
        if has_extension {
            let text = self.text(name_span).to_string();
            self.report(
                Code::ValueNeedsEquals,
                name_span,
                format!("an address with extension needs `=` before its value, e.g. `{text}1=10`"),
            );
            return Value {
                modifier: None,
                expr: ValueExpr::Missing,
                has_equals: false,
            };
        }
        let start = self.position;
        let sign = match self.peek() {
            Some(Token::Minus) | Some(Token::Plus)
                if matches!(
                    self.peek_nth(1),
                    Some(Token::Number)
                        | Some(Token::LeftParen)
                        | Some(Token::Letter)
                        | Some(Token::Identifier)
                        | Some(Token::SystemVariable)
                ) =>
            {
                let negative = self.peek() == Some(Token::Minus);
                self.advance();
                Some(negative)
            }
            _ => None,
        };
        match self.peek() {
            Some(Token::Number) if self.position < self.lexemes.len() => {
                let number_span = self.advance();
                let span = self.span_at(start).to(number_span);
                // A number beyond the range of a double is reported and its value is unknown.
                let expr = match self.number_value(number_span) {
                    Some(value) => ValueExpr::Constant {
                        value: if sign == Some(true) { -value } else { value },
                        span,
                    },
                    None => ValueExpr::Expr(self.push_expr(ExprKind::Error, span)),
                };
                Value {
                    modifier: None,
                    expr,
                    has_equals: false,
                }
            }
            Some(Token::String) if kind == AddressKind::Tool => {
                // `T"DRILL"` without `=` is not valid, but the intent is clear.
                let span = self.advance();
                let fix = Fix::replace(
                    "Write `T=\"...\"`",
                    Span::new(span.start(), span.start()),
                    "=",
                );
                self.report_with_fix(
                    Code::ValueNeedsEquals,
                    span,
                    "a tool name is assigned with `=`: `T=\"NAME\"`",
                    fix,
                );
                let expr = self.push_expr(ExprKind::String, span);
                Value {
                    modifier: None,
                    expr: ValueExpr::Expr(expr),
                    has_equals: false,
                }
            }
            Some(Token::BadNumber) => {
                let span = self.advance();
                self.report_bad_number(span);
                Value {
                    modifier: None,
                    expr: ValueExpr::Missing,
                    has_equals: false,
                }
            }
            Some(Token::Identifier)
                if self.position < self.lexemes.len()
                    && keywords::is_modifier_name(&self.upper_name(self.current_span()))
                    && self.peek_nth(1) == Some(Token::LeftParen) =>
            {
                // `Z AC(17)`: the `=` is missing.
                let modifier_span = self.current_span();
                let value = self.parse_modifier_value(kind, name_span);
                let end = self.previous_end();
                let written = self.line[modifier_span.start()..end].to_string();
                let address = self.text(name_span).to_string();
                let fix = Fix::replace(
                    format!("Write `{address}={written}`"),
                    Span::new(name_span.start(), end),
                    format!("{address}={written}"),
                );
                self.report_with_fix(
                    Code::ModifierWithoutEquals,
                    Span::new(name_span.start(), end),
                    format!(
                        "a position modifier needs `=` after the address: `{address}={written}`"
                    ),
                    fix,
                );
                value
            }
            Some(Token::LeftParen)
            | Some(Token::Letter)
            | Some(Token::Identifier)
            | Some(Token::SystemVariable)
                if self.value_without_equals_here(sign.is_some()) =>
            {
                // `Z(5+1)`, `Y-R2`, `X R1`: an expression or variable value needs `=`.
                let value_start = self.span_at(start);
                let expr = self.parse_expression();
                let expr_span = self.expr_span(expr);
                let whole_value = value_start.to(expr_span);
                let address = self.text(name_span).to_string();
                let value_text = self.text(whole_value).to_string();
                let replacement = format!("{address}={value_text}");
                let fix = Fix::replace(
                    format!("Write `{replacement}`"),
                    name_span.to(whole_value),
                    replacement.clone(),
                );
                self.report_with_fix(
                    Code::ValueNeedsEquals,
                    name_span.to(whole_value),
                    format!("a value that is not a single constant needs `=`: `{replacement}`"),
                    fix,
                );
                let expr = if sign == Some(true) {
                    self.push_expr(ExprKind::Unary(UnaryOp::Negate, expr), whole_value)
                } else {
                    expr
                };
                Value {
                    modifier: None,
                    expr: ValueExpr::Expr(expr),
                    has_equals: false,
                }
            }
            Some(Token::Letter)
                if self.letter_at(self.position) == Some(b'R')
                    && self.peek_nth(1) == Some(Token::Number)
                    && self.adjacent(self.position + 1) =>
            {
                // `X R1`: a variable value needs `=`.
                let r_span = self.advance().to(self.advance());
                let address = self.text(name_span).to_string();
                let parameter = self.text(r_span).to_string();
                let fix = Fix::replace(
                    format!("Write `{address}={parameter}`"),
                    name_span.to(r_span),
                    format!("{address}={parameter}"),
                );
                self.report_with_fix(
                    Code::ValueNeedsEquals,
                    name_span.to(r_span),
                    format!("a value that is not a constant needs `=`: `{address}={parameter}`"),
                    fix,
                );
                let number = self
                    .text(r_span)
                    .get(1..)
                    .and_then(|digits| digits.parse().ok())
                    .unwrap_or(0);
                let expr = self.push_expr(ExprKind::RParameter(number), r_span);
                Value {
                    modifier: None,
                    expr: ValueExpr::Expr(expr),
                    has_equals: false,
                }
            }
            _ => {
                if sign.is_some() {
                    self.position = start;
                }
                let text = self.text(name_span).to_string();
                self.report(
                    Code::MissingValue,
                    name_span,
                    format!(
                        "address `{text}` has no value (`{text}0` cannot be shortened to `{text}`)"
                    ),
                );
                Value {
                    modifier: None,
                    expr: ValueExpr::Missing,
                    has_equals: false,
                }
            }
        }
    }

    /// Whether the tokens at the current position are a value written without `=` (`Y-R2`, `Z(5+1)`),
    /// rather than the next word of the block. Only a signed value, a bracket right after the address,
    /// an R parameter or a plain variable name count; another address letter is the next word.
    pub(super) fn value_without_equals_here(&self, signed: bool) -> bool {
        match self.peek() {
            Some(Token::LeftParen) => {
                signed || self.adjacent(self.position) || self.brackets_hold_a_value()
            }
            Some(Token::Letter) => {
                signed
                    && self.letter_at(self.position) == Some(b'R')
                    && self.peek_nth(1) == Some(Token::Number)
            }
            Some(Token::SystemVariable) => signed,
            Some(Token::Identifier) => {
                let upper = self.upper_name(self.current_span());
                let plain_name = keywords::statement_keyword(&upper).is_none()
                    && GCode::from_name(&upper).is_none()
                    && !keywords::is_modifier_name(&upper);
                // `TRANS X _CPA`, `X SIN(30)`: after an address that has no value, a user's name or
                // a function (not an instruction or address of the control) is the value with its
                // `=` left out, not a word of its own.
                plain_name
                    && (signed
                        || (keywords::named_address(&upper).is_none()
                            && (keywords::is_function(&upper)
                                || !keywords::is_instruction(&upper))
                            && !self.context.is_macro(&upper)))
            }
            _ => false,
        }
    }

    /// Whether the brackets at the current position (`Z (R1+2)`, apart from the address) hold a value
    /// rather than words: a number, an operator, an R parameter or a system variable inside. Siemens
    /// has no bracket comments, so such brackets after an address without value are its value with
    /// the `=` left out; a bracketed word alone (`X (MOVE)`) stays a misplaced comment.
    pub(super) fn brackets_hold_a_value(&self) -> bool {
        // A value is short; looking further would make a long line of brackets quadratic.
        const LOOK_AHEAD: usize = 64;
        let mut depth = 0usize;
        for index in self.position..self.lexemes.len().min(self.position + LOOK_AHEAD) {
            match self.token_at(index) {
                Some(Token::LeftParen) => depth += 1,
                Some(Token::RightParen) => {
                    depth = depth.saturating_sub(1);
                    if depth == 0 {
                        return false;
                    }
                }
                Some(Token::Number)
                | Some(Token::SystemVariable)
                | Some(Token::Plus)
                | Some(Token::Minus)
                | Some(Token::Star)
                | Some(Token::Slash) => return true,
                _ => {}
            }
        }
        false
    }
}
