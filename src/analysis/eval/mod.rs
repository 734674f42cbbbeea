//! Static evaluation of NC expressions: numbers, texts, R parameters and user variables whose values
//! are known, the operators of reference §8.2 with the control's comparison tolerance (§18.1), indexed
//! reads and the predefined functions. Anything the program does not determine (a system variable, an
//! unassigned variable, a function not computed here) is `None`: unknown, never a guessed value.
//!
//! - `value`: the values and the rules for comparing and converting them;
//! - `variables`: R parameters and typed user variables, program levels, joins;
//! - `array`: the elements of array variables;
//! - `evaluator`: the walk over an expression tree;
//! - `functions`: the predefined functions.

mod array;
mod evaluator;
mod functions;
mod value;
mod var_type;
mod variables;

#[cfg(test)]
mod tests;

pub use array::{element_indexes, IndexError, MAX_DIMENSIONS, MAX_FOLLOWED_ELEMENTS};
pub use functions::{function_arguments, is_evaluated_function};
pub use value::{real_equal, real_less, real_less_equal, Value, INT_RANGE};
pub use var_type::VarType;
pub use variables::{AssignError, DefineError, Locals, Variables};

use crate::diagnostics::Span;
use crate::syntax::ast::{Block, ExprId};

/// How the control evaluates, where machine data decide it.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct EvalOptions {
    /// MD10280 `PROG_FUNCTION_MASK` bit 0 = 1: `<` and `>` compare REAL values exactly; `==`, `<>`,
    /// `<=` and `>=` keep the relative tolerance (reference §18.1).
    pub exact_less_greater: bool,
}

/// Why an expression could not be evaluated when that is an error of the program, not a lack of
/// knowledge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EvalError {
    /// Division by zero (`/`, `DIV`, `MOD`; alarm 14051).
    DivisionByZero(Span),
    /// A result beyond the range of a double (alarm 14051).
    Overflow(Span),
    /// A function's argument outside its domain, described by the text: SQRT(-1), ACOS(2), LN(0)
    /// (alarm 14051).
    Domain(Span, &'static str),
    /// A function called with a wrong number of arguments; it takes the number given (the least when
    /// too few were written, the most when too many).
    ArgumentCount(Span, usize),
    /// A known index outside the dimensions of a defined array (alarm 17020).
    IndexOutOfRange(Span),
}

impl EvalError {
    pub fn span(self) -> Span {
        match self {
            EvalError::DivisionByZero(span)
            | EvalError::Overflow(span)
            | EvalError::Domain(span, _)
            | EvalError::ArgumentCount(span, _)
            | EvalError::IndexOutOfRange(span) => span,
        }
    }
}

/// Evaluates `id` of `block` (whose text is `line`). `Ok(None)` means unknown.
pub fn evaluate_value(
    block: &Block,
    line: &str,
    id: ExprId,
    variables: &Variables,
    options: &EvalOptions,
) -> Result<Option<Value>, EvalError> {
    evaluator::Evaluator {
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
