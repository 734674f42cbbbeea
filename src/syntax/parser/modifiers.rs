//! The value after `=` and the position modifiers (`X=AC(10)`, `Z=IC(-5)`; reference §1.8): the
//! modifier with its one value, the forms without parentheses (`Z=AC17`, `Z=AC 17`), a misspelt
//! modifier (`AB(..)`), and whether the address and the configured axis take the modifier.

use crate::config::AxisKind;
use crate::diagnostics::{Code, Fix, Span};
use crate::syntax::ast::{AddressKind, ExprId, ExprKind, Modifier, Value, ValueExpr};
use crate::syntax::keywords;
use crate::syntax::lexer::Token;
use crate::syntax::parser::cursor::Parser;
use crate::syntax::parser::literals::parse_number;

impl Parser<'_> {
    /// After `=`: a modifier such as `AC(..)` (with the checks of reference §1.8) or an expression.
    pub(super) fn parse_value_after_equals(&mut self, kind: AddressKind, name_span: Span) -> Value {
        let equals = self.advance();
        if self.at_end() {
            let text = self.text(name_span.to(equals)).to_string();
            self.report(
                Code::MissingValue,
                name_span.to(equals),
                format!("`{text}` has no value"),
            );
            return Value {
                modifier: None,
                expr: ValueExpr::Missing,
                has_equals: true,
            };
        }
        if self.is_at(Token::Identifier) {
            let name = self.upper_name(self.current_span());
            let name_token_span = self.current_span();
            if keywords::is_modifier_name(&name) {
                if self.peek_nth(1) == Some(Token::LeftParen) {
                    return self.parse_modifier_value(kind, name_span);
                }
                self.report_modifier_without_parentheses(name_token_span, &name);
                return Value {
                    modifier: Modifier::from_name(&name)
                        .map(|modifier| (modifier, name_token_span)),
                    expr: ValueExpr::Missing,
                    has_equals: true,
                };
            }
            if let Some((modifier, digits)) = split_modifier_and_digits(&name) {
                // `Z=AC17` lexes as the name `AC17`; a directly following `.5` belongs to the value.
                self.advance();
                let mut span = name_token_span;
                let mut value_text = digits.to_string();
                if self.adjacent(self.position) && self.is_at(Token::Number) {
                    let number_span = self.advance();
                    value_text.push_str(self.text(number_span));
                    span = span.to(number_span);
                }
                let modifier_text = &self.text(name_token_span)[..modifier.as_str().len()];
                let replacement = format!("{modifier_text}({value_text})");
                let fix = Fix::replace(format!("Write `{replacement}`"), span, replacement.clone());
                self.report_with_fix(
                    Code::ModifierWithoutParentheses,
                    span,
                    format!(
                        "the value of {} must be in parentheses: `{replacement}`",
                        modifier.as_str()
                    ),
                    fix,
                );
                let expr = match parse_number(&value_text) {
                    Some(value) => self.push_expr(ExprKind::Number(value), span),
                    None => {
                        self.report_number_out_of_range(span);
                        self.push_expr(ExprKind::Error, span)
                    }
                };
                return Value {
                    modifier: Some((modifier, name_token_span)),
                    expr: ValueExpr::Expr(expr),
                    has_equals: true,
                };
            }
            if self.peek_nth(1) == Some(Token::LeftParen) && !keywords::is_function(&name) {
                if let Some(nearest) = nearest_modifier(&name) {
                    let fix = Fix::replace(
                        format!("Write `{}`", nearest.as_str()),
                        name_token_span,
                        nearest.as_str(),
                    );
                    self.report_with_fix(
                        Code::ModifierUnknown,
                        name_token_span,
                        format!(
                            "`{name}` is not a position modifier; did you mean `{}`? (modifiers: AC, IC, DC, ACP, ACN, DAC, DIC, RAC, RIC)",
                            nearest.as_str()
                        ),
                        fix,
                    );
                    // Parse the bracket as an ordinary expression so its contents are checked.
                    let expr = self.parse_call_expression_without_function_check();
                    return Value {
                        modifier: None,
                        expr: ValueExpr::Expr(expr),
                        has_equals: true,
                    };
                }
            }
        }
        let expr = self.parse_expression();
        Value {
            modifier: None,
            expr: ValueExpr::Expr(expr),
            has_equals: true,
        }
    }

    pub(super) fn report_modifier_without_parentheses(&mut self, modifier_span: Span, name: &str) {
        // `Z=AC 17` or `Z=AC -17`: offer the bracketed form when a constant follows.
        let modifier_text = self.text(modifier_span).to_string();
        self.advance();
        let start = self.position;
        let signed_number = matches!(self.peek(), Some(Token::Minus) | Some(Token::Plus))
            && self.peek_nth(1) == Some(Token::Number);
        if signed_number || self.is_at(Token::Number) {
            // The whole expression that follows is the value (`AC 1.2+SIN(30)`): the fix brackets
            // all of it, so that it keeps its meaning.
            let value = self.parse_expression();
            let value_span = self.span_at(start).to(self.expr_span(value));
            let value_text = self.text(value_span).to_string();
            let span = modifier_span.to(value_span);
            let replacement = format!("{modifier_text}({value_text})");
            let fix = Fix::replace(format!("Write `{replacement}`"), span, replacement.clone());
            self.report_with_fix(
                Code::ModifierWithoutParentheses,
                span,
                format!("the value of {name} must be in parentheses: `{replacement}`"),
                fix,
            );
        } else {
            self.position = start;
            self.report(
                Code::ModifierWithoutParentheses,
                modifier_span,
                format!("{name} needs its value in parentheses, e.g. `{name}(10)`"),
            );
        }
    }

    /// `AC(expr)` and friends, at the current position (the modifier name).
    pub(super) fn parse_modifier_value(&mut self, kind: AddressKind, address_span: Span) -> Value {
        let modifier_span = self.advance();
        let name = self.upper_name(modifier_span);
        let modifier = Modifier::from_name(&name).unwrap_or(Modifier::Ac);
        let open = self.advance();
        self.modifier_depth += 1;
        self.group_depth += 1;
        let mut values: Vec<Option<ExprId>> = Vec::new();
        let mut close = None;
        loop {
            if self.at_end() {
                break;
            }
            if self.is_at(Token::RightParen) {
                close = Some(self.advance());
                break;
            }
            if self.is_at(Token::Comma) {
                self.advance();
                values.push(None);
                continue;
            }
            let expr = self.parse_expression();
            values.push(Some(expr));
            if self.is_at(Token::Comma) {
                self.advance();
                if self.is_at(Token::RightParen) {
                    values.push(None);
                }
            } else if !self.is_at(Token::RightParen) {
                break;
            }
        }
        self.modifier_depth -= 1;
        self.group_depth -= 1;
        let end = close.map(|span| span.end()).unwrap_or(self.previous_end());
        let whole = Span::new(modifier_span.start(), end);
        let modifier_text = self.text(modifier_span).to_string();
        let value_count = values.iter().filter(|value| value.is_some()).count();
        if close.is_none() {
            let fix = Fix::replace("Close the parenthesis", Span::new(end, end), ")");
            self.report_with_fix(
                Code::ModifierUnclosed,
                whole,
                format!("`{modifier_text}(` is not closed"),
                fix,
            );
        } else if values.is_empty() || value_count == 0 {
            self.report(
                Code::ModifierEmpty,
                whole,
                format!("`{modifier_text}()` has no value"),
            );
        } else if values.len() > 1 {
            self.report(
                Code::ModifierTooManyValues,
                whole,
                format!(
                    "{modifier_text} takes exactly one value, not {}",
                    values.len()
                ),
            );
        }
        let _ = open;
        self.check_modifier_allowed(kind, address_span, modifier, modifier_span, whole);
        Value {
            modifier: Some((modifier, modifier_span)),
            expr: values
                .into_iter()
                .flatten()
                .next()
                .map_or(ValueExpr::Missing, ValueExpr::Expr),
            has_equals: true,
        }
    }

    pub(super) fn check_modifier_allowed(
        &mut self,
        kind: AddressKind,
        address_span: Span,
        modifier: Modifier,
        modifier_span: Span,
        whole: Span,
    ) {
        let address = self.text(address_span).to_ascii_uppercase();
        if !kind.accepts_modifier() {
            // Offer to keep the value and drop the modifier.
            let inner_start = (modifier_span.end() + 1).min(whole.end());
            let inner_end = if self.line[..whole.end()].ends_with(')') {
                whole.end() - 1
            } else {
                whole.end()
            }
            .max(inner_start);
            let inner = self.line[inner_start..inner_end].to_string();
            let fix = Fix::replace(format!("Write `{address}={inner}`"), whole, inner.clone());
            self.report_with_fix(
                Code::ModifierNotAllowed,
                whole,
                format!(
                    "{} cannot be used on `{address}`: position modifiers apply to axes, I/J/K, AP, POS/POSA and SPOS/SPOSA",
                    modifier.as_str()
                ),
                fix,
            );
            return;
        }
        if kind != AddressKind::Axis {
            return;
        }
        let axis_kind = self.context.axis_kind(&address);
        if modifier.needs_rotary_axis() {
            match axis_kind {
                Some(kind @ (AxisKind::Linear | AxisKind::Transverse)) => self.report(
                    Code::ModifierNeedsRotaryAxis,
                    whole,
                    format!(
                        "{} approaches a rotary position; `{address}` is a {} axis",
                        modifier.as_str(),
                        kind.as_str()
                    ),
                ),
                Some(AxisKind::Rotary) if modifier.needs_modulo_axis() => self.report(
                    Code::ModifierNeedsRotaryAxis,
                    whole,
                    format!(
                        "{} needs a modulo rotary axis; `{address}` is configured as rotary without modulo range",
                        modifier.as_str()
                    ),
                ),
                _ => {}
            }
        }
        if modifier.needs_transverse_axis()
            && axis_kind.is_some()
            && axis_kind != Some(AxisKind::Transverse)
        {
            self.report(
                Code::ModifierNeedsTransverseAxis,
                whole,
                format!(
                    "{} gives a diameter or radius value; `{address}` is not configured as transverse axis",
                    modifier.as_str()
                ),
            );
        }
    }
}

/// `AC17` → (AC, "17"): a modifier name run together with its value.
fn split_modifier_and_digits(upper: &str) -> Option<(Modifier, &str)> {
    let split = upper.find(|character: char| character.is_ascii_digit())?;
    let (name, digits) = upper.split_at(split);
    if !digits.bytes().all(|byte| byte.is_ascii_digit()) {
        return None;
    }
    Some((Modifier::from_name(name)?, digits))
}

/// The modifier one edit away from `name` (`AB` → `AC`), for a likely typo.
fn nearest_modifier(name: &str) -> Option<Modifier> {
    if name.len() > 4 || name.len() < 2 {
        return None;
    }
    Modifier::ALL
        .iter()
        .copied()
        .filter(|modifier| {
            !matches!(
                modifier,
                Modifier::Cac | Modifier::Cic | Modifier::Cdc | Modifier::Cacp | Modifier::Cacn
            )
        })
        .find(|modifier| edit_distance_is_one(name, modifier.as_str()))
}

fn edit_distance_is_one(left: &str, right: &str) -> bool {
    let left = left.as_bytes();
    let right = right.as_bytes();
    if left == right {
        return false;
    }
    match left.len() as isize - right.len() as isize {
        0 => left.iter().zip(right).filter(|(a, b)| a != b).count() == 1,
        1 | -1 => {
            let (longer, shorter) = if left.len() > right.len() {
                (left, right)
            } else {
                (right, left)
            };
            (0..longer.len()).any(|skip| {
                longer[..skip] == shorter[..skip] && longer[skip + 1..] == shorter[skip..]
            })
        }
        _ => false,
    }
}
