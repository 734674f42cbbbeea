//! What `fmt` and `renumber` share: collecting the files, reading each in its encoding, applying a
//! rewrite, and writing the file back in the same encoding (or, with `--check`, only telling).
//!
//! A file keeps its bytes outside what the rewrite changes: UTF-8 stays UTF-8 (with its byte-order
//! mark if it had one), a file read as Windows-1252 (which also covers GBK and other 8-bit files,
//! since every byte decodes to its own character) is encoded back byte for byte. A file that cannot
//! be written back exactly (invalid UTF-8 after a byte-order mark) is refused with a message.

use super::check::{collect_program_files, run_configs, ProblemReporter};
use super::exit_codes::{EXIT_ERRORS_FOUND, EXIT_OK, EXIT_TROUBLE};
use crate::config::MachineConfig;
use crate::io::source_file::{
    decode_source, decode_windows_1252, SourceEncoding, MAX_SOURCE_FILE_SIZE,
};
use std::collections::HashMap;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

const UTF8_BOM: &[u8] = b"\xEF\xBB\xBF";

/// The options both commands share.
pub(super) struct RewriteRun<'a> {
    pub paths: &'a [PathBuf],
    pub config_path: Option<&'a Path>,
    /// Only report which files would change (exit 1 if any), write nothing.
    pub check: bool,
    /// "reformatted", "renumbered": what the command did, for its messages.
    pub done_verb: &'static str,
}

/// Runs a rewrite over the files; `rewrite` gives the new text or an error message for a file.
pub(super) fn run_rewrite(
    run: &RewriteRun<'_>,
    rewrite: &dyn Fn(&str, &MachineConfig) -> Result<String, String>,
    stdout: &mut dyn Write,
    stderr: &mut dyn Write,
) -> io::Result<u8> {
    let mut problems = ProblemReporter {
        stderr,
        any_problem: false,
    };
    let Some(mut configs) = run_configs(run.config_path, None, &mut problems) else {
        return Ok(EXIT_TROUBLE);
    };
    let files = collect_program_files(run.paths, &mut configs, &mut problems);
    let mut changed = 0usize;
    let mut unchanged = 0usize;
    for path in &files {
        let folder = path.parent().unwrap_or(Path::new(""));
        let Some(config) = configs.for_folder(folder, &mut problems) else {
            continue;
        };
        let original = match read_file(path) {
            Ok(original) => original,
            Err(message) => {
                problems.report(format_args!("{}: {message}", path.display()));
                continue;
            }
        };
        let new_text = match rewrite(&original.text, &config) {
            Ok(new_text) => new_text,
            Err(message) => {
                problems.report(format_args!(
                    "{}: {message}; the file was not changed",
                    path.display()
                ));
                continue;
            }
        };
        if new_text == original.text {
            unchanged += 1;
            continue;
        }
        changed += 1;
        if run.check {
            writeln!(stdout, "would be {}: {}", run.done_verb, path.display())?;
            continue;
        }
        let result = encode(&new_text, &original).and_then(|bytes| write_in_place(path, &bytes));
        match result {
            Ok(()) => writeln!(stdout, "{}: {}", run.done_verb, path.display())?,
            Err(message) => problems.report(format_args!(
                "{}: {message}; the file was not changed",
                path.display()
            )),
        }
    }
    let files_word = |count: usize| if count == 1 { "file" } else { "files" };
    let summary = if run.check {
        format!("would be {}", run.done_verb)
    } else {
        run.done_verb.to_string()
    };
    writeln!(
        stdout,
        "{changed} {} {summary}, {unchanged} {} unchanged",
        files_word(changed),
        files_word(unchanged)
    )?;
    Ok(if problems.any_problem {
        EXIT_TROUBLE
    } else if run.check && changed > 0 {
        EXIT_ERRORS_FOUND
    } else {
        EXIT_OK
    })
}

/// A program file as read, with what is needed to write it back in its own encoding.
struct OriginalFile {
    text: String,
    encoding: SourceEncoding,
    had_bom: bool,
}

fn read_file(path: &Path) -> Result<OriginalFile, String> {
    let size = std::fs::metadata(path)
        .map_err(|error| error.to_string())?
        .len();
    if size > MAX_SOURCE_FILE_SIZE {
        return Err(format!(
            "the file is too large to be a part program ({} MiB)",
            size.div_ceil(1024 * 1024)
        ));
    }
    let bytes = std::fs::read(path).map_err(|error| error.to_string())?;
    let decoded = decode_source(&bytes);
    let original = OriginalFile {
        text: decoded.text,
        encoding: decoded.encoding,
        had_bom: bytes.starts_with(UTF8_BOM),
    };
    // Refuse up front what could not be written back exactly.
    if original.encoding == SourceEncoding::Utf8Lossy {
        return Err("the file has a UTF-8 byte-order mark but is not valid UTF-8, so it cannot be rewritten without changing bytes; it was not changed".to_string());
    }
    match encode(&original.text, &original) {
        Ok(round_trip) if round_trip == bytes => Ok(original),
        _ => Err(
            "the file's encoding cannot be reproduced byte for byte, so it is not rewritten"
                .to_string(),
        ),
    }
}

/// The bytes of `text` in the original file's encoding.
fn encode(text: &str, original: &OriginalFile) -> Result<Vec<u8>, String> {
    match original.encoding {
        SourceEncoding::Utf8 => {
            let mut bytes = Vec::with_capacity(text.len() + 3);
            if original.had_bom {
                bytes.extend_from_slice(UTF8_BOM);
            }
            bytes.extend_from_slice(text.as_bytes());
            Ok(bytes)
        }
        SourceEncoding::Windows1252 => {
            let table = windows_1252_encoder();
            text.chars()
                .map(|character| {
                    table.get(&character).copied().ok_or_else(|| {
                        format!(
                            "the character {character:?} has no byte in the file's 8-bit encoding"
                        )
                    })
                })
                .collect()
        }
        SourceEncoding::Utf8Lossy => {
            Err("the file is not valid UTF-8 after its byte-order mark".to_string())
        }
    }
}

/// The inverse of `decode_windows_1252`: every one of the 256 bytes decodes to its own character.
fn windows_1252_encoder() -> &'static HashMap<char, u8> {
    static TABLE: std::sync::OnceLock<HashMap<char, u8>> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let all_bytes: Vec<u8> = (0..=255).collect();
        decode_windows_1252(&all_bytes)
            .chars()
            .zip(all_bytes)
            .collect()
    })
}

/// Writes a temporary file beside the target and renames it over the target, so that a failed write
/// never leaves half a program behind.
fn write_in_place(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let file_name = path
        .file_name()
        .map(|name| name.to_string_lossy().into_owned())
        .unwrap_or_default();
    let temporary = path.with_file_name(format!(".{file_name}.sinumerik-lsp.tmp"));
    std::fs::write(&temporary, bytes).map_err(|error| format!("cannot write: {error}"))?;
    if let Ok(metadata) = std::fs::metadata(path) {
        let _ = std::fs::set_permissions(&temporary, metadata.permissions());
    }
    std::fs::rename(&temporary, path).map_err(|error| {
        let _ = std::fs::remove_file(&temporary);
        format!("cannot replace the file: {error}")
    })
}
