//! Expressions: binary operators by precedence (reference §8.2), unary operators, the comparison
//! spellings read inside conditions, and the depth limit that keeps hostile nesting linear and the
//! stack bounded. The operands are parsed in `operands.rs`.

use crate::diagnostics::{Code, Fix, Span};
use crate::syntax::ast::{BinaryOp, ExprId, ExprKind, UnaryOp};
use crate::syntax::keywords;
use crate::syntax::lexer::Token;
use crate::syntax::parser::cursor::Parser;

/// Deepest nesting of parentheses, brackets and unary operators the parser follows. Real programs stay
/// far below; deeper input is reported (S170) and skipped in linear time.
pub const MAX_EXPRESSION_DEPTH: u32 = 128;

impl Parser<'_> {
    /// Parses an expression; always returns a node (an `Error` node after reporting a problem).
    pub(super) fn parse_expression(&mut self) -> ExprId {
        self.parse_binary(0)
    }

    pub(super) fn binary_operator_here(&self) -> Option<(BinaryOp, u8)> {
        if self.position >= self.lexemes.len() {
            return None;
        }
        let op = match self.peek()? {
            Token::Plus => BinaryOp::Add,
            Token::Minus => BinaryOp::Subtract,
            Token::Star => BinaryOp::Multiply,
            Token::Slash => BinaryOp::Divide,
            Token::Concat => BinaryOp::Concat,
            Token::Equal => BinaryOp::Equal,
            Token::NotEqual => BinaryOp::NotEqual,
            Token::Less => BinaryOp::Less,
            Token::Greater => BinaryOp::Greater,
            Token::LessEqual => BinaryOp::LessEqual,
            Token::GreaterEqual => BinaryOp::GreaterEqual,
            Token::Colon => BinaryOp::Chain,
            Token::Identifier => {
                let mut buffer = [0u8; 32];
                let upper = keywords::uppercase(self.text(self.current_span()), &mut buffer)?;
                keywords::word_operator(upper)?
            }
            _ => return None,
        };
        // Precedence of reference §8.2: comparisons bind weakest, then `<<`, OR, XOR, AND, B_OR,
        // B_XOR, B_AND, `+ -`, `* / DIV MOD`.
        let power = match op {
            BinaryOp::Equal
            | BinaryOp::NotEqual
            | BinaryOp::Less
            | BinaryOp::Greater
            | BinaryOp::LessEqual
            | BinaryOp::GreaterEqual
            | BinaryOp::Chain => 1,
            BinaryOp::Concat => 2,
            BinaryOp::Or => 3,
            BinaryOp::Xor => 4,
            BinaryOp::And => 5,
            BinaryOp::BitOr => 6,
            BinaryOp::BitXor => 7,
            BinaryOp::BitAnd => 8,
            BinaryOp::Add | BinaryOp::Subtract => 9,
            BinaryOp::Multiply | BinaryOp::Divide | BinaryOp::IntegerDivide | BinaryOp::Modulo => {
                10
            }
        };
        Some((op, power))
    }

    pub(super) fn parse_binary(&mut self, minimum_power: u8) -> ExprId {
        let mut left = self.parse_unary();
        loop {
            let (op, power, width) = match self.binary_operator_here() {
                Some((op, power)) => (op, power, 1),
                None => match self.condition_comparison_here() {
                    Some((op, width)) => (op, 1, width),
                    None => {
                        if self.skip_unknown_infix_name(&mut left) {
                            continue;
                        }
                        break;
                    }
                },
            };
            if power < minimum_power {
                break;
            }
            if width != 1 || self.is_at(Token::Assign) {
                let start = self.current_span();
                let end = self.span_at(self.position + width - 1);
                let written = self.line[start.start()..end.end()].to_string();
                let proper = match op {
                    BinaryOp::LessEqual => "<=",
                    BinaryOp::GreaterEqual => ">=",
                    _ => "==",
                };
                let fix = Fix::replace(format!("Write `{proper}`"), start.to(end), proper);
                self.report_with_fix(
                    Code::ComparisonSpelling,
                    start.to(end),
                    format!("a comparison is written `{proper}`, not `{written}`"),
                    fix,
                );
            }
            for _ in 0..width {
                self.advance();
            }
            let right = self.parse_binary(power + 1);
            let span = self.expr_span(left).to(self.expr_span(right));
            if op.is_comparison() {
                self.check_comparison_operands(left, right, span);
            }
            left = self.push_expr(ExprKind::Binary(op, left, right), span);
        }
        left
    }

    /// Inside a condition, `=` is read as `==`, and `=<`, `=>` as `<=`, `>=` (seen in real programs;
    /// reported with S174). Returns the operator and how many tokens it spans.
    pub(super) fn condition_comparison_here(&self) -> Option<(BinaryOp, usize)> {
        if self.condition_depth == 0 || !self.is_at(Token::Assign) {
            return None;
        }
        let next_adjacent = self.adjacent(self.position + 1);
        match self.peek_nth(1) {
            Some(Token::Less) if next_adjacent => Some((BinaryOp::LessEqual, 2)),
            Some(Token::Greater) if next_adjacent => Some((BinaryOp::GreaterEqual, 2)),
            _ => Some((BinaryOp::Equal, 1)),
        }
    }

    /// Inside brackets, a plain name right after an operand (`(A _DEC2)`) can only be a macro that
    /// expands to operators. Its meaning is unknown, so the value becomes an error node and parsing goes
    /// on; a known macro is accepted silently.
    pub(super) fn skip_unknown_infix_name(&mut self, left: &mut ExprId) -> bool {
        if self.group_depth == 0 || !self.is_at(Token::Identifier) {
            return false;
        }
        let span = self.current_span();
        let upper = self.upper_name(span);
        if keywords::statement_keyword(&upper).is_some() || keywords::is_modifier_name(&upper) {
            return false;
        }
        self.advance();
        if !self.context.is_macro(&upper) {
            self.report(
                Code::UnknownNameBetweenOperands,
                span,
                format!("`{upper}` stands between operands; if it is a macro (DEFINE ... AS), its definition is not known here, so this value is not checked"),
            );
        }
        let whole = self.expr_span(*left).to(span);
        *left = self.push_expr(ExprKind::Error, whole);
        true
    }

    /// `R1==1 AND R2==2` parses as `(R1 == (1 AND R2)) == 2` because comparisons bind weakest: a
    /// comparison chained onto a comparison whose right side is a bare AND/OR is almost surely meant as
    /// two bracketed comparisons. `MASK B_AND 4 <> 0` is read as intended and is left alone.
    pub(super) fn check_comparison_operands(&mut self, left: ExprId, _right: ExprId, span: Span) {
        if self.precedence_reported {
            return;
        }
        let exprs = &self.block.exprs;
        let chained_on_logical = match exprs[left.0 as usize].kind {
            ExprKind::Binary(op, _, inner_right) if op.is_comparison() => matches!(
                exprs[inner_right.0 as usize].kind,
                ExprKind::Binary(inner_op, _, _) if inner_op.is_logical()
            ),
            _ => false,
        };
        if chained_on_logical {
            self.precedence_reported = true;
            self.report(
                Code::ComparisonPrecedence,
                span,
                "comparisons bind weaker than AND/OR, so this reads as `a == (b AND c) == d`; bracket each comparison, e.g. `(R1==1) AND (R2==2)`",
            );
        }
    }

    pub(super) fn parse_unary(&mut self) -> ExprId {
        self.depth += 1;
        let result = if self.depth > MAX_EXPRESSION_DEPTH {
            self.skip_too_deep()
        } else {
            self.parse_unary_inner()
        };
        self.depth -= 1;
        result
    }

    /// Skips a sub-expression that is nested too deeply: consumes tokens until the bracket that closes
    /// the enclosing level, so the outer levels still see their closing brackets.
    pub(super) fn skip_too_deep(&mut self) -> ExprId {
        let start = self.current_span();
        if !self.depth_reported {
            self.depth_reported = true;
            self.report(
                Code::TooDeeplyNested,
                start,
                format!("this expression is nested more than {MAX_EXPRESSION_DEPTH} levels deep; the rest of it is not checked"),
            );
        }
        let mut depth = 0usize;
        while !self.at_end() {
            if depth == 0 && self.is_at(Token::Identifier) && self.jump_keyword_here().is_some() {
                // `IF NOT NOT ... GOTOF END`: the jump is not part of the skipped expression.
                break;
            }
            match self.peek() {
                Some(Token::LeftParen) | Some(Token::LeftBracket) => depth += 1,
                Some(Token::RightParen) | Some(Token::RightBracket) | Some(Token::Comma) => {
                    if depth == 0 {
                        break;
                    }
                    if self.peek() != Some(Token::Comma) {
                        depth -= 1;
                    }
                }
                _ => {}
            }
            self.advance();
        }
        let span = self.span_since(start);
        self.push_expr(ExprKind::Error, span)
    }

    pub(super) fn parse_unary_inner(&mut self) -> ExprId {
        let start = self.current_span();
        let op = match self.peek() {
            _ if self.position >= self.lexemes.len() => None,
            Some(Token::Minus) => Some(UnaryOp::Negate),
            Some(Token::Plus) => Some(UnaryOp::Plus),
            Some(Token::Concat) => Some(UnaryOp::ToString),
            Some(Token::Identifier) => match self.upper_name(self.current_span()).as_str() {
                "NOT" => Some(UnaryOp::Not),
                "B_NOT" => Some(UnaryOp::BitNot),
                _ => None,
            },
            _ => None,
        };
        if let Some(op) = op {
            self.advance();
            let operand = self.parse_unary();
            let span = start.to(self.expr_span(operand));
            return self.push_expr(ExprKind::Unary(op, operand), span);
        }
        self.parse_primary()
    }
}
