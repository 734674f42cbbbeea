//! The walk over an expression tree of one block: operands, operators in the tree the parser built
//! (reference §8.2), indexed reads and function calls.

use super::array::IndexError;
use super::functions::{apply, function_arguments, FunctionError};
use super::options::{EvalError, EvalOptions};
use super::value::{as_int, real_equal, real_less, real_less_equal, Value};
use super::variables::Variables;
use crate::diagnostics::Span;
use crate::syntax::ast::{BinaryOp, Block, ExprId, ExprKind, UnaryOp};
use std::borrow::Cow;
use std::sync::Arc;

/// Nodes visited before an evaluation gives up as unknown; the parser already bounds the depth, this
/// bounds the work on a line of many operators.
const MAX_STEPS: usize = 100_000;

pub(super) struct Evaluator<'a> {
    pub block: &'a Block,
    pub line: &'a str,
    pub variables: &'a Variables,
    pub options: &'a EvalOptions,
    pub steps: usize,
}

type Evaluated = Result<Option<Value>, EvalError>;

/// A number result: known only when finite, an overflow when finite operands gave infinity.
fn number(span: Span, value: f64) -> Evaluated {
    if value.is_finite() {
        Ok(Some(Value::Number(value)))
    } else {
        Err(EvalError::Overflow(span))
    }
}

/// The upper-case form of a name, without allocating for the short names nearly all programs use.
fn upper(name: &str) -> Cow<'_, str> {
    if name.bytes().any(|byte| byte.is_ascii_lowercase()) {
        Cow::Owned(name.to_ascii_uppercase())
    } else {
        Cow::Borrowed(name)
    }
}

impl Evaluator<'_> {
    pub(super) fn value(&mut self, id: ExprId) -> Evaluated {
        self.steps += 1;
        if self.steps > MAX_STEPS {
            return Ok(None);
        }
        let expr = self.block.expr(id);
        let span = expr.span;
        match &expr.kind {
            ExprKind::Number(value) => {
                Ok(Some(Value::Number(*value)).filter(|_| value.is_finite()))
            }
            ExprKind::String => Ok(self.string_literal(span)),
            ExprKind::List(_) | ExprKind::Error => Ok(None),
            ExprKind::RParameter(number) => {
                Ok(self.variables.r_parameter(*number).map(Value::Number))
            }
            ExprKind::RParameterIndexed(index) => self.indexed_r_parameter(*index, span),
            ExprKind::Name { indexes } => self.name(span, indexes),
            ExprKind::SystemVariable { indexes } => {
                let name = upper(self.name_text(span));
                match (name.as_ref(), indexes.as_slice()) {
                    ("$PI", []) => Ok(Some(Value::Number(std::f64::consts::PI))),
                    // `$R[n]` names the same parameters as `R[n]` (reference §8.1).
                    ("$R", [index]) => self.indexed_r_parameter(*index, span),
                    _ => Ok(None),
                }
            }
            ExprKind::Parenthesized(inner) => self.value(*inner),
            ExprKind::Unary(op, operand) => {
                let operand = self.value(*operand)?;
                self.unary(*op, operand, span)
            }
            ExprKind::Binary(op, left, right) => self.binary(*op, *left, *right, span),
            ExprKind::Call { name, args } => self.call(*name, args, span),
        }
    }

    /// The text of a name, without the indexes that follow it.
    fn name_text(&self, span: Span) -> &str {
        let text = &self.line[span.start()..span.end()];
        text.split('[').next().unwrap_or_default().trim()
    }

    fn string_literal(&self, span: Span) -> Option<Value> {
        let text = &self.line[span.start()..span.end()];
        // An unterminated string has been reported; its value is not what the program meant.
        let inner = text.strip_prefix('"')?.strip_suffix('"')?;
        Some(Value::text_from(inner))
    }

    /// An index that selects something: a whole number from 0.
    fn index(&mut self, id: ExprId) -> Result<Option<IndexValue>, EvalError> {
        Ok(match self.value(id)?.and_then(|value| value.number()) {
            Some(value) if value.fract() != 0.0 => None,
            Some(value) if value < 0.0 => Some(IndexValue::Negative),
            Some(value) if value <= u32::MAX as f64 => Some(IndexValue::At(value as usize)),
            Some(_) => Some(IndexValue::Beyond),
            None => None,
        })
    }

    /// `R[index]`: R parameters are numbered from 0; how many there are is machine data (MD28050)
    /// the evaluator does not know, so only a negative number is known to be out of range.
    fn indexed_r_parameter(&mut self, index: ExprId, span: Span) -> Evaluated {
        match self.index(index)? {
            Some(IndexValue::At(number)) => {
                Ok(self.variables.r_parameter(number as u32).map(Value::Number))
            }
            Some(IndexValue::Negative) => Err(EvalError::IndexOutOfRange(span)),
            Some(IndexValue::Beyond) | None => Ok(None),
        }
    }

    fn name(&mut self, span: Span, indexes: &[ExprId]) -> Evaluated {
        if indexes.is_empty() {
            let name = upper(self.name_text(span));
            return Ok(match name.as_ref() {
                "TRUE" => Some(Value::from_bool(true)),
                "FALSE" => Some(Value::from_bool(false)),
                name => self.variables.value(name, &[]),
            });
        }
        // Every index is evaluated, so that its own errors are found even when another is unknown.
        let mut values = Vec::with_capacity(indexes.len());
        for index in indexes {
            values.push(self.index(*index)?);
        }
        let name = upper(self.name_text(span));
        let Some(dimensions) = self.variables.dimensions(&name) else {
            return Ok(None);
        };
        if dimensions.len() != values.len() {
            return Ok(None);
        }
        // A known index outside its dimension is an error even when another index is unknown.
        let outside = values
            .iter()
            .zip(dimensions)
            .any(|(index, size)| match index {
                Some(IndexValue::At(index)) => index >= size,
                Some(IndexValue::Negative | IndexValue::Beyond) => true,
                None => false,
            });
        if outside {
            return Err(EvalError::IndexOutOfRange(span));
        }
        let mut at = Vec::with_capacity(values.len());
        for value in values {
            match value {
                Some(IndexValue::At(index)) => at.push(index),
                _ => return Ok(None),
            }
        }
        match self.variables.read(&name, &at) {
            Ok(value) => Ok(value),
            Err(IndexError::OutOfRange { .. }) => Err(EvalError::IndexOutOfRange(span)),
            Err(IndexError::Count { .. }) => Ok(None),
        }
    }

    fn unary(&mut self, op: UnaryOp, operand: Option<Value>, span: Span) -> Evaluated {
        let Some(operand) = operand else {
            return Ok(None);
        };
        if op == UnaryOp::ToString {
            return Ok(operand.to_text().map(Value::Text));
        }
        let Some(value) = operand.number() else {
            return Ok(None);
        };
        match op {
            UnaryOp::Negate => number(span, -value),
            UnaryOp::Plus => number(span, value),
            UnaryOp::Not => Ok(Some(Value::from_bool(value == 0.0))),
            UnaryOp::BitNot => Ok(as_int(value).map(|value| Value::Number(f64::from(!value)))),
            UnaryOp::ToString => Ok(None),
        }
    }

    fn binary(&mut self, op: BinaryOp, left: ExprId, right: ExprId, span: Span) -> Evaluated {
        let left = self.value(left)?;
        let right = self.value(right)?;
        match op {
            BinaryOp::And | BinaryOp::Or => return Ok(logical(op, left, right)),
            BinaryOp::Concat => {
                let joined = left
                    .and_then(|left| left.to_text())
                    .zip(right.and_then(|right| right.to_text()))
                    .map(|(left, right)| Value::Text(Arc::from(format!("{left}{right}"))));
                return Ok(joined);
            }
            BinaryOp::Equal | BinaryOp::NotEqual => {
                if let (Some(Value::Text(left)), Some(Value::Text(right))) = (&left, &right) {
                    let equal = left == right;
                    return Ok(Some(Value::from_bool(equal == (op == BinaryOp::Equal))));
                }
            }
            _ => {}
        }
        let (Some(left), Some(right)) = (
            left.and_then(|value| value.number()),
            right.and_then(|value| value.number()),
        ) else {
            return Ok(None);
        };
        let exact = self.options.exact_less_greater;
        let truth = |value: bool| Ok(Some(Value::from_bool(value)));
        match op {
            BinaryOp::Add => number(span, left + right),
            BinaryOp::Subtract => number(span, left - right),
            BinaryOp::Multiply => number(span, left * right),
            BinaryOp::Divide | BinaryOp::IntegerDivide | BinaryOp::Modulo if right == 0.0 => {
                Err(EvalError::DivisionByZero(span))
            }
            BinaryOp::Divide => number(span, left / right),
            // Integer division truncates toward zero.
            BinaryOp::IntegerDivide => number(span, (left / right).trunc()),
            // The remainder of that division: it takes the sign of the dividend.
            BinaryOp::Modulo => number(span, left % right),
            BinaryOp::Equal => truth(real_equal(left, right)),
            BinaryOp::NotEqual => truth(!real_equal(left, right)),
            BinaryOp::Less => truth(real_less(left, right, exact)),
            BinaryOp::Greater => truth(real_less(right, left, exact)),
            BinaryOp::LessEqual => truth(real_less_equal(left, right)),
            BinaryOp::GreaterEqual => truth(real_less_equal(right, left)),
            BinaryOp::Xor => truth((left != 0.0) != (right != 0.0)),
            BinaryOp::BitAnd | BinaryOp::BitOr | BinaryOp::BitXor => {
                let (Some(left), Some(right)) = (as_int(left), as_int(right)) else {
                    return Ok(None);
                };
                let bits = match op {
                    BinaryOp::BitAnd => left & right,
                    BinaryOp::BitOr => left | right,
                    _ => left ^ right,
                };
                Ok(Some(Value::Number(f64::from(bits))))
            }
            BinaryOp::And | BinaryOp::Or | BinaryOp::Concat | BinaryOp::Chain => Ok(None),
        }
    }

    fn call(&mut self, name: Span, args: &[Option<ExprId>], span: Span) -> Evaluated {
        let upper_name = upper(&self.line[name.start()..name.end()]);
        if let Some((least, most)) = function_arguments(&upper_name) {
            if args.len() < least || args.len() > most {
                let expected = if args.len() < least { least } else { most };
                return Err(EvalError::ArgumentCount(span, expected));
            }
        }
        let mut values = Vec::with_capacity(args.len());
        for argument in args {
            values.push(match argument {
                Some(id) => self.value(*id)?,
                None => None,
            });
        }
        match apply(&upper_name, &values) {
            Ok(Some(Value::Number(value))) => number(span, value),
            Ok(value) => Ok(value),
            Err(FunctionError::Domain(what)) => Err(EvalError::Domain(span, what)),
        }
    }
}

/// An evaluated index.
#[derive(Clone, Copy)]
enum IndexValue {
    At(usize),
    Negative,
    /// Beyond any size the analysis follows.
    Beyond,
}

/// AND and OR in three-valued logic: a known FALSE decides AND and a known TRUE decides OR whatever
/// the other operand is, so an unknown operand does not make those results unknown.
fn logical(op: BinaryOp, left: Option<Value>, right: Option<Value>) -> Option<Value> {
    let truth = |value: &Option<Value>| match value {
        Some(Value::Number(value)) => Some(*value != 0.0),
        _ => None,
    };
    // A text operand is a type error the control rejects; nothing is decided then.
    let is_text = |value: &Option<Value>| matches!(value, Some(Value::Text(_)));
    if is_text(&left) || is_text(&right) {
        return None;
    }
    let (left, right) = (truth(&left), truth(&right));
    let deciding = op == BinaryOp::Or;
    if left == Some(deciding) || right == Some(deciding) {
        return Some(Value::from_bool(deciding));
    }
    // Neither operand decides, so both must be known, and both are the other truth value.
    let (Some(left), Some(right)) = (left, right) else {
        return None;
    };
    Some(Value::from_bool(left && right))
}
