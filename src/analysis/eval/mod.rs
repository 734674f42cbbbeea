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
mod evaluate;
mod evaluator;
mod functions;
mod options;
mod value;
mod var_type;
mod variables;

#[cfg(test)]
mod tests;

pub use array::{element_indexes, IndexError, MAX_DIMENSIONS, MAX_FOLLOWED_ELEMENTS};
pub use evaluate::{evaluate, evaluate_value};
pub use functions::{function_arguments, is_evaluated_function};
pub use options::{EvalError, EvalOptions};
pub use value::{real_equal, real_less, real_less_equal, Value, INT_RANGE};
pub use var_type::VarType;
pub use variables::{AssignError, DefineError, Locals, Variables};
