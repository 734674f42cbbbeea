//! Section repetition: `REPEAT LABEL1 [LABEL2|ENDLABEL] [P=n]` and `REPEATB LABEL [P=n]` (reference
//! §8.4, §17.7), with their labels and repetition count.
//!
//! Each repetition also leaves a record of what the block checks read of it (see `checked_view.rs`).

use crate::diagnostics::Span;
use crate::syntax::ast::{ExprId, ExprKind, Statement, ValueExpr};
use crate::syntax::lexer::Token;
use crate::syntax::parser::checked_view::RepeatWords;
use crate::syntax::parser::cursor::Parser;

impl Parser<'_> {
    /// `REPEAT` followed by a name: the labels, then the count. Every name that follows is read as a
    /// label, as the control's syntax has it; a third one has no meaning and is read over.
    pub(super) fn parse_section_repeat(&mut self, keyword_span: Span) {
        let start = self.advance();
        let end = self.is_at(Token::Identifier).then(|| self.advance());
        while self.is_at(Token::Identifier) {
            self.advance();
        }
        let end_is_endlabel =
            end.is_some_and(|end| self.text(end).eq_ignore_ascii_case("ENDLABEL"));
        let index = self.block.statements.len();
        let keyword_and_labels = self.span_since(keyword_span);
        self.block.statements.push(Statement::SectionRepeat {
            start,
            end,
            end_is_endlabel,
            count: None,
            span: keyword_and_labels,
        });
        let (count, span) = self.parse_repeat_count(index, keyword_span, keyword_and_labels);
        if let Some(Statement::SectionRepeat {
            count: count_slot,
            span: span_slot,
            ..
        }) = self.block.statements.get_mut(index)
        {
            *count_slot = count;
            *span_slot = span;
        }
    }

    /// `REPEATB`, its label (only one: a second name is a statement of its own) and the count.
    pub(super) fn parse_block_repeat(&mut self, keyword_span: Span) {
        let label = self.is_at(Token::Identifier).then(|| self.advance());
        let index = self.block.statements.len();
        let keyword_and_label = self.span_since(keyword_span);
        self.block.statements.push(Statement::BlockRepeat {
            label,
            count: None,
            span: keyword_and_label,
        });
        let (count, span) = self.parse_repeat_count(index, keyword_span, keyword_and_label);
        if let Some(Statement::BlockRepeat {
            count: count_slot,
            span: span_slot,
            ..
        }) = self.block.statements.get_mut(index)
        {
            *count_slot = count;
            *span_slot = span;
        }
    }

    /// Reads the `P` word after the labels of the statement at `index` (already pushed), records what
    /// the block checks read of the statement, and returns the count with the statement's whole span.
    /// The word is read as any address word is, with the same findings (`P=` without a value, a
    /// modifier that `P` does not take); a word with an extension (`P1=2`) or a modifier is not a
    /// count and stays an address word of its own after the statement.
    fn parse_repeat_count(
        &mut self,
        index: usize,
        keyword: Span,
        keyword_and_labels: Span,
    ) -> (Option<ExprId>, Span) {
        let mut count_word = None;
        if self.letter_at(self.position) == Some(b'P') {
            let statements_before = self.block.statements.len();
            self.parse_letter_word();
            let is_count = self.block.statements.len() == statements_before + 1
                && matches!(
                    self.block.statements.last(),
                    Some(Statement::Address(word))
                        if word.extension.is_none() && word.value.modifier.is_none()
                );
            if is_count {
                if let Some(Statement::Address(word)) = self.block.statements.pop() {
                    count_word = Some(word);
                }
            }
        }
        let count = count_word.as_ref().and_then(|word| match word.value.expr {
            ValueExpr::Missing => None,
            ValueExpr::Constant { value, span } => {
                Some(self.push_expr(ExprKind::Number(value), span))
            }
            ValueExpr::Expr(id) => Some(id),
        });
        let span = match &count_word {
            Some(word) => keyword_and_labels.to(word.span),
            None => keyword_and_labels,
        };
        self.repeats.push(RepeatWords {
            index,
            keyword,
            keyword_and_labels,
            count_word,
        });
        (count, span)
    }
}
