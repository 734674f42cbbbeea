//! Applies one parsed block to the modal state, the way the control's interpreter does, and describes
//! the resulting move. What this engine does not model (spatial rotations, basic frames, calls of
//! subprograms, jumps) turns the affected values into "unknown" or "uncertain": it never shows a
//! number it cannot stand behind.
//!
//! This file only declares the engine's files and re-exports what the rest of the crate uses: the
//! `Engine` struct lives in `engine/engine_state.rs`, one block's step in `engine/step*.rs`, the
//! description of a move in `engine/moves.rs`, checkpoints in `engine/snapshot.rs`. Files of the
//! engine import each other by their own paths, never through this file.

mod assignments;
mod axis_words;
mod block_words;
mod checks;
mod circle_checks;
mod circles;
mod contours;
pub(crate) mod corner_requests;
mod definitions;
pub(crate) mod engine_state;
pub(crate) mod evaluation;
mod frame_variables;
mod frames;
mod indirect_axes;
mod join;
mod machine_checks;
pub(crate) mod macros;
pub(crate) mod moves;
mod polar;
pub(crate) mod snapshot;
pub mod spindle;
mod step;
mod step_motion;
mod step_words;
pub(crate) mod timing;

pub use corner_requests::{ContourRequest, CornerElement, OpenAngle};
pub use engine_state::Engine;
pub use moves::{ArcMove, Move};
pub use snapshot::{EngineSnapshot, PositionShift};
