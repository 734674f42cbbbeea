//! The statements of a block as the block checks read them.
//!
//! The block checks (G groups, instructions that stand alone, addresses written twice) were written
//! when a REPEAT or REPEATB statement was an instruction made of the keyword and its labels, followed
//! by the count as an address word `P`, and when the value of each CASE branch was not a statement.
//! Their findings quote those statements, so the checks still read a block that way: the parser
//! records [`RepeatWords`] for each repetition (`repeats.rs`), and [`statements_as_checked`] gives the
//! checks the statements as they were.

use crate::diagnostics::Span;
use crate::syntax::ast::{AddressWord, Statement};

/// What the block checks read of one REPEAT or REPEATB statement.
pub(super) struct RepeatWords {
    /// The index of the statement in the block.
    pub(super) index: usize,
    pub(super) keyword: Span,
    /// From the keyword to its last label.
    pub(super) keyword_and_labels: Span,
    /// The `P` word taken as the count.
    pub(super) count_word: Option<AddressWord>,
}

/// The statements of the block as the block checks read them (see the module documentation),
/// and how many of them the interpreter runs (those before a synchronized action's actions).
pub(super) fn statements_as_checked(
    statements: &[Statement],
    repeats: &[RepeatWords],
    interpreted_count: usize,
) -> (Vec<Statement>, usize) {
    let mut checked = Vec::with_capacity(statements.len() + repeats.len());
    let mut checked_interpreted = None;
    let mut repeats = repeats.iter().peekable();
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
