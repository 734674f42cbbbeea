//! The standard cycles of the real programs in `../shared/corpus/real` (reference §16): every
//! executed call of CYCLE81-89, CYCLE840, HOLES1, HOLES2 and CYCLE801 is counted, and none may
//! leave a position unknown that was known before it. A call that runs a program of the library
//! (the corpus has copies of some cycles in a program's folder) is counted apart: that file is what
//! the control runs. A position that was not known before the call (it depends on data the program
//! does not contain) is printed with the call and not held against it. The built-in models may
//! raise no error-level finding on the corpus (the corpus programs run on real machines).
//! `cargo test --release --test corpus_cycles -- --nocapture` prints the figures.
//!
//! When the corpus is not there, the test prints `corpus not found at ...; skipping` and passes.

#[path = "support/corpus_files.rs"]
mod corpus_files;

use corpus_files::{corpus_dir, program_files};
use sinumerik_lsp::analysis::execution::{execute_collecting, ExecutedMove, ExecutionOptions};
use sinumerik_lsp::analysis::library::{MemoryLibrary, ProgramLibrary};
use sinumerik_lsp::analysis::ProgramKind;
use sinumerik_lsp::config::MachineConfig;
use sinumerik_lsp::diagnostics::{Code, Severity};
use sinumerik_lsp::io::source_file::read_source_file;
use sinumerik_lsp::syntax::ast::{CallKind, Statement};
use sinumerik_lsp::syntax::lines::line_ranges;
use sinumerik_lsp::syntax::{parse_line, SyntaxContext};
use std::collections::BTreeSet;
use std::path::Path;

const MODELLED: [&str; 13] = [
    "CYCLE81", "CYCLE82", "CYCLE83", "CYCLE84", "CYCLE840", "CYCLE85", "CYCLE86", "CYCLE87",
    "CYCLE88", "CYCLE89", "HOLES1", "HOLES2", "CYCLE801",
];

/// The findings of the built-in models.
const CYCLE_CODES: [Code; 6] = [
    Code::CycleReferencePlane,
    Code::PatternWithoutModalCall,
    Code::PatternWithoutHoles,
    Code::CircleOfHolesTooLong,
    Code::CycleDepthDisagrees,
    Code::GridWithoutRowsOrColumns,
];

/// The program files of a folder as a library, by file name.
fn folder_library(dir: &Path) -> MemoryLibrary {
    let mut library = MemoryLibrary::default();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return library;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let is_program = path.extension().is_some_and(|extension| {
            extension.eq_ignore_ascii_case("spf") || extension.eq_ignore_ascii_case("mpf")
        });
        let Ok(source) = read_source_file(&path) else {
            continue;
        };
        if is_program {
            let stem = path.file_stem().unwrap().to_string_lossy().to_string();
            library.insert(&stem, &path.display().to_string(), &source.text);
        }
    }
    library
}

/// The modelled cycle a line calls directly (not `MCALL`), upper case.
fn called_cycle(line: &str, context: &SyntaxContext) -> Option<String> {
    let (block, _) = parse_line(line, context);
    block
        .interpreted_statements()
        .iter()
        .find_map(|statement| match statement {
            Statement::Call {
                kind: CallKind::Named,
                name: Some(name),
                ..
            } => {
                let name = line.get(name.start()..name.end())?.to_ascii_uppercase();
                MODELLED.contains(&name.as_str()).then_some(name)
            }
            _ => None,
        })
}

/// The geometry axes a move knows at its start and at its end.
fn known(values: &[(std::sync::Arc<str>, f64)]) -> BTreeSet<String> {
    values
        .iter()
        .map(|(name, _)| name.to_string())
        .filter(|name| ["X", "Y", "Z"].contains(&name.as_str()))
        .collect()
}

#[derive(Default)]
struct Figures {
    /// Executions of a block that ran a built-in model (a direct call or a modal trigger).
    modelled: usize,
    /// Of those, the ones after which an axis known before is unknown.
    lost: Vec<String>,
    /// Executed direct calls that ran a program of the library.
    by_file: usize,
    /// Executed direct calls without a move of a built-in model and without a finding that explains
    /// it (an alarm, or a cycle without motion).
    silent: Vec<String>,
    /// Executions whose plane position before the call was not known: (call, axes).
    unknown_before: Vec<String>,
    /// Executed direct calls without the model's moves whose arguments use variables.
    unknown_arguments: Vec<String>,
}

#[test]
fn every_cycle_call_of_the_corpus_is_followed() {
    let dir = corpus_dir();
    if !dir.is_dir() {
        println!("corpus not found at {}; skipping", dir.display());
        return;
    }
    let mut files = Vec::new();
    program_files(&dir, &mut files);
    let config = MachineConfig::mill();
    let context = SyntaxContext::new(&config);
    let options = ExecutionOptions::default();
    let mut figures = Figures::default();
    let mut errors = Vec::new();
    for path in files {
        let Ok(source) = read_source_file(&path) else {
            continue;
        };
        let text = source.text.as_str();
        let relative = path.strip_prefix(&dir).unwrap().display().to_string();
        let library = folder_library(path.parent().unwrap());
        let kind = ProgramKind::from_extension(path.extension().and_then(|e| e.to_str()));
        let (execution, moves) = execute_collecting(text, &config, kind, &library, &options);
        for item in &execution.findings {
            let code = item.diagnostic.code;
            if CYCLE_CODES.contains(&code) && item.diagnostic.severity == Severity::Error {
                errors.push(format!(
                    "{relative}:{}: {} {}",
                    item.line + 1,
                    code.as_str(),
                    item.diagnostic.message
                ));
            }
        }
        // The runs of moves of one trigger: same file, line, pass and stack, made by a model.
        let mut groups: Vec<Vec<&ExecutedMove>> = Vec::new();
        for executed in moves
            .iter()
            .filter(|executed| executed.movement.cycle.is_some())
        {
            let same = groups
                .last()
                .and_then(|group| group.last())
                .is_some_and(|last| {
                    last.path == executed.path
                        && last.movement.line == executed.movement.line
                        && last.pass == executed.pass
                        && last.stack == executed.stack
                });
            if same {
                groups.last_mut().unwrap().push(executed);
            } else {
                groups.push(vec![executed]);
            }
        }
        for group in &groups {
            let (first, last) = (group[0], group[group.len() - 1]);
            let at = format!(
                "{relative}:{} ({})",
                first.movement.line + 1,
                first.movement.cycle.as_deref().unwrap_or("")
            );
            figures.modelled += 1;
            let before = known(&first.movement.start);
            let after = known(&last.movement.end);
            let missing_before: Vec<&str> = ["X", "Y"]
                .into_iter()
                .filter(|axis| !before.contains(*axis))
                .collect();
            if !missing_before.is_empty() {
                figures.unknown_before.push(format!(
                    "{at}: {} not known before",
                    missing_before.join(" ")
                ));
            }
            let lost: Vec<&String> = before
                .iter()
                .filter(|axis| !after.contains(*axis))
                .collect();
            if !lost.is_empty() || !after.contains("Z") {
                figures
                    .lost
                    .push(format!("{at}: known before {before:?}, after {after:?}"));
            }
        }
        // Direct calls in the program itself.
        for (index, (start, end)) in line_ranges(text).enumerate() {
            let line = &text[start..end];
            let Some(name) = called_cycle(line, &context) else {
                continue;
            };
            let passes = execution.passes_of_line(index);
            if passes == 0 {
                continue;
            }
            if library.find(&name).is_some() {
                figures.by_file += passes as usize;
                continue;
            }
            let made_moves = moves.iter().any(|executed| {
                executed.path.is_none()
                    && executed.stack.is_empty()
                    && executed.movement.line == index
                    && executed.movement.cycle.is_some()
            });
            let explained = execution
                .findings
                .iter()
                .any(|item| item.line == index && CYCLE_CODES.contains(&item.diagnostic.code));
            // Arguments written with variables may depend on data the program does not contain
            // (machine data, global user data): the model then leaves the tool axis unknown.
            let arguments = line.split_once('(').map_or("", |(_, rest)| rest);
            let with_variables = arguments
                .split(';')
                .next()
                .unwrap_or("")
                .contains(|c: char| c.is_ascii_alphabetic() || c == '_' || c == '$');
            if !made_moves && !explained && with_variables {
                figures.unknown_arguments.push(format!(
                    "{relative}:{}: {}",
                    index + 1,
                    line.trim()
                ));
            } else if !made_moves && !explained {
                figures
                    .silent
                    .push(format!("{relative}:{}: {}", index + 1, line.trim()));
            }
        }
    }
    println!(
        "{} executions of built-in cycle models, {} direct calls that ran a file of the library",
        figures.modelled, figures.by_file
    );
    for item in &figures.unknown_before {
        println!("  position before the call not known (it depends on data the program does not contain): {item}");
    }
    for item in &figures.unknown_arguments {
        println!("  arguments with values the run does not know (the tool axis is unknown after it): {item}");
    }
    for item in &figures.silent {
        println!("  call without the model's moves: {item}");
    }
    assert!(
        figures.modelled >= 20,
        "only {} executions of cycle models in the corpus",
        figures.modelled
    );
    assert!(
        figures.lost.is_empty(),
        "cycles that leave positions unknown:\n{}",
        figures.lost.join("\n")
    );
    assert!(
        figures.silent.is_empty(),
        "calls not followed:\n{}",
        figures.silent.join("\n")
    );
    assert!(
        errors.is_empty(),
        "error-level cycle findings on the corpus:\n{}",
        errors.join("\n")
    );
}
