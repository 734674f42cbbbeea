//! The type of a user variable (reference §8.1): as declared, the value it starts with, and whether it
//! holds text.

use super::value::Value;
use std::sync::Arc;

/// The type of a user variable (reference §8.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum VarType {
    Int,
    Real,
    Bool,
    Char,
    /// STRING[n]; the length limit is not followed.
    Text,
    /// An axis name, held as text.
    Axis,
    /// Frames are not followed as values: a FRAME variable is always unknown.
    Frame,
}

impl VarType {
    /// The type of a `DEF` or `PROC` parameter as declared; REAL when no type is written.
    pub fn of_declared(data_type: Option<crate::syntax::ast::DataType>) -> VarType {
        use crate::syntax::ast::DataType;
        match data_type {
            Some(DataType::Int) => VarType::Int,
            Some(DataType::Bool) => VarType::Bool,
            Some(DataType::Char) => VarType::Char,
            Some(DataType::String) => VarType::Text,
            Some(DataType::Axis) => VarType::Axis,
            Some(DataType::Frame) => VarType::Frame,
            Some(DataType::Real) | None => VarType::Real,
        }
    }
}

impl VarType {
    /// The value a variable starts with: LUD variables start at the zero of their type (reference §8.1,
    /// §17.1): 0, FALSE, the empty string. What an AXIS variable holds before its first assignment is
    /// not documented, and frames are not followed, so those start unknown.
    pub(super) fn zero(self) -> Option<Value> {
        match self {
            VarType::Int | VarType::Real | VarType::Bool | VarType::Char => {
                Some(Value::Number(0.0))
            }
            VarType::Text => Some(Value::Text(Arc::from(""))),
            VarType::Axis | VarType::Frame => None,
        }
    }

    pub(super) fn holds_text(self) -> bool {
        matches!(self, VarType::Text | VarType::Axis)
    }
}
