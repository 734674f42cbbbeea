//! The operands of an expression: numbers, strings, R parameters, names and system variables with
//! their indexes, function calls with their arguments, bracketed values and lists; and the closing
//! bracket that a group expects.

use crate::diagnostics::{Code, Fix, Span};
use crate::syntax::ast::{ExprId, ExprKind};
use crate::syntax::keywords;
use crate::syntax::lexer::Token;
use crate::syntax::parser::assignments::r_parameter_in_system_variable;
use crate::syntax::parser::cursor::Parser;

impl Parser<'_> {
    pub(super) fn parse_primary(&mut self) -> ExprId {
        let span = self.current_span();
        if self.at_end() {
            let at = Span::new(self.previous_end(), self.previous_end());
            self.report(Code::ExpectedExpression, at, "a value is missing here");
            return self.push_expr(ExprKind::Error, at);
        }
        match self.peek() {
            Some(Token::Number) => {
                self.advance();
                match self.number_value(span) {
                    Some(value) => self.push_expr(ExprKind::Number(value), span),
                    None => self.push_expr(ExprKind::Error, span),
                }
            }
            Some(token @ (Token::HexNumber | Token::BinaryNumber)) => {
                self.advance();
                let text = self.text(span);
                let radix = if token == Token::HexNumber { 16 } else { 2 };
                // A literal wider than 64 bits was NaN before; it is reported and unknown instead.
                match u64::from_str_radix(&text[2..text.len() - 1], radix) {
                    Ok(value) => self.push_expr(ExprKind::Number(value as f64), span),
                    Err(_) => {
                        self.report_number_out_of_range(span);
                        self.push_expr(ExprKind::Error, span)
                    }
                }
            }
            Some(Token::BadNumber) | Some(Token::BadQuoted) => {
                self.advance();
                self.report_bad_number(span);
                self.push_expr(ExprKind::Error, span)
            }
            Some(Token::String) => {
                self.advance();
                self.push_expr(ExprKind::String, span)
            }
            Some(Token::UnterminatedString) => {
                self.advance();
                self.report_unterminated_string(span);
                self.push_expr(ExprKind::String, span)
            }
            Some(Token::Letter) => self.parse_letter_operand(),
            Some(Token::Identifier) => self.parse_name_operand(),
            Some(Token::SystemVariable) => {
                self.advance();
                if let Some(number) = r_parameter_in_system_variable(self.text(span)) {
                    return self.push_expr(ExprKind::RParameter(number), span);
                }
                let mut indexes = Vec::new();
                let mut whole = span;
                if self.is_at(Token::LeftBracket) {
                    let (list, index_span) = self.parse_index_list();
                    indexes = list;
                    whole = span.to(index_span);
                }
                self.push_expr(ExprKind::SystemVariable { indexes }, whole)
            }
            Some(Token::LeftParen) => {
                let open = self.advance();
                self.group_depth += 1;
                let inner = self.parse_expression();
                self.group_depth -= 1;
                if self.is_at(Token::Comma) {
                    let mut items = vec![inner];
                    while self.is_at(Token::Comma) {
                        self.advance();
                        items.push(self.parse_expression());
                    }
                    let close = self.expect_close(Token::RightParen, open);
                    return self.push_expr(ExprKind::List(items), open.to(close));
                }
                let close = self.expect_close(Token::RightParen, open);
                self.push_expr(ExprKind::Parenthesized(inner), open.to(close))
            }
            _ => {
                let at = Span::new(span.start(), span.start());
                let text = self.text(span).to_string();
                self.report(
                    Code::ExpectedExpression,
                    span,
                    format!("a value was expected, found `{text}`"),
                );
                self.push_expr(ExprKind::Error, at)
            }
        }
    }

    /// A letter inside an expression: `R1`, `R[i]`, an axis name (`X`, `X1`) or a one-letter parameter.
    pub(super) fn parse_letter_operand(&mut self) -> ExprId {
        let span = self.advance();
        let letter = self.text(span).as_bytes()[0].to_ascii_uppercase();
        if letter == b'R' {
            if self.adjacent(self.position) && self.is_at(Token::Number) {
                if let Some(number) = self.integer_at(self.position) {
                    let number_span = self.advance();
                    return self.push_expr(
                        ExprKind::RParameter(number.min(u64::from(u32::MAX)) as u32),
                        span.to(number_span),
                    );
                }
            }
            if self.is_at(Token::LeftBracket) {
                let (indexes, index_span) = self.parse_index_list();
                let index = indexes
                    .first()
                    .copied()
                    .unwrap_or_else(|| self.push_expr(ExprKind::Error, index_span));
                return self.push_expr(ExprKind::RParameterIndexed(index), span.to(index_span));
            }
        }
        let mut whole = span;
        if self.adjacent(self.position)
            && self.is_at(Token::Number)
            && self.integer_at(self.position).is_some()
        {
            whole = span.to(self.advance());
        }
        let mut indexes = Vec::new();
        if self.is_at(Token::LeftBracket) {
            let (list, index_span) = self.parse_index_list();
            indexes = list;
            whole = whole.to(index_span);
        }
        self.push_expr(ExprKind::Name { indexes }, whole)
    }

    pub(super) fn parse_name_operand(&mut self) -> ExprId {
        let span = self.current_span();
        let upper = self.upper_name(span);
        if keywords::word_operator(&upper).is_some() {
            let at = Span::new(span.start(), span.start());
            self.report(
                Code::ExpectedExpression,
                span,
                format!("a value was expected before `{upper}`"),
            );
            return self.push_expr(ExprKind::Error, at);
        }
        if self.peek_nth(1) == Some(Token::LeftParen) {
            if keywords::is_modifier_name(&upper) {
                let message = if self.modifier_depth > 0 {
                    format!("position modifiers cannot be nested: `{upper}(..)` inside another modifier")
                } else {
                    format!(
                        "{upper}(..) only stands directly after `=` of an axis or other address"
                    )
                };
                let code = if self.modifier_depth > 0 {
                    Code::ModifierNested
                } else {
                    Code::ModifierOutsideAddress
                };
                let expr = self.parse_call_expression_without_function_check();
                let whole = self.expr_span(expr);
                self.report(code, whole, message);
                return expr;
            }
            if !keywords::is_function(&upper) {
                self.report(
                    Code::UnknownFunction,
                    span,
                    format!("`{upper}` is not a predefined function; a value in an expression cannot come from a subprogram"),
                );
            }
            return self.parse_call_expression_without_function_check();
        }
        self.advance();
        let mut indexes = Vec::new();
        let mut whole = span;
        if self.is_at(Token::LeftBracket) {
            let (list, index_span) = self.parse_index_list();
            indexes = list;
            whole = span.to(index_span);
        }
        self.push_expr(ExprKind::Name { indexes }, whole)
    }

    /// `NAME(args)` at the current position as an expression node.
    pub(super) fn parse_call_expression_without_function_check(&mut self) -> ExprId {
        let name = self.advance();
        let (args, args_span) = self.parse_argument_list();
        self.push_expr(ExprKind::Call { name, args }, name.to(args_span))
    }

    /// `(a, , b)` at the current position; empty arguments are `None`.
    pub(super) fn parse_argument_list(&mut self) -> (Vec<Option<ExprId>>, Span) {
        self.group_depth += 1;
        let result = self.parse_argument_list_inner();
        self.group_depth -= 1;
        result
    }

    pub(super) fn parse_argument_list_inner(&mut self) -> (Vec<Option<ExprId>>, Span) {
        let open = self.advance();
        let mut args = Vec::new();
        if self.is_at(Token::RightParen) {
            let close = self.advance();
            return (args, open.to(close));
        }
        loop {
            if self.is_at(Token::Comma) {
                args.push(None);
                self.advance();
                if self.is_at(Token::RightParen) {
                    args.push(None);
                }
                continue;
            }
            if self.is_at(Token::RightParen) || self.at_end() {
                break;
            }
            let expr = self.parse_expression();
            args.push(Some(expr));
            if self.is_at(Token::Comma) {
                self.advance();
                if self.is_at(Token::RightParen) {
                    args.push(None);
                }
            } else {
                break;
            }
        }
        let close = self.expect_close(Token::RightParen, open);
        (args, open.to(close))
    }

    /// `[a, b]` at the current position.
    pub(super) fn parse_index_list(&mut self) -> (Vec<ExprId>, Span) {
        let open = self.advance();
        self.group_depth += 1;
        let mut indexes = Vec::new();
        while !self.at_end() && !self.is_at(Token::RightBracket) {
            indexes.push(self.parse_expression());
            if self.is_at(Token::Comma) {
                self.advance();
            } else {
                break;
            }
        }
        self.group_depth -= 1;
        let close = self.expect_close(Token::RightBracket, open);
        (indexes, open.to(close))
    }

    /// Consumes the expected closing bracket, or reports the unclosed opening one (once per line).
    pub(super) fn expect_close(&mut self, token: Token, open: Span) -> Span {
        if self.is_at(token) {
            return self.advance();
        }
        // An unterminated string swallows the rest of the line, bracket included: S132 says it all.
        let after_unterminated_string = self.position > 0
            && self.token_at(self.position - 1) == Some(Token::UnterminatedString);
        if !self.unclosed_reported && !after_unterminated_string {
            self.unclosed_reported = true;
            let (code, closing) = if token == Token::RightParen {
                (Code::UnbalancedParentheses, ")")
            } else {
                (Code::UnbalancedBrackets, "]")
            };
            let end = self.previous_end();
            let found = if self.at_end() {
                "the end of the block".to_string()
            } else {
                format!("`{}`", self.text(self.current_span()))
            };
            let message = format!("this `{}` is not closed before {found}", self.text(open));
            // Inserting the bracket helps only when the block has fewer closing brackets than
            // opening ones; else something else stopped the reading (`SIN(30$0)`), and a bracket
            // inserted here would leave one too many.
            let opening = if token == Token::RightParen {
                Token::LeftParen
            } else {
                Token::LeftBracket
            };
            let count = |wanted: Token| {
                (0..self.lexemes.len())
                    .filter(|&index| self.token_at(index) == Some(wanted))
                    .count()
            };
            if count(opening) > count(token) {
                let fix = Fix::replace(format!("Insert `{closing}`"), Span::new(end, end), closing);
                self.report_with_fix(code, open, message, fix);
            } else {
                self.report(code, open, message);
            }
        }
        Span::new(self.previous_end(), self.previous_end())
    }
}
