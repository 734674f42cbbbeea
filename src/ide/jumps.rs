//! Where a jump lands, shared with the interpreter: the rule lives in the syntax layer
//! (`crate::syntax::jumps`) so that navigation, the cross-file diagnostics, renumbering and execution
//! all agree on which block a jump reaches.

pub use crate::syntax::jumps::{resolve_jump, JumpResolution};
