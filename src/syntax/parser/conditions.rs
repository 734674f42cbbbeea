//! Conditions: of IF, WHILE, UNTIL and CASE, and of synchronized actions (`WHEN ... DO`). Inside a
//! condition `=` reads as `==` (see `expressions.rs`); a finding about comparisons chained onto AND/OR
//! gets the fix that brackets each comparison.

use crate::diagnostics::{Code, Fix, Span};
use crate::syntax::ast::{BinaryOp, ExprId, Statement};
use crate::syntax::keywords;
use crate::syntax::lexer::Token;
use crate::syntax::parser::cursor::Parser;

impl Parser<'_> {
    pub(super) fn parse_condition(&mut self, keyword_span: Span) -> Option<ExprId> {
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
    pub(super) fn attach_precedence_fix(
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

    /// `WHEN`/`WHENEVER`/`FROM`/`EVERY` with its condition; the statements after `DO` are the actions.
    pub(super) fn parse_sync_condition(&mut self, keyword_span: Span) {
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
}
