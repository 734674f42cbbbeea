//! The layout of a block: the skip level, the block number and the label, then statements up to the
//! comment. Each statement goes to its grammar area by its first token, and a statement keyword by its
//! kind; a bracket where a word belongs is an ISO-dialect comment. The block checks run last.

use crate::diagnostics::{Code, Fix, Span};
use crate::syntax::ast::{BlockNumber, Statement};
use crate::syntax::keywords::StatementKeyword;
use crate::syntax::lexer::{Lexeme, Token};
use crate::syntax::parser::cursor::Parser;

impl Parser<'_> {
    pub(super) fn parse_block(&mut self) {
        self.check_block_length();
        if let Some(Lexeme {
            token: Some(Token::Comment),
            span,
        }) = self.lexemes.last()
        {
            self.block.comment = Some(*span);
        }
        if self.peek() == Some(Token::Percent) && self.position == 0 {
            // A punched-tape header such as `%_N_PART_MPF` names the program; it is not a block.
            self.block.is_header = true;
            return;
        }
        self.parse_skip_level();
        self.parse_block_number();
        self.parse_label();
        while !self.at_end() {
            let before = self.position;
            self.parse_statement();
            if self.position == before {
                // Every statement parser consumes at least one token; this guards the loop anyway.
                self.advance();
            }
        }
        self.check_block();
    }

    pub(super) fn check_block_length(&mut self) {
        // Characters are never more than bytes, so most lines skip the count.
        let character_count = if self.line.len() > self.context.max_block_length {
            self.line.chars().count()
        } else {
            0
        };
        if character_count > self.context.max_block_length {
            self.report(
                Code::BlockTooLong,
                Span::new(0, self.line.len()),
                format!(
                    "this block has {character_count} characters; the control accepts at most {} (comment included)",
                    self.context.max_block_length
                ),
            );
        }
    }

    pub(super) fn parse_skip_level(&mut self) {
        if !self.is_at(Token::Slash) {
            return;
        }
        let slash = self.advance();
        let mut level = 0u8;
        let mut span = slash;
        if self.adjacent(self.position) && self.peek() == Some(Token::Number) {
            let number_span = self.advance();
            span = slash.to(number_span);
            match self.integer_at(self.position - 1) {
                Some(value) if value <= u64::from(self.context.max_skip_level) => {
                    level = value as u8
                }
                _ => {
                    self.report(
                        Code::InvalidSkipLevel,
                        span,
                        format!(
                            "skip level `{}` does not exist: the levels are /0 to /{} (alarm 14060)",
                            self.text(span),
                            self.context.max_skip_level
                        ),
                    );
                    level = self.context.max_skip_level;
                }
            }
        }
        self.block.skip = Some((level, span));
    }

    pub(super) fn parse_block_number(&mut self) {
        let is_n = self.letter_at(self.position) == Some(b'N');
        let is_main = self.is_at(Token::Colon);
        if !(is_n || is_main) || self.peek_nth(1) != Some(Token::Number) {
            return;
        }
        // `N` followed by `=` or a name is something else (e.g. a variable called N in a PROC).
        let start = self.advance();
        let number_span = self.advance();
        let span = start.to(number_span);
        let value = match self.integer_at(self.position - 1) {
            Some(value) => value,
            None => {
                self.report(
                    Code::InvalidNumber,
                    number_span,
                    format!(
                        "block number `{}` must be a positive whole number",
                        self.text(number_span)
                    ),
                );
                0
            }
        };
        self.block.number = Some(BlockNumber {
            value,
            main: is_main,
            span,
        });
    }

    pub(super) fn parse_label(&mut self) {
        let position = self.position;
        match (self.token_at(position), self.token_at(position + 1)) {
            (Some(Token::Identifier), Some(Token::Colon)) => {
                let span = self.advance();
                self.advance();
                self.check_name_style(span, "label");
                self.block.label = Some(span);
            }
            (Some(Token::Letter), Some(Token::Colon)) => {
                let span = self.advance();
                self.advance();
                self.report(
                    Code::InvalidLabel,
                    span,
                    format!(
                        "`{}` is an address letter and cannot be a label; label names start with two letters",
                        self.text(span)
                    ),
                );
                self.block.label = Some(span);
            }
            (Some(Token::Letter), Some(Token::Number))
                if self.adjacent(position + 1)
                    && self.token_at(position + 2) == Some(Token::Colon)
                    && self.integer_at(position + 1).is_some() =>
            {
                let span = self.span_at(position).to(self.span_at(position + 1));
                self.position += 3;
                self.report(
                    Code::LabelStyle,
                    span,
                    format!(
                        "label `{}` starts with a single letter; names should start with two letters so they are not read as address words",
                        self.text(span)
                    ),
                );
                self.block.label = Some(span);
            }
            (Some(Token::Number), Some(Token::Identifier))
                if self.adjacent(position + 1)
                    && self.token_at(position + 2) == Some(Token::Colon) =>
            {
                let span = self.span_at(position).to(self.span_at(position + 1));
                self.position += 3;
                self.report(
                    Code::InvalidLabel,
                    span,
                    format!(
                        "label `{}` starts with a digit; names must start with two letters",
                        self.text(span)
                    ),
                );
                self.block.label = Some(span);
            }
            _ => {}
        }
    }

    pub(super) fn check_name_style(&mut self, span: Span, what: &str) {
        let name = self.text(span);
        if name.chars().count() > 31 {
            self.report(
                Code::LabelStyle,
                span,
                format!(
                    "{what} `{name}` has {} characters; names should have at most 31",
                    name.chars().count()
                ),
            );
        }
    }

    // ----- statements ---------------------------------------------------------------------------

    pub(super) fn parse_statement(&mut self) {
        let Some(token) = self.peek() else {
            let span = self.advance();
            self.report(
                Code::UnexpectedCharacter,
                span,
                format!(
                    "`{}` has no meaning in an NC block outside a string or comment",
                    self.text(span).escape_debug()
                ),
            );
            return;
        };
        match token {
            Token::Letter => self.parse_letter_word(),
            Token::Identifier => self.parse_identifier_statement(),
            Token::SystemVariable => self.parse_system_variable_assignment(),
            Token::LeftParen => self.parse_parenthesis_comment(),
            Token::UnterminatedString => {
                let span = self.advance();
                self.report_unterminated_string(span);
            }
            Token::BadNumber | Token::BadQuoted => {
                let span = self.advance();
                self.report_bad_number(span);
            }
            Token::RightParen => {
                let span = self.advance();
                self.report(
                    Code::UnbalancedParentheses,
                    span,
                    "this `)` has no matching `(`",
                );
            }
            Token::RightBracket => {
                let span = self.advance();
                self.report(
                    Code::UnbalancedBrackets,
                    span,
                    "this `]` has no matching `[`",
                );
            }
            _ => {
                let span = self.advance();
                let text = self.text(span).to_string();
                self.report(
                    Code::UnexpectedToken,
                    span,
                    format!("`{text}` cannot stand here: a block holds address words, G functions, assignments and statements"),
                );
            }
        }
    }

    /// `(TEXT)` where a word belongs: an ISO-dialect comment, which Siemens mode reads as an expression.
    pub(super) fn parse_parenthesis_comment(&mut self) {
        let open = self.advance();
        let mut depth = 1usize;
        let mut close = None;
        // Text, not an expression: two operands side by side (`TOOL 1`, `T1 D1 FINISH`), or one
        // name without digits (`ROUGHING`); an operator or a comma makes it a value.
        let mut text_like = false;
        let mut operands = 0usize;
        let mut operators = 0usize;
        // The previous token when it was an operand, and whether it was a single letter.
        let mut previous_operand: Option<(Span, bool)> = None;
        while self.position < self.lexemes.len() && self.peek() != Some(Token::Comment) {
            let token = self.peek();
            let span = self.advance();
            let operand = matches!(
                token,
                Some(
                    Token::Number
                        | Token::Letter
                        | Token::Identifier
                        | Token::SystemVariable
                        | Token::String
                )
            );
            if depth == 1 && operand {
                // A letter and the digits right after it are one word (`R1`, `X10`).
                let joined = previous_operand.is_some_and(|(previous, letter)| {
                    letter && previous.end() == span.start() && token == Some(Token::Number)
                });
                if previous_operand.is_some() && !joined {
                    text_like = true;
                }
                if !joined {
                    operands += 1;
                }
                previous_operand = Some((span, token == Some(Token::Letter)));
            } else if !matches!(token, Some(Token::RightParen)) || depth > 1 {
                previous_operand = None;
                operators += 1;
            }
            match token {
                Some(Token::LeftParen) => depth += 1,
                Some(Token::RightParen) => {
                    depth -= 1;
                    if depth == 0 {
                        close = Some(span);
                        break;
                    }
                }
                _ => {}
            }
        }
        let Some(close) = close else {
            self.report(
                Code::UnbalancedParentheses,
                open,
                "this `(` is never closed; parentheses are not comments in Siemens mode",
            );
            return;
        };
        let span = open.to(close);
        let single_name = operands == 1
            && operators == 0
            && self.line[open.end()..close.start()]
                .trim()
                .bytes()
                .all(|byte| byte.is_ascii_alphabetic() || byte == b'_');
        let text_like = text_like || single_name;
        let inner = self.line[open.end()..close.start()].trim().to_string();
        let message = format!(
            "`({inner})` is not a comment in Siemens mode: parentheses hold expressions, comments start with `;`"
        );
        if text_like && self.at_end() && self.block.comment.is_none() {
            // Only text becomes a comment: a value (`M202(0.0024)`, arguments, an expression) would
            // be deleted by it.
            let fix = Fix::replace(
                format!("Make it a comment: `; {inner}`"),
                span,
                format!("; {inner}"),
            );
            self.report_with_fix(Code::ParenthesisComment, span, message, fix);
        } else {
            self.report(Code::ParenthesisComment, span, message);
        }
    }

    // ----- keyword statements -------------------------------------------------------------------

    pub(super) fn parse_keyword_statement(&mut self, keyword: StatementKeyword) {
        let keyword_span = self.advance();
        match keyword {
            StatementKeyword::Structure(structure) => self.parse_structure(structure, keyword_span),
            StatementKeyword::Jump(kind) => self.parse_jump(kind, keyword_span, None),
            StatementKeyword::Def if self.text(keyword_span).eq_ignore_ascii_case("REDEF") => {
                // `REDEF name attributes` changes attributes of an existing variable (also of machine
                // data in access files); it has no type and defines nothing new.
                while !self.at_end() {
                    self.advance();
                }
                let span = self.span_since(keyword_span);
                self.block.statements.push(Statement::Instruction {
                    name: keyword_span,
                    args: Vec::new(),
                    span,
                });
            }
            StatementKeyword::Def => self.parse_definition(keyword_span),
            StatementKeyword::Define => self.parse_macro_definition(keyword_span),
            StatementKeyword::Proc => self.parse_procedure_header(keyword_span),
            StatementKeyword::Extern => self.parse_extern(keyword_span),
            StatementKeyword::Return => self.parse_return(keyword_span),
            StatementKeyword::Call | StatementKeyword::ExtCall => {
                self.parse_program_call(keyword_span)
            }
            StatementKeyword::PCall => self.parse_path_call(keyword_span),
            StatementKeyword::MCall => self.parse_modal_call(keyword_span),
            StatementKeyword::SyncCondition => self.parse_sync_condition(keyword_span),
            StatementKeyword::Do => {
                if self.block.sync_actions_from.is_none() {
                    self.block.sync_actions_from = Some(self.block.statements.len());
                }
            }
            StatementKeyword::RepeatBackward => self.parse_block_repeat(keyword_span),
        }
    }
}
