//! The entry points of evaluation: an expression of a block as a value or a number, `None` when
//! unknown.

use super::evaluator::Evaluator;
use super::options::{EvalError, EvalOptions};
use super::value::Value;
use super::variables::Variables;
use crate::syntax::ast::{Block, ExprId};

/// Evaluates `id` of `block` (whose text is `line`). `Ok(None)` means unknown.
pub fn evaluate_value(
    block: &Block,
    line: &str,
    id: ExprId,
    variables: &Variables,
    options: &EvalOptions,
) -> Result<Option<Value>, EvalError> {
    Evaluator {
        block,
        line,
        variables,
        options,
        steps: 0,
    }
    .value(id)
}

/// Evaluates `id` as a number with the default options; a text is unknown here. `Ok(None)` means
/// unknown.
pub fn evaluate(
    block: &Block,
    line: &str,
    id: ExprId,
    variables: &Variables,
) -> Result<Option<f64>, EvalError> {
    Ok(
        evaluate_value(block, line, id, variables, &EvalOptions::default())?
            .and_then(|value| value.number()),
    )
}
