//! How well the interpreter resolves the real programs of `../shared/corpus/real`: the share of moves
//! that have a value for every axis their block writes (in `end`, or in `mcs` for a block in machine
//! coordinates), and the share with an empty `uncertain` list. The called programs are the other
//! program files of the same folder. `cargo test --release --test corpus_execution -- --nocapture`
//! prints the figures and the files with the most unresolved moves.
//!
//! When the corpus is not there, the test prints `corpus not found at ...; skipping` and passes.

#[path = "support/corpus_files.rs"]
mod corpus_files;

use corpus_files::{corpus_dir, glob_matches, known_invalid, program_files};
use sinumerik_lsp::analysis::axis_lookup::AxisLookup;
use sinumerik_lsp::analysis::execution::{execute_collecting, ExecutedMove, ExecutionOptions};
use sinumerik_lsp::analysis::library::MemoryLibrary;
use sinumerik_lsp::analysis::ProgramKind;
use sinumerik_lsp::config::MachineConfig;
use sinumerik_lsp::io::source_file::read_source_file;
use sinumerik_lsp::syntax::ast::{
    AddressKind, AddressWord, Block, ExprKind, Extension, NamedAddress, Statement,
};
use sinumerik_lsp::syntax::gcodes::GCode;
use sinumerik_lsp::syntax::lines::line_ranges;
use sinumerik_lsp::syntax::{parse_line, SyntaxContext};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The shares this build reaches at least (94.9 % resolved, 92.7 % without uncertain axes over 58,084
/// executed moves), so that a change that resolves less fails. The goal is 95 % and 60 %; the rest
/// depends on data the programs do not contain (global user data, tool and machine data, operator R
/// parameters), see docs/execution.md.
const MIN_RESOLVED_SHARE: f64 = 0.945;
const MIN_CERTAIN_SHARE: f64 = 0.92;

/// The program files of a folder as a library, by file name.
fn folder_library(dir: &Path, texts: &mut HashMap<PathBuf, String>) -> MemoryLibrary {
    let mut library = MemoryLibrary::default();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return library;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let is_program = path.extension().is_some_and(|extension| {
            extension.eq_ignore_ascii_case("spf") || extension.eq_ignore_ascii_case("mpf")
        });
        if !is_program {
            continue;
        }
        let Ok(source) = read_source_file(&path) else {
            continue;
        };
        let stem = path.file_stem().unwrap().to_string_lossy().to_string();
        library.insert(&stem, &path.display().to_string(), &source.text);
        texts.insert(path, source.text);
    }
    library
}

/// The axis `AX[X]=`, `POS[X]=` or `POSA[X]=` writes when the brackets name a configured axis; an axis
/// given by a variable is not known from the text alone and is not counted.
fn bracketed_axis(
    block: &Block,
    line: &str,
    config: &MachineConfig,
    word: &AddressWord,
) -> Option<usize> {
    let address = line.get(word.name.start()..word.name.end())?;
    if !["AX", "POS", "POSA"]
        .iter()
        .any(|name| address.eq_ignore_ascii_case(name))
    {
        return None;
    }
    let Some(Extension::Index { indexes, .. }) = &word.extension else {
        return None;
    };
    let [id] = indexes.as_slice() else {
        return None;
    };
    let expr = block.expr(*id);
    let ExprKind::Name { indexes } = &expr.kind else {
        return None;
    };
    let written = line.get(expr.span.start()..expr.span.end())?;
    if !indexes.is_empty() {
        return None;
    }
    config
        .axes
        .iter()
        .position(|axis| axis.name.eq_ignore_ascii_case(written))
}

/// Whether the move has a value for every axis its block writes.
fn resolved(
    executed: &ExecutedMove,
    line: &str,
    context: &SyntaxContext,
    config: &MachineConfig,
    lookup: &AxisLookup,
) -> bool {
    let (block, _) = parse_line(line, context);
    let statements = block.interpreted_statements();
    let machine_coordinates = statements.iter().any(|statement| {
        matches!(statement, Statement::GCode { code, .. } if code.group() == 9 && !matches!(code, GCode::WorkOffset(_)))
    });
    statements.iter().all(|statement| {
        let Statement::Address(word) = statement else {
            return true;
        };
        let index = match word.kind {
            AddressKind::Axis => lookup.index(config, line, word),
            AddressKind::Named(NamedAddress::IndirectAxis | NamedAddress::Positioning) => {
                bracketed_axis(&block, line, config, word)
            }
            _ => None,
        };
        let Some(index) = index else {
            return true;
        };
        let name = config.axes[index].name.as_str();
        let known_in = |values: &[(std::sync::Arc<str>, f64)]| {
            values.iter().any(|(axis, _)| axis.as_ref() == name)
        };
        known_in(&executed.movement.end)
            || (machine_coordinates && executed.movement.machine.as_deref().is_some_and(known_in))
    })
}

#[test]
fn corpus_moves_are_resolved() {
    let dir = corpus_dir();
    if !dir.is_dir() {
        println!("corpus not found at {}; skipping", dir.display());
        return;
    }
    let invalid = known_invalid();
    let mut files = Vec::new();
    program_files(&dir, &mut files);
    let config = MachineConfig::mill();
    let context = SyntaxContext::new(&config);
    let lookup = AxisLookup::new(&config);
    let options = ExecutionOptions::default();
    let (mut moves, mut resolved_moves, mut certain_moves) = (0usize, 0usize, 0usize);
    let mut per_file = Vec::new();
    for path in files {
        let relative = path
            .strip_prefix(&dir)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        if invalid
            .iter()
            .any(|pattern| glob_matches(pattern, &relative))
        {
            continue;
        }
        let source = read_source_file(&path).expect("readable corpus file");
        let mut texts = HashMap::new();
        let library = folder_library(path.parent().unwrap(), &mut texts);
        let kind = ProgramKind::from_extension(path.extension().and_then(|e| e.to_str()));
        let (_, executed) = execute_collecting(&source.text, &config, kind, &library, &options);
        let mut lines_of: HashMap<Option<String>, Vec<(usize, usize)>> = HashMap::new();
        let (mut file_resolved, mut file_certain) = (0, 0);
        for movement in &executed {
            let key = movement.path.as_deref().map(str::to_string);
            let text = match &key {
                None => source.text.as_str(),
                Some(path) => texts.get(Path::new(path)).map(String::as_str).unwrap_or(""),
            };
            let ranges = lines_of
                .entry(key)
                .or_insert_with(|| line_ranges(text).collect());
            let line = ranges
                .get(movement.movement.line)
                .map_or("", |&(start, end)| &text[start..end]);
            if resolved(movement, line, &context, &config, &lookup) {
                file_resolved += 1;
            }
            if movement.movement.uncertain.is_empty() {
                file_certain += 1;
            }
        }
        moves += executed.len();
        resolved_moves += file_resolved;
        certain_moves += file_certain;
        per_file.push((relative, executed.len(), file_resolved, file_certain));
    }
    let share = |count: usize| count as f64 / moves.max(1) as f64;
    println!(
        "{moves} executed moves: {:.1} % resolved for every axis their block writes, {:.1} % without uncertain axes",
        100.0 * share(resolved_moves),
        100.0 * share(certain_moves)
    );
    per_file.sort_by_key(|(_, total, resolved, _)| std::cmp::Reverse(total - resolved));
    for (file, total, resolved, certain) in per_file.iter().take(15) {
        println!("  {file}: {total} moves, {resolved} resolved, {certain} certain");
    }
    assert!(moves > 1000, "the corpus gave only {moves} moves");
    assert!(
        share(resolved_moves) >= MIN_RESOLVED_SHARE,
        "only {:.1} % of the moves are resolved",
        100.0 * share(resolved_moves)
    );
    assert!(
        share(certain_moves) >= MIN_CERTAIN_SHARE,
        "only {:.1} % of the moves are free of uncertain axes",
        100.0 * share(certain_moves)
    );
}
