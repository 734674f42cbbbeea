//! Calls and returns (reference §8.3, §17): the callee found through the library, its parameters
//! bound by position (an omitted one is 0, §17.1), its own level of user variables, `P` repetitions,
//! `SAVE`, the modal call `MCALL`, the return by `M17`/`RET`/end of file, and the level limit.

use crate::analysis::engine::engine_state::Engine;
use crate::analysis::eval::{element_indexes, evaluate, Value, VarType, Variables};
use crate::analysis::execution::block_run::Next;
use crate::analysis::execution::interpreter::Interpreter;
use crate::analysis::execution::outcome::{CallSite, ProgramEnd};
use crate::analysis::execution::paths::{
    Activation, Argument, CallFrame, Control, ModalCall, SavedModal,
};
use crate::analysis::execution::program::ProgramUnit;
use crate::diagnostics::{Code, Span};
use crate::syntax::ast::{AddressKind, Block, CallKind, ExprId, ExprKind, Statement, ValueExpr};
use std::sync::Arc;

/// A call about to be run.
pub(super) struct PendingCall {
    unit: usize,
    arguments: Vec<Argument>,
    /// Per argument, the caller's variable it names (upper case, an R parameter as `R<n>`), for
    /// parameters passed by reference.
    targets: Vec<Option<String>>,
    repetitions: u32,
    /// The line of the call in the calling program.
    line: usize,
    span: Span,
}

impl PendingCall {
    /// The program the call runs, by its index among the run's programs.
    pub(super) fn unit(&self) -> usize {
        self.unit
    }
}

/// What a subprogram's `PROC` line declares.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct ProcInfo {
    /// The parameters in order: name, passed by reference (`VAR`), default value of an omitted
    /// argument (`PROC SUB(REAL PA=5)`, else 0).
    parameters: Vec<(String, bool, Option<f64>, VarType)>,
    save: bool,
}

impl<'a, 's> Interpreter<'a, 's> {
    /// The program a call of `name` runs, read once.
    pub(super) fn find_unit(&mut self, name: &str) -> Option<usize> {
        if let Some(found) = self.unit_names.get(name) {
            return *found;
        }
        let macros = self.library_macros();
        let found = self.library.find(name).map(|program| {
            let unit = ProgramUnit::with_macro_names(
                program.name.clone(),
                Some(Arc::clone(&program.path)),
                Arc::clone(&program.text),
                self.config,
                macros.names(),
            );
            self.add_unit(unit)
        });
        self.unit_names.insert(name.to_string(), found);
        found
    }

    /// The call of `block` the interpreter runs itself, when its program is found.
    pub(super) fn prepare_call(
        &mut self,
        control: &Control,
        engine: &Engine<'a>,
        unit: &ProgramUnit,
        pc: usize,
        block: &Block,
    ) -> Option<PendingCall> {
        let line = unit.line(pc);
        let statements = block.interpreted_statements();
        let (name, args, span) = statements.iter().find_map(|statement| match statement {
            Statement::Call {
                kind: kind @ (CallKind::Named | CallKind::Indirect),
                name: Some(name),
                args,
                span,
            } => Some((callee_name(line, *name, *kind)?, args, *span)),
            _ => None,
        })?;
        let _ = control;
        // A macro reads like a call; the engine expands it instead (the program's own macros and
        // those of the definition files win over a program of the same name).
        if engine.is_macro(&name) {
            return None;
        }
        let index = self.find_unit(&name)?;
        let arguments = evaluate_arguments(engine, block, line, args);
        Some(PendingCall {
            unit: index,
            arguments,
            targets: argument_targets(block, line, args),
            repetitions: repetitions(engine, block, line),
            line: pc,
            span,
        })
    }

    /// Keeps track of `MCALL` and gives the modal call to run after a block that moved.
    pub(super) fn modal_call_after(
        &mut self,
        control: &mut Control,
        engine: &mut Engine<'a>,
        block: &Block,
        pc: usize,
        moved: bool,
    ) -> Option<PendingCall> {
        let line = self.units[control.level().unit].line(pc).to_string();
        for statement in block.interpreted_statements() {
            if let Statement::Call {
                kind: CallKind::Modal,
                name,
                args,
                ..
            } = statement
            {
                control.level_mut().modal_call = name.and_then(|name| {
                    Some(ModalCall {
                        name: callee_name(&line, name, CallKind::Named)?,
                        arguments: evaluate_arguments(engine, block, &line, args),
                    })
                });
                return None;
            }
        }
        if !moved {
            return None;
        }
        let modal = control.level().modal_call.clone()?;
        match self.find_unit(&modal.name) {
            Some(unit) => Some(PendingCall {
                unit,
                arguments: modal.arguments,
                targets: Vec::new(),
                repetitions: 1,
                line: pc,
                span: Span::default(),
            }),
            // A standard drilling cycle without a program of its own runs as its built-in model.
            None if super::cycles::cycle_state::is_drilling(&modal.name)
                && !engine.is_macro(&modal.name) =>
            {
                self.run_modal_cycle(control, engine, pc, &line, block, &modal);
                None
            }
            None => {
                // A program the analysis cannot see runs after the block: anything may change.
                engine.forget_after_unknown_call();
                None
            }
        }
    }

    /// Starts the called program on a level of its own.
    pub(super) fn enter(
        &mut self,
        control: &mut Control,
        engine: &mut Engine<'a>,
        call: PendingCall,
    ) -> Next {
        if control.levels.len() >= self.options.max_levels {
            let name = self.units[call.unit].name.clone();
            // On a way the program may not take, the alarm is a possibility, not a certainty.
            let undecided = control.open_decisions(&self.covered).next().is_some();
            let (code, way) = match undecided {
                true => (
                    Code::LevelLimitOnUndecidedWay,
                    "on a way that depends on conditions the program does not determine, ",
                ),
                false => (Code::SubprogramLevelExceeded, ""),
            };
            self.report(
                control,
                call.line,
                code,
                call.span,
                format!(
                    "{way}calling {name} here needs program level {}, beyond the control's {} levels (alarm 14012): the program stops there",
                    control.levels.len() + 1,
                    self.options.max_levels
                ),
            );
            return Next::Stop;
        }
        let info = self.proc_info(call.unit);
        let saved = info.save.then_some(SavedModal {
            groups: engine.state.groups,
            frame: engine.state.frame,
        });
        // Arrays passed by reference (`VAR REAL A[3]`): the subprogram works on their elements.
        let arrays: Vec<Option<ArrayValues>> = info
            .parameters
            .iter()
            .enumerate()
            .map(|(index, (_, by_reference, _, _))| {
                let target = call.targets.get(index)?.as_ref()?;
                by_reference
                    .then(|| array_elements(&engine.state.variables, target))
                    .flatten()
            })
            .collect();
        let caller_locals = engine.state.variables.take_locals();
        let mut references = Vec::new();
        for (index, (parameter, by_reference, default, var_type)) in
            info.parameters.iter().enumerate()
        {
            let value = match call.arguments.get(index) {
                None | Some(Argument::Omitted) => Some(default.unwrap_or(0.0)),
                Some(Argument::Given(value)) => *value,
            };
            // A parameter is a variable of the subprogram's own level, of its declared type.
            let variables = &mut engine.state.variables;
            if let Some(Some(array)) = arrays.get(index) {
                if variables.define(parameter, *var_type, &array.0).is_ok() {
                    store_elements(variables, parameter, array);
                }
            } else if variables.define(parameter, *var_type, &[]).is_ok() {
                let _ = variables.assign(parameter, &[], value.map(Value::Number));
            } else {
                variables.set_variable(parameter, value);
            }
            if *by_reference {
                if let Some(Some(target)) = call.targets.get(index) {
                    references.push((parameter.clone(), target.clone()));
                }
            }
        }
        let caller = control.level();
        let mut stack: Vec<CallSite> = caller.stack.to_vec();
        stack.push(CallSite {
            path: self.units[caller.unit].path.clone(),
            line: call.line,
        });
        control.levels.push(Activation {
            unit: call.unit,
            pc: 0,
            loops: Vec::new(),
            call: Some(Box::new(CallFrame {
                repetitions_left: call.repetitions.saturating_sub(1),
                saved,
                caller_locals,
                references,
            })),
            retest_for: None,
            modal_call: None,
            jump_passes: Vec::new(),
            label_marks: Vec::new(),
            repeats: Vec::new(),
            curve_table: None,
            stack: Arc::from(stack),
        });
        Next::Moved
    }

    /// The end of a program level: M17/RET (or the end of the file) return to the caller, M2/M30 end
    /// the program (in a subprogram as configured, reference §17.4).
    pub(super) fn end_level(
        &mut self,
        control: &mut Control,
        engine: &mut Engine<'a>,
        end: ProgramEnd,
    ) -> Next {
        if control.levels.len() == 1
            || (end == ProgramEnd::End && !self.options.m30_ends_subprogram)
        {
            return Next::Stop;
        }
        let level = control.levels.pop().expect("a called level");
        let call = level.call.expect("a called level has its call");
        if let Some(saved) = &call.saved {
            engine.restore_saved(&saved.groups, saved.frame);
        }
        let written: Vec<(String, Result<ArrayValues, Option<f64>>)> = call
            .references
            .iter()
            .map(|(parameter, target)| {
                let variables = &engine.state.variables;
                let value = array_elements(variables, parameter)
                    .ok_or_else(|| variables.variable(parameter));
                (target.clone(), value)
            })
            .collect();
        engine.state.variables.restore_locals(call.caller_locals);
        let variables = &mut engine.state.variables;
        for (target, value) in written {
            match value {
                Ok(array) => store_elements(variables, &target, &array),
                Err(value) => match target
                    .strip_prefix('R')
                    .and_then(|number| number.parse::<u32>().ok())
                {
                    Some(number) => variables.set_r_parameter(number, value),
                    None => variables.set_variable(&target, value),
                },
            }
        }
        if call.repetitions_left > 0 {
            // The next pass runs without the parameters, which the first pass only receives
            // (reference §17.7).
            let line = control.level().pc.saturating_sub(1);
            return self.enter(
                control,
                engine,
                PendingCall {
                    unit: level.unit,
                    arguments: Vec::new(),
                    targets: Vec::new(),
                    repetitions: call.repetitions_left,
                    line,
                    span: Span::default(),
                },
            );
        }
        Next::Moved
    }

    /// The PROC line of a program: its parameters and whether it has SAVE.
    fn proc_info(&mut self, unit_index: usize) -> ProcInfo {
        let unit = Arc::clone(&self.units[unit_index]);
        let mut parser = crate::syntax::LineParser::new();
        let mut block = Block::default();
        let empty = crate::analysis::eval::Variables::default();
        for index in 0..unit.line_count().min(64) {
            unit.parse(&mut parser, index, &mut block);
            let line = unit.line(index);
            for statement in &block.statements {
                if let Statement::ProcedureHeader { params, save, .. } = statement {
                    let parameters = params
                        .iter()
                        .map(|parameter| {
                            let name = line[parameter.name.start()..parameter.name.end()]
                                .to_ascii_uppercase();
                            let default = parameter
                                .default
                                .and_then(|id| evaluate(&block, line, id, &empty).ok().flatten());
                            let var_type = VarType::of_declared(parameter.data_type);
                            (name, parameter.by_reference, default, var_type)
                        })
                        .collect();
                    return ProcInfo {
                        parameters,
                        save: *save,
                    };
                }
            }
        }
        ProcInfo::default()
    }
}

/// The upper-case name a call statement names: a name, `L123`, or the string of `CALL "NAME"`.
fn callee_name(line: &str, name: Span, kind: CallKind) -> Option<String> {
    let text = line.get(name.start()..name.end())?.trim();
    let text = match kind {
        // `CALL "NAME"`, and `PCALL /_N_CMA_DIR/_N_NAME_SPF` (a path, without quotes): the program
        // is the last part of the path, named the control's way or plainly.
        CallKind::Indirect => {
            let text = match text.strip_prefix('"') {
                Some(quoted) => quoted.strip_suffix('"')?,
                None => text,
            };
            let file = text.rsplit('/').next().unwrap_or(text);
            let upper = file.to_ascii_uppercase();
            let inner = upper.strip_prefix("_N_").and_then(|rest| {
                rest.strip_suffix("_SPF")
                    .or_else(|| rest.strip_suffix("_MPF"))
            });
            return inner
                .map(str::to_string)
                .or((!upper.is_empty()).then_some(upper))
                .filter(|name| !name.is_empty());
        }
        _ => text,
    };
    (!text.is_empty()).then(|| text.to_ascii_uppercase())
}

pub(super) fn evaluate_arguments(
    engine: &Engine,
    block: &Block,
    line: &str,
    args: &[Option<ExprId>],
) -> Vec<Argument> {
    args.iter()
        .map(|argument| match argument {
            None => Argument::Omitted,
            Some(id) => Argument::Given(
                evaluate(block, line, *id, &engine.state.variables)
                    .ok()
                    .flatten(),
            ),
        })
        .collect()
}

/// The dimensions and the elements (the last index counting fastest) of an array variable.
type ArrayValues = (Vec<usize>, Vec<Option<Value>>);

/// The elements of the array `name`, `None` when it is not an array (or too large to follow).
fn array_elements(variables: &Variables, name: &str) -> Option<ArrayValues> {
    let dimensions = variables.dimensions(name)?.to_vec();
    if dimensions.is_empty() {
        return None;
    }
    let total: usize = dimensions.iter().product();
    if total > crate::analysis::eval::MAX_FOLLOWED_ELEMENTS {
        return None;
    }
    let elements = (0..total)
        .map(|position| variables.value(name, &element_indexes(position, &dimensions)))
        .collect();
    Some((dimensions, elements))
}

fn store_elements(variables: &mut Variables, name: &str, (dimensions, elements): &ArrayValues) {
    for (position, element) in elements.iter().enumerate() {
        let _ = variables.assign(
            name,
            &element_indexes(position, dimensions),
            element.clone(),
        );
    }
}

/// The variable each argument names, when it is a plain variable or R parameter.
fn argument_targets(block: &Block, line: &str, args: &[Option<ExprId>]) -> Vec<Option<String>> {
    args.iter()
        .map(|argument| {
            let expr = block.expr((*argument)?);
            match &expr.kind {
                ExprKind::Name { indexes } if indexes.is_empty() => {
                    Some(line[expr.span.start()..expr.span.end()].to_ascii_uppercase())
                }
                ExprKind::RParameter(number) => Some(format!("R{number}")),
                _ => None,
            }
        })
        .collect()
}

/// The `P` of a call block: how often the subprogram runs (1 when not written or not known).
fn repetitions(engine: &Engine, block: &Block, line: &str) -> u32 {
    block
        .interpreted_statements()
        .iter()
        .find_map(|statement| match statement {
            Statement::Address(word) if word.kind == AddressKind::Repetitions => {
                match word.value.expr {
                    ValueExpr::Constant { value, .. } => Some(value),
                    ValueExpr::Expr(id) => evaluate(block, line, id, &engine.state.variables)
                        .ok()
                        .flatten(),
                    ValueExpr::Missing => None,
                }
            }
            _ => None,
        })
        .filter(|value| *value >= 1.0 && *value <= 9999.0 && value.fract() == 0.0)
        .map_or(1, |value| value as u32)
}
