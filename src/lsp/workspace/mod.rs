//! The workspace: the index of every program file the server knows, kept current in the background,
//! and the libraries through which a document's run finds the programs it calls.
//!
//! - `index.rs`: the index and what the server knows about its entries.
//! - `updates.rs`: indexing the folders, watched files, debounced updates of open documents, the
//!   cross-file findings.
//! - `library_texts.rs`: the texts of called programs read from disk.
//! - `library.rs`: `WorkspaceLibrary`, a document's called programs through the index.
//! - `call_sites.rs`: a subprogram's call sites and the state at each, for its entry state.

pub mod call_sites;
pub mod index;
pub mod library;
pub mod library_texts;
pub mod updates;
