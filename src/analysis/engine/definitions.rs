//! `DEF` statements (typed variables and arrays with their initial values) and the dispatch of an
//! assignment to R parameters, variables, system variables and G groups.

use crate::analysis::engine::engine_state::Engine;
use crate::analysis::engine::evaluation::{evaluate_or_report, evaluate_value_or_report};
use crate::analysis::eval::Value;
use crate::diagnostics::Diagnostic;
use crate::syntax::ast::*;

impl<'a> Engine<'a> {
    /// `DEF`: LUD variables of their type, starting at zero (reference §8.1) or at their initial
    /// value (`=5`, `=(1,2,3)`, `=SET(..)`, `=REP(..)`); arrays of up to three dimensions.
    pub(super) fn apply_definition(
        &mut self,
        line: &str,
        block: &Block,
        data_type: Option<DataType>,
        declarators: &[Declarator],
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        use crate::analysis::eval::{evaluate_value, EvalOptions, Value, VarType};
        let var_type = VarType::of_declared(data_type);
        let options = EvalOptions::default();
        for declarator in declarators {
            let upper = line[declarator.name.start()..declarator.name.end()].to_ascii_uppercase();
            let mut dimensions = Vec::with_capacity(declarator.dimensions.len());
            for id in &declarator.dimensions {
                match evaluate_or_report(block, line, *id, &self.state.variables, diagnostics) {
                    Some(size) if size >= 1.0 && size.fract() == 0.0 && size <= 1e9 => {
                        dimensions.push(size as usize)
                    }
                    _ => {
                        dimensions.clear();
                        break;
                    }
                }
            }
            if dimensions.len() != declarator.dimensions.len() {
                // An array whose size is not known: nothing of it is followed.
                self.state.variables.set_variable(&upper, None);
                continue;
            }
            if self
                .state
                .variables
                .define(&upper, var_type, &dimensions)
                .is_err()
            {
                self.state.variables.forget_variable(&upper);
                continue;
            }
            if self.flow_uncertain {
                self.state.variables.forget_variable(&upper);
                continue;
            }
            let value_of = |id: ExprId, variables: &crate::analysis::eval::Variables| {
                evaluate_value(block, line, id, variables, &options)
                    .ok()
                    .flatten()
            };
            let elements: Vec<Option<Value>> = match &declarator.initial {
                None => continue,
                // An AXIS variable's initial value is an axis name written bare (`DEF AXIS AC1=X`).
                Some(Initializer::Value(id)) => vec![value_of(*id, &self.state.variables)
                    .or_else(|| self.axis_name_value(line, block, &upper, Some(*id)))],
                Some(Initializer::List(items) | Initializer::Set(items)) => items
                    .iter()
                    .map(|item| {
                        item.and_then(|id| {
                            value_of(id, &self.state.variables)
                                .or_else(|| self.axis_name_value(line, block, &upper, Some(id)))
                        })
                    })
                    .collect(),
                Some(Initializer::Repeat { value, count }) => {
                    let element = value_of(*value, &self.state.variables);
                    let total: usize = dimensions.iter().product::<usize>().max(1);
                    let count = match count {
                        None => Some(total),
                        Some(id) => value_of(*id, &self.state.variables)
                            .and_then(|value| value.number())
                            .filter(|count| *count >= 0.0 && count.fract() == 0.0)
                            .map(|count| (count as usize).min(total)),
                    };
                    match count {
                        Some(count) => vec![element; count],
                        None => {
                            self.state.variables.forget_variable(&upper);
                            continue;
                        }
                    }
                }
            };
            if dimensions.is_empty() {
                let _ =
                    self.state
                        .variables
                        .assign(&upper, &[], elements.into_iter().next().flatten());
                continue;
            }
            // Initial values fill the array in the order of its last index first (row by row).
            let total: usize = dimensions.iter().product();
            for (position, element) in elements.into_iter().enumerate().take(total) {
                let indexes = crate::analysis::eval::element_indexes(position, &dimensions);
                let _ = self.state.variables.assign(&upper, &indexes, element);
            }
        }
    }
    pub(super) fn apply_assignment(
        &mut self,
        line: &str,
        block: &Block,
        target: &AssignTarget,
        target_span: crate::diagnostics::Span,
        value: Option<ExprId>,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        let evaluated = value.and_then(|id| {
            evaluate_value_or_report(block, line, id, &self.state.variables, diagnostics)
        });
        // After a jump or inside a control structure the assignment may run any number of times.
        let evaluated = if self.flow_uncertain { None } else { evaluated };
        let number = evaluated.as_ref().and_then(Value::number);
        match target {
            AssignTarget::RParameter(parameter) => {
                self.state.variables.set_r_parameter(*parameter, number)
            }
            AssignTarget::RParameterIndexed(index) => self.write_indexed_r_parameter(
                line,
                block,
                *index,
                target_span,
                number,
                diagnostics,
            ),
            AssignTarget::Variable { indexes } => self.write_variable(
                line,
                block,
                target_span,
                indexes,
                value,
                evaluated,
                diagnostics,
            ),
            // `$R[n]` names the same parameters as `R[n]` (reference §8.1).
            AssignTarget::SystemVariable { indexes }
                if indexes.len() == 1 && is_r_parameter_array(line, target_span) =>
            {
                self.write_indexed_r_parameter(
                    line,
                    block,
                    indexes[0],
                    target_span,
                    number,
                    diagnostics,
                )
            }
            AssignTarget::SystemVariable { indexes } => {
                self.apply_system_variable_write(
                    line,
                    block,
                    target_span,
                    indexes,
                    value,
                    diagnostics,
                );
            }
            AssignTarget::GGroup { group } => {
                self.apply_group_write(line, block, *group, value, diagnostics);
            }
        }
    }
}

/// Whether an assignment's target is `$R[...]`, the R parameters by number.
pub(super) fn is_r_parameter_array(line: &str, target_span: crate::diagnostics::Span) -> bool {
    let written = &line[target_span.start()..target_span.end()];
    written
        .split('[')
        .next()
        .is_some_and(|name| name.trim().eq_ignore_ascii_case("$R"))
}
