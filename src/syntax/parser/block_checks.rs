//! The block checks: a pass over the statements of a parsed block that finds what no single statement
//! shows: two G functions of one group (alarm 12060) or of the syntax-defining groups (12070), an
//! instruction that must stand alone but does not, axis words in a dwell block, an address written
//! twice (12010, 16420). It reads only the line and the statements, and reports through the same
//! bound as the parser.

use crate::diagnostics::{Code, Diagnostic, Span};
use crate::syntax::ast::{AddressKind, AddressWord, Extension, NamedAddress, Statement};
use crate::syntax::gcodes::{self, GCode};
use crate::syntax::parser::checked_view::statements_as_checked;
use crate::syntax::parser::cursor::Parser;
use crate::syntax::parser::findings::push_bounded;

impl Parser<'_> {
    /// Runs the block checks over the statements the parser has read (those the interpreter runs, not
    /// the actions of a synchronized action). A block with repetitions or CASE branches is checked as
    /// `checked_view.rs` shows it; any other block as it is, without a copy.
    pub(super) fn check_block(&mut self) {
        let statements = std::mem::take(&mut self.block.statements);
        let interpreted_count = self.block.sync_actions_from.unwrap_or(statements.len());
        let mut checks = BlockChecks {
            line: self.line,
            diagnostics: &mut *self.diagnostics,
        };
        if self.repeats.is_empty() && !self.has_case_branches {
            checks.check_statements(&statements[..interpreted_count.min(statements.len())]);
        } else {
            let (checked, checked_interpreted) =
                statements_as_checked(&statements, &self.repeats, interpreted_count);
            checks.check_statements(&checked[..checked_interpreted]);
        }
        self.block.statements = statements;
    }
}

/// The pass: the line (for the texts the findings quote) and the line's findings so far.
struct BlockChecks<'a> {
    line: &'a str,
    diagnostics: &'a mut Vec<Diagnostic>,
}

impl BlockChecks<'_> {
    fn text(&self, span: Span) -> &str {
        &self.line[span.start()..span.end()]
    }

    fn report(&mut self, code: Code, span: Span, message: String) {
        push_bounded(self.diagnostics, Diagnostic::new(code, span, message));
    }

    fn check_statements(&mut self, interpreted: &[Statement]) {
        self.check_g_groups(interpreted);
        self.check_alone_instructions(interpreted);
        self.check_repeated_addresses(interpreted);
    }

    fn check_g_groups(&mut self, statements: &[Statement]) {
        // A bit per group seen so far; the first span of a group is looked up again only when the group
        // repeats, which keeps the common block free of per-block tables.
        let mut seen_groups: u64 = 0;
        let mut syntax_defining: Option<(GCode, Span)> = None;
        for statement in statements {
            let Statement::GCode { code, span } = statement else {
                continue;
            };
            let group = code.group();
            if gcodes::is_syntax_defining_group(group) {
                if let Some((first, _)) = syntax_defining {
                    self.report(
                        Code::SyntaxDefiningConflict,
                        *span,
                        format!(
                            "{} and {} cannot stand in one block: both decide what the axis words mean (groups 1, 2, 3; alarm 12070)",
                            first.name(),
                            code.name()
                        ),
                    );
                } else {
                    syntax_defining = Some((*code, *span));
                }
                continue;
            }
            let bit = 1u64 << (group as u32).min(63);
            if seen_groups & bit != 0 {
                let first_span = statements
                    .iter()
                    .find_map(|earlier| match earlier {
                        Statement::GCode { code, span } if code.group() == group => Some(*span),
                        _ => None,
                    })
                    .unwrap_or(*span);
                let first_text = self.text(first_span).to_string();
                self.report(
                    Code::SameGroupTwice,
                    *span,
                    format!(
                        "`{}` and `{first_text}` belong to the same G group {group}; only one may stand in a block (alarm 12060)",
                        self.text(*span)
                    ),
                );
            } else {
                seen_groups |= bit;
            }
        }
    }

    fn check_alone_instructions(&mut self, statements: &[Statement]) {
        self.check_dwell_block(statements);
        let Some((instruction, instruction_span)) =
            statements.iter().find_map(|statement| match statement {
                Statement::GCode { code, span } if code.must_stand_alone() => Some((*code, *span)),
                _ => None,
            })
        else {
            return;
        };
        let name = instruction.name();
        // G25/G26 (working-area limits) also take the spindle speed limit `S`, so they are exempt.
        if matches!(name.as_ref(), "G25" | "G26") {
            return;
        }
        for statement in statements {
            let allowed = match statement {
                Statement::GCode { .. } => true,
                Statement::Address(word) => matches!(
                    word.kind,
                    AddressKind::Axis
                        | AddressKind::Interpolation
                        | AddressKind::Named(NamedAddress::PolarAngle)
                        | AddressKind::Named(NamedAddress::PolarRadius)
                        | AddressKind::Named(NamedAddress::RotationInPlane)
                        | AddressKind::Named(NamedAddress::IndirectAxis)
                ),
                _ => false,
            };
            if !allowed {
                let span = statement.span();
                let text = self.text(span).to_string();
                let instruction_text = self.text(instruction_span).to_string();
                self.report(
                    Code::InstructionNotAlone,
                    span,
                    format!("`{instruction_text}` must stand in a block of its own; move `{text}` to another block"),
                );
            }
        }
    }

    /// G4 dwells for F seconds or S revolutions and is written in a block of its own (reference §2.4):
    /// axis words in a G4 block are reported.
    fn check_dwell_block(&mut self, statements: &[Statement]) {
        let is_dwell = |statement: &Statement| matches!(statement, Statement::GCode { code, .. } if code.is_dwell());
        let Some(dwell_span) = statements
            .iter()
            .find(|statement| is_dwell(statement))
            .map(Statement::span)
        else {
            return;
        };
        for statement in statements {
            if let Statement::Address(word) = statement {
                if matches!(word.kind, AddressKind::Axis | AddressKind::Interpolation) {
                    let text = self.text(word.span).to_string();
                    let dwell = self.text(dwell_span).to_string();
                    self.report(
                        Code::InstructionNotAlone,
                        word.span,
                        format!("`{dwell}` (dwell) must stand in a block of its own with only F (seconds) or S (revolutions); move `{text}` to another block"),
                    );
                }
            }
        }
    }

    fn check_repeated_addresses(&mut self, statements: &[Statement]) {
        // Blocks are short, so comparing each word with the earlier ones costs less than hashing; a
        // hostile block with thousands of words is capped so that it stays linear.
        const MAX_COMPARED: usize = 64;
        let considered = &statements[..statements.len().min(MAX_COMPARED)];
        for (index, statement) in considered.iter().enumerate() {
            let Statement::Address(word) = statement else {
                continue;
            };
            if matches!(word.kind, AddressKind::MFunction | AddressKind::HFunction) {
                continue;
            }
            let Some(first) = considered[..index]
                .iter()
                .find_map(|earlier| match earlier {
                    Statement::Address(earlier) if self.same_address(earlier, word) => {
                        Some(earlier)
                    }
                    _ => None,
                })
            else {
                continue;
            };
            let first_text = self.text(first.span).to_string();
            let key = self.text(word.name).to_ascii_uppercase();
            let alarm = if word.kind == AddressKind::Axis {
                "16420"
            } else {
                "12010"
            };
            self.report(
                Code::AddressTwice,
                word.span,
                format!(
                    "`{key}` is already programmed in this block (`{first_text}`; alarm {alarm})"
                ),
            );
        }
    }

    fn same_address(&self, left: &AddressWord, right: &AddressWord) -> bool {
        if !self
            .text(left.name)
            .eq_ignore_ascii_case(self.text(right.name))
        {
            return false;
        }
        match (&left.extension, &right.extension) {
            (None, None) => true,
            (
                Some(Extension::Number { value: a, .. }),
                Some(Extension::Number { value: b, .. }),
            ) => a == b,
            (Some(Extension::Index { span: a, .. }), Some(Extension::Index { span: b, .. })) => {
                let compact = |span: Span| self.text(span).bytes().filter(|byte| *byte != b' ');
                compact(*a)
                    .map(|byte| byte.to_ascii_uppercase())
                    .eq(compact(*b).map(|byte| byte.to_ascii_uppercase()))
            }
            _ => false,
        }
    }
}
