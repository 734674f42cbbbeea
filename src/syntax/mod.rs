//! The syntax layer: lexer, block parser, syntax diagnostics. No IO and no protocol types: text in,
//! blocks and diagnostics out.

pub mod ast;
mod case;
pub mod context;
pub mod gcodes;
pub mod jumps;
mod keyword_lines;
pub mod keywords;
pub mod lexer;
pub mod lines;
pub mod parser;
mod program;
pub mod structure;
pub mod unconfigured_axes;

pub use ast::Block;
pub use context::SyntaxContext;
pub use keyword_lines::{lines_containing, macro_defined_by, macro_names};
pub use parser::{parse_line, LineParser};
pub use program::{check_program, visit_blocks, visit_blocks_with_macros};
