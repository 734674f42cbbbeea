//! Go to definition, find references, rename and document highlights, across the documents of a
//! [`WorkspaceIndex`](crate::ide::workspace::WorkspaceIndex): labels and block numbers used as jump
//! targets (per program, direction-aware), `DEF` variables and `PROC` parameters (per program),
//! global `DEF`s of `.DEF` files, R parameters (channel-wide), `DEFINE` macros and programs (`PROC`
//! names, file names, calls, `EXTERN`).
//!
//! - `symbol.rs`: the symbol under a cursor and how names and calls resolve.
//! - `occurrences.rs`: every occurrence of a symbol in the workspace.
//! - `definition.rs`: definition, references, highlights.
//! - `rename.rs`: prepare-rename, rename and its collisions.
//! - `workspace_symbols.rs`: the workspace symbol search.

mod definition;
mod occurrences;
mod rename;
mod symbol;
mod workspace_symbols;

pub use definition::{definition, highlights, references};
pub use occurrences::occurrences;
pub use rename::{jump_keyword, prepare_rename, rename, RenameError, WorkspaceEdit};
pub use symbol::{resolve_call, resolve_name, symbol_at, Occurrence, Role, Symbol};
pub use workspace_symbols::{workspace_symbols, WorkspaceSymbolKind};
