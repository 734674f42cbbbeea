//! Tests of the evaluator through parsed lines, so that each case also checks that the parser builds
//! the tree the rule is about.

mod functions;
mod operators;
mod reads;
mod variables;

use super::*;
use crate::diagnostics::{Severity, Span};
use crate::syntax::ast::{AssignTarget, ExprId, Statement};
use crate::syntax::{parse_line, SyntaxContext};

/// Evaluates `expression` as the value of `R0=expression`; a line the parser rejects fails the test,
/// as the case would not test what it says.
fn eval_with(
    expression: &str,
    variables: &Variables,
    options: &EvalOptions,
) -> Result<Option<Value>, EvalError> {
    let line = format!("R0={expression}");
    let (block, diagnostics) = parse_line(&line, &SyntaxContext::default());
    let errors: Vec<_> = diagnostics
        .iter()
        .filter(|diagnostic| diagnostic.severity == Severity::Error)
        .collect();
    assert!(errors.is_empty(), "`{line}` does not parse: {errors:?}");
    let value = block
        .statements
        .iter()
        .find_map(|statement| match statement {
            Statement::Assignment {
                target: AssignTarget::RParameter(0),
                value,
                ..
            } => *value,
            _ => None,
        })
        .expect("an assignment to R0");
    evaluate_value(&block, &line, value, variables, options)
}

fn eval_in(expression: &str, variables: &Variables) -> Result<Option<Value>, EvalError> {
    eval_with(expression, variables, &EvalOptions::default())
}

/// The number `expression` gives with no variables known; panics on an error.
fn number(expression: &str) -> Option<f64> {
    number_in(expression, &Variables::default())
}

fn number_in(expression: &str, variables: &Variables) -> Option<f64> {
    match eval_in(expression, variables) {
        Ok(value) => value.map(|value| {
            value
                .number()
                .unwrap_or_else(|| panic!("`{expression}` gave a text: {value:?}"))
        }),
        Err(error) => panic!("`{expression}` failed: {error:?}"),
    }
}

/// The text `expression` gives with no variables known; panics on an error or a number.
fn text(expression: &str) -> Option<String> {
    match eval_in(expression, &Variables::default()) {
        Ok(value) => value.map(|value| {
            value
                .text()
                .unwrap_or_else(|| panic!("`{expression}` gave a number: {value:?}"))
                .to_string()
        }),
        Err(error) => panic!("`{expression}` failed: {error:?}"),
    }
}

fn error(expression: &str) -> EvalError {
    match eval_in(expression, &Variables::default()) {
        Err(error) => error,
        Ok(value) => panic!("`{expression}` gave {value:?}, not an error"),
    }
}

/// Asserts that `expression` gives `expected` to 1e-9.
#[track_caller]
fn assert_near(expression: &str, expected: f64) {
    let value = number(expression).unwrap_or_else(|| panic!("`{expression}` is unknown"));
    assert!(
        (value - expected).abs() < 1e-9,
        "`{expression}` gave {value}, expected {expected}"
    );
}

#[test]
fn the_numeric_entry_keeps_working_for_numbers_and_leaves_texts_unknown() {
    let line = "R0=2*3 R1=\"AB\"";
    let (block, _) = parse_line(line, &SyntaxContext::default());
    let values: Vec<ExprId> = block
        .statements
        .iter()
        .filter_map(|statement| match statement {
            Statement::Assignment { value, .. } => *value,
            _ => None,
        })
        .collect();
    let variables = Variables::default();
    assert_eq!(evaluate(&block, line, values[0], &variables), Ok(Some(6.0)));
    assert_eq!(evaluate(&block, line, values[1], &variables), Ok(None));
}
