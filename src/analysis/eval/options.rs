//! How the control evaluates where machine data decide it (`EvalOptions`), and the errors of the
//! program an evaluation finds (`EvalError`).

use crate::diagnostics::Span;

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
