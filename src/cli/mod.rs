//! The command line of `sinumerik-lsp`: argument parsing, the `check` command and its output.
//!
//! - `args.rs`: turns the arguments into a command, without touching the filesystem.
//! - `check.rs`: the `check` command: walking folders, finding each file's `sinumerik.toml`, running
//!   the checker, exit codes.
//! - `report.rs`: the human and JSON output formats and the byte-span to character-column conversion.
//! - `formats/`: the output formats of `check` as one interface: human, JSON, SARIF, GitHub workflow
//!   commands, GitLab Code Quality.
//! - `library.rs`: the programs a program calls, found in its folder, the parents up to its
//!   `sinumerik.toml` and the `--cycles` folders.
//! - `fmt.rs`, `renumber.rs`: the rewriting commands; `rewrite.rs`: what they share (writing a file
//!   back in its own encoding, `--check`).
//!
//! ```text
//! sinumerik-lsp check [--format human|json|sarif|github|gitlab] [--config FILE] [--extensions mpf,spf] [--cycles DIR]... PATH...
//! sinumerik-lsp --help | --version
//! ```
//!
//! Exit codes of `check`:
//! - 0: no diagnostic of severity error (warnings and infos do not fail a run);
//! - 1: at least one diagnostic of severity error;
//! - 2: a usage error, a path that cannot be read, a configuration file that cannot be used, a folder
//!   without program files, or a file over 256 MiB. The other files are still checked and reported, so
//!   2 wins over 1 only to say that the run was incomplete.
//!
//! This is the only module (with the language server's) that does IO and knows output formats; the
//! checker itself works on plain text and returns plain values.

mod args;
mod check;
mod check_index;
mod command_line;
mod exit_codes;
mod fmt;
mod formats;
pub mod library;
pub(crate) mod preview;
mod preview_svg;
mod renumber;
mod report;
mod rewrite;
/// Reading program files lives in `crate::io` (the server reads them too); this name stays so that
/// code written against the command line's module keeps compiling.
pub use crate::io::source_file;

pub use command_line::{run, run_with_output, wants_language_server};
pub use exit_codes::{EXIT_ERRORS_FOUND, EXIT_OK, EXIT_TROUBLE};
