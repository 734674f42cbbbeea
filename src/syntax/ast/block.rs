//! One parsed line: its skip level, block number, label, statements and comment, with the arena of
//! its expression nodes.

use crate::diagnostics::Span;
use crate::syntax::ast::expr::{Expr, ExprId};
use crate::syntax::ast::statement::Statement;

/// `N10` or `:10` at the start of a block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BlockNumber {
    pub value: u64,
    /// `:10` marks a main block.
    pub main: bool,
    pub span: Span,
}

/// One parsed line. Spans are byte offsets into the line.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Block {
    /// Skip level (`/` is level 0) and the span of the marker.
    pub skip: Option<(u8, Span)>,
    pub number: Option<BlockNumber>,
    /// The label name, without its colon.
    pub label: Option<Span>,
    pub statements: Vec<Statement>,
    pub comment: Option<Span>,
    /// Index in `statements` from which on the statements are actions of a synchronized action.
    pub sync_actions_from: Option<usize>,
    /// The line is a program header in punched-tape format (`%_N_NAME_MPF`).
    pub is_header: bool,
    pub exprs: Vec<Expr>,
}

impl Block {
    /// Empties the block but keeps its allocations for the next line.
    pub fn clear(&mut self) {
        self.skip = None;
        self.number = None;
        self.label = None;
        self.statements.clear();
        self.comment = None;
        self.sync_actions_from = None;
        self.is_header = false;
        self.exprs.clear();
    }

    pub fn expr(&self, id: ExprId) -> &Expr {
        &self.exprs[id.0 as usize]
    }

    /// The statements the interpreter executes (not the main-run actions of a synchronized action).
    pub fn interpreted_statements(&self) -> &[Statement] {
        match self.sync_actions_from {
            Some(index) => &self.statements[..index],
            None => &self.statements,
        }
    }
}
