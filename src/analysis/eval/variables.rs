//! What is known about the variables of a program at one point: R parameters, and user variables with
//! their type and array shape (reference §8.1). Values are `None` where unknown.
//!
//! The document analysis keeps a copy of the state every 512 blocks, so a copy must be cheap: names are
//! shared (`Arc<str>`), arrays are shared until one copy writes to them, and arrays too large to follow
//! keep only their shape.

use super::array::{Array, IndexError, MAX_DIMENSIONS};
use super::value::{round_half_away, Value, INT_RANGE};
pub use super::var_type::VarType;
use std::collections::HashMap;
use std::sync::Arc;

/// Why a definition was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DefineError {
    /// The name is defined already at this program level (alarm 12170).
    AlreadyDefined,
    /// More than [`MAX_DIMENSIONS`] dimensions.
    TooManyDimensions,
    /// A dimension of size 0.
    EmptyDimension,
}

/// Why an assignment did not store its value. After `ValueOutOfRange` the element is unknown; after the
/// others nothing was written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AssignError {
    /// Indexes were given for a name without a definition the analysis has seen.
    NotDefined,
    Index(IndexError),
    /// The value does not fit the type (an INT beyond 32 bits, a CHAR beyond 0 to 255).
    ValueOutOfRange(VarType),
}

/// The R parameters and user variables known at a point of the program.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Variables {
    r_parameters: HashMap<u32, f64>,
    /// User variables by upper-case name.
    named: HashMap<Arc<str>, Variable>,
}

/// The defined variables of one program level, put aside while a subprogram runs.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Locals {
    variables: HashMap<Arc<str>, Variable>,
}

impl Locals {
    pub fn is_empty(&self) -> bool {
        self.variables.is_empty()
    }

    /// Where two ways meet while a subprogram runs: the caller's variables put aside on each way,
    /// joined as [`Variables::join`] joins.
    pub fn join(&mut self, other: &Locals) {
        for (name, variable) in self.variables.iter_mut() {
            match other.variables.get(name) {
                Some(other_variable) if variable.same_shape(other_variable) => {
                    variable.join(other_variable)
                }
                _ => variable.forget(),
            }
        }
        for (name, other_variable) in &other.variables {
            if !self.variables.contains_key(name) {
                let mut variable = other_variable.clone();
                variable.forget();
                self.variables.insert(name.clone(), variable);
            }
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
struct Variable {
    /// `None` for a name the program assigns without a definition the analysis has seen (a global
    /// variable of a definition file, or a mistake): it holds any value as written.
    var_type: Option<VarType>,
    cells: Cells,
}

#[derive(Debug, Clone)]
enum Cells {
    Scalar(Option<Value>),
    Array(Arc<Array>),
}

impl PartialEq for Cells {
    fn eq(&self, other: &Cells) -> bool {
        match (self, other) {
            (Cells::Scalar(left), Cells::Scalar(right)) => left == right,
            (Cells::Array(left), Cells::Array(right)) => Arc::ptr_eq(left, right) || left == right,
            _ => false,
        }
    }
}

impl Variable {
    fn untyped(value: Option<Value>) -> Variable {
        Variable {
            var_type: None,
            cells: Cells::Scalar(value),
        }
    }

    fn read(&self, indexes: &[usize]) -> Result<Option<Value>, IndexError> {
        match &self.cells {
            Cells::Scalar(value) if indexes.is_empty() => Ok(value.clone()),
            Cells::Scalar(_) => Err(IndexError::Count { expected: 0 }),
            Cells::Array(array) => Ok(array.get(array.offset(indexes)?)),
        }
    }

    fn assign(&mut self, indexes: &[usize], value: Option<Value>) -> Result<(), AssignError> {
        match &mut self.cells {
            Cells::Scalar(slot) => {
                if !indexes.is_empty() {
                    return Err(AssignError::Index(IndexError::Count { expected: 0 }));
                }
                let (value, result) = convert(self.var_type, value);
                *slot = value;
                result
            }
            Cells::Array(array) => {
                let offset = array.offset(indexes).map_err(AssignError::Index)?;
                let (value, result) = convert(self.var_type, value);
                // A write that changes nothing leaves an array shared with copies of the state.
                if array.get(offset) != value {
                    let var_type = self.var_type.unwrap_or(VarType::Real);
                    Arc::make_mut(array).set(offset, value, var_type);
                }
                result
            }
        }
    }

    fn forget(&mut self) {
        match &mut self.cells {
            Cells::Scalar(value) => *value = None,
            Cells::Array(array) => {
                if !array.is_unknown() {
                    *array = Arc::new(array.unknown_like());
                }
            }
        }
    }

    fn same_shape(&self, other: &Variable) -> bool {
        self.var_type == other.var_type
            && match (&self.cells, &other.cells) {
                (Cells::Scalar(_), Cells::Scalar(_)) => true,
                (Cells::Array(left), Cells::Array(right)) => left.same_shape(right),
                _ => false,
            }
    }

    /// Keeps the values both ways agree on; the shapes are the same.
    fn join(&mut self, other: &Variable) {
        match (&mut self.cells, &other.cells) {
            (Cells::Scalar(value), Cells::Scalar(other_value)) => {
                if value != other_value {
                    *value = None;
                }
            }
            (Cells::Array(array), Cells::Array(other_array)) => {
                if array.is_unknown() || Arc::ptr_eq(array, other_array) || **array == **other_array
                {
                    return;
                }
                if other_array.is_unknown() {
                    self.forget();
                    return;
                }
                let joined = Arc::make_mut(array);
                let var_type = self.var_type.unwrap_or(VarType::Real);
                for offset in 0..joined.followed_len() {
                    if joined.get(offset) != other_array.get(offset) {
                        joined.set(offset, None, var_type);
                    }
                }
            }
            _ => self.forget(),
        }
    }
}

/// The value `value` becomes when stored in a variable of `var_type`, and whether it fit. INT and CHAR
/// round half away from zero like the control; BOOL stores 0 or 1. A text stored in a number or a
/// number stored in a text is unknown: the control's conversion is not followed.
fn convert(
    var_type: Option<VarType>,
    value: Option<Value>,
) -> (Option<Value>, Result<(), AssignError>) {
    let Some(value) = value else {
        return (None, Ok(()));
    };
    let Some(var_type) = var_type else {
        let finite = value.number().is_none_or(f64::is_finite);
        return (finite.then_some(value), Ok(()));
    };
    let whole_in = |number: f64, range: std::ops::RangeInclusive<f64>| {
        let rounded = round_half_away(number);
        if range.contains(&rounded) {
            (Some(Value::Number(rounded)), Ok(()))
        } else {
            (None, Err(AssignError::ValueOutOfRange(var_type)))
        }
    };
    match (var_type, value) {
        (VarType::Int, Value::Number(number)) => whole_in(number, INT_RANGE),
        (VarType::Char, Value::Number(number)) => whole_in(number, 0.0..=255.0),
        (VarType::Real, Value::Number(number)) => (Some(Value::Number(number)), Ok(())),
        (VarType::Bool, Value::Number(number)) => (Some(Value::from_bool(number != 0.0)), Ok(())),
        (VarType::Text | VarType::Axis, Value::Text(text)) => (Some(Value::Text(text)), Ok(())),
        _ => (None, Ok(())),
    }
}

impl Variables {
    pub fn r_parameter(&self, number: u32) -> Option<f64> {
        self.r_parameters.get(&number).copied()
    }

    pub fn set_r_parameter(&mut self, number: u32, value: Option<f64>) {
        match value.filter(|value| value.is_finite()) {
            Some(value) => {
                self.r_parameters.insert(number, value);
            }
            None => {
                self.r_parameters.remove(&number);
            }
        }
    }

    /// Every R parameter unknown: a write whose index is unknown may have changed any of them.
    pub fn forget_r_parameters(&mut self) {
        self.r_parameters.clear();
    }

    /// Defines a variable of `var_type`, an array when `dimensions` is not empty, with every element at
    /// the zero of the type. A name only assigned so far (without a definition) takes the definition.
    pub fn define(
        &mut self,
        upper_name: &str,
        var_type: VarType,
        dimensions: &[usize],
    ) -> Result<(), DefineError> {
        if dimensions.len() > MAX_DIMENSIONS {
            return Err(DefineError::TooManyDimensions);
        }
        if dimensions.contains(&0) {
            return Err(DefineError::EmptyDimension);
        }
        if self
            .named
            .get(upper_name)
            .is_some_and(|variable| variable.var_type.is_some())
        {
            return Err(DefineError::AlreadyDefined);
        }
        let cells = if dimensions.is_empty() {
            Cells::Scalar(var_type.zero())
        } else {
            Cells::Array(Arc::new(Array::new(var_type, dimensions)))
        };
        self.named.insert(
            Arc::from(upper_name),
            Variable {
                var_type: Some(var_type),
                cells,
            },
        );
        Ok(())
    }

    /// Stores `value` (`None`: unknown) in the variable or, with `indexes` (0-based), in one element,
    /// converted to the variable's type. A name without definition is created as a scalar that holds
    /// any value.
    pub fn assign(
        &mut self,
        upper_name: &str,
        indexes: &[usize],
        value: Option<Value>,
    ) -> Result<(), AssignError> {
        match self.named.get_mut(upper_name) {
            Some(variable) => variable.assign(indexes, value),
            None if indexes.is_empty() => {
                let (value, result) = convert(None, value);
                self.named
                    .insert(Arc::from(upper_name), Variable::untyped(value));
                result
            }
            None => Err(AssignError::NotDefined),
        }
    }

    /// The value of the variable or of one element; `None` when unknown, not defined, or when the
    /// indexes do not select an element.
    pub fn value(&self, upper_name: &str, indexes: &[usize]) -> Option<Value> {
        self.read(upper_name, indexes).ok().flatten()
    }

    /// Like [`Variables::value`], but says when the indexes do not fit the variable's shape.
    pub fn read(&self, upper_name: &str, indexes: &[usize]) -> Result<Option<Value>, IndexError> {
        match self.named.get(upper_name) {
            Some(variable) => variable.read(indexes),
            None => Ok(None),
        }
    }

    /// The type of a defined variable (`None` also for a name assigned without definition).
    pub fn var_type(&self, upper_name: &str) -> Option<VarType> {
        self.named.get(upper_name)?.var_type
    }

    /// The sizes of the dimensions of a known variable: empty for a scalar.
    pub fn dimensions(&self, upper_name: &str) -> Option<&[usize]> {
        match &self.named.get(upper_name)?.cells {
            Cells::Scalar(_) => Some(&[]),
            Cells::Array(array) => Some(array.dimensions()),
        }
    }

    /// The numeric value of a scalar variable.
    pub fn variable(&self, upper_name: &str) -> Option<f64> {
        self.value(upper_name, &[])?.number()
    }

    /// Sets a scalar variable to a number (`None`: unknown), converted to its type; a name without
    /// definition is created. An array given here becomes unknown, as the write is not understood.
    pub fn set_variable(&mut self, upper_name: &str, value: Option<f64>) {
        let value = value.map(Value::Number);
        match self.named.get_mut(upper_name) {
            Some(variable) if matches!(variable.cells, Cells::Array(_)) => variable.forget(),
            Some(variable) => {
                // A value out of the type's range leaves the variable unknown, which is all a caller
                // without error handling can want.
                let _ = variable.assign(&[], value);
            }
            None => {
                let (value, _) = convert(None, value);
                self.named
                    .insert(Arc::from(upper_name), Variable::untyped(value));
            }
        }
    }

    /// The variable's values become unknown; its definition stays.
    pub fn forget_variable(&mut self, upper_name: &str) {
        if let Some(variable) = self.named.get_mut(upper_name) {
            variable.forget();
        }
    }

    /// Forgets every value: after a call of an unknown subprogram, anything may have changed. The
    /// definitions stay.
    pub fn forget_all(&mut self) {
        self.r_parameters.clear();
        for variable in self.named.values_mut() {
            variable.forget();
        }
    }

    /// Forgets what a called program without arguments can write: the R parameters and the names
    /// assigned without a definition (global data); the variables this level defined stay
    /// (reference §17.6, MD11120 = 0).
    pub fn forget_global(&mut self) {
        self.r_parameters.clear();
        for variable in self.named.values_mut() {
            if variable.var_type.is_none() {
                variable.forget();
            }
        }
    }

    /// Puts aside the defined variables of the running program level when it calls a subprogram (LUD
    /// variables belong to their level, reference §17.6); R parameters and names assigned without a
    /// definition (global variables) stay visible.
    pub fn take_locals(&mut self) -> Locals {
        let (variables, globals) = std::mem::take(&mut self.named)
            .into_iter()
            .partition(|(_, variable)| variable.var_type.is_some());
        self.named = globals;
        Locals { variables }
    }

    /// Returns from a subprogram: its defined variables end, the caller's come back. A name the
    /// subprogram assigned without defining it that is also a variable of the caller may have been the
    /// caller's variable (program-global user data, MD11120), so that variable becomes unknown.
    pub fn restore_locals(&mut self, locals: Locals) {
        let callee = std::mem::replace(&mut self.named, locals.variables);
        for (name, variable) in callee {
            if variable.var_type.is_some() {
                continue;
            }
            match self.named.get_mut(&name) {
                Some(caller) => caller.forget(),
                None => {
                    self.named.insert(name, variable);
                }
            }
        }
    }

    /// Where two ways through the program meet: what differs between them, or is known on one way
    /// only, becomes unknown.
    pub fn join(&mut self, other: &Variables) {
        self.r_parameters
            .retain(|number, value| other.r_parameters.get(number) == Some(value));
        for (name, variable) in self.named.iter_mut() {
            match other.named.get(name) {
                Some(other_variable) if variable.same_shape(other_variable) => {
                    variable.join(other_variable)
                }
                _ => variable.forget(),
            }
        }
        for (name, other_variable) in &other.named {
            if !self.named.contains_key(name) {
                let mut variable = other_variable.clone();
                variable.forget();
                self.named.insert(name.clone(), variable);
            }
        }
    }
}
