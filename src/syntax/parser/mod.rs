//! The block parser: one line in, one [`Block`](crate::syntax::ast::Block) plus its syntax diagnostics
//! out. It never fails and never recurses deeper than [`MAX_EXPRESSION_DEPTH`], so hostile lines cost
//! linear time and bounded stack.
//!
//! The parser's state and token cursor are in `cursor.rs`; each grammar area adds its methods to it in
//! a file of its own, and the block checks run as a pass of their own once a block is read
//! (`block_checks.rs`). This file only declares the parts and says what the rest of the crate sees.

mod arena;
mod assignments;
mod block_checks;
mod calls;
mod checked_view;
mod conditions;
mod control_flow;
mod cursor;
#[cfg(test)]
mod declaration_tests;
mod declarations;
mod definitions;
mod expressions;
mod findings;
#[cfg(test)]
mod flow_tests;
mod layout;
mod line_parser;
mod literals;
mod modifiers;
mod names;
mod operands;
mod plain_block;
mod repeats;
mod values;
mod words;

pub use arena::MAX_TREE_HEIGHT;
pub use expressions::MAX_EXPRESSION_DEPTH;
pub use findings::MAX_DIAGNOSTICS_PER_LINE;
pub use line_parser::{parse_line, LineParser};
pub use literals::parse_number;
