//! The values of a block's words and expressions as the engine reads them: evaluated with the
//! program's variables, with the program's errors (alarms 14051, 14020, 17020) reported; and the axis
//! name of a word for messages.

use crate::analysis::engine::engine_state::Engine;
use crate::analysis::eval::{
    evaluate_value, function_arguments, EvalError, EvalOptions, Value, Variables,
};
use crate::diagnostics::Code;
use crate::diagnostics::Diagnostic;
use crate::syntax::ast::{AddressWord, Block, ExprId, Extension, ValueExpr};

impl<'a> Engine<'a> {
    /// The value of a word's expression (constant or evaluated), or `None` when unknown.
    pub(super) fn word_value(
        &self,
        line: &str,
        block: &Block,
        word: &AddressWord,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> Option<f64> {
        match word.value.expr {
            ValueExpr::Missing => None,
            ValueExpr::Constant { value, .. } => Some(value),
            ValueExpr::Expr(id) => {
                evaluate_or_report(block, line, id, &self.state.variables, diagnostics)
            }
        }
    }
}

/// The number an expression gives, or `None` when unknown or a text; errors of the program are
/// reported.
pub(super) fn evaluate_or_report(
    block: &Block,
    line: &str,
    id: ExprId,
    variables: &Variables,
    diagnostics: &mut Vec<Diagnostic>,
) -> Option<f64> {
    evaluate_value_or_report(block, line, id, variables, diagnostics)?.number()
}
/// The value an expression gives, or `None` when unknown; errors of the program (alarms 14051,
/// 14020, 17020) are reported.
pub(super) fn evaluate_value_or_report(
    block: &Block,
    line: &str,
    id: ExprId,
    variables: &Variables,
    diagnostics: &mut Vec<Diagnostic>,
) -> Option<Value> {
    match evaluate_value(block, line, id, variables, &EvalOptions::default()) {
        Ok(value) => value,
        Err(error) => {
            diagnostics.push(eval_error_diagnostic(line, error));
            None
        }
    }
}
/// The axis name of a word: the letter and its numeric extension (`X`, `X1`), or the whole name.
pub(crate) fn axis_name(line: &str, word: &AddressWord) -> String {
    AxisName(line, word).to_string()
}

/// The axis name of a word, written only when a message needs it: most words never do, and building a
/// string per word cost an allocation per axis word of every block.
pub(crate) struct AxisName<'a>(pub &'a str, pub &'a AddressWord);

impl std::fmt::Display for AxisName<'_> {
    fn fmt(&self, formatter: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let AxisName(line, word) = self;
        for character in line[word.name.start()..word.name.end()].chars() {
            write!(formatter, "{}", character.to_ascii_uppercase())?;
        }
        if let Some(Extension::Number { value, .. }) = &word.extension {
            write!(formatter, "{value}")?;
        }
        Ok(())
    }
}

/// Longest quotation of program text in a message, in characters.
const MAX_QUOTE_CHARACTERS: usize = 60;

/// `text` for a message, shortened when long: a finding about a megabyte-long name helps nobody.
pub(super) fn quoted(text: &str) -> String {
    // Looks at most one character past the limit, however long the text.
    if text.chars().nth(MAX_QUOTE_CHARACTERS).is_none() {
        return text.to_string();
    }
    let mut short: String = text.chars().take(MAX_QUOTE_CHARACTERS - 1).collect();
    short.push('…');
    short
}

/// A whole number for a message, short whatever its size.
pub(super) fn whole_number(number: f64) -> String {
    if number.abs() < 1e15 {
        format!("{}", number as i64)
    } else {
        format!("{number:e}")
    }
}

/// The finding for an error of the program found while evaluating an expression of `line`.
pub(super) fn eval_error_diagnostic(line: &str, error: EvalError) -> Diagnostic {
    match error {
        EvalError::DivisionByZero(span) => {
            Diagnostic::new(Code::DivisionByZero, span, "division by zero (alarm 14051)")
        }
        EvalError::Overflow(span) => Diagnostic::new(
            Code::ArithmeticError,
            span,
            "arithmetic overflow: the result is beyond the range of a double (alarm 14051)",
        ),
        EvalError::Domain(span, what) => {
            Diagnostic::new(Code::ArithmeticError, span, format!("{what} (alarm 14051)"))
        }
        EvalError::ArgumentCount(span, expected) => {
            let text = &line[span.start()..span.end()];
            let name = text.split('(').next().unwrap_or_default().trim();
            let name = name.to_ascii_uppercase();
            let takes = match function_arguments(&name) {
                Some((least, most)) if least != most => format!("{least} or {most} arguments"),
                _ if expected == 1 => "1 argument".to_string(),
                _ => format!("{expected} arguments"),
            };
            let message = format!("{} takes {takes} (alarm 14020)", quoted(&name));
            Diagnostic::new(Code::FunctionArgumentCount, span, message)
        }
        EvalError::IndexOutOfRange(span) => Diagnostic::new(
            Code::IndexOutOfRange,
            span,
            format!(
                "`{}`: the index is out of range (alarm 17020)",
                quoted(&line[span.start()..span.end()])
            ),
        ),
    }
}
