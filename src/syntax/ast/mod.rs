//! The parsed form of one block. A block owns its expression nodes in a small arena (`exprs`) so that a
//! caller can reuse one `Block` for every line of a program without allocating again.
//!
//! The types are grouped by concern, one file each; the rest of the crate names them through this
//! module.

mod address;
mod block;
mod declaration;
mod expr;
mod statement;

pub use address::{AddressKind, AddressWord, Extension, Modifier, NamedAddress, Value, ValueExpr};
pub use block::{Block, BlockNumber};
pub use declaration::{DataType, Declarator, Initializer, ProcParameter};
pub use expr::{BinaryOp, Expr, ExprId, ExprKind, UnaryOp};
pub use statement::{AssignTarget, CallKind, JumpKind, JumpTarget, Statement, StructureKeyword};
