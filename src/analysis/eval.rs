//! Static evaluation of NC expressions: numbers, R parameters and user variables whose values are known,
//! arithmetic, comparisons and the predefined functions. Anything the program does not determine (a
//! system variable, an unassigned variable, a string) is `None`: unknown, never a guessed number.

use crate::diagnostics::Span;
use crate::syntax::ast::{BinaryOp, Block, ExprId, ExprKind, UnaryOp};
use std::collections::HashMap;

/// The values of R parameters and user variables known at a point of the program.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Variables {
    r_parameters: HashMap<u32, f64>,
    /// User variables by upper-case name; `None` marks a variable that exists but is unknown.
    named: HashMap<String, Option<f64>>,
}

impl Variables {
    pub fn r_parameter(&self, number: u32) -> Option<f64> {
        self.r_parameters.get(&number).copied()
    }

    pub fn set_r_parameter(&mut self, number: u32, value: Option<f64>) {
        match value {
            Some(value) => {
                self.r_parameters.insert(number, value);
            }
            None => {
                self.r_parameters.remove(&number);
            }
        }
    }

    pub fn variable(&self, upper_name: &str) -> Option<f64> {
        self.named.get(upper_name).copied().flatten()
    }

    pub fn set_variable(&mut self, upper_name: &str, value: Option<f64>) {
        self.named.insert(upper_name.to_string(), value);
    }

    /// Puts the user variables of the running program level aside (a call starts a level of its own);
    /// R parameters are global and stay.
    pub fn take_locals(&mut self) -> Variables {
        Variables {
            r_parameters: HashMap::new(),
            named: std::mem::take(&mut self.named),
        }
    }

    /// Brings back the user variables `take_locals` put aside (the return to the caller's level).
    pub fn restore_locals(&mut self, locals: Variables) {
        self.named = locals.named;
    }

    /// Forgets what differs from `other`: a value known on one way and different or unknown on the
    /// other becomes unknown where the ways meet.
    pub fn join(&mut self, other: &Variables) {
        self.r_parameters
            .retain(|number, value| other.r_parameters.get(number) == Some(value));
        for (name, value) in self.named.iter_mut() {
            if other.named.get(name) != Some(value) {
                *value = None;
            }
        }
        for name in other.named.keys() {
            if !self.named.contains_key(name) {
                self.named.insert(name.clone(), None);
            }
        }
    }

    /// Forgets every value: after a call of an unknown subprogram, anything may have changed.
    pub fn forget_all(&mut self) {
        self.r_parameters.clear();
        for value in self.named.values_mut() {
            *value = None;
        }
    }
}

/// Why an expression could not be evaluated when that is an error of the program, not a lack of
/// knowledge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EvalError {
    /// Division by zero (alarm 14051).
    DivisionByZero(Span),
}

/// Evaluates `id` of `block` (whose text is `line`). `Ok(None)` means unknown.
pub fn evaluate(
    block: &Block,
    line: &str,
    id: ExprId,
    variables: &Variables,
) -> Result<Option<f64>, EvalError> {
    Evaluator {
        block,
        line,
        variables,
        steps: 0,
    }
    .value(id)
}

struct Evaluator<'a> {
    block: &'a Block,
    line: &'a str,
    variables: &'a Variables,
    /// Guards against pathological trees; the parser already bounds depth.
    steps: usize,
}

/// REAL values compare with a relative tolerance on the control (reference §8.2).
fn real_equal(left: f64, right: f64) -> bool {
    let scale = left.abs().max(right.abs()).max(1.0);
    (left - right).abs() <= 1e-12 * scale
}

fn truth(value: bool) -> f64 {
    if value {
        1.0
    } else {
        0.0
    }
}

impl Evaluator<'_> {
    fn value(&mut self, id: ExprId) -> Result<Option<f64>, EvalError> {
        self.steps += 1;
        if self.steps > 100_000 {
            return Ok(None);
        }
        let expr = self.block.expr(id);
        let result = match &expr.kind {
            ExprKind::Number(value) => Some(*value),
            ExprKind::String | ExprKind::List(_) | ExprKind::Error => None,
            ExprKind::RParameter(number) => self.variables.r_parameter(*number),
            ExprKind::RParameterIndexed(index) => match self.value(*index)? {
                Some(index) if index >= 0.0 && index.fract() == 0.0 => {
                    self.variables.r_parameter(index as u32)
                }
                _ => None,
            },
            ExprKind::Name { indexes } => {
                if !indexes.is_empty() {
                    None
                } else {
                    let name = self.line[expr.span.start()..expr.span.end()].to_ascii_uppercase();
                    match name.as_str() {
                        "TRUE" => Some(1.0),
                        "FALSE" => Some(0.0),
                        "$PI" => Some(std::f64::consts::PI),
                        _ => self.variables.variable(&name),
                    }
                }
            }
            ExprKind::SystemVariable { .. } => {
                let name = &self.line[expr.span.start()..expr.span.end()];
                name.eq_ignore_ascii_case("$PI")
                    .then_some(std::f64::consts::PI)
            }
            ExprKind::Parenthesized(inner) => self.value(*inner)?,
            ExprKind::Unary(op, operand) => {
                let operand = self.value(*operand)?;
                match op {
                    UnaryOp::Negate => operand.map(|value| -value),
                    UnaryOp::Plus => operand,
                    UnaryOp::Not => operand.map(|value| truth(value == 0.0)),
                    UnaryOp::BitNot | UnaryOp::ToString => None,
                }
            }
            ExprKind::Binary(op, left, right) => self.binary(*op, *left, *right, expr.span)?,
            ExprKind::Call { name, args } => self.call(*name, args)?,
        };
        Ok(result.filter(|value| value.is_finite()))
    }

    fn binary(
        &mut self,
        op: BinaryOp,
        left: ExprId,
        right: ExprId,
        span: Span,
    ) -> Result<Option<f64>, EvalError> {
        let (Some(left), Some(right)) = (self.value(left)?, self.value(right)?) else {
            return Ok(None);
        };
        Ok(match op {
            BinaryOp::Add => Some(left + right),
            BinaryOp::Subtract => Some(left - right),
            BinaryOp::Multiply => Some(left * right),
            BinaryOp::Divide => {
                if right == 0.0 {
                    return Err(EvalError::DivisionByZero(span));
                }
                Some(left / right)
            }
            BinaryOp::IntegerDivide => {
                if right.trunc() == 0.0 {
                    return Err(EvalError::DivisionByZero(span));
                }
                Some((left.trunc() / right.trunc()).trunc())
            }
            BinaryOp::Modulo => {
                if right == 0.0 {
                    return Err(EvalError::DivisionByZero(span));
                }
                Some(left % right)
            }
            BinaryOp::Equal => Some(truth(real_equal(left, right))),
            BinaryOp::NotEqual => Some(truth(!real_equal(left, right))),
            BinaryOp::Less => Some(truth(left < right && !real_equal(left, right))),
            BinaryOp::Greater => Some(truth(left > right && !real_equal(left, right))),
            BinaryOp::LessEqual => Some(truth(left < right || real_equal(left, right))),
            BinaryOp::GreaterEqual => Some(truth(left > right || real_equal(left, right))),
            BinaryOp::And => Some(truth(left != 0.0 && right != 0.0)),
            BinaryOp::Or => Some(truth(left != 0.0 || right != 0.0)),
            BinaryOp::Xor => Some(truth((left != 0.0) != (right != 0.0))),
            BinaryOp::BitAnd
            | BinaryOp::BitOr
            | BinaryOp::BitXor
            | BinaryOp::Concat
            | BinaryOp::Chain => None,
        })
    }

    fn call(&mut self, name: Span, args: &[Option<ExprId>]) -> Result<Option<f64>, EvalError> {
        let mut values = Vec::with_capacity(args.len());
        for argument in args {
            match argument {
                Some(id) => values.push(self.value(*id)?),
                None => values.push(None),
            }
        }
        let name = self.line[name.start()..name.end()].to_ascii_uppercase();
        let one = |values: &[Option<f64>]| match values {
            [Some(value)] => Some(*value),
            _ => None,
        };
        let two = |values: &[Option<f64>]| match values {
            [Some(first), Some(second)] => Some((*first, *second)),
            _ => None,
        };
        // Angles are in degrees (reference §8.2).
        Ok(match name.as_str() {
            "SIN" => one(&values).map(|value| value.to_radians().sin()),
            "COS" => one(&values).map(|value| value.to_radians().cos()),
            "TAN" => one(&values).map(|value| value.to_radians().tan()),
            "ASIN" => one(&values).map(|value| value.asin().to_degrees()),
            "ACOS" => one(&values).map(|value| value.acos().to_degrees()),
            "ATAN2" => two(&values).map(|(y, x)| y.atan2(x).to_degrees()),
            "SQRT" => one(&values).filter(|value| *value >= 0.0).map(f64::sqrt),
            "POT" => one(&values).map(|value| value * value),
            "ABS" => one(&values).map(f64::abs),
            "TRUNC" => one(&values).map(f64::trunc),
            // Half away from zero, the recommendation of reference §8.2 ([?]).
            "ROUND" => one(&values).map(f64::round),
            "LN" => one(&values).filter(|value| *value > 0.0).map(f64::ln),
            "EXP" => one(&values).map(f64::exp),
            "MIN" => two(&values).map(|(first, second)| first.min(second)),
            "MAX" => two(&values).map(|(first, second)| first.max(second)),
            "ITOR" => one(&values),
            "RTOI" => one(&values).map(f64::round),
            _ => None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::ast::{AssignTarget, Statement};
    use crate::syntax::{parse_line, SyntaxContext};

    /// Evaluates the value of the first assignment in `line`.
    fn eval(line: &str, variables: &Variables) -> Result<Option<f64>, EvalError> {
        let (block, _) = parse_line(line, &SyntaxContext::default());
        let value = block
            .statements
            .iter()
            .find_map(|statement| match statement {
                Statement::Assignment {
                    target: AssignTarget::RParameter(_),
                    value,
                    ..
                } => *value,
                _ => None,
            })
            .expect("an R parameter assignment");
        evaluate(&block, line, value, variables)
    }

    #[test]
    fn arithmetic_follows_the_reference() {
        let mut variables = Variables::default();
        variables.set_r_parameter(1, Some(10.0));
        assert_eq!(eval("R2=R1*2+SIN(30)", &variables), Ok(Some(20.5)));
        assert_eq!(eval("R3=2+3*4", &variables), Ok(Some(14.0)));
        assert_eq!(eval("R4=POT(3)+TRUNC(-2.7)", &variables), Ok(Some(7.0)));
        assert_eq!(eval("R5=7 DIV 2", &variables), Ok(Some(3.0)));
        assert_eq!(eval("R6=7 MOD 4", &variables), Ok(Some(3.0)));
    }

    #[test]
    fn unknown_values_stay_unknown() {
        let variables = Variables::default();
        assert_eq!(eval("R2=R1+1", &variables), Ok(None));
        assert_eq!(eval("R2=$AA_IW[X]", &variables), Ok(None));
        assert_eq!(eval("R2=UNKNOWNVAR*0", &variables), Ok(None));
    }

    #[test]
    fn division_by_zero_is_an_error() {
        let variables = Variables::default();
        assert!(matches!(
            eval("R1=1/0", &variables),
            Err(EvalError::DivisionByZero(_))
        ));
    }

    #[test]
    fn comparisons_use_a_relative_tolerance() {
        let variables = Variables::default();
        assert_eq!(eval("R1=(0.1+0.2)==0.3", &variables), Ok(Some(1.0)));
        assert_eq!(eval("R1=1<2", &variables), Ok(Some(1.0)));
    }
}
