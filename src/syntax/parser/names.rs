//! Statements that start with a name: statement keywords (handed on), G functions by name (`TRANS`),
//! multi-letter addresses and axes (`CR=5`, `POS[X]=10`), variable assignments, predefined
//! instructions, and calls of subprograms and macros. Also the names the control reads as calls though
//! an address word was meant (`ZAC(17)`, `XR1`, `CR5`), reported with a fix.

use crate::diagnostics::{Code, Fix, Span};
use crate::syntax::ast::{
    AddressKind, AddressWord, AssignTarget, CallKind, Extension, Statement, Value, ValueExpr,
};
use crate::syntax::gcodes::GCode;
use crate::syntax::keywords;
use crate::syntax::lexer::Token;
use crate::syntax::parser::cursor::Parser;

impl Parser<'_> {
    pub(super) fn parse_identifier_statement(&mut self) {
        let name_span = self.current_span();
        let mut buffer = [0u8; 32];
        let upper = keywords::uppercase(self.text(name_span), &mut buffer)
            .unwrap_or("")
            .to_string();
        if let Some(keyword) = keywords::statement_keyword(&upper) {
            self.parse_keyword_statement(keyword);
            return;
        }
        if let Some(code) = GCode::from_name(&upper) {
            self.advance();
            self.block.statements.push(Statement::GCode {
                code,
                span: name_span,
            });
            return;
        }
        let next = self.peek_nth(1);
        if is_access_level_keyword(&upper) && next == Some(Token::Number) {
            // `APW 11 APR 11` in a definition file sets the access levels of the definitions below.
            self.advance();
            self.advance();
            let span = self.span_since(name_span);
            self.block.statements.push(Statement::Instruction {
                name: name_span,
                args: Vec::new(),
                span,
            });
            return;
        }
        if next == Some(Token::Assign) || next == Some(Token::LeftBracket) {
            self.advance();
            let named = keywords::named_address(&upper);
            let axis = self.context.axis_kind(&upper);
            if named.is_some() || axis.is_some() {
                let kind = match named {
                    Some(named) => AddressKind::Named(named),
                    None => AddressKind::Axis,
                };
                let mut extension = None;
                if self.is_at(Token::LeftBracket) {
                    let (indexes, span) = self.parse_index_list();
                    extension = Some(Extension::Index { indexes, span });
                }
                let value = if self.is_at(Token::Assign) {
                    self.parse_value_after_equals(kind, name_span)
                } else {
                    let text = self.text(name_span).to_string();
                    self.report(
                        Code::ValueNeedsEquals,
                        name_span,
                        format!("`{text}` needs `=` and a value"),
                    );
                    Value {
                        modifier: None,
                        expr: ValueExpr::Missing,
                        has_equals: false,
                    }
                };
                let span = self.span_since(name_span);
                self.block.statements.push(Statement::Address(AddressWord {
                    kind,
                    name: name_span,
                    extension,
                    value,
                    span,
                }));
                return;
            }
            let mut indexes = Vec::new();
            let mut target_span = name_span;
            if self.is_at(Token::LeftBracket) {
                let (list, span) = self.parse_index_list();
                indexes = list;
                target_span = name_span.to(span);
            }
            if !self.is_at(Token::Assign) {
                // `ARRAY[1]` alone, or `NAME[...]` followed by something else: read it as a call.
                let text = self.text(target_span).to_string();
                self.report(
                    Code::ValueNeedsEquals,
                    target_span,
                    format!("`{text}` needs `=` and a value"),
                );
                return;
            }
            let value = self.parse_assignment_value(target_span);
            let span = self.span_since(target_span);
            self.block.statements.push(Statement::Assignment {
                target: AssignTarget::Variable { indexes },
                target_span,
                value,
                span,
            });
            return;
        }
        let has_arguments = next == Some(Token::LeftParen);
        if keywords::is_instruction(&upper) {
            self.advance();
            let args = if has_arguments {
                self.parse_argument_list().0
            } else {
                Vec::new()
            };
            let span = self.span_since(name_span);
            self.block.statements.push(Statement::Instruction {
                name: name_span,
                args,
                span,
            });
            return;
        }
        if !self.context.is_macro(&upper) {
            self.check_name_read_as_call(&upper, name_span, has_arguments);
        }
        // The span may have grown (a `.5` that belongs to `CR5.5`), so read the position again.
        if self.position < self.lexemes.len() && self.current_span() == name_span {
            self.advance();
        }
        let args = if has_arguments && self.is_at(Token::LeftParen) {
            self.parse_argument_list().0
        } else {
            Vec::new()
        };
        let span = self.span_since(name_span);
        self.block.statements.push(Statement::Call {
            kind: CallKind::Named,
            name: Some(name_span),
            args,
            span,
        });
    }

    /// `ZAC(17)`, `XR1`, `CR5`: names the control reads as subprogram calls, though the programmer most
    /// likely meant an address with `=` (reference §1.6, §8.9).
    pub(super) fn check_name_read_as_call(
        &mut self,
        upper: &str,
        name_span: Span,
        has_arguments: bool,
    ) {
        let written = self.text(name_span).to_string();
        let first = upper.as_bytes().first().copied().unwrap_or(b'?');
        let rest = &upper[1.min(upper.len())..];
        let single_axis = |letter: u8| -> bool {
            is_axis_letter(letter)
                && (self
                    .context
                    .axis_kind(&(letter as char).to_string())
                    .is_some()
                    || matches!(letter, b'X' | b'Y' | b'Z'))
        };
        let mut suggestion: Option<(Span, String)> = None;
        if has_arguments && single_axis(first) && keywords::is_modifier_name(rest) {
            suggestion = Some((name_span, format!("{}={}", &written[..1], &written[1..])));
        } else if !has_arguments {
            if let Some(split) = split_named_address_and_digits(upper) {
                let mut span = name_span;
                let mut value = written[split..].to_string();
                if self.adjacent(self.position + 1) && self.peek_nth(1) == Some(Token::Number) {
                    let number_span = self.span_at(self.position + 1);
                    value.push_str(self.text(number_span));
                    span = span.to(number_span);
                    // Consume the name and the fraction together.
                    self.position += 2;
                }
                suggestion = Some((span, format!("{}={}", &written[..split], value)));
            } else if (single_axis(first) || matches!(first, b'I' | b'J' | b'K' | b'F' | b'S'))
                && rest.len() >= 2
                && rest.as_bytes()[0] == b'R'
                && rest[1..].bytes().all(|byte| byte.is_ascii_digit())
            {
                suggestion = Some((name_span, format!("{}={}", &written[..1], &written[1..])));
            }
        }
        if let Some((span, replacement)) = suggestion {
            let shown = if has_arguments {
                format!("{replacement}(...)")
            } else {
                replacement.clone()
            };
            let fix = Fix::replace(format!("Write `{shown}`"), span, replacement.clone());
            let called = if has_arguments {
                format!("{written}(...)")
            } else {
                written.clone()
            };
            self.report_with_fix(
                Code::NameReadAsCall,
                span,
                format!(
                    "the control reads `{called}` as a call of a subprogram named {written}, not as an address word; did you mean `{shown}`?"
                ),
                fix,
            );
        }
    }
}

/// Letters that name axes when the machine configuration has such an axis (reference §1.7).
fn is_axis_letter(letter: u8) -> bool {
    matches!(
        letter,
        b'X' | b'Y' | b'Z' | b'A' | b'B' | b'C' | b'U' | b'V' | b'W' | b'Q' | b'E'
    )
}

/// Access levels for reading and writing the definitions that follow (`APR 15 APW 12`).
fn is_access_level_keyword(upper: &str) -> bool {
    matches!(upper, "APR" | "APW" | "APRP" | "APWP" | "APRB" | "APWB")
}

/// `CR5` → 2: a multi-letter address run together with a number; returns where the digits start.
fn split_named_address_and_digits(upper: &str) -> Option<usize> {
    let split = upper.find(|character: char| character.is_ascii_digit())?;
    let (name, digits) = upper.split_at(split);
    if !digits.bytes().all(|byte| byte.is_ascii_digit()) {
        return None;
    }
    matches!(name, "CR" | "AP" | "RP" | "AR" | "TURN" | "RPL").then_some(split)
}
