//! Control flow: the structure keywords (IF/ELSE/ENDIF, WHILE, FOR ... TO, REPEAT/UNTIL, LOOP, CASE
//! with its branches) and the jumps (GOTOF, GOTOB, GOTO, GOTOC, GOTOS) with their targets, also after
//! `IF condition`. How structures nest across blocks is checked in `syntax/structure.rs`.

use crate::diagnostics::{Code, Span};
use crate::syntax::ast::{ExprId, JumpKind, JumpTarget, Statement, StructureKeyword};
use crate::syntax::gcodes::GCode;
use crate::syntax::keywords::{self, StatementKeyword};
use crate::syntax::lexer::Token;
use crate::syntax::parser::cursor::Parser;

impl Parser<'_> {
    pub(super) fn parse_structure(&mut self, keyword: StructureKeyword, keyword_span: Span) {
        match keyword {
            StructureKeyword::If => {
                let condition = self.parse_condition(keyword_span);
                if let Some(StatementKeyword::Jump(kind)) = self.jump_keyword_here() {
                    let jump_span = self.advance();
                    self.parse_jump(kind, jump_span.to(keyword_span), condition);
                    // Several `IF ... GOTO` may follow in one block.
                    return;
                }
                self.push_structure(keyword, condition, self.span_since(keyword_span));
            }
            StructureKeyword::While | StructureKeyword::Until => {
                let condition = self.parse_condition(keyword_span);
                self.push_structure(keyword, condition, self.span_since(keyword_span));
            }
            StructureKeyword::For => {
                // `FOR CNT=1 TO 3`: the start is an assignment, the end value is the condition. Only an
                // assignment is parsed here (never a whole statement), so `FOR FOR FOR ...` cannot recurse.
                let counter_is_assignable = matches!(
                    self.peek(),
                    Some(Token::Identifier) | Some(Token::Letter) | Some(Token::SystemVariable)
                ) && self.position < self.lexemes.len()
                    && !self.is_keyword_here();
                if counter_is_assignable {
                    match self.peek() {
                        Some(Token::Letter) if self.letter_at(self.position) == Some(b'R') => {
                            self.parse_r_parameter_assignment()
                        }
                        Some(Token::SystemVariable) => self.parse_system_variable_assignment(),
                        _ => self.parse_counter_assignment(),
                    }
                }
                let mut condition = None;
                if self.is_at(Token::Identifier) && self.upper_name(self.current_span()) == "TO" {
                    self.advance();
                    condition = self.parse_condition(keyword_span);
                } else {
                    self.report(
                        Code::ExpectedExpression,
                        keyword_span,
                        "FOR needs a counter, a start value and `TO` with the end value: `FOR CNT=1 TO 10`",
                    );
                }
                self.push_structure(keyword, condition, self.span_since(keyword_span));
            }
            StructureKeyword::Case => {
                let condition = self.parse_condition(keyword_span);
                self.push_structure(keyword, condition, self.span_since(keyword_span));
                if self.is_at(Token::Identifier) && self.upper_name(self.current_span()) == "OF" {
                    self.advance();
                }
                // Pairs of `value GOTOF label`, then `DEFAULT GOTOF label`.
                while !self.at_end() {
                    let (value, value_span) = if self.is_at(Token::Identifier)
                        && self.upper_name(self.current_span()) == "DEFAULT"
                    {
                        (None, self.advance())
                    } else {
                        let value = self.parse_expression();
                        (Some(value), self.expr_span(value))
                    };
                    match self.jump_keyword_here() {
                        Some(StatementKeyword::Jump(kind)) => {
                            self.block.statements.push(Statement::CaseBranch {
                                value,
                                span: value_span,
                            });
                            self.has_case_branches = true;
                            let jump_span = self.advance();
                            self.parse_jump(kind, jump_span, None);
                        }
                        _ => {
                            if !self.at_end() {
                                let span = self.advance();
                                self.report(
                                    Code::UnexpectedToken,
                                    span,
                                    "CASE expects pairs of `value GOTOF label` and a final `DEFAULT GOTOF label`",
                                );
                            }
                        }
                    }
                }
            }
            StructureKeyword::Repeat => {
                // `REPEAT LABEL1 [LABEL2|ENDLABEL] P=n` repeats a section; `REPEAT` alone opens a loop.
                if self.is_at(Token::Identifier) {
                    self.parse_section_repeat(keyword_span);
                    return;
                }
                self.push_structure(keyword, None, keyword_span);
            }
            _ => {
                self.push_structure(keyword, None, keyword_span);
            }
        }
    }

    fn push_structure(&mut self, keyword: StructureKeyword, condition: Option<ExprId>, span: Span) {
        self.block.statements.push(Statement::Structure {
            keyword,
            condition,
            span,
        });
    }

    /// Whether the name at the current position is a statement keyword or G function name.
    pub(super) fn is_keyword_here(&self) -> bool {
        if !self.is_at(Token::Identifier) {
            return false;
        }
        let upper = self.upper_name(self.current_span());
        keywords::statement_keyword(&upper).is_some() || GCode::from_name(&upper).is_some()
    }

    pub(super) fn jump_keyword_here(&self) -> Option<StatementKeyword> {
        if !self.is_at(Token::Identifier) {
            return None;
        }
        let mut buffer = [0u8; 32];
        let upper = keywords::uppercase(self.text(self.current_span()), &mut buffer)?;
        match keywords::statement_keyword(upper) {
            Some(keyword @ StatementKeyword::Jump(_)) => Some(keyword),
            _ => None,
        }
    }

    pub(super) fn parse_jump(
        &mut self,
        kind: JumpKind,
        keyword_span: Span,
        condition: Option<ExprId>,
    ) {
        let target = if self.at_end() {
            if kind != JumpKind::Gotos {
                let text = self.text(keyword_span).to_string();
                self.report(
                    Code::ExpectedExpression,
                    keyword_span,
                    format!("`{text}` needs a jump target (a label or block number)"),
                );
            }
            JumpTarget::None
        } else if self.is_at(Token::Identifier)
            && !matches!(
                self.peek_nth(1),
                Some(Token::LeftBracket) | Some(Token::LeftParen)
            )
        {
            JumpTarget::Label(self.advance())
        } else if self.letter_at(self.position) == Some(b'N')
            && self.peek_nth(1) == Some(Token::Number)
        {
            let letter = self.advance();
            let number = self.advance();
            let value = self.integer_at(self.position - 1).unwrap_or(0);
            JumpTarget::BlockNumber {
                value,
                span: letter.to(number),
            }
        } else if self.is_at(Token::Letter)
            && matches!(self.peek_nth(1), Some(Token::Number))
            && self.adjacent(self.position + 1)
            && self.letter_at(self.position) != Some(b'R')
        {
            // A short label such as `L1` (reported where it is defined).
            let letter = self.advance();
            let number = self.advance();
            JumpTarget::Label(letter.to(number))
        } else {
            JumpTarget::Computed(self.parse_expression())
        };
        let span = self.span_since(keyword_span);
        self.block.statements.push(Statement::Jump {
            kind,
            target,
            condition,
            span,
        });
    }
}
