//! Assignments to R parameters by computed number (`R[i]=`, `$R[i]=`) and to user variables and their
//! array elements, through the typed store of `eval::Variables`.

use crate::analysis::engine::engine_state::Engine;
use crate::analysis::engine::evaluation::{evaluate_or_report, quoted, whole_number};
use crate::analysis::eval::{AssignError, IndexError, Value, VarType};
use crate::diagnostics::{Code, Diagnostic, Span};
use crate::syntax::ast::{Block, ExprId, ExprKind};

/// An evaluated index: a whole number from 0, a whole negative number, or anything else (unknown).
enum Index {
    At(usize),
    Negative(f64),
    Unknown,
}

fn index_of(value: Option<f64>) -> Index {
    match value {
        Some(value) if value.fract() == 0.0 && value < 0.0 => Index::Negative(value),
        Some(value) if value.fract() == 0.0 && value <= u32::MAX as f64 => {
            Index::At(value as usize)
        }
        _ => Index::Unknown,
    }
}

impl Engine<'_> {
    /// `R[index]=value` or `$R[index]=value`. An unknown index may have written any R parameter.
    pub(super) fn write_indexed_r_parameter(
        &mut self,
        line: &str,
        block: &Block,
        index: ExprId,
        target_span: Span,
        value: Option<f64>,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        let index = evaluate_or_report(block, line, index, &self.state.variables, diagnostics);
        match index_of(index) {
            // An index is at most u32::MAX (see `index_of`).
            Index::At(number) => self.state.variables.set_r_parameter(number as u32, value),
            Index::Negative(number) => diagnostics.push(Diagnostic::new(
                Code::IndexOutOfRange,
                target_span,
                format!(
                    "R parameters are numbered from 0, not {} (alarm 17020)",
                    whole_number(number)
                ),
            )),
            Index::Unknown => self.state.variables.forget_r_parameters(),
        }
    }

    /// `NAME=value` or `NAME[i, j, k]=value`: stored converted to the variable's type. An element
    /// whose index is not known may be any element, so the whole array becomes unknown.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn write_variable(
        &mut self,
        line: &str,
        block: &Block,
        target_span: Span,
        indexes: &[ExprId],
        value_expr: Option<ExprId>,
        value: Option<Value>,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        let written = &line[target_span.start()..target_span.end()];
        let name = written
            .split('[')
            .next()
            .unwrap_or_default()
            .trim()
            .to_ascii_uppercase();
        let value = match value {
            None if !self.flow_uncertain => self.axis_name_value(line, block, &name, value_expr),
            value => value,
        };
        let mut at = Vec::with_capacity(indexes.len());
        let mut known = true;
        for index in indexes {
            let index = evaluate_or_report(block, line, *index, &self.state.variables, diagnostics);
            match index_of(index) {
                Index::At(index) => at.push(index),
                Index::Negative(number) => {
                    if self.state.variables.dimensions(&name).is_some() {
                        diagnostics.push(Diagnostic::new(
                            Code::IndexOutOfRange,
                            target_span,
                            format!(
                                "`{}`: indexes count from 0, not {} (alarm 17020)",
                                quoted(written),
                                whole_number(number)
                            ),
                        ));
                    }
                    return;
                }
                Index::Unknown => known = false,
            }
        }
        if !known {
            self.state.variables.forget_variable(&name);
            return;
        }
        match self.state.variables.assign(&name, &at, value) {
            Err(AssignError::Index(IndexError::OutOfRange {
                dimension,
                index,
                size,
            })) => {
                let array = if at.len() == 1 {
                    format!("`{}`", quoted(&name))
                } else {
                    format!("dimension {} of `{}`", dimension + 1, quoted(&name))
                };
                diagnostics.push(Diagnostic::new(
                    Code::IndexOutOfRange,
                    target_span,
                    format!(
                        "index {index} is out of range: {array} has {size} elements, 0 to {} (alarm 17020)",
                        size - 1
                    ),
                ));
            }
            // A value out of the type's range has left the variable unknown; what the control reports
            // then is not documented. Indexes on a scalar or a variable whose definition is not
            // known write nothing the analysis follows.
            Err(AssignError::ValueOutOfRange(_))
            | Err(AssignError::Index(IndexError::Count { .. }))
            | Err(AssignError::NotDefined)
            | Ok(()) => {}
        }
    }

    /// The value of `AXVAR=X` for an AXIS variable: a bare configured axis name stands for itself.
    pub(super) fn axis_name_value(
        &self,
        line: &str,
        block: &Block,
        target: &str,
        value_expr: Option<ExprId>,
    ) -> Option<Value> {
        if self.state.variables.var_type(target) != Some(VarType::Axis) {
            return None;
        }
        let mut id = value_expr?;
        while let ExprKind::Parenthesized(inner) = block.expr(id).kind {
            id = inner;
        }
        let expr = block.expr(id);
        let ExprKind::Name { indexes } = &expr.kind else {
            return None;
        };
        let name = line[expr.span.start()..expr.span.end()].to_ascii_uppercase();
        let is_variable = self.state.variables.dimensions(&name).is_some();
        (indexes.is_empty() && !is_variable && self.axis_index(&name).is_some())
            .then(|| Value::text_from(&name))
    }
}

#[cfg(test)]
mod tests;
