//! sinumerik-lsp: a language server and command-line checker for SINUMERIK NC programs.
//!
//! Layers, from the bottom: `diagnostics` (shared vocabulary), `config` (machine data), `syntax`
//! (lexer, parser, syntax diagnostics), `analysis` (modal state, resolved positions, semantic
//! diagnostics), `ide` (the language features), `io` (reading program files, the preview's JSON), then
//! side by side `cli` (the command line) and `lsp` (the language server), which `main.rs` chooses
//! between. See ARCHITECTURE.md.

// `unsafe` lives in one module, `lsp/transport/sys/`, which alone is allowed it.
#![deny(unsafe_code)]

pub mod analysis;
pub mod cli;
pub mod config;
pub mod diagnostics;
pub mod ide;
pub mod io;
pub mod lsp;
pub mod syntax;
