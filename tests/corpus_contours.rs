//! Every executed block of the real programs in `../shared/corpus/real` that programs a rounding or
//! chamfer (`RND`, `CHF`, `CHR`) is followed: its moves end at known positions in the plane wherever
//! the blocks as programmed (the run without the corner stage) do, the corner stage inserts
//! elements, and it reports no error. The called programs are the other program
//! files of the same folder.
//!
//! When the corpus is not there, the test prints `corpus not found at ...; skipping` and passes.

#[path = "support/corpus_files.rs"]
mod corpus_files;

use corpus_files::{corpus_dir, program_files};
use sinumerik_lsp::analysis::execution::entry::RunSetup;
use sinumerik_lsp::analysis::execution::{
    execute_collecting, execute_programmed, ExecutedMove, ExecutionOptions,
};
use sinumerik_lsp::analysis::library::MemoryLibrary;
use sinumerik_lsp::analysis::ProgramKind;
use sinumerik_lsp::config::MachineConfig;
use sinumerik_lsp::diagnostics::Severity;
use sinumerik_lsp::io::source_file::read_source_file;
use sinumerik_lsp::syntax::lines::line_ranges;
use std::collections::HashMap;

/// Whether the code part of `line` (before `;`) writes `RND=`, `CHF=` or `CHR=`.
fn programs_corner(line: &str) -> bool {
    let code = line.split(';').next().unwrap_or("").to_ascii_uppercase();
    let bytes = code.as_bytes();
    ["RND", "CHF", "CHR"].iter().any(|word| {
        code.match_indices(word).any(|(at, _)| {
            let before_ok =
                at == 0 || !(bytes[at - 1].is_ascii_alphanumeric() || bytes[at - 1] == b'_');
            let rest = code[at + word.len()..].trim_start();
            before_ok && rest.starts_with('=')
        })
    })
}

#[test]
fn corpus_corners_are_followed() {
    let dir = corpus_dir();
    if !dir.is_dir() {
        println!("corpus not found at {}; skipping", dir.display());
        return;
    }
    let mut files = Vec::new();
    program_files(&dir, &mut files);
    let config = MachineConfig::mill();
    let options = ExecutionOptions::default();
    let (mut blocks, mut known_blocks, mut inserted) = (0usize, 0usize, 0usize);
    let mut failures = Vec::new();
    for path in files {
        let Ok(source) = read_source_file(&path) else {
            continue;
        };
        if !source.text.lines().any(programs_corner) {
            continue;
        }
        let mut library = MemoryLibrary::default();
        let mut texts: HashMap<String, String> = HashMap::new();
        for entry in std::fs::read_dir(path.parent().unwrap())
            .into_iter()
            .flatten()
            .flatten()
        {
            let other = entry.path();
            let is_program = other.extension().is_some_and(|extension| {
                extension.eq_ignore_ascii_case("spf") || extension.eq_ignore_ascii_case("mpf")
            });
            if let (true, Ok(other_source)) = (is_program, read_source_file(&other)) {
                let stem = other.file_stem().unwrap().to_string_lossy().to_string();
                library.insert(&stem, &other.display().to_string(), &other_source.text);
                texts.insert(other.display().to_string(), other_source.text);
            }
        }
        let kind = ProgramKind::from_extension(path.extension().and_then(|e| e.to_str()));
        let (execution, moves) =
            execute_collecting(&source.text, &config, kind, &library, &options);
        let mut programmed: Vec<ExecutedMove> = Vec::new();
        execute_programmed(
            &source.text,
            &config,
            kind,
            &library,
            &options,
            &RunSetup::default(),
            &mut |executed| programmed.push(executed),
        );
        // The first move of each execution of a block, as programmed: whether the plane is known.
        let plane_known = |movement: &sinumerik_lsp::analysis::Move| {
            movement.plane.is_some_and(|(first, second)| {
                [first, second]
                    .iter()
                    .all(|axis| movement.end.iter().any(|(name, _)| name.as_ref() == *axis))
            })
        };
        let programmed_known: HashMap<(Option<String>, usize, u32), bool> = programmed
            .iter()
            .map(|executed| {
                (
                    (
                        executed.path.as_deref().map(str::to_string),
                        executed.movement.line,
                        executed.pass,
                    ),
                    plane_known(&executed.movement),
                )
            })
            .collect();
        let mut ranges: HashMap<Option<String>, Vec<(usize, usize)>> = HashMap::new();
        for executed in &moves {
            if executed.movement.inserted.is_some() {
                inserted += 1;
                continue;
            }
            let text = match &executed.path {
                None => source.text.as_str(),
                Some(file) => texts.get(file.as_ref()).map_or("", String::as_str),
            };
            let lines = ranges
                .entry(executed.path.as_deref().map(str::to_string))
                .or_insert_with(|| line_ranges(text).collect());
            let line = lines
                .get(executed.movement.line)
                .map_or("", |&(start, end)| &text[start..end]);
            if !programs_corner(line) {
                continue;
            }
            blocks += 1;
            let movement = &executed.movement;
            let key = (
                executed.path.as_deref().map(str::to_string),
                movement.line,
                executed.pass,
            );
            let was_known = programmed_known.get(&key).copied().unwrap_or(false);
            known_blocks += usize::from(was_known);
            let known = !was_known || plane_known(movement);
            if !known {
                failures.push(format!(
                    "{}:{}: `{}` leaves the plane's positions unknown: end {:?}, uncertain {:?}",
                    path.display(),
                    movement.line + 1,
                    line.trim(),
                    movement.end,
                    movement.uncertain
                ));
            }
        }
        for finding in &execution.findings {
            let code = finding.diagnostic.code.as_str();
            if finding.diagnostic.severity == Severity::Error
                && matches!(
                    code,
                    "E430" | "E431" | "E432" | "E433" | "A240" | "A241" | "A242"
                )
            {
                failures.push(format!(
                    "{}:{}: {code} {}",
                    path.display(),
                    finding.line + 1,
                    finding.diagnostic.message
                ));
            }
        }
    }
    println!("{blocks} executed blocks with RND/CHF/CHR ({known_blocks} with known positions as programmed), {inserted} inserted elements");
    assert!(
        known_blocks > 0,
        "the corpus has no executed block with RND, CHF or CHR at known positions"
    );
    assert!(
        inserted > 0,
        "no rounding or chamfer was inserted in the corpus"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
