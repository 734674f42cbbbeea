//! sinumerik-lsp: a language server and command-line checker for SINUMERIK NC programs.
//!
//! Layers, from the bottom: `diagnostics` (shared vocabulary), `config` (machine data), `syntax`
//! (lexer, parser, syntax diagnostics), `analysis` (modal state, resolved positions, semantic
//! diagnostics), `cli` (the command line), `lsp` (the language server). See ARCHITECTURE.md.

// `unsafe` lives in one module, `lsp/transport/sys.rs`, which alone is allowed it.
#![deny(unsafe_code)]

pub mod analysis;
pub mod cli;
pub mod config;
pub mod diagnostics;
pub mod ide;
pub mod lsp;
pub mod syntax;
