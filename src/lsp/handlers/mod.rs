//! One file per language feature: each turns a request into a call of the core (mostly `ide`) on the
//! document's analysis and converts the answer to LSP types. None of them imports another's file
//! except for shared helpers named below, and none imports the server.
//!
//! - `hover.rs`, `inlay.rs`: hover and inlay hints (`ide::hover`, `ide::inlay`): positions converted,
//!   answers wrapped.
//! - `completion.rs`, `signature.rs`, `semantic.rs`: completion items, signature help, semantic tokens.
//! - `navigation.rs`: definition, references, highlights, rename, workspace symbols.
//! - `outline.rs`: document symbols and folding ranges.
//! - `code_action.rs`: quick fixes; `config_fixes.rs`: quick fixes that edit `sinumerik.toml`; `rewrite_commands.rs`: renumber and format (with
//!   `workspace_edit.rs`, versioned workspace edits).
//! - `endpoint_preview.rs`: `sinumerik.endpointPreview`; `modal_state.rs`: `sinumerik/modalState`.

pub mod code_action;
pub mod completion;
pub mod config_fixes;
pub mod endpoint_preview;
pub mod hover;
pub mod inlay;
pub mod modal_state;
pub mod navigation;
pub mod outline;
pub mod rewrite_commands;
pub mod semantic;
pub mod signature;
pub mod workspace_edit;
