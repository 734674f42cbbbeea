//! The state of the parser while it reads one line, and its cursor over the line's tokens.
//!
//! [`Parser`] is shared by every grammar area of the parser: each adds its own `impl Parser` block in
//! its own file and reads the line through the accessors here. They are called for nearly every token
//! from those other files, so the small ones are `#[inline]`.

use crate::diagnostics::{Diagnostic, Span};
use crate::syntax::ast::Block;
use crate::syntax::context::SyntaxContext;
use crate::syntax::lexer::{Lexeme, Token};
use crate::syntax::parser::checked_view::RepeatWords;

/// One line being parsed: its tokens and the position in them, the block and findings being filled,
/// and the flags that keep a finding from being reported twice.
pub(super) struct Parser<'a> {
    pub(super) line: &'a str,
    pub(super) lexemes: &'a [Lexeme],
    pub(super) position: usize,
    pub(super) block: &'a mut Block,
    pub(super) diagnostics: &'a mut Vec<Diagnostic>,
    pub(super) context: &'a SyntaxContext,
    pub(super) depth: u32,
    pub(super) depth_reported: bool,
    pub(super) unclosed_reported: bool,
    /// Greater than zero while parsing the value inside `AC(..)` and friends.
    pub(super) modifier_depth: u32,
    pub(super) precedence_reported: bool,
    /// Greater than zero while parsing the condition of IF, WHILE, UNTIL or a synchronized action.
    pub(super) condition_depth: u32,
    /// Greater than zero inside parentheses or brackets of an expression.
    pub(super) group_depth: u32,
    /// The REPEAT and REPEATB statements of the block, as the block checks read them.
    pub(super) repeats: Vec<RepeatWords>,
    /// Whether a CASE branch was pushed: the block checks then leave such statements out.
    pub(super) has_case_branches: bool,
    /// The height of every node in `block.exprs` (a leaf is 1), kept beside the arena.
    pub(super) heights: &'a mut Vec<u32>,
}

impl<'a> Parser<'a> {
    pub(super) fn new(
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

    #[inline]
    pub(super) fn token_at(&self, index: usize) -> Option<Token> {
        self.lexemes.get(index).and_then(|lexeme| lexeme.token)
    }

    #[inline]
    pub(super) fn peek(&self) -> Option<Token> {
        self.token_at(self.position)
    }

    #[inline]
    pub(super) fn peek_nth(&self, offset: usize) -> Option<Token> {
        self.token_at(self.position + offset)
    }

    #[inline]
    pub(super) fn span_at(&self, index: usize) -> Span {
        match self.lexemes.get(index) {
            Some(lexeme) => lexeme.span,
            None => Span::new(self.line.len(), self.line.len()),
        }
    }

    #[inline]
    pub(super) fn current_span(&self) -> Span {
        self.span_at(self.position)
    }

    #[inline]
    pub(super) fn previous_end(&self) -> usize {
        if self.position == 0 {
            0
        } else {
            self.span_at(self.position - 1).end()
        }
    }

    #[inline]
    pub(super) fn text(&self, span: Span) -> &'a str {
        &self.line[span.start()..span.end()]
    }

    #[inline]
    pub(super) fn text_at(&self, index: usize) -> &'a str {
        self.text(self.span_at(index))
    }

    /// True at the end of the line or at its comment.
    #[inline]
    pub(super) fn at_end(&self) -> bool {
        matches!(self.peek(), None | Some(Token::Comment)) && self.position >= self.lexemes.len()
            || self.peek() == Some(Token::Comment)
    }

    #[inline]
    pub(super) fn is_at(&self, token: Token) -> bool {
        self.position < self.lexemes.len() && self.peek() == Some(token)
    }

    /// Whether the token at `index` starts right where the previous one ends (no blank between).
    #[inline]
    pub(super) fn adjacent(&self, index: usize) -> bool {
        index > 0
            && index < self.lexemes.len()
            && self.span_at(index - 1).end() == self.span_at(index).start()
    }

    /// From the start of `start` to the end of the last consumed token.
    #[inline]
    pub(super) fn span_since(&self, start: Span) -> Span {
        start.to(Span::new(self.previous_end(), self.previous_end()))
    }

    #[inline]
    pub(super) fn advance(&mut self) -> Span {
        let span = self.current_span();
        if self.position < self.lexemes.len() {
            self.position += 1;
        }
        span
    }

    #[inline]
    pub(super) fn letter_at(&self, index: usize) -> Option<u8> {
        if self.token_at(index) == Some(Token::Letter) {
            Some(self.text_at(index).as_bytes()[0].to_ascii_uppercase())
        } else {
            None
        }
    }

    #[inline]
    pub(super) fn upper_name(&self, span: Span) -> String {
        self.text(span).to_ascii_uppercase()
    }

    /// Parses an unsigned integer token's text; `None` for decimals, exponents or overflow.
    pub(super) fn integer_at(&self, index: usize) -> Option<u64> {
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
}
