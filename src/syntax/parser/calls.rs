//! Calls and procedure headers: `CALL`/`EXTCALL` with a program name, `PCALL` with a path, `MCALL`
//! (modal call), `EXTERN` declarations, `RET`, and the `PROC` header with its parameter names and
//! attributes (the parameters' types and defaults are read in `declarations.rs`).

use crate::diagnostics::{Code, Span};
use crate::syntax::ast::{CallKind, Statement};
use crate::syntax::lexer::Token;
use crate::syntax::parser::cursor::Parser;
use crate::syntax::parser::definitions::is_type_name;

impl Parser<'_> {
    /// The name (an identifier or a single letter) at the current position, taken.
    fn name_here(&mut self) -> Option<Span> {
        (self.is_at(Token::Identifier) || self.is_at(Token::Letter)).then(|| self.advance())
    }

    /// Like [`Self::name_here`]; without a name, `message` is reported at the keyword.
    pub(super) fn name_or_report(&mut self, keyword_span: Span, message: &str) -> Option<Span> {
        let name = self.name_here();
        if name.is_none() {
            self.report(Code::ExpectedExpression, keyword_span, message);
        }
        name
    }

    /// `EXTERN name(types)`: the declared name; the rest only has to balance.
    pub(super) fn parse_extern(&mut self, keyword_span: Span) {
        let name = self.name_here();
        self.skip_balanced_rest();
        let span = self.span_since(keyword_span);
        self.block
            .statements
            .push(Statement::ExternDeclaration { name, span });
    }

    /// `RET`, with the return values of a function in parentheses read over.
    pub(super) fn parse_return(&mut self, keyword_span: Span) {
        if self.is_at(Token::LeftParen) {
            self.parse_argument_list();
        }
        let span = self.span_since(keyword_span);
        self.block.statements.push(Statement::Return { span });
    }

    /// `CALL` or `EXTCALL` with the name of the program as an expression (`CALL "PART"`).
    pub(super) fn parse_program_call(&mut self, keyword_span: Span) {
        let name = if self.at_end() {
            self.report(
                Code::ExpectedExpression,
                keyword_span,
                format!(
                    "`{}` needs the name of the program to call",
                    self.text(keyword_span)
                ),
            );
            None
        } else {
            let expr = self.parse_expression();
            Some(self.expr_span(expr))
        };
        // `CALL "PART" BLOCK START TO END` names a section of the program; keep it as written.
        if self.is_at(Token::Identifier) && self.upper_name(self.current_span()) == "BLOCK" {
            while !self.at_end() {
                self.advance();
            }
        }
        self.push_indirect_call(name, keyword_span);
    }

    /// `PCALL` with a path such as `/_N_CMA_DIR/_N_NAME_SPF`.
    pub(super) fn parse_path_call(&mut self, keyword_span: Span) {
        // PCALL takes a path (`/_N_CMA_DIR/_N_NAME_SPF`) that is not an expression.
        let start = self.position;
        while !self.at_end() && !self.is_at(Token::LeftParen) {
            self.advance();
        }
        let name = if self.position > start {
            Some(self.span_at(start).to(self.span_at(self.position - 1)))
        } else {
            None
        };
        self.push_indirect_call(name, keyword_span);
    }

    /// `MCALL NAME(args)` or `MCALL L123`; `MCALL` alone switches the modal call off.
    pub(super) fn parse_modal_call(&mut self, keyword_span: Span) {
        let mut name = None;
        let mut args = Vec::new();
        if self.is_at(Token::Identifier) {
            name = Some(self.advance());
            if self.is_at(Token::LeftParen) {
                args = self.parse_argument_list().0;
            }
        } else if self.letter_at(self.position) == Some(b'L')
            && self.peek_nth(1) == Some(Token::Number)
        {
            let letter = self.advance();
            let number = self.advance();
            name = Some(letter.to(number));
        }
        let span = self.span_since(keyword_span);
        self.block.statements.push(Statement::Call {
            kind: CallKind::Modal,
            name,
            args,
            span,
        });
    }

    /// Ends a CALL, EXTCALL or PCALL statement: its optional arguments, then the statement.
    pub(super) fn push_indirect_call(&mut self, name: Option<Span>, keyword_span: Span) {
        let args = if self.is_at(Token::LeftParen) {
            self.parse_argument_list().0
        } else {
            Vec::new()
        };
        let span = self.span_since(keyword_span);
        self.block.statements.push(Statement::Call {
            kind: CallKind::Indirect,
            name,
            args,
            span,
        });
    }

    pub(super) fn parse_procedure_header(&mut self, keyword_span: Span) {
        let name = self.name_or_report(keyword_span, "PROC needs the name of the subprogram");
        let mut parameters = Vec::new();
        let list_start = self.position;
        if self.is_at(Token::LeftParen) {
            let open = self.advance();
            let mut depth = 1i32;
            while !self.at_end() && depth > 0 {
                let token = self.peek();
                let span = self.advance();
                match token {
                    Some(Token::LeftParen) | Some(Token::LeftBracket) => depth += 1,
                    Some(Token::RightParen) | Some(Token::RightBracket) => depth -= 1,
                    Some(Token::Identifier) | Some(Token::Letter) if depth == 1 => {
                        let upper = self.upper_name(span);
                        let followed_by_end = matches!(
                            self.peek(),
                            Some(Token::Comma)
                                | Some(Token::RightParen)
                                | Some(Token::LeftBracket)
                                | Some(Token::Assign)
                        ) || self.at_end();
                        if followed_by_end && !is_type_name(&upper) && upper != "VAR" {
                            parameters.push(span);
                        }
                    }
                    _ => {}
                }
            }
            if depth > 0 {
                self.report(
                    Code::UnbalancedParentheses,
                    open,
                    "the parameter list of PROC is not closed",
                );
            }
        }
        // Attributes such as SAVE, SBLOF, DISPLOF, ACTBLOCNO follow the parameter list.
        let mut save = false;
        while !self.at_end() {
            let token = self.peek();
            let span = self.advance();
            save |=
                token == Some(Token::Identifier) && self.text(span).eq_ignore_ascii_case("SAVE");
        }
        let params = self.parse_procedure_params(list_start);
        let span = self.span_since(keyword_span);
        self.block.statements.push(Statement::ProcedureHeader {
            name,
            parameters,
            params,
            save,
            span,
        });
    }

    /// Consumes the rest of the block, checking only that brackets balance.
    pub(super) fn skip_balanced_rest(&mut self) {
        let start = self.current_span();
        let mut depth = 0i32;
        while !self.at_end() {
            match self.peek() {
                Some(Token::LeftParen) | Some(Token::LeftBracket) => depth += 1,
                Some(Token::RightParen) | Some(Token::RightBracket) => depth -= 1,
                _ => {}
            }
            self.advance();
        }
        if depth != 0 {
            self.report(
                Code::UnbalancedParentheses,
                start,
                "parentheses or brackets in this declaration do not balance",
            );
        }
    }
}
