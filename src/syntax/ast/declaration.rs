//! Declarations: the data types, the names of a `DEF` with their sizes and initial values, and the
//! parameters of a `PROC` header.

use crate::diagnostics::Span;
use crate::syntax::ast::expr::ExprId;

/// The data types of `DEF` and of `PROC` parameters (reference §8.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DataType {
    Int,
    Real,
    Bool,
    Char,
    /// `STRING[n]`; the length is not kept.
    String,
    Axis,
    Frame,
}

impl DataType {
    /// The type a name (in upper case) stands for.
    pub fn from_name(upper: &str) -> Option<DataType> {
        Some(match upper {
            "INT" => DataType::Int,
            "REAL" => DataType::Real,
            "BOOL" => DataType::Bool,
            "CHAR" => DataType::Char,
            "STRING" => DataType::String,
            "AXIS" => DataType::Axis,
            "FRAME" => DataType::Frame,
            _ => return None,
        })
    }
}

/// One name of a `DEF` with its array sizes and initial value: `TAB[3,4]=REP(0)`.
#[derive(Debug, Clone, PartialEq)]
pub struct Declarator {
    /// The whole name, also where `names` has only its first letter (`V1AR`, reported as S162).
    pub name: Span,
    /// The array sizes, one per dimension (the control allows up to three); empty for a scalar.
    pub dimensions: Vec<ExprId>,
    pub initial: Option<Initializer>,
}

/// The initial value of a `DEF` name.
#[derive(Debug, Clone, PartialEq)]
pub enum Initializer {
    /// `=5`, `="ABC"`, `=X`: one value.
    Value(ExprId),
    /// `=(1,2,3)` for an array: its elements in order; an empty element (`(1,,3)`) is `None`.
    List(Vec<Option<ExprId>>),
    /// `=SET(1,2,3)`: the same as a list.
    Set(Vec<Option<ExprId>>),
    /// `=REP(value)` fills the whole array, `=REP(value, count)` its first `count` elements.
    Repeat {
        value: ExprId,
        count: Option<ExprId>,
    },
}

/// One parameter of a `PROC` header: `REAL PA=5`, `VAR REAL TAB[,]`.
#[derive(Debug, Clone, PartialEq)]
pub struct ProcParameter {
    pub name: Span,
    pub data_type: Option<DataType>,
    /// `VAR`: passed by reference, the caller must give a variable.
    pub by_reference: bool,
    /// The number of array dimensions: 1 for `A[]`, 2 for `A[,]`, 0 for a scalar.
    pub dimensions: usize,
    /// The value an omitted argument takes (`PROC SUB(REAL PA=5)`).
    pub default: Option<ExprId>,
}
