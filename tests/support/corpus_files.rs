//! The real programs of `../shared/corpus/real` for tests: where they are, which are known to be
//! invalid (`tests/corpus_known_invalid.txt`), and the program files of a folder in a stable order.

// Each test file uses the part it needs.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

pub fn corpus_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/corpus/real")
}

/// `*` in a pattern of the known-invalid list matches any run of characters.
pub fn glob_matches(pattern: &str, text: &str) -> bool {
    match pattern.split_once('*') {
        None => pattern == text,
        Some((head, tail)) => {
            text.starts_with(head)
                && text.len() >= head.len() + tail.len()
                && (0..=text.len() - head.len()).any(|skip| {
                    text.get(head.len() + skip..)
                        .is_some_and(|rest| glob_matches(tail, rest))
                })
        }
    }
}

/// The path patterns of the known-invalid list, relative to the corpus folder.
pub fn known_invalid() -> Vec<String> {
    let list = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus_known_invalid.txt"),
    )
    .expect("the known-invalid list is readable");
    list.lines()
        .filter(|line| !line.trim().is_empty() && !line.starts_with('#'))
        .filter_map(|line| {
            line.split_once('\t')
                .map(|(path, _)| path.trim().to_string())
        })
        .collect()
}

/// The `.mpf` and `.spf` files under `dir`, sorted, subfolders included.
pub fn program_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("readable corpus folder")
        .map(|entry| entry.expect("readable entry").path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            program_files(&path, out);
        } else if path.extension().is_some_and(|extension| {
            extension.eq_ignore_ascii_case("mpf") || extension.eq_ignore_ascii_case("spf")
        }) {
            out.push(path);
        }
    }
}
