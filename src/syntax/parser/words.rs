//! Words that start with a single letter: G functions by number (`G1`, `G[8]=2`), address words
//! (`X10`, `X1=10`, `S[SP]=100`), subprogram numbers (`L140(2)`) and the letters that have no meaning
//! there (`N` after the start, `O`). What kind of address a letter is, and the check that an axis word
//! names a configured axis.

use crate::diagnostics::{Code, Span};
use crate::syntax::ast::{
    AddressKind, AddressWord, AssignTarget, CallKind, ExprKind, Extension, NamedAddress, Statement,
};
use crate::syntax::gcodes::GCode;
use crate::syntax::lexer::Token;
use crate::syntax::parser::cursor::Parser;

impl Parser<'_> {
    pub(super) fn parse_letter_word(&mut self) {
        let letter = self.letter_at(self.position).unwrap_or(b'?');
        match letter {
            b'G' => self.parse_g_word(),
            b'R' => self.parse_r_parameter_assignment(),
            b'N' => {
                let span = self.advance();
                if self.is_at(Token::Number) {
                    let number = self.advance();
                    self.report(
                        Code::UnexpectedToken,
                        span.to(number),
                        "a block number must stand at the start of the block",
                    );
                } else {
                    self.report(
                        Code::MissingValue,
                        span,
                        "`N` needs a block number and must stand at the start of the block",
                    );
                }
            }
            b'O' => {
                let span = self.advance();
                self.report(
                    Code::UnexpectedToken,
                    span,
                    "the address `O` does not exist in Siemens mode (is it a zero?)",
                );
                if self.is_at(Token::Number) {
                    self.advance();
                }
            }
            _ => self.parse_address_word(letter),
        }
    }

    pub(super) fn parse_g_word(&mut self) {
        let letter_span = self.advance();
        match self.peek() {
            Some(Token::Number) if self.position < self.lexemes.len() => {
                let number_span = self.advance();
                let span = letter_span.to(number_span);
                match self.integer_at(self.position - 1) {
                    Some(number) => {
                        let number = number.min(u64::from(u32::MAX)) as u32;
                        match GCode::from_number(number) {
                            Some(code) => {
                                self.block.statements.push(Statement::GCode { code, span })
                            }
                            None if self.context.is_macro(&format!("G{number}")) => {
                                // A machine may define `G300` as a macro (DEFINE G300 AS ...).
                                self.block.statements.push(Statement::Call {
                                    kind: CallKind::Named,
                                    name: Some(span),
                                    args: Vec::new(),
                                    span,
                                });
                            }
                            None => {
                                self.report(
                                    Code::UnknownGCode,
                                    span,
                                    format!("`G{number}` is not a G function of Siemens mode (alarm 12470)"),
                                );
                                self.block
                                    .statements
                                    .push(Statement::UnknownGCode { number, span });
                            }
                        }
                    }
                    None => {
                        let text = self.text(span).to_string();
                        self.report(
                            Code::InvalidNumber,
                            span,
                            format!("`{text}`: G functions are numbered with whole numbers"),
                        );
                    }
                }
            }
            Some(Token::LeftBracket) => {
                // `G[8]=2` selects G function 2 of group 8.
                let (indexes, index_span) = self.parse_index_list();
                let group = indexes
                    .first()
                    .copied()
                    .unwrap_or_else(|| self.push_expr(ExprKind::Error, index_span));
                let value = self.parse_assignment_value(letter_span);
                let span = self.span_since(letter_span);
                self.block.statements.push(Statement::Assignment {
                    target: AssignTarget::GGroup { group },
                    target_span: letter_span.to(index_span),
                    value,
                    span,
                });
            }
            _ => {
                self.report(
                    Code::MissingValue,
                    letter_span,
                    "`G` needs the number of a G function, e.g. `G1`",
                );
            }
        }
    }

    pub(super) fn classify_letter(&self, letter: u8, extension: Option<u32>) -> AddressKind {
        match letter {
            b'F' => AddressKind::Feed,
            b'S' => AddressKind::Spindle,
            b'T' => AddressKind::Tool,
            b'D' => AddressKind::ToolEdge,
            b'M' => AddressKind::MFunction,
            b'H' => AddressKind::HFunction,
            b'L' => AddressKind::SubprogramNumber,
            b'P' => AddressKind::Repetitions,
            b'I' | b'J' | b'K' => AddressKind::Interpolation,
            b'A' | b'B' | b'C' if matches!(extension, Some(2..=5)) => {
                // A2..C5 are orientation components by default (reference §1.7), unless the machine
                // configures such an axis.
                let mut buffer = [0u8; 12];
                if self
                    .context
                    .axis_kind(axis_name(letter, extension, &mut buffer))
                    .is_some()
                {
                    AddressKind::Axis
                } else {
                    AddressKind::Named(NamedAddress::Other)
                }
            }
            _ => AddressKind::Axis,
        }
    }

    /// An address word that starts with a single letter: `X10`, `X=R1`, `X1=10`, `M2=5`, `S[SP]=100`.
    pub(super) fn parse_address_word(&mut self, letter: u8) {
        let name_span = self.advance();
        let mut extension = None;
        // A numeric extension exists only when `=` follows the digits (`X1=10` is axis X1).
        if self.adjacent(self.position)
            && self.peek() == Some(Token::Number)
            && self.peek_nth(1) == Some(Token::Assign)
        {
            if let Some(value) = self.integer_at(self.position) {
                let span = self.advance();
                extension = Some(Extension::Number {
                    value: value.min(u64::from(u32::MAX)) as u32,
                    span,
                });
            }
        } else if self.is_at(Token::LeftBracket) && letter != b'L' {
            let (indexes, span) = self.parse_index_list();
            extension = Some(Extension::Index { indexes, span });
        }
        let extension_number = match &extension {
            Some(Extension::Number { value, .. }) => Some(*value),
            _ => None,
        };
        let kind = self.classify_letter(letter, extension_number);
        let value = self.parse_word_value(kind, name_span, extension.is_some());
        let span = self.span_since(name_span);
        if kind == AddressKind::Axis {
            self.check_axis_configured(letter, extension_number, span);
        }
        let word = AddressWord {
            kind,
            name: name_span,
            extension,
            value,
            span,
        };
        if kind == AddressKind::SubprogramNumber {
            // `L140(2)` calls the subprogram L140 with parameters.
            let args = if self.is_at(Token::LeftParen) && self.adjacent(self.position) {
                self.parse_argument_list().0
            } else {
                Vec::new()
            };
            let call_span = self.span_since(span);
            self.block.statements.push(Statement::Call {
                kind: CallKind::Named,
                name: Some(span),
                args,
                span: call_span,
            });
        } else {
            self.block.statements.push(Statement::Address(word));
        }
    }

    /// Reports an axis word of an axis the machine does not have. Inlined for the common word of a
    /// configured one-letter axis, with everything else out of line: a call for every axis word cost
    /// more than the check.
    #[inline]
    pub(super) fn check_axis_configured(&mut self, letter: u8, extension: Option<u32>, span: Span) {
        if extension.is_none() && self.context.axis_kind_by_letter(letter).is_some() {
            return;
        }
        self.check_axis_configured_by_name(letter, extension, span);
    }

    #[inline(never)]
    pub(super) fn check_axis_configured_by_name(
        &mut self,
        letter: u8,
        extension: Option<u32>,
        span: Span,
    ) {
        let configured = match extension {
            None => self.context.axis_kind_by_letter(letter).is_some(),
            Some(_) => {
                let mut buffer = [0u8; 12];
                self.context
                    .axis_kind(axis_name(letter, extension, &mut buffer))
                    .is_some()
            }
        };
        if !configured {
            let mut buffer = [0u8; 12];
            let name = axis_name(letter, extension, &mut buffer);
            let name = name.to_string();
            self.report(
                Code::AxisNotConfigured,
                span,
                crate::syntax::unconfigured_axes::occurrence_message(
                    &name,
                    &self.context.axis_list(),
                ),
            );
        }
    }
}

/// Writes an axis name such as `X` or `X1` into `buffer` without allocating.
fn axis_name(letter: u8, extension: Option<u32>, buffer: &mut [u8; 12]) -> &str {
    buffer[0] = letter;
    let mut length = 1;
    if let Some(number) = extension {
        let digits = number.to_string();
        for byte in digits.bytes().take(buffer.len() - 1) {
            buffer[length] = byte;
            length += 1;
        }
    }
    std::str::from_utf8(&buffer[..length]).unwrap_or("?")
}
