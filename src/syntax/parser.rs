//! The block parser: one line in, one [`Block`] plus its syntax diagnostics out. It never fails and never
//! recurses deeper than [`MAX_EXPRESSION_DEPTH`], so hostile lines cost linear time and bounded stack.

use crate::config::AxisKind;
use crate::diagnostics::{Code, Diagnostic, Fix, Span};
use crate::syntax::ast::*;
use crate::syntax::context::SyntaxContext;
use crate::syntax::gcodes::GCode;
use crate::syntax::keywords::{self, StatementKeyword};
use crate::syntax::lexer::{lex_line_into, Lexeme, Token};

#[cfg(test)]
mod declaration_tests;
mod declarations;
#[cfg(test)]
mod flow_tests;
mod plain_block;
mod repeats;

/// Deepest nesting of parentheses, brackets and unary operators the parser follows. Real programs stay
/// far below; deeper input is reported (S170) and skipped in linear time.
pub const MAX_EXPRESSION_DEPTH: u32 = 128;

/// How high the tree of one expression may grow (a leaf is 1, `a+b` is 2). Chains such as
/// `1+1+1+...` are parsed in a loop and grow the tree without deepening the parser's recursion, so
/// this bound is what keeps every recursive walk of the tree (evaluation, formatting, checks) within a
/// small, fixed stack, whatever the length of the line.
pub const MAX_TREE_HEIGHT: u32 = 256;

/// Most findings reported for one line; the last one says that more were dropped.
pub const MAX_DIAGNOSTICS_PER_LINE: usize = 200;

/// Longest quotation of program text inside a message, in characters.
const MAX_QUOTE_CHARACTERS: usize = 60;

/// Shortens every `quoted` part of a message that is longer than [`MAX_QUOTE_CHARACTERS`] to its start
/// and end around an ellipsis. The span still marks the whole text; a message quoting a megabyte-long
/// name helps nobody in an editor or a terminal.
fn shorten_long_quotes(message: String) -> String {
    if message.len() <= MAX_QUOTE_CHARACTERS * 2 {
        return message;
    }
    let mut out = String::with_capacity(message.len().min(1024));
    for (index, part) in message.split('`').enumerate() {
        if index > 0 {
            out.push('`');
        }
        let is_quote = index % 2 == 1;
        let character_count = if is_quote { part.chars().count() } else { 0 };
        if is_quote && character_count > MAX_QUOTE_CHARACTERS {
            out.extend(part.chars().take(MAX_QUOTE_CHARACTERS - 15));
            out.push('…');
            out.extend(part.chars().skip(character_count - 10));
        } else {
            out.push_str(part);
        }
    }
    // A quoted text that holds a backtick itself ends its quote early, so the rest of it was not
    // shortened above: keep the start and the end of such a message (found by the fuzzer).
    let character_count = out.chars().count();
    if character_count > MAX_MESSAGE_CHARACTERS {
        let tail: String = out.chars().skip(character_count - 80).collect();
        out = out.chars().take(MAX_MESSAGE_CHARACTERS - 81).collect();
        out.push('…');
        out.push_str(&tail);
    }
    out
}

/// Longest message, in characters, even when its quotations could not be found.
const MAX_MESSAGE_CHARACTERS: usize = 300;

/// A reusable parser: keeps its token buffer between lines.
#[derive(Default)]
pub struct LineParser {
    lexemes: Vec<Lexeme>,
    /// The height of each expression node of the block being parsed (see [`MAX_TREE_HEIGHT`]).
    heights: Vec<u32>,
}

impl LineParser {
    pub fn new() -> LineParser {
        LineParser::default()
    }

    /// Parses `line` (without its line terminator) into `block` and appends the findings to
    /// `diagnostics`. Both are cleared first; their allocations are reused.
    pub fn parse(
        &mut self,
        line: &str,
        context: &SyntaxContext,
        block: &mut Block,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        self.parse_with(line, context, block, diagnostics, true);
    }

    /// Like [`LineParser::parse`], but never takes the fast path for plain blocks. Exists so that tests
    /// can prove both paths give the same result.
    #[doc(hidden)]
    pub fn parse_without_fast_path(
        &mut self,
        line: &str,
        context: &SyntaxContext,
        block: &mut Block,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        self.parse_with(line, context, block, diagnostics, false);
    }

    fn parse_with(
        &mut self,
        line: &str,
        context: &SyntaxContext,
        block: &mut Block,
        diagnostics: &mut Vec<Diagnostic>,
        allow_fast_path: bool,
    ) {
        block.clear();
        diagnostics.clear();
        if allow_fast_path {
            let mut parser = Parser::new(line, &[], block, diagnostics, context, &mut self.heights);
            if parser.parse_plain_block() {
                return;
            }
            block.clear();
            diagnostics.clear();
        }
        lex_line_into(line, &mut self.lexemes);
        Parser::new(
            line,
            &self.lexemes,
            block,
            diagnostics,
            context,
            &mut self.heights,
        )
        .parse_block();
    }
}

/// Parses one line with a fresh parser; convenient for tests and single lookups.
pub fn parse_line(line: &str, context: &SyntaxContext) -> (Block, Vec<Diagnostic>) {
    let mut block = Block::default();
    let mut diagnostics = Vec::new();
    LineParser::new().parse(line, context, &mut block, &mut diagnostics);
    (block, diagnostics)
}

struct Parser<'a> {
    line: &'a str,
    lexemes: &'a [Lexeme],
    position: usize,
    block: &'a mut Block,
    diagnostics: &'a mut Vec<Diagnostic>,
    context: &'a SyntaxContext,
    depth: u32,
    depth_reported: bool,
    unclosed_reported: bool,
    /// Greater than zero while parsing the value inside `AC(..)` and friends.
    modifier_depth: u32,
    precedence_reported: bool,
    /// Greater than zero while parsing the condition of IF, WHILE, UNTIL or a synchronized action.
    condition_depth: u32,
    /// Greater than zero inside parentheses or brackets of an expression.
    group_depth: u32,
    /// The REPEAT and REPEATB statements of the block, as the block checks read them.
    repeats: Vec<repeats::RepeatWords>,
    /// Whether a CASE branch was pushed: the block checks then leave such statements out.
    has_case_branches: bool,
    /// The height of every node in `block.exprs` (a leaf is 1), kept beside the arena.
    heights: &'a mut Vec<u32>,
}

/// Letters that name axes when the machine configuration has such an axis (reference §1.7).
fn is_axis_letter(letter: u8) -> bool {
    matches!(
        letter,
        b'X' | b'Y' | b'Z' | b'A' | b'B' | b'C' | b'U' | b'V' | b'W' | b'Q' | b'E'
    )
}

impl<'a> Parser<'a> {
    fn new(
        line: &'a str,
        lexemes: &'a [Lexeme],
        block: &'a mut Block,
        diagnostics: &'a mut Vec<Diagnostic>,
        context: &'a SyntaxContext,
        heights: &'a mut Vec<u32>,
    ) -> Parser<'a> {
        heights.clear();
        Parser {
            line,
            lexemes,
            position: 0,
            block,
            diagnostics,
            context,
            depth: 0,
            depth_reported: false,
            unclosed_reported: false,
            modifier_depth: 0,
            precedence_reported: false,
            condition_depth: 0,
            group_depth: 0,
            repeats: Vec::new(),
            has_case_branches: false,
            heights,
        }
    }

    // ----- token access -------------------------------------------------------------------------

    fn token_at(&self, index: usize) -> Option<Token> {
        self.lexemes.get(index).and_then(|lexeme| lexeme.token)
    }

    fn peek(&self) -> Option<Token> {
        self.token_at(self.position)
    }

    fn peek_nth(&self, offset: usize) -> Option<Token> {
        self.token_at(self.position + offset)
    }

    fn span_at(&self, index: usize) -> Span {
        match self.lexemes.get(index) {
            Some(lexeme) => lexeme.span,
            None => Span::new(self.line.len(), self.line.len()),
        }
    }

    fn current_span(&self) -> Span {
        self.span_at(self.position)
    }

    fn previous_end(&self) -> usize {
        if self.position == 0 {
            0
        } else {
            self.span_at(self.position - 1).end()
        }
    }

    fn text(&self, span: Span) -> &'a str {
        &self.line[span.start()..span.end()]
    }

    fn text_at(&self, index: usize) -> &'a str {
        self.text(self.span_at(index))
    }

    /// True at the end of the line or at its comment.
    fn at_end(&self) -> bool {
        matches!(self.peek(), None | Some(Token::Comment)) && self.position >= self.lexemes.len()
            || self.peek() == Some(Token::Comment)
    }

    fn is_at(&self, token: Token) -> bool {
        self.position < self.lexemes.len() && self.peek() == Some(token)
    }

    /// Whether the token at `index` starts right where the previous one ends (no blank between).
    fn adjacent(&self, index: usize) -> bool {
        index > 0
            && index < self.lexemes.len()
            && self.span_at(index - 1).end() == self.span_at(index).start()
    }

    /// From the start of `start` to the end of the last consumed token.
    fn span_since(&self, start: Span) -> Span {
        start.to(Span::new(self.previous_end(), self.previous_end()))
    }

    fn advance(&mut self) -> Span {
        let span = self.current_span();
        if self.position < self.lexemes.len() {
            self.position += 1;
        }
        span
    }

    fn letter_at(&self, index: usize) -> Option<u8> {
        if self.token_at(index) == Some(Token::Letter) {
            Some(self.text_at(index).as_bytes()[0].to_ascii_uppercase())
        } else {
            None
        }
    }

    fn upper_name(&self, span: Span) -> String {
        self.text(span).to_ascii_uppercase()
    }

    fn report(&mut self, code: Code, span: Span, message: impl Into<String>) {
        self.push_diagnostic(Diagnostic::new(code, span, message));
    }

    fn report_with_fix(&mut self, code: Code, span: Span, message: impl Into<String>, fix: Fix) {
        self.push_diagnostic(Diagnostic::new(code, span, message).with_fix(fix));
    }

    /// Keeps a line's findings bounded: a line of repeated junk would otherwise give one finding per
    /// token, which helps nobody and costs memory. The last kept finding says that more were dropped.
    fn push_diagnostic(&mut self, mut diagnostic: Diagnostic) {
        let count = self.diagnostics.len();
        if count >= MAX_DIAGNOSTICS_PER_LINE {
            return;
        }
        if count == MAX_DIAGNOSTICS_PER_LINE - 1 {
            diagnostic = Diagnostic::new(
                Code::TooManyDiagnostics,
                diagnostic.span,
                format!(
                    "this line has more than {} findings; the rest are not shown",
                    MAX_DIAGNOSTICS_PER_LINE - 1
                ),
            );
        }
        diagnostic.message = shorten_long_quotes(diagnostic.message);
        if let Some(fix) = diagnostic.fix.as_mut() {
            fix.title = shorten_long_quotes(std::mem::take(&mut fix.title));
        }
        self.diagnostics.push(diagnostic);
    }

    fn push_expr(&mut self, kind: ExprKind, span: Span) -> ExprId {
        let height = self.height_of(&kind);
        let kind = if height > MAX_TREE_HEIGHT {
            self.report_too_long(span);
            ExprKind::Error
        } else {
            kind
        };
        let height = if matches!(kind, ExprKind::Error) {
            1
        } else {
            height
        };
        self.block.exprs.push(Expr { kind, span });
        self.heights.push(height);
        ExprId(self.block.exprs.len() as u32 - 1)
    }

    /// The height of a node of `kind`: one more than its highest child. A chain of operators
    /// (`1+1+1+...`) is built by a loop, not by recursion, so only this height bounds the depth of the
    /// tree that evaluation and other walks recurse over.
    fn height_of(&self, kind: &ExprKind) -> u32 {
        let child = |id: &ExprId| self.heights.get(id.0 as usize).copied().unwrap_or(1);
        let highest = match kind {
            ExprKind::RParameterIndexed(inner)
            | ExprKind::Unary(_, inner)
            | ExprKind::Parenthesized(inner) => child(inner),
            ExprKind::Binary(_, left, right) => child(left).max(child(right)),
            ExprKind::Name { indexes } | ExprKind::SystemVariable { indexes } => {
                indexes.iter().map(child).max().unwrap_or(0)
            }
            ExprKind::Call { args, .. } => args.iter().flatten().map(child).max().unwrap_or(0),
            ExprKind::List(items) => items.iter().map(child).max().unwrap_or(0),
            _ => 0,
        };
        highest.saturating_add(1)
    }

    /// Reports, once per block, an expression with more than [`MAX_TREE_HEIGHT`] operations nested
    /// in each other; the node becomes an error node, so its value is unknown.
    fn report_too_long(&mut self, span: Span) {
        // One S170 per block, whether the parser's nesting or the tree's height was exceeded first.
        if self.depth_reported {
            return;
        }
        self.depth_reported = true;
        self.report(
            Code::TooDeeplyNested,
            span,
            format!("this expression chains more than {MAX_TREE_HEIGHT} operations; its value is not evaluated"),
        );
    }

    fn expr_span(&self, id: ExprId) -> Span {
        self.block.exprs[id.0 as usize].span
    }

    /// Parses an unsigned integer token's text; `None` for decimals, exponents or overflow.
    fn integer_at(&self, index: usize) -> Option<u64> {
        if self.token_at(index) != Some(Token::Number) {
            return None;
        }
        let mut value: u64 = 0;
        for byte in self.text_at(index).bytes() {
            if !byte.is_ascii_digit() {
                return None;
            }
            value = value.checked_mul(10)?.checked_add(u64::from(byte - b'0'))?;
        }
        Some(value)
    }

    // ----- block layout -------------------------------------------------------------------------

    fn parse_block(&mut self) {
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

    fn check_block_length(&mut self) {
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

    fn parse_skip_level(&mut self) {
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

    fn parse_block_number(&mut self) {
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

    fn parse_label(&mut self) {
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

    fn check_name_style(&mut self, span: Span, what: &str) {
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

    fn parse_statement(&mut self) {
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

    fn report_unterminated_string(&mut self, span: Span) {
        let fix = Fix::replace(
            "Close the string at the end of the line",
            Span::new(span.end(), span.end()),
            "\"",
        );
        self.report_with_fix(
            Code::UnterminatedString,
            span,
            "this string has no closing `\"` on its line (strings cannot continue onto the next line)",
            fix,
        );
    }

    fn report_bad_number(&mut self, span: Span) {
        let text = self.text(span).to_string();
        let message = if text.starts_with('\'') {
            format!(
                "`{text}` is not a valid literal: write hexadecimal as 'H1F' and binary as 'B101'"
            )
        } else {
            format!("`{text}` is not a valid number")
        };
        self.report(Code::InvalidNumber, span, message);
    }

    /// The value of the number token at `span`, or `None` after reporting S133 when it lies beyond the
    /// range of a double (`1EX400`, a number of ten thousand digits): such a number used to become
    /// infinity, which must never be shown as a position.
    fn number_value(&mut self, span: Span) -> Option<f64> {
        let value = parse_number(self.text(span));
        if value.is_none() {
            self.report_number_out_of_range(span);
        }
        value
    }

    fn report_number_out_of_range(&mut self, span: Span) {
        let text = self.text(span).to_string();
        self.report(
            Code::InvalidNumber,
            span,
            format!("`{text}` is too large for a number: the control computes with values up to about 1.8EX308"),
        );
    }

    /// `(TEXT)` where a word belongs: an ISO-dialect comment, which Siemens mode reads as an expression.
    fn parse_parenthesis_comment(&mut self) {
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

    fn parse_letter_word(&mut self) {
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

    fn parse_g_word(&mut self) {
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

    fn parse_r_parameter_assignment(&mut self) {
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

    fn classify_letter(&self, letter: u8, extension: Option<u32>) -> AddressKind {
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
    fn parse_address_word(&mut self, letter: u8) {
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
    fn check_axis_configured(&mut self, letter: u8, extension: Option<u32>, span: Span) {
        if extension.is_none() && self.context.axis_kind_by_letter(letter).is_some() {
            return;
        }
        self.check_axis_configured_by_name(letter, extension, span);
    }

    #[inline(never)]
    fn check_axis_configured_by_name(&mut self, letter: u8, extension: Option<u32>, span: Span) {
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
                super::unconfigured_axes::occurrence_message(&name, &self.context.axis_list()),
            );
        }
    }

    /// The value of an address word: a constant (`X10`, `X-5.5`), or `=` and an expression or modifier.
    fn parse_word_value(
        &mut self,
        kind: AddressKind,
        name_span: Span,
        has_extension: bool,
    ) -> Value {
        if self.is_at(Token::Assign) {
            return self.parse_value_after_equals(kind, name_span);
        }
        if has_extension {
            let text = self.text(name_span).to_string();
            self.report(
                Code::ValueNeedsEquals,
                name_span,
                format!("an address with extension needs `=` before its value, e.g. `{text}1=10`"),
            );
            return Value {
                modifier: None,
                expr: ValueExpr::Missing,
                has_equals: false,
            };
        }
        let start = self.position;
        let sign = match self.peek() {
            Some(Token::Minus) | Some(Token::Plus)
                if matches!(
                    self.peek_nth(1),
                    Some(Token::Number)
                        | Some(Token::LeftParen)
                        | Some(Token::Letter)
                        | Some(Token::Identifier)
                        | Some(Token::SystemVariable)
                ) =>
            {
                let negative = self.peek() == Some(Token::Minus);
                self.advance();
                Some(negative)
            }
            _ => None,
        };
        match self.peek() {
            Some(Token::Number) if self.position < self.lexemes.len() => {
                let number_span = self.advance();
                let span = self.span_at(start).to(number_span);
                // A number beyond the range of a double is reported and its value is unknown.
                let expr = match self.number_value(number_span) {
                    Some(value) => ValueExpr::Constant {
                        value: if sign == Some(true) { -value } else { value },
                        span,
                    },
                    None => ValueExpr::Expr(self.push_expr(ExprKind::Error, span)),
                };
                Value {
                    modifier: None,
                    expr,
                    has_equals: false,
                }
            }
            Some(Token::String) if kind == AddressKind::Tool => {
                // `T"DRILL"` without `=` is not valid, but the intent is clear.
                let span = self.advance();
                let fix = Fix::replace(
                    "Write `T=\"...\"`",
                    Span::new(span.start(), span.start()),
                    "=",
                );
                self.report_with_fix(
                    Code::ValueNeedsEquals,
                    span,
                    "a tool name is assigned with `=`: `T=\"NAME\"`",
                    fix,
                );
                let expr = self.push_expr(ExprKind::String, span);
                Value {
                    modifier: None,
                    expr: ValueExpr::Expr(expr),
                    has_equals: false,
                }
            }
            Some(Token::BadNumber) => {
                let span = self.advance();
                self.report_bad_number(span);
                Value {
                    modifier: None,
                    expr: ValueExpr::Missing,
                    has_equals: false,
                }
            }
            Some(Token::Identifier)
                if self.position < self.lexemes.len()
                    && keywords::is_modifier_name(&self.upper_name(self.current_span()))
                    && self.peek_nth(1) == Some(Token::LeftParen) =>
            {
                // `Z AC(17)`: the `=` is missing.
                let modifier_span = self.current_span();
                let value = self.parse_modifier_value(kind, name_span);
                let end = self.previous_end();
                let written = self.line[modifier_span.start()..end].to_string();
                let address = self.text(name_span).to_string();
                let fix = Fix::replace(
                    format!("Write `{address}={written}`"),
                    Span::new(name_span.start(), end),
                    format!("{address}={written}"),
                );
                self.report_with_fix(
                    Code::ModifierWithoutEquals,
                    Span::new(name_span.start(), end),
                    format!(
                        "a position modifier needs `=` after the address: `{address}={written}`"
                    ),
                    fix,
                );
                value
            }
            Some(Token::LeftParen)
            | Some(Token::Letter)
            | Some(Token::Identifier)
            | Some(Token::SystemVariable)
                if self.value_without_equals_here(sign.is_some()) =>
            {
                // `Z(5+1)`, `Y-R2`, `X R1`: an expression or variable value needs `=`.
                let value_start = self.span_at(start);
                let expr = self.parse_expression();
                let expr_span = self.expr_span(expr);
                let whole_value = value_start.to(expr_span);
                let address = self.text(name_span).to_string();
                let value_text = self.text(whole_value).to_string();
                let replacement = format!("{address}={value_text}");
                let fix = Fix::replace(
                    format!("Write `{replacement}`"),
                    name_span.to(whole_value),
                    replacement.clone(),
                );
                self.report_with_fix(
                    Code::ValueNeedsEquals,
                    name_span.to(whole_value),
                    format!("a value that is not a single constant needs `=`: `{replacement}`"),
                    fix,
                );
                let expr = if sign == Some(true) {
                    self.push_expr(ExprKind::Unary(UnaryOp::Negate, expr), whole_value)
                } else {
                    expr
                };
                Value {
                    modifier: None,
                    expr: ValueExpr::Expr(expr),
                    has_equals: false,
                }
            }
            Some(Token::Letter)
                if self.letter_at(self.position) == Some(b'R')
                    && self.peek_nth(1) == Some(Token::Number)
                    && self.adjacent(self.position + 1) =>
            {
                // `X R1`: a variable value needs `=`.
                let r_span = self.advance().to(self.advance());
                let address = self.text(name_span).to_string();
                let parameter = self.text(r_span).to_string();
                let fix = Fix::replace(
                    format!("Write `{address}={parameter}`"),
                    name_span.to(r_span),
                    format!("{address}={parameter}"),
                );
                self.report_with_fix(
                    Code::ValueNeedsEquals,
                    name_span.to(r_span),
                    format!("a value that is not a constant needs `=`: `{address}={parameter}`"),
                    fix,
                );
                let number = self
                    .text(r_span)
                    .get(1..)
                    .and_then(|digits| digits.parse().ok())
                    .unwrap_or(0);
                let expr = self.push_expr(ExprKind::RParameter(number), r_span);
                Value {
                    modifier: None,
                    expr: ValueExpr::Expr(expr),
                    has_equals: false,
                }
            }
            _ => {
                if sign.is_some() {
                    self.position = start;
                }
                let text = self.text(name_span).to_string();
                self.report(
                    Code::MissingValue,
                    name_span,
                    format!(
                        "address `{text}` has no value (`{text}0` cannot be shortened to `{text}`)"
                    ),
                );
                Value {
                    modifier: None,
                    expr: ValueExpr::Missing,
                    has_equals: false,
                }
            }
        }
    }

    /// Whether the tokens at the current position are a value written without `=` (`Y-R2`, `Z(5+1)`),
    /// rather than the next word of the block. Only a signed value, a bracket right after the address,
    /// an R parameter or a plain variable name count; another address letter is the next word.
    fn value_without_equals_here(&self, signed: bool) -> bool {
        match self.peek() {
            Some(Token::LeftParen) => {
                signed || self.adjacent(self.position) || self.brackets_hold_a_value()
            }
            Some(Token::Letter) => {
                signed
                    && self.letter_at(self.position) == Some(b'R')
                    && self.peek_nth(1) == Some(Token::Number)
            }
            Some(Token::SystemVariable) => signed,
            Some(Token::Identifier) => {
                let upper = self.upper_name(self.current_span());
                let plain_name = keywords::statement_keyword(&upper).is_none()
                    && GCode::from_name(&upper).is_none()
                    && !keywords::is_modifier_name(&upper);
                // `TRANS X _CPA`, `X SIN(30)`: after an address that has no value, a user's name or
                // a function (not an instruction or address of the control) is the value with its
                // `=` left out, not a word of its own.
                plain_name
                    && (signed
                        || (keywords::named_address(&upper).is_none()
                            && (keywords::is_function(&upper)
                                || !keywords::is_instruction(&upper))
                            && !self.context.is_macro(&upper)))
            }
            _ => false,
        }
    }

    /// Whether the brackets at the current position (`Z (R1+2)`, apart from the address) hold a value
    /// rather than words: a number, an operator, an R parameter or a system variable inside. Siemens
    /// has no bracket comments, so such brackets after an address without value are its value with
    /// the `=` left out; a bracketed word alone (`X (MOVE)`) stays a misplaced comment.
    fn brackets_hold_a_value(&self) -> bool {
        // A value is short; looking further would make a long line of brackets quadratic.
        const LOOK_AHEAD: usize = 64;
        let mut depth = 0usize;
        for index in self.position..self.lexemes.len().min(self.position + LOOK_AHEAD) {
            match self.token_at(index) {
                Some(Token::LeftParen) => depth += 1,
                Some(Token::RightParen) => {
                    depth = depth.saturating_sub(1);
                    if depth == 0 {
                        return false;
                    }
                }
                Some(Token::Number)
                | Some(Token::SystemVariable)
                | Some(Token::Plus)
                | Some(Token::Minus)
                | Some(Token::Star)
                | Some(Token::Slash) => return true,
                _ => {}
            }
        }
        false
    }

    /// After `=`: a modifier such as `AC(..)` (with the checks of reference §1.8) or an expression.
    fn parse_value_after_equals(&mut self, kind: AddressKind, name_span: Span) -> Value {
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

    fn report_modifier_without_parentheses(&mut self, modifier_span: Span, name: &str) {
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
    fn parse_modifier_value(&mut self, kind: AddressKind, address_span: Span) -> Value {
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

    fn check_modifier_allowed(
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

    /// The value of an assignment to something that is not an address: a modifier there is an error.
    fn parse_assignment_value(&mut self, target_span: Span) -> Option<ExprId> {
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

    fn parse_system_variable_assignment(&mut self) {
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

    fn parse_identifier_statement(&mut self) {
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
    fn check_name_read_as_call(&mut self, upper: &str, name_span: Span, has_arguments: bool) {
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

    // ----- keyword statements -------------------------------------------------------------------

    fn parse_keyword_statement(&mut self, keyword: StatementKeyword) {
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
            StatementKeyword::Extern => {
                let name = if self.is_at(Token::Identifier) || self.is_at(Token::Letter) {
                    Some(self.advance())
                } else {
                    None
                };
                self.skip_balanced_rest();
                let span = self.span_since(keyword_span);
                self.block
                    .statements
                    .push(Statement::ExternDeclaration { name, span });
            }
            StatementKeyword::Return => {
                if self.is_at(Token::LeftParen) {
                    self.parse_argument_list();
                }
                let span = self.span_since(keyword_span);
                self.block.statements.push(Statement::Return { span });
            }
            StatementKeyword::Call | StatementKeyword::ExtCall => {
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
                if self.is_at(Token::Identifier) && self.upper_name(self.current_span()) == "BLOCK"
                {
                    while !self.at_end() {
                        self.advance();
                    }
                }
                self.push_indirect_call(name, keyword_span);
            }
            StatementKeyword::PCall => {
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
            StatementKeyword::MCall => {
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
            StatementKeyword::SyncCondition => {
                let condition = self.parse_condition(keyword_span);
                let span = self.span_since(keyword_span);
                self.block
                    .statements
                    .push(Statement::SyncCondition { condition, span });
                if self.is_at(Token::Identifier) && self.upper_name(self.current_span()) == "DO" {
                    let do_span = self.advance();
                    self.block.sync_actions_from = Some(self.block.statements.len());
                    if self.at_end() {
                        self.report(
                            Code::ExpectedExpression,
                            do_span,
                            "a synchronized action needs at least one action after DO",
                        );
                    }
                }
            }
            StatementKeyword::Do => {
                if self.block.sync_actions_from.is_none() {
                    self.block.sync_actions_from = Some(self.block.statements.len());
                }
            }
            StatementKeyword::RepeatBackward => self.parse_block_repeat(keyword_span),
        }
    }

    /// Ends a CALL, EXTCALL or PCALL statement: its optional arguments, then the statement.
    fn push_indirect_call(&mut self, name: Option<Span>, keyword_span: Span) {
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

    fn parse_structure(&mut self, keyword: StructureKeyword, keyword_span: Span) {
        match keyword {
            StructureKeyword::If => {
                let condition = self.parse_condition(keyword_span);
                if let Some(StatementKeyword::Jump(kind)) = self.jump_keyword_here() {
                    let jump_span = self.advance();
                    self.parse_jump(kind, jump_span.to(keyword_span), condition);
                    // Several `IF ... GOTO` may follow in one block.
                    return;
                }
                let span = self.span_since(keyword_span);
                self.block.statements.push(Statement::Structure {
                    keyword,
                    condition,
                    span,
                });
            }
            StructureKeyword::While | StructureKeyword::Until => {
                let condition = self.parse_condition(keyword_span);
                let span = self.span_since(keyword_span);
                self.block.statements.push(Statement::Structure {
                    keyword,
                    condition,
                    span,
                });
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
                let span = self.span_since(keyword_span);
                self.block.statements.push(Statement::Structure {
                    keyword,
                    condition,
                    span,
                });
            }
            StructureKeyword::Case => {
                let condition = self.parse_condition(keyword_span);
                let span = self.span_since(keyword_span);
                self.block.statements.push(Statement::Structure {
                    keyword,
                    condition,
                    span,
                });
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
                self.block.statements.push(Statement::Structure {
                    keyword,
                    condition: None,
                    span: keyword_span,
                });
            }
            _ => {
                self.block.statements.push(Statement::Structure {
                    keyword,
                    condition: None,
                    span: keyword_span,
                });
            }
        }
    }

    /// Whether the name at the current position is a statement keyword or G function name.
    fn is_keyword_here(&self) -> bool {
        if !self.is_at(Token::Identifier) {
            return false;
        }
        let upper = self.upper_name(self.current_span());
        keywords::statement_keyword(&upper).is_some() || GCode::from_name(&upper).is_some()
    }

    /// The counter of a FOR loop: a user variable (or one-letter parameter) assigned its start value.
    fn parse_counter_assignment(&mut self) {
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

    fn parse_condition(&mut self, keyword_span: Span) -> Option<ExprId> {
        let missing = self.at_end()
            || self.jump_keyword_here().is_some()
            || (self.is_at(Token::Identifier)
                && matches!(self.upper_name(self.current_span()).as_str(), "OF" | "DO"));
        if missing {
            let text = self.text(keyword_span).to_string();
            self.report(
                Code::ExpectedExpression,
                keyword_span,
                format!("`{text}` needs a condition"),
            );
            return None;
        }
        self.precedence_reported = false;
        self.condition_depth += 1;
        let first_token = self.position;
        let diagnostics_before = self.diagnostics.len();
        let condition = self.parse_expression();
        self.condition_depth -= 1;
        self.attach_precedence_fix(first_token, self.position, diagnostics_before);
        Some(condition)
    }

    /// Gives an S172 finding inside a condition its fix: each comparison between AND/OR operators is
    /// bracketed, which is what `IF R1==1 AND R2==2` means to anyone reading it (reference T101).
    fn attach_precedence_fix(
        &mut self,
        first_token: usize,
        end_token: usize,
        diagnostics_before: usize,
    ) {
        let Some(index) = (diagnostics_before..self.diagnostics.len())
            .find(|&index| self.diagnostics[index].code == Code::ComparisonPrecedence)
        else {
            return;
        };
        let (mut first_token, mut end_token) = (first_token, end_token);
        // A condition wholly in brackets (`IF (A>=1 OR B>=1)`): its operators are inside them.
        while end_token > first_token + 2 && self.wholly_bracketed(first_token, end_token) {
            first_token += 1;
            end_token -= 1;
        }
        if end_token <= first_token {
            return;
        }
        let mut segments: Vec<(usize, usize)> = Vec::new();
        let mut separators: Vec<Span> = Vec::new();
        let mut depth = 0i32;
        let mut segment_start = first_token;
        for token_index in first_token..end_token {
            match self.token_at(token_index) {
                Some(Token::LeftParen) | Some(Token::LeftBracket) => depth += 1,
                Some(Token::RightParen) | Some(Token::RightBracket) => depth -= 1,
                Some(Token::Identifier) if depth == 0 => {
                    let upper = self.text_at(token_index).to_ascii_uppercase();
                    if keywords::word_operator(&upper).is_some_and(BinaryOp::is_logical) {
                        segments.push((segment_start, token_index));
                        separators.push(self.span_at(token_index));
                        segment_start = token_index + 1;
                    }
                }
                _ => {}
            }
        }
        segments.push((segment_start, end_token));
        if segments.iter().any(|(start, end)| start >= end) {
            return;
        }
        let is_comparison = |token: Option<Token>| {
            matches!(
                token,
                Some(
                    Token::Equal
                        | Token::NotEqual
                        | Token::Less
                        | Token::Greater
                        | Token::LessEqual
                        | Token::GreaterEqual
                )
            )
        };
        let mut text = String::new();
        for (position, (start, end)) in segments.iter().enumerate() {
            if position > 0 {
                text.push(' ');
                text.push_str(self.text(separators[position - 1]));
                text.push(' ');
            }
            let segment = &self.line[self.span_at(*start).start()..self.span_at(end - 1).end()];
            let mut depth = 0i32;
            let has_comparison = (*start..*end).any(|token_index| {
                match self.token_at(token_index) {
                    Some(Token::LeftParen) | Some(Token::LeftBracket) => depth += 1,
                    Some(Token::RightParen) | Some(Token::RightBracket) => depth -= 1,
                    _ => {}
                }
                depth == 0 && is_comparison(self.token_at(token_index))
            });
            if has_comparison {
                text.push('(');
                text.push_str(segment);
                text.push(')');
            } else {
                text.push_str(segment);
            }
        }
        let span = self.span_at(first_token).to(self.span_at(end_token - 1));
        if text == self.text(span) {
            // No comparison stands between the operators at this level: nothing to bracket.
            return;
        }
        self.diagnostics[index].fix = Some(Fix::replace(
            format!("Bracket the comparisons: `{text}`"),
            span,
            text,
        ));
    }

    /// Whether the tokens `first..end` are one pair of round brackets and what they enclose.
    fn wholly_bracketed(&self, first: usize, end: usize) -> bool {
        if self.token_at(first) != Some(Token::LeftParen)
            || self.token_at(end - 1) != Some(Token::RightParen)
        {
            return false;
        }
        let mut depth = 0i32;
        for token_index in first..end {
            match self.token_at(token_index) {
                Some(Token::LeftParen) | Some(Token::LeftBracket) => depth += 1,
                Some(Token::RightParen) | Some(Token::RightBracket) => depth -= 1,
                _ => {}
            }
            if depth == 0 && token_index + 1 < end {
                return false;
            }
        }
        depth == 0
    }

    fn jump_keyword_here(&self) -> Option<StatementKeyword> {
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

    fn parse_jump(&mut self, kind: JumpKind, keyword_span: Span, condition: Option<ExprId>) {
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

    /// `DEF [NCK|CHAN ...] TYPE name[=init], name2[dims]` — read leniently: only the declared names and
    /// the balance of brackets are checked here. Sizes and initial values are read afterwards
    /// (`parser/declarations.rs`).
    fn parse_definition(&mut self, keyword_span: Span) {
        let mut names = Vec::new();
        let mut data_type = None;
        let mut expect_name = false;
        let mut seen_type = false;
        let mut in_initializer = false;
        let mut invalid_name_reported = false;
        let mut depth: i32 = 0;
        let mut after_type_index = false;
        while !self.at_end() {
            let token = self.peek();
            let span = self.advance();
            match token {
                Some(Token::LeftParen) | Some(Token::LeftBracket) => depth += 1,
                Some(Token::RightParen) | Some(Token::RightBracket) => {
                    depth -= 1;
                    if depth == 0 && after_type_index {
                        after_type_index = false;
                        expect_name = true;
                    }
                }
                Some(Token::Comma) if depth == 0 => {
                    expect_name = true;
                    in_initializer = false;
                }
                Some(Token::Assign) if depth == 0 => {
                    expect_name = false;
                    in_initializer = true;
                }
                Some(Token::Identifier) | Some(Token::Letter) if depth == 0 && !in_initializer => {
                    let upper = self.upper_name(span);
                    if is_definition_attribute(&upper) {
                        // Attributes such as `LLI 0 ULI 4` or `APR 7` may stand before or after the
                        // type; their value is not a name.
                        if definition_attribute_takes_value(&upper) {
                            if matches!(self.peek(), Some(Token::Minus) | Some(Token::Plus)) {
                                self.advance();
                            }
                            if !self.at_end() {
                                self.advance();
                            }
                        }
                    } else if !seen_type && is_type_name(&upper) {
                        seen_type = true;
                        data_type = DataType::from_name(&upper);
                        expect_name = true;
                        if upper == "STRING" && self.is_at(Token::LeftBracket) {
                            expect_name = false;
                            after_type_index = true;
                        }
                    } else if expect_name {
                        expect_name = false;
                        self.check_definition_name(token, span);
                        names.push(span);
                    } else if seen_type {
                        let text = self.text(span).to_string();
                        self.report(
                            Code::UnexpectedToken,
                            span,
                            format!("`{text}` follows a name without a comma: separate the names of one DEF with `,`"),
                        );
                    }
                }
                Some(Token::SystemVariable) | Some(Token::Number) if expect_name && depth == 0 => {
                    expect_name = false;
                    invalid_name_reported = true;
                    // `1COUNT` lexes as a number and a name: report them as one name.
                    let mut span = span;
                    if token == Some(Token::Number)
                        && self.is_at(Token::Identifier)
                        && self.adjacent(self.position)
                    {
                        span = span.to(self.advance());
                    }
                    let text = self.text(span).to_string();
                    let message = if token == Some(Token::SystemVariable) {
                        format!("`{text}` is a system variable; DEF defines user variables only")
                    } else {
                        format!("`{text}` cannot be a variable name: names start with two letters")
                    };
                    self.report(Code::InvalidLabel, span, message);
                }
                Some(Token::UnterminatedString) => self.report_unterminated_string(span),
                _ => {}
            }
        }
        if depth > 0 {
            self.report(
                Code::UnbalancedBrackets,
                keyword_span,
                "this definition has an unclosed bracket or parenthesis",
            );
        }
        if names.is_empty() && !invalid_name_reported {
            let message = if seen_type {
                "DEF needs the name of the variable after its type"
            } else {
                "DEF needs a type (INT, REAL, BOOL, CHAR, STRING[n], AXIS, FRAME) and a name"
            };
            self.report(Code::ExpectedExpression, keyword_span, message);
        }
        let declarators = self.parse_declarators(&names);
        let span = self.span_since(keyword_span);
        self.block.statements.push(Statement::Definition {
            names,
            data_type,
            declarators,
            span,
        });
    }

    /// A defined name must not be an address letter (`DEF REAL A`) and should start with two letters.
    fn check_definition_name(&mut self, token: Option<Token>, span: Span) {
        if token == Some(Token::Letter) {
            let text = self.text(span).to_string();
            if self.is_at(Token::Number) && self.adjacent(self.position) {
                // `V1AR` lexes as a letter, a number and a name: it is one name.
                let mut whole = span.to(self.advance());
                if self.is_at(Token::Identifier) && self.adjacent(self.position) {
                    whole = whole.to(self.advance());
                }
                let name = self.text(whole).to_string();
                self.report(
                    Code::LabelStyle,
                    whole,
                    format!(
                        "`{name}` starts with a single letter; names should start with two letters"
                    ),
                );
            } else {
                self.report(
                    Code::InvalidLabel,
                    span,
                    format!("`{text}` is an address letter and cannot be a variable name; names start with two letters"),
                );
            }
        } else {
            self.check_name_style(span, "variable");
        }
    }

    fn parse_macro_definition(&mut self, keyword_span: Span) {
        let name = if self.is_at(Token::Identifier) || self.is_at(Token::Letter) {
            Some(self.advance())
        } else {
            self.report(
                Code::ExpectedExpression,
                keyword_span,
                "DEFINE needs a name: `DEFINE NAME AS ...`",
            );
            None
        };
        if self.is_at(Token::Identifier) && self.upper_name(self.current_span()) == "AS" {
            self.advance();
        } else if name.is_some() {
            self.report(
                Code::UnexpectedToken,
                self.current_span(),
                "DEFINE needs `AS` after the name: `DEFINE NAME AS ...`",
            );
        }
        let body_start = self.current_span().start();
        while !self.at_end() {
            let token = self.peek();
            let span = self.advance();
            if token == Some(Token::UnterminatedString) {
                self.report_unterminated_string(span);
            }
        }
        let body = Span::new(body_start.min(self.previous_end()), self.previous_end());
        let span = self.span_since(keyword_span);
        self.block
            .statements
            .push(Statement::MacroDefinition { name, body, span });
    }

    fn parse_procedure_header(&mut self, keyword_span: Span) {
        let name = if self.is_at(Token::Identifier) || self.is_at(Token::Letter) {
            Some(self.advance())
        } else {
            self.report(
                Code::ExpectedExpression,
                keyword_span,
                "PROC needs the name of the subprogram",
            );
            None
        };
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
    fn skip_balanced_rest(&mut self) {
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

    // ----- expressions --------------------------------------------------------------------------

    /// Parses an expression; always returns a node (an `Error` node after reporting a problem).
    fn parse_expression(&mut self) -> ExprId {
        self.parse_binary(0)
    }

    fn binary_operator_here(&self) -> Option<(BinaryOp, u8)> {
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

    fn parse_binary(&mut self, minimum_power: u8) -> ExprId {
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
    fn condition_comparison_here(&self) -> Option<(BinaryOp, usize)> {
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
    fn skip_unknown_infix_name(&mut self, left: &mut ExprId) -> bool {
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
    fn check_comparison_operands(&mut self, left: ExprId, _right: ExprId, span: Span) {
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

    fn parse_unary(&mut self) -> ExprId {
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
    fn skip_too_deep(&mut self) -> ExprId {
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

    fn parse_unary_inner(&mut self) -> ExprId {
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

    fn parse_primary(&mut self) -> ExprId {
        let span = self.current_span();
        if self.at_end() {
            let at = Span::new(self.previous_end(), self.previous_end());
            self.report(Code::ExpectedExpression, at, "a value is missing here");
            return self.push_expr(ExprKind::Error, at);
        }
        match self.peek() {
            Some(Token::Number) => {
                self.advance();
                match self.number_value(span) {
                    Some(value) => self.push_expr(ExprKind::Number(value), span),
                    None => self.push_expr(ExprKind::Error, span),
                }
            }
            Some(token @ (Token::HexNumber | Token::BinaryNumber)) => {
                self.advance();
                let text = self.text(span);
                let radix = if token == Token::HexNumber { 16 } else { 2 };
                // A literal wider than 64 bits was NaN before; it is reported and unknown instead.
                match u64::from_str_radix(&text[2..text.len() - 1], radix) {
                    Ok(value) => self.push_expr(ExprKind::Number(value as f64), span),
                    Err(_) => {
                        self.report_number_out_of_range(span);
                        self.push_expr(ExprKind::Error, span)
                    }
                }
            }
            Some(Token::BadNumber) | Some(Token::BadQuoted) => {
                self.advance();
                self.report_bad_number(span);
                self.push_expr(ExprKind::Error, span)
            }
            Some(Token::String) => {
                self.advance();
                self.push_expr(ExprKind::String, span)
            }
            Some(Token::UnterminatedString) => {
                self.advance();
                self.report_unterminated_string(span);
                self.push_expr(ExprKind::String, span)
            }
            Some(Token::Letter) => self.parse_letter_operand(),
            Some(Token::Identifier) => self.parse_name_operand(),
            Some(Token::SystemVariable) => {
                self.advance();
                if let Some(number) = r_parameter_in_system_variable(self.text(span)) {
                    return self.push_expr(ExprKind::RParameter(number), span);
                }
                let mut indexes = Vec::new();
                let mut whole = span;
                if self.is_at(Token::LeftBracket) {
                    let (list, index_span) = self.parse_index_list();
                    indexes = list;
                    whole = span.to(index_span);
                }
                self.push_expr(ExprKind::SystemVariable { indexes }, whole)
            }
            Some(Token::LeftParen) => {
                let open = self.advance();
                self.group_depth += 1;
                let inner = self.parse_expression();
                self.group_depth -= 1;
                if self.is_at(Token::Comma) {
                    let mut items = vec![inner];
                    while self.is_at(Token::Comma) {
                        self.advance();
                        items.push(self.parse_expression());
                    }
                    let close = self.expect_close(Token::RightParen, open);
                    return self.push_expr(ExprKind::List(items), open.to(close));
                }
                let close = self.expect_close(Token::RightParen, open);
                self.push_expr(ExprKind::Parenthesized(inner), open.to(close))
            }
            _ => {
                let at = Span::new(span.start(), span.start());
                let text = self.text(span).to_string();
                self.report(
                    Code::ExpectedExpression,
                    span,
                    format!("a value was expected, found `{text}`"),
                );
                self.push_expr(ExprKind::Error, at)
            }
        }
    }

    /// A letter inside an expression: `R1`, `R[i]`, an axis name (`X`, `X1`) or a one-letter parameter.
    fn parse_letter_operand(&mut self) -> ExprId {
        let span = self.advance();
        let letter = self.text(span).as_bytes()[0].to_ascii_uppercase();
        if letter == b'R' {
            if self.adjacent(self.position) && self.is_at(Token::Number) {
                if let Some(number) = self.integer_at(self.position) {
                    let number_span = self.advance();
                    return self.push_expr(
                        ExprKind::RParameter(number.min(u64::from(u32::MAX)) as u32),
                        span.to(number_span),
                    );
                }
            }
            if self.is_at(Token::LeftBracket) {
                let (indexes, index_span) = self.parse_index_list();
                let index = indexes
                    .first()
                    .copied()
                    .unwrap_or_else(|| self.push_expr(ExprKind::Error, index_span));
                return self.push_expr(ExprKind::RParameterIndexed(index), span.to(index_span));
            }
        }
        let mut whole = span;
        if self.adjacent(self.position)
            && self.is_at(Token::Number)
            && self.integer_at(self.position).is_some()
        {
            whole = span.to(self.advance());
        }
        let mut indexes = Vec::new();
        if self.is_at(Token::LeftBracket) {
            let (list, index_span) = self.parse_index_list();
            indexes = list;
            whole = whole.to(index_span);
        }
        self.push_expr(ExprKind::Name { indexes }, whole)
    }

    fn parse_name_operand(&mut self) -> ExprId {
        let span = self.current_span();
        let upper = self.upper_name(span);
        if keywords::word_operator(&upper).is_some() {
            let at = Span::new(span.start(), span.start());
            self.report(
                Code::ExpectedExpression,
                span,
                format!("a value was expected before `{upper}`"),
            );
            return self.push_expr(ExprKind::Error, at);
        }
        if self.peek_nth(1) == Some(Token::LeftParen) {
            if keywords::is_modifier_name(&upper) {
                let message = if self.modifier_depth > 0 {
                    format!("position modifiers cannot be nested: `{upper}(..)` inside another modifier")
                } else {
                    format!(
                        "{upper}(..) only stands directly after `=` of an axis or other address"
                    )
                };
                let code = if self.modifier_depth > 0 {
                    Code::ModifierNested
                } else {
                    Code::ModifierOutsideAddress
                };
                let expr = self.parse_call_expression_without_function_check();
                let whole = self.expr_span(expr);
                self.report(code, whole, message);
                return expr;
            }
            if !keywords::is_function(&upper) {
                self.report(
                    Code::UnknownFunction,
                    span,
                    format!("`{upper}` is not a predefined function; a value in an expression cannot come from a subprogram"),
                );
            }
            return self.parse_call_expression_without_function_check();
        }
        self.advance();
        let mut indexes = Vec::new();
        let mut whole = span;
        if self.is_at(Token::LeftBracket) {
            let (list, index_span) = self.parse_index_list();
            indexes = list;
            whole = span.to(index_span);
        }
        self.push_expr(ExprKind::Name { indexes }, whole)
    }

    /// `NAME(args)` at the current position as an expression node.
    fn parse_call_expression_without_function_check(&mut self) -> ExprId {
        let name = self.advance();
        let (args, args_span) = self.parse_argument_list();
        self.push_expr(ExprKind::Call { name, args }, name.to(args_span))
    }

    /// `(a, , b)` at the current position; empty arguments are `None`.
    fn parse_argument_list(&mut self) -> (Vec<Option<ExprId>>, Span) {
        self.group_depth += 1;
        let result = self.parse_argument_list_inner();
        self.group_depth -= 1;
        result
    }

    fn parse_argument_list_inner(&mut self) -> (Vec<Option<ExprId>>, Span) {
        let open = self.advance();
        let mut args = Vec::new();
        if self.is_at(Token::RightParen) {
            let close = self.advance();
            return (args, open.to(close));
        }
        loop {
            if self.is_at(Token::Comma) {
                args.push(None);
                self.advance();
                if self.is_at(Token::RightParen) {
                    args.push(None);
                }
                continue;
            }
            if self.is_at(Token::RightParen) || self.at_end() {
                break;
            }
            let expr = self.parse_expression();
            args.push(Some(expr));
            if self.is_at(Token::Comma) {
                self.advance();
                if self.is_at(Token::RightParen) {
                    args.push(None);
                }
            } else {
                break;
            }
        }
        let close = self.expect_close(Token::RightParen, open);
        (args, open.to(close))
    }

    /// `[a, b]` at the current position.
    fn parse_index_list(&mut self) -> (Vec<ExprId>, Span) {
        let open = self.advance();
        self.group_depth += 1;
        let mut indexes = Vec::new();
        while !self.at_end() && !self.is_at(Token::RightBracket) {
            indexes.push(self.parse_expression());
            if self.is_at(Token::Comma) {
                self.advance();
            } else {
                break;
            }
        }
        self.group_depth -= 1;
        let close = self.expect_close(Token::RightBracket, open);
        (indexes, open.to(close))
    }

    /// Consumes the expected closing bracket, or reports the unclosed opening one (once per line).
    fn expect_close(&mut self, token: Token, open: Span) -> Span {
        if self.is_at(token) {
            return self.advance();
        }
        // An unterminated string swallows the rest of the line, bracket included: S132 says it all.
        let after_unterminated_string = self.position > 0
            && self.token_at(self.position - 1) == Some(Token::UnterminatedString);
        if !self.unclosed_reported && !after_unterminated_string {
            self.unclosed_reported = true;
            let (code, closing) = if token == Token::RightParen {
                (Code::UnbalancedParentheses, ")")
            } else {
                (Code::UnbalancedBrackets, "]")
            };
            let end = self.previous_end();
            let found = if self.at_end() {
                "the end of the block".to_string()
            } else {
                format!("`{}`", self.text(self.current_span()))
            };
            let message = format!("this `{}` is not closed before {found}", self.text(open));
            // Inserting the bracket helps only when the block has fewer closing brackets than
            // opening ones; else something else stopped the reading (`SIN(30$0)`), and a bracket
            // inserted here would leave one too many.
            let opening = if token == Token::RightParen {
                Token::LeftParen
            } else {
                Token::LeftBracket
            };
            let count = |wanted: Token| {
                (0..self.lexemes.len())
                    .filter(|&index| self.token_at(index) == Some(wanted))
                    .count()
            };
            if count(opening) > count(token) {
                let fix = Fix::replace(format!("Insert `{closing}`"), Span::new(end, end), closing);
                self.report_with_fix(code, open, message, fix);
            } else {
                self.report(code, open, message);
            }
        }
        Span::new(self.previous_end(), self.previous_end())
    }

    // ----- checks over the whole block ----------------------------------------------------------

    fn check_block(&mut self) {
        let statements = std::mem::take(&mut self.block.statements);
        let interpreted_count = self.block.sync_actions_from.unwrap_or(statements.len());
        // The findings quote the statements as they were before the parser kept repetitions and CASE
        // branches (see `parser/repeats.rs`); a block with neither is checked as it is, without a copy.
        if self.repeats.is_empty() && !self.has_case_branches {
            let interpreted = &statements[..interpreted_count.min(statements.len())];
            self.check_statements(interpreted);
        } else {
            let (checked, checked_interpreted) =
                self.statements_as_checked(&statements, interpreted_count);
            self.check_statements(&checked[..checked_interpreted]);
        }
        self.block.statements = statements;
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
            if crate::syntax::gcodes::is_syntax_defining_group(group) {
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

/// Attributes of `DEF` in definition files (reference §8.1): storage, synchronisation, access levels,
/// limits, units and initialisation.
fn is_definition_attribute(upper: &str) -> bool {
    matches!(
        upper,
        "NCK"
            | "CHAN"
            | "SYNR"
            | "SYNW"
            | "SYNRW"
            | "APR"
            | "APW"
            | "APRP"
            | "APWP"
            | "APRB"
            | "APWB"
            | "PHY"
            | "LLI"
            | "ULI"
            | "INIPO"
            | "INIRE"
            | "INICF"
            | "PRLOC"
    )
}

fn definition_attribute_takes_value(upper: &str) -> bool {
    matches!(
        upper,
        "APR" | "APW" | "APRP" | "APWP" | "APRB" | "APWB" | "PHY" | "LLI" | "ULI"
    )
}

/// Access levels for reading and writing the definitions that follow (`APR 15 APW 12`).
fn is_access_level_keyword(upper: &str) -> bool {
    matches!(upper, "APR" | "APW" | "APRP" | "APWP" | "APRB" | "APWB")
}

fn is_type_name(upper: &str) -> bool {
    matches!(
        upper,
        "INT" | "REAL" | "BOOL" | "CHAR" | "STRING" | "AXIS" | "FRAME"
    )
}

/// Parses a number token's text (`10`, `.5`, `1.5EX-3`). `None` when the text is not a number or its
/// value is not finite (beyond about 1.8e308), so that no caller can turn it into an infinite position.
pub fn parse_number(text: &str) -> Option<f64> {
    if let Some(value) = parse_simple_decimal(text.as_bytes()) {
        return Some(value);
    }
    // The exponent is written `EX` (`1.5EX-3`); the standard parser reads it as `1.5e-3`, correctly
    // rounded, and gives 0 for `0EX400` where multiplying by 10^400 gave NaN.
    let value: f64 = match text.bytes().position(|byte| byte == b'E' || byte == b'e') {
        None => text.parse().ok()?,
        Some(position) => {
            let exponent = text.get(position + 2..)?;
            format!("{}e{exponent}", &text[..position]).parse().ok()?
        }
    };
    value.is_finite().then_some(value)
}

/// Exact fast path for the numbers CAM programs are made of (`123.456`): when the digits form an
/// integer below 2^53 and at most 22 decimals follow, one IEEE division gives the correctly rounded
/// value, the same as the standard parser.
fn parse_simple_decimal(bytes: &[u8]) -> Option<f64> {
    if bytes.is_empty() || bytes.len() > MAX_SIMPLE_DECIMAL_LENGTH {
        return None;
    }
    let mut mantissa: u64 = 0;
    let mut decimals: Option<usize> = None;
    for &byte in bytes {
        match byte {
            b'0'..=b'9' => {
                mantissa = mantissa * 10 + u64::from(byte - b'0');
                if let Some(count) = decimals.as_mut() {
                    *count += 1;
                }
            }
            b'.' if decimals.is_none() => decimals = Some(0),
            _ => return None,
        }
    }
    decimal_from_parts(mantissa, decimals.unwrap_or(0))
}

/// Longest number text (digits and point) the exact fast path takes: 17 digits cannot overflow `u64`.
const MAX_SIMPLE_DECIMAL_LENGTH: usize = 17;

/// `mantissa / 10^decimals`, exact when the mantissa is below 2^53 (both operands are exact doubles and
/// IEEE division rounds correctly); `None` otherwise.
fn decimal_from_parts(mantissa: u64, decimals: usize) -> Option<f64> {
    const POWERS_OF_TEN: [f64; 23] = [
        1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
        1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
    ];
    if mantissa >= 1 << 53 {
        return None;
    }
    Some(mantissa as f64 / *POWERS_OF_TEN.get(decimals)?)
}

/// `$R1` is the spelling of R1 inside synchronized actions.
fn r_parameter_in_system_variable(text: &str) -> Option<u32> {
    let rest = text.strip_prefix('$')?;
    let digits = rest.strip_prefix('R').or_else(|| rest.strip_prefix('r'))?;
    if digits.is_empty() || !digits.bytes().all(|byte| byte.is_ascii_digit()) {
        return None;
    }
    digits.parse().ok()
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

/// `CR5` → 2: a multi-letter address run together with a number; returns where the digits start.
fn split_named_address_and_digits(upper: &str) -> Option<usize> {
    let split = upper.find(|character: char| character.is_ascii_digit())?;
    let (name, digits) = upper.split_at(split);
    if !digits.bytes().all(|byte| byte.is_ascii_digit()) {
        return None;
    }
    matches!(name, "CR" | "AP" | "RP" | "AR" | "TURN" | "RPL").then_some(split)
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_conditional_jump_keeps_its_condition() {
        let line = "IF R1<3 GOTOB LOOP1";
        let (block, diagnostics) = parse_line(line, &SyntaxContext::default());
        assert!(diagnostics.is_empty(), "{diagnostics:?}");
        let [Statement::Jump {
            kind: JumpKind::Gotob,
            condition: Some(condition),
            ..
        }] = block.statements.as_slice()
        else {
            panic!("expected one conditional jump, got {:?}", block.statements);
        };
        let span = block.expr(*condition).span;
        assert_eq!(&line[span.start()..span.end()], "R1<3");
        let (block, _) = parse_line("GOTOF END", &SyntaxContext::default());
        assert!(matches!(
            block.statements.as_slice(),
            [Statement::Jump {
                condition: None,
                ..
            }]
        ));
    }
}
