//! Section repetition: `REPEAT LABEL1 [LABEL2|ENDLABEL] [P=n]` and `REPEATB LABEL [P=n]` (reference
//! §8.4, §17.7), with their labels and repetition count.
//!
//! The block checks (G groups, instructions that stand alone, addresses written twice) were written
//! when such a statement was an instruction made of the keyword and its labels, followed by the
//! count as an address word `P`, and when the value of each CASE branch was not a statement. Their
//! findings quote those statements, so the checks still read a block that way:
//! [`Parser::statements_as_checked`] gives them the statements as they were.

use super::*;

/// What the block checks read of one REPEAT or REPEATB statement.
pub(super) struct RepeatWords {
    /// The index of the statement in the block.
    index: usize,
    keyword: Span,
    /// From the keyword to its last label.
    keyword_and_labels: Span,
    /// The `P` word taken as the count.
    count_word: Option<AddressWord>,
}

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

    /// The statements of the block as the block checks read them (see the module documentation),
    /// and how many of them the interpreter runs (those before a synchronized action's actions).
    pub(super) fn statements_as_checked(
        &self,
        statements: &[Statement],
        interpreted_count: usize,
    ) -> (Vec<Statement>, usize) {
        let mut checked = Vec::with_capacity(statements.len() + self.repeats.len());
        let mut checked_interpreted = None;
        let mut repeats = self.repeats.iter().peekable();
        for (index, statement) in statements.iter().enumerate() {
            if index == interpreted_count {
                checked_interpreted = Some(checked.len());
            }
            match statement {
                Statement::CaseBranch { .. } => {}
                Statement::SectionRepeat { .. } | Statement::BlockRepeat { .. } => {
                    while repeats.next_if(|words| words.index < index).is_some() {}
                    match repeats.next_if(|words| words.index == index) {
                        Some(words) => {
                            checked.push(Statement::Instruction {
                                name: words.keyword,
                                args: Vec::new(),
                                span: words.keyword_and_labels,
                            });
                            if let Some(word) = &words.count_word {
                                checked.push(Statement::Address(word.clone()));
                            }
                        }
                        None => checked.push(statement.clone()),
                    }
                }
                _ => checked.push(statement.clone()),
            }
        }
        let checked_interpreted = checked_interpreted.unwrap_or(checked.len());
        (checked, checked_interpreted)
    }
}
