//! What the command line and the language server both need of the world outside the core: reading
//! program files from disk, and the preview's JSON document. Both sit above `analysis` and `ide`
//! and below `cli` and `lsp`, so that neither of those two imports the other.
//!
//! - `source_file.rs`: reading program files: size limit, UTF-8 with Windows-1252 fallback, BOM.
//! - `preview_json.rs`: the moves of a program as the preview's JSON, written move by move.

pub mod preview_json;
pub mod source_file;
