//! The block's expression arena as the parser fills it: every node is pushed with its height, and a
//! tree that would grow higher than [`MAX_TREE_HEIGHT`] gets an error node instead.

use crate::diagnostics::{Code, Span};
use crate::syntax::ast::{Expr, ExprId, ExprKind};
use crate::syntax::parser::cursor::Parser;

/// How high the tree of one expression may grow (a leaf is 1, `a+b` is 2). Chains such as
/// `1+1+1+...` are parsed in a loop and grow the tree without deepening the parser's recursion, so
/// this bound is what keeps every recursive walk of the tree (evaluation, formatting, checks) within a
/// small, fixed stack, whatever the length of the line.
pub const MAX_TREE_HEIGHT: u32 = 256;

impl Parser<'_> {
    pub(super) fn push_expr(&mut self, kind: ExprKind, span: Span) -> ExprId {
        let height = self.height_of(&kind);
        let kind = if height > MAX_TREE_HEIGHT {
            self.report_too_long(span);
            ExprKind::Error
        } else {
            kind
        };
        let height = if matches!(kind, ExprKind::Error) {
            1
        } else {
            height
        };
        self.block.exprs.push(Expr { kind, span });
        self.heights.push(height);
        ExprId(self.block.exprs.len() as u32 - 1)
    }

    /// The height of a node of `kind`: one more than its highest child. A chain of operators
    /// (`1+1+1+...`) is built by a loop, not by recursion, so only this height bounds the depth of the
    /// tree that evaluation and other walks recurse over.
    pub(super) fn height_of(&self, kind: &ExprKind) -> u32 {
        let child = |id: &ExprId| self.heights.get(id.0 as usize).copied().unwrap_or(1);
        let highest = match kind {
            ExprKind::RParameterIndexed(inner)
            | ExprKind::Unary(_, inner)
            | ExprKind::Parenthesized(inner) => child(inner),
            ExprKind::Binary(_, left, right) => child(left).max(child(right)),
            ExprKind::Name { indexes } | ExprKind::SystemVariable { indexes } => {
                indexes.iter().map(child).max().unwrap_or(0)
            }
            ExprKind::Call { args, .. } => args.iter().flatten().map(child).max().unwrap_or(0),
            ExprKind::List(items) => items.iter().map(child).max().unwrap_or(0),
            _ => 0,
        };
        highest.saturating_add(1)
    }

    /// Reports, once per block, an expression with more than [`MAX_TREE_HEIGHT`] operations nested
    /// in each other; the node becomes an error node, so its value is unknown.
    pub(super) fn report_too_long(&mut self, span: Span) {
        // One S170 per block, whether the parser's nesting or the tree's height was exceeded first.
        if self.depth_reported {
            return;
        }
        self.depth_reported = true;
        self.report(
            Code::TooDeeplyNested,
            span,
            format!("this expression chains more than {MAX_TREE_HEIGHT} operations; its value is not evaluated"),
        );
    }

    pub(super) fn expr_span(&self, id: ExprId) -> Span {
        self.block.exprs[id.0 as usize].span
    }
}
