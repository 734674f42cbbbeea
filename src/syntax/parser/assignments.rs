//! Assignments to what is not an address word: R parameters (`R1=5`, `R[R2]=1`), system variables
//! (`$TC_DP1[1,1]=0`, `$R1` in synchronized actions), the counter of a FOR loop, and the value of any
//! such assignment, where a position modifier is an error.

use crate::diagnostics::{Code, Span};
use crate::syntax::ast::{AddressKind, AssignTarget, ExprId, ExprKind, NamedAddress, Statement};
use crate::syntax::keywords;
use crate::syntax::lexer::Token;
use crate::syntax::parser::cursor::Parser;

impl Parser<'_> {
    pub(super) fn parse_r_parameter_assignment(&mut self) {
        let letter_span = self.advance();
        let target;
        let target_span;
        if self.adjacent(self.position) && self.peek() == Some(Token::Number) {
            let number_span = self.advance();
            target_span = letter_span.to(number_span);
            match self.integer_at(self.position - 1) {
                Some(number) => {
                    target = AssignTarget::RParameter(number.min(u64::from(u32::MAX)) as u32)
                }
                None => {
                    let text = self.text(target_span).to_string();
                    self.report(
                        Code::InvalidNumber,
                        target_span,
                        format!("`{text}`: R parameters are numbered with whole numbers"),
                    );
                    target = AssignTarget::RParameter(0);
                }
            }
        } else if self.is_at(Token::LeftBracket) {
            let (indexes, index_span) = self.parse_index_list();
            target_span = letter_span.to(index_span);
            let index = indexes
                .first()
                .copied()
                .unwrap_or_else(|| self.push_expr(ExprKind::Error, index_span));
            target = AssignTarget::RParameterIndexed(index);
        } else {
            // A lone `R` is an address without meaning in Siemens mode (R is not a radius: use CR=).
            self.report(
                Code::MissingValue,
                letter_span,
                "`R` alone has no meaning: R parameters are written `R1=...`, a circle radius is `CR=...`",
            );
            return;
        }
        if !self.is_at(Token::Assign) {
            let text = self.text(target_span).to_string();
            self.report(
                Code::ValueNeedsEquals,
                target_span,
                format!("`{text}` is an R parameter: assign it with `{text}=...` (a circle radius is written `CR=...`)"),
            );
            // Skip a value written without `=` so it is not reported twice.
            if self.is_at(Token::Number) {
                self.advance();
            }
            return;
        }
        let value = self.parse_assignment_value(target_span);
        let span = self.span_since(target_span);
        self.block.statements.push(Statement::Assignment {
            target,
            target_span,
            value,
            span,
        });
    }

    /// The value of an assignment to something that is not an address: a modifier there is an error.
    pub(super) fn parse_assignment_value(&mut self, target_span: Span) -> Option<ExprId> {
        if !self.is_at(Token::Assign) {
            let text = self.text(target_span).to_string();
            self.report(
                Code::ValueNeedsEquals,
                target_span,
                format!("`{text}` needs `=` and a value"),
            );
            return None;
        }
        let equals = self.advance();
        if self.at_end() {
            self.report(
                Code::MissingValue,
                target_span.to(equals),
                format!("`{}=` has no value", self.text(target_span)),
            );
            return None;
        }
        if self.is_at(Token::Identifier) && self.peek_nth(1) == Some(Token::LeftParen) {
            let name = self.upper_name(self.current_span());
            if keywords::is_modifier_name(&name) {
                let modifier_span = self.current_span();
                let value = self.parse_modifier_value(
                    AddressKind::Named(NamedAddress::Positioning),
                    target_span,
                );
                let whole = Span::new(modifier_span.start(), self.previous_end());
                let target = self.text(target_span).to_string();
                self.report(
                    Code::ModifierOutsideAddress,
                    whole,
                    format!(
                        "{name} only applies to an axis or other address; `{target}` is a variable"
                    ),
                );
                return value.expr.expr_id();
            }
        }
        Some(self.parse_expression())
    }

    pub(super) fn parse_system_variable_assignment(&mut self) {
        let name_span = self.advance();
        let text = self.text(name_span);
        let r_number = r_parameter_in_system_variable(text);
        let mut indexes = Vec::new();
        let mut target_span = name_span;
        if self.is_at(Token::LeftBracket) {
            let (list, span) = self.parse_index_list();
            indexes = list;
            target_span = name_span.to(span);
        }
        let value = self.parse_assignment_value(target_span);
        let span = self.span_since(target_span);
        let target = match r_number {
            Some(number) => AssignTarget::RParameter(number),
            None => AssignTarget::SystemVariable { indexes },
        };
        self.block.statements.push(Statement::Assignment {
            target,
            target_span,
            value,
            span,
        });
    }

    /// The counter of a FOR loop: a user variable (or one-letter parameter) assigned its start value.
    pub(super) fn parse_counter_assignment(&mut self) {
        let target_span = self.advance();
        let value = self.parse_assignment_value(target_span);
        let span = self.span_since(target_span);
        self.block.statements.push(Statement::Assignment {
            target: AssignTarget::Variable {
                indexes: Vec::new(),
            },
            target_span,
            value,
            span,
        });
    }
}

/// `$R1` is the spelling of R1 inside synchronized actions.
pub(super) fn r_parameter_in_system_variable(text: &str) -> Option<u32> {
    let rest = text.strip_prefix('$')?;
    let digits = rest.strip_prefix('R').or_else(|| rest.strip_prefix('r'))?;
    if digits.is_empty() || !digits.bytes().all(|byte| byte.is_ascii_digit()) {
        return None;
    }
    digits.parse().ok()
}
