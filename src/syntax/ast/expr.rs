//! Expressions: the nodes of a block's arena (`Block::exprs`), addressed by [`ExprId`], with their
//! operators.

use crate::diagnostics::Span;

/// Index of an expression node in `Block::exprs`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ExprId(pub u32);

/// A binary operator, in the control's precedence order (see `Expr`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinaryOp {
    Multiply,
    Divide,
    IntegerDivide,
    Modulo,
    Add,
    Subtract,
    BitAnd,
    BitXor,
    BitOr,
    And,
    Xor,
    Or,
    Concat,
    Equal,
    NotEqual,
    Less,
    Greater,
    LessEqual,
    GreaterEqual,
    /// The frame chain operator `:`.
    Chain,
}

impl BinaryOp {
    pub fn is_logical(self) -> bool {
        matches!(
            self,
            BinaryOp::And
                | BinaryOp::Or
                | BinaryOp::Xor
                | BinaryOp::BitAnd
                | BinaryOp::BitOr
                | BinaryOp::BitXor
        )
    }

    pub fn is_comparison(self) -> bool {
        matches!(
            self,
            BinaryOp::Equal
                | BinaryOp::NotEqual
                | BinaryOp::Less
                | BinaryOp::Greater
                | BinaryOp::LessEqual
                | BinaryOp::GreaterEqual
        )
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnaryOp {
    Negate,
    Plus,
    Not,
    BitNot,
    /// `<<` with a right operand only: converts the operand to a string.
    ToString,
}

/// One expression node.
#[derive(Debug, Clone, PartialEq)]
pub enum ExprKind {
    Number(f64),
    /// A string literal; the span (of the node) includes the quotes.
    String,
    /// `R1`, also written `$R1` in synchronized actions.
    RParameter(u32),
    /// `R[expr]`.
    RParameterIndexed(ExprId),
    /// A name: variable, parameter, axis (`X`, `X1`, `SP1`), constant (`TRUE`). `indexes` holds the
    /// `[...]` arguments when present.
    Name {
        indexes: Vec<ExprId>,
    },
    /// A system variable such as `$P_GG[13]`.
    SystemVariable {
        indexes: Vec<ExprId>,
    },
    /// A function call `NAME(args)`; empty arguments (`F(1,,3)`) are `None`.
    Call {
        name: Span,
        args: Vec<Option<ExprId>>,
    },
    Unary(UnaryOp, ExprId),
    Binary(BinaryOp, ExprId, ExprId),
    Parenthesized(ExprId),
    /// `(a, b, c)`: a list of values, as some instructions take (`OSCTRL[Z]=(1,2)`).
    List(Vec<ExprId>),
    /// Something that could not be parsed; a diagnostic has been reported.
    Error,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
}
