//! The crate's only `unsafe` code: what the server does through the C library. Each piece stays
//! because it measurably helps one of the server's goal figures (`docs/performance.md`, "Transport
//! machinery, side by side"), and `SINUMERIK_LSP_MEASURE_WITHOUT` turns each off for that measurement.
//! The crate denies `unsafe_code`; `transport/mod.rs` allows it for this module alone.
//!
//! - `process.rs`: the allocator's options and the size of the stdio pipes' buffers.
//! - `frozen.rs`: bytes in pages of their own that are never written again ([`FrozenBytes`]).
//! - `stdout.rs`: the output written straight to the descriptor, frozen pages handed to a pipe with
//!   `vmsplice` instead of copied into it ([`StdoutOutput`]).

mod frozen;
mod process;
mod stdout;

pub use frozen::FrozenBytes;
pub use process::{configure_allocator, enlarge_stdio_buffers};
pub use stdout::{OutputPiece, StdoutOutput};
