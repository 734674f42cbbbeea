//! The programs mutations start from: every file under `fixtures/` (except the fuzz reproducers, which
//! are replayed on their own) and, when present, the real programs of `../shared/corpus/real`, read in
//! place and never copied.

#[path = "../../tests/support/generated.rs"]
mod generated;

use std::fs;
use std::path::{Path, PathBuf};

/// One seed program, split into lines (without terminators).
pub struct Seed {
    pub lines: Vec<String>,
    /// Made by the shared generator (long, regular programs) rather than read from a file.
    pub generated: bool,
}

/// Files larger than this are read only up to it: a case should take milliseconds.
const MAX_SEED_BYTES: usize = 512 * 1024;

/// The seeds: fixtures first, then the corpus when it exists, then programs of the shared generator
/// when it exists. Also says how many came from the corpus and from the generator.
pub fn load_seeds(crate_dir: &Path) -> (Vec<Seed>, usize, usize) {
    let mut seeds = Vec::new();
    for path in files_below(&crate_dir.join("fixtures")) {
        if path.components().any(|part| part.as_os_str() == "fuzz") {
            continue;
        }
        seeds.extend(read_seed(&path));
    }
    let fixture_count = seeds.len();
    for path in files_below(&corpus_dir(crate_dir)) {
        seeds.extend(read_seed(&path));
    }
    let corpus_count = seeds.len() - fixture_count;
    let before_generated = seeds.len();
    // Long generated programs, incremental ones above all: they exercise the checkpoints and the
    // shifts the document model carries across intervals of incremental blocks.
    for style in ["inc", "mixed", "turning", "cam3d"] {
        if let Some(text) = generated::generate(style, 6_000) {
            seeds.push(Seed {
                lines: split_lines(&text),
                generated: true,
            });
        }
    }
    let generated_count = seeds.len() - before_generated;
    (seeds, corpus_count, generated_count)
}

/// Where the real programs are, relative to the crate.
pub fn corpus_dir(crate_dir: &Path) -> PathBuf {
    crate_dir.join("../shared/corpus/real")
}

/// Every file below `dir`, in sorted order; none when `dir` does not exist.
pub fn files_below(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(folder) = pending.pop() {
        let Ok(entries) = fs::read_dir(&folder) else {
            continue;
        };
        for entry in entries.flatten() {
            let Ok(kind) = entry.file_type() else {
                continue;
            };
            if kind.is_dir() {
                pending.push(entry.path());
            } else if kind.is_file() {
                files.push(entry.path());
            }
        }
    }
    files.sort();
    files
}

fn read_seed(path: &Path) -> Option<Seed> {
    let mut bytes = fs::read(path).ok()?;
    bytes.truncate(MAX_SEED_BYTES);
    let text = sinumerik_lsp::io::source_file::decode_source(&bytes).text;
    let lines = split_lines(&text);
    (!lines.is_empty()).then_some(Seed {
        lines,
        generated: false,
    })
}

/// The lines of `text` as the checker splits them (LF, CRLF, lone CR).
pub fn split_lines(text: &str) -> Vec<String> {
    sinumerik_lsp::syntax::lines::line_ranges(text)
        .map(|(start, end)| text[start..end].to_string())
        .collect()
}
