//! What the interpreter keeps for the cycle models between blocks, and which drilling cycles have a
//! built-in model.

use super::drilling::DRILLING_CYCLES;
use crate::syntax::SyntaxContext;
use std::sync::Arc;

/// What the interpreter keeps for the cycle models.
#[derive(Default)]
pub(crate) struct CycleState {
    /// The cycle whose blocks are running: its moves say so.
    pub(crate) current: Option<Arc<str>>,
    /// How the cycles' blocks are read, made once per run.
    pub(super) context: Option<SyntaxContext>,
}

/// Whether `name` (upper case) is a drilling cycle with a built-in model.
pub(crate) fn is_drilling(name: &str) -> bool {
    DRILLING_CYCLES.contains(&name)
}
