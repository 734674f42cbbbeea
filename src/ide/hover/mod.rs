//! The hover: plain functions over the analysis's block reports and the parser's words, in one file
//! per concern. This file only declares them and re-exports.
//!
//! - `hover_at.rs`: the hover at a place (which word, what the run and the times add).
//! - `axis.rs`: an axis word's hover; `resolution.rs`: how one resolved value is explained (the sum,
//!   inch, diameter, DIAM90 increments, G53/G153/SUPA, why it is unknown).
//! - `gcode.rs`: a G function's hover; `block.rs`: the block's modal state and end point.

pub mod axis;
pub mod block;
pub mod gcode;
pub mod hover_at;
pub mod resolution;

pub use hover_at::{hover_at, HoverText};
