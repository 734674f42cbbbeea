//! Checks across blocks that need only syntax: control structures must nest (IF/ELSE/ENDIF, WHILE,
//! FOR, REPEAT/UNTIL, LOOP), as the control demands before it runs a program (alarm 12640).

use crate::diagnostics::{Code, Diagnostic, LineDiagnostic, Span};
use crate::syntax::ast::{Block, Statement, StructureKeyword};
use crate::syntax::parser::MAX_DIAGNOSTICS_PER_LINE;

/// Deepest nesting followed. The control allows far fewer levels (commonly 16); the bound keeps a
/// hostile line of a million `LOOP`s from costing memory and a million findings.
const MAX_OPEN_STRUCTURES: usize = 256;

/// An open structure: its keyword, line and span.
#[derive(Debug, Clone, PartialEq)]
struct Open {
    keyword: StructureKeyword,
    line: usize,
    span: Span,
    has_else: bool,
}

/// Follows the structure keywords of a program block by block.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StructureChecker {
    open: Vec<Open>,
    /// Whether the nesting bound was reported already (once per program).
    too_deep_reported: bool,
    /// Structures opened beyond the bound, which are not followed: the next closing keywords close
    /// them without a check, so that 100,000 nested IFs with their ENDIFs do not give 99,744 findings
    /// of "ENDIF without IF" (found with the hostile-file tests).
    untracked: usize,
}

fn name(keyword: StructureKeyword) -> &'static str {
    match keyword {
        StructureKeyword::If => "IF",
        StructureKeyword::Else => "ELSE",
        StructureKeyword::EndIf => "ENDIF",
        StructureKeyword::While => "WHILE",
        StructureKeyword::EndWhile => "ENDWHILE",
        StructureKeyword::For => "FOR",
        StructureKeyword::EndFor => "ENDFOR",
        StructureKeyword::Repeat => "REPEAT",
        StructureKeyword::Until => "UNTIL",
        StructureKeyword::Loop => "LOOP",
        StructureKeyword::EndLoop => "ENDLOOP",
        StructureKeyword::Case => "CASE",
    }
}

/// The keyword that closes an opening keyword.
pub fn closer(keyword: StructureKeyword) -> Option<StructureKeyword> {
    Some(match keyword {
        StructureKeyword::If => StructureKeyword::EndIf,
        StructureKeyword::While => StructureKeyword::EndWhile,
        StructureKeyword::For => StructureKeyword::EndFor,
        StructureKeyword::Repeat => StructureKeyword::Until,
        StructureKeyword::Loop => StructureKeyword::EndLoop,
        _ => return None,
    })
}

impl StructureChecker {
    /// Feeds one block; diagnostics go to `out` with `line`.
    pub fn feed(&mut self, line: usize, block: &Block, out: &mut Vec<LineDiagnostic>) {
        let out_before = out.len();
        for statement in block.interpreted_statements() {
            if out.len() - out_before >= MAX_DIAGNOSTICS_PER_LINE {
                // The parser's findings of this line are bounded the same way.
                break;
            }
            let Statement::Structure { keyword, span, .. } = statement else {
                continue;
            };
            let keyword = *keyword;
            if closer(keyword).is_some() {
                if self.open.len() >= MAX_OPEN_STRUCTURES {
                    if !self.too_deep_reported {
                        self.too_deep_reported = true;
                        out.push(mismatch(
                            line,
                            *span,
                            format!("control structures are nested more than {MAX_OPEN_STRUCTURES} levels deep; deeper levels are not checked"),
                        ));
                    }
                    self.untracked += 1;
                    continue;
                }
                self.open.push(Open {
                    keyword,
                    line,
                    span: *span,
                    has_else: false,
                });
                continue;
            }
            if self.untracked > 0 && keyword != StructureKeyword::Case {
                // Inside the levels that are not followed: ELSE belongs to one of them, and a closing
                // keyword closes the innermost.
                if keyword != StructureKeyword::Else {
                    self.untracked -= 1;
                }
                continue;
            }
            match keyword {
                StructureKeyword::Else => match self.open.last_mut() {
                    Some(open) if open.keyword == StructureKeyword::If && !open.has_else => {
                        open.has_else = true;
                    }
                    Some(open) if open.keyword == StructureKeyword::If => out.push(mismatch(
                        line,
                        *span,
                        "a second ELSE in the same IF".to_string(),
                    )),
                    _ => out.push(mismatch(
                        line,
                        *span,
                        format!("ELSE without IF{}", self.innermost_note()),
                    )),
                },
                StructureKeyword::Case => {}
                closing => {
                    let expected_opener = [
                        StructureKeyword::If,
                        StructureKeyword::While,
                        StructureKeyword::For,
                        StructureKeyword::Repeat,
                        StructureKeyword::Loop,
                    ]
                    .into_iter()
                    .find(|opener| closer(*opener) == Some(closing));
                    match self.open.last() {
                        Some(open) if closer(open.keyword) == Some(closing) => {
                            self.open.pop();
                        }
                        _ => {
                            let opener = expected_opener.map(name).unwrap_or("?");
                            out.push(mismatch(
                                line,
                                *span,
                                format!(
                                    "{} without matching {opener}{}",
                                    name(closing),
                                    self.innermost_note()
                                ),
                            ));
                            // Recover: close the nearest matching structure, if there is one.
                            if let Some(index) = self
                                .open
                                .iter()
                                .rposition(|open| closer(open.keyword) == Some(closing))
                            {
                                self.open.truncate(index);
                            }
                        }
                    }
                }
            }
        }
    }

    /// Lines were inserted or removed: structures opened at or after `from` move by `delta` lines.
    pub fn shift_lines(&mut self, from: usize, delta: isize) {
        for open in &mut self.open {
            if open.line >= from {
                open.line = open.line.saturating_add_signed(delta);
            }
        }
    }

    fn innermost_note(&self) -> String {
        match self.open.last() {
            // No line number: the message must stay true when lines are inserted above the opening
            // keyword, so that an edited document keeps the findings of unchanged blocks.
            Some(open) => format!(
                " (the innermost open structure is the {} above, closed by {})",
                name(open.keyword),
                closer(open.keyword).map(name).unwrap_or("?")
            ),
            None => String::new(),
        }
    }

    /// Reports every structure still open at the end of the program.
    pub fn finish(self, out: &mut Vec<LineDiagnostic>) {
        for open in self.open {
            out.push(mismatch(
                open.line,
                open.span,
                format!(
                    "{} is never closed by {}",
                    name(open.keyword),
                    closer(open.keyword).map(name).unwrap_or("?")
                ),
            ));
        }
    }
}

fn mismatch(line: usize, span: Span, message: String) -> LineDiagnostic {
    LineDiagnostic {
        line,
        diagnostic: Diagnostic::new(
            Code::StructureMismatch,
            span,
            format!("{message} (alarm 12640)"),
        ),
    }
}
