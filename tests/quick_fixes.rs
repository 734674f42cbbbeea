//! Every quick fix the server offers keeps the program's meaning: for every program of `fixtures/`
//! and of the real corpus (`../shared/corpus/real`, skipped with a message when absent), the server
//! (in this process) is asked for the code actions of the whole document, every fix that edits the
//! program is applied, and the result must
//! - no longer have that finding on that line (one fewer finding of its code there),
//! - keep every other line as it was (the positions of the other blocks do not move),
//! - keep every number of the line's code: a fix never deletes a value or turns it into a comment.
//!
//! Fixes that edit the configuration (S180, A235, A236) are counted; `lsp_config_fixes.rs` applies
//! them. The test prints a table of the fixes tried per code.

#[path = "support/corpus_files.rs"]
mod corpus_files;
#[path = "support/lsp_client.rs"]
mod lsp_client;

use corpus_files::{corpus_dir, program_files};
use lsp_client::{apply_text_edits, file_uri, temp_folder, TestClient};
use serde_json::{json, Value};
use sinumerik_lsp::analysis::{diagnose_program, ProgramKind};
use sinumerik_lsp::cli::source_file::read_source_file;
use sinumerik_lsp::config::MachineConfig;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The program files of `fixtures/` (`.mpf`, `.spf`, `.nc`), sorted.
fn fixture_programs(folder: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(folder)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            fixture_programs(&path, out);
        } else if path.extension().is_some_and(|extension| {
            ["mpf", "spf", "nc"]
                .iter()
                .any(|known| extension.eq_ignore_ascii_case(known))
        }) {
            out.push(path);
        }
    }
}

/// The lines of a text as the checker splits them.
fn lines_of(text: &str) -> Vec<&str> {
    sinumerik_lsp::syntax::lines::line_ranges(text)
        .map(|(start, end)| &text[start..end])
        .collect()
}

/// The numbers written in the code of a line (outside its comment and strings), sorted: digit runs
/// with their decimal point.
fn numbers_in_code(line: &str) -> Vec<String> {
    let mut numbers = Vec::new();
    let mut in_string = false;
    let mut current = String::new();
    for character in line.chars() {
        if in_string {
            in_string = character != '"';
            continue;
        }
        if character.is_ascii_digit() || (character == '.' && !current.is_empty()) {
            current.push(character);
            continue;
        }
        if !current.is_empty() {
            numbers.push(std::mem::take(&mut current));
        }
        match character {
            '"' => in_string = true,
            ';' => break,
            _ => {}
        }
    }
    if !current.is_empty() {
        numbers.push(current);
    }
    numbers.sort();
    numbers
}

/// Whether every number of `old` is still in the code of `new` (as many times), or what the fix
/// made a comment is text: not an expression or argument list (`(TOOL 1)` of another dialect), as
/// the expression parser, given it as the value of `R1=(..)`, says.
fn keeps_numbers(old: &str, new: &str) -> bool {
    let mut left = numbers_in_code(new);
    let kept = numbers_in_code(old).iter().all(|number| {
        match left.iter().position(|candidate| candidate == number) {
            Some(index) => {
                left.remove(index);
                true
            }
            None => false,
        }
    });
    kept || new.split_once(';').is_some_and(|(_, comment)| {
        let inner = comment.trim();
        let context = sinumerik_lsp::syntax::SyntaxContext::default();
        let (_, findings) = sinumerik_lsp::syntax::parse_line(&format!("R1=({inner})"), &context);
        !inner.contains(',')
            && findings
                .iter()
                .any(|finding| finding.severity == sinumerik_lsp::diagnostics::Severity::Error)
    })
}

#[derive(Default)]
struct Tally {
    tried: usize,
    passed: usize,
    configuration: usize,
}

/// Tries every fix of one program; adds to `table` and to `failures`.
async fn try_fixes(
    client: &mut TestClient,
    folder: &Path,
    name: &str,
    text: &str,
    table: &mut BTreeMap<String, Tally>,
    failures: &mut Vec<String>,
) {
    let kind = ProgramKind::from_file_name(name);
    let path = folder.join(name);
    let uri = file_uri(&path);
    client.open(&uri, 1, text).await;
    let diagnostics = client.diagnostics(&uri, 1).await;
    let lines = lines_of(text);
    let actions = if diagnostics.is_empty() {
        Vec::new()
    } else {
        let end = lines.len() as u32 + 1;
        client
            .request(
                "textDocument/codeAction",
                json!({"textDocument": {"uri": uri}, "range": {"start": {"line": 0, "character": 0}, "end": {"line": end, "character": 0}}, "context": {"diagnostics": diagnostics}}),
            )
            .await
            .expect("code actions are answered")
            .as_array()
            .cloned()
            .unwrap_or_default()
    };
    client
        .notify(
            "textDocument/didClose",
            json!({"textDocument": {"uri": uri}}),
        )
        .await;
    let config = MachineConfig::default();
    for action in actions {
        let diagnostic = &action["diagnostics"][0];
        let code = diagnostic["code"].as_str().unwrap_or("?").to_string();
        let line = diagnostic["range"]["start"]["line"].as_u64().unwrap() as usize;
        let tally = table.entry(code.clone()).or_default();
        let Some(edits) = action["edit"]["changes"][uri.as_str()].as_array() else {
            tally.configuration += 1;
            continue;
        };
        tally.tried += 1;
        let fixed = apply_text_edits(text, edits);
        let fixed_lines = lines_of(&fixed);
        let place = format!("{name}:{} {code} `{}`", line + 1, lines[line]);
        let others_kept = fixed_lines.len() == lines.len()
            && lines
                .iter()
                .zip(&fixed_lines)
                .enumerate()
                .all(|(index, (old, new))| index == line || old == new);
        if !others_kept {
            failures.push(format!("{place}: other lines changed"));
            continue;
        }
        if !keeps_numbers(lines[line], fixed_lines[line]) {
            failures.push(format!(
                "{place}: a value is lost in `{}`",
                fixed_lines[line]
            ));
            continue;
        }
        let count = |findings: &[sinumerik_lsp::diagnostics::LineDiagnostic]| {
            findings
                .iter()
                .filter(|item| item.line == line && item.diagnostic.code.as_str() == code)
                .count()
        };
        let before = count(&diagnose_program(text, &config, kind));
        let after = count(&diagnose_program(&fixed, &config, kind));
        if after >= before {
            failures.push(format!(
                "{place}: still reported after the fix `{}`",
                fixed_lines[line]
            ));
            continue;
        }
        tally.passed += 1;
    }
}

#[test]
fn every_quick_fix_keeps_the_other_blocks_and_every_value() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut programs = Vec::new();
    fixture_programs(&root.join("fixtures"), &mut programs);
    let fixtures = programs.len();
    let corpus = corpus_dir();
    if corpus.is_dir() {
        program_files(&corpus, &mut programs);
    } else {
        println!("corpus not found at {}; skipping it", corpus.display());
    }
    let folder = temp_folder("quick-fixes");
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .unwrap();
    let (table, failures) = runtime.block_on(async {
        let mut client = TestClient::in_process();
        client.initialize(json!({}), Value::Null).await;
        let mut table = BTreeMap::new();
        let mut failures = Vec::new();
        for (index, path) in programs.iter().enumerate() {
            let Ok(source) = read_source_file(path) else {
                continue;
            };
            // A name of its own in the temporary folder, with the program's extension.
            let extension = path
                .extension()
                .map(|extension| extension.to_string_lossy().into_owned())
                .unwrap_or_default();
            let name = format!("P{index}.{extension}");
            try_fixes(
                &mut client,
                &folder,
                &name,
                &source.text,
                &mut table,
                &mut failures,
            )
            .await;
            if failures.len() > 200 {
                break;
            }
        }
        (table, failures)
    });
    let _ = std::fs::remove_dir_all(&folder);
    println!(
        "{} programs ({fixtures} fixtures); quick fixes per code:",
        programs.len()
    );
    println!(
        "{:<6} {:>7} {:>7} {:>14}",
        "code", "tried", "passed", "configuration"
    );
    for (code, tally) in &table {
        println!(
            "{code:<6} {:>7} {:>7} {:>14}",
            tally.tried, tally.passed, tally.configuration
        );
    }
    let tried: usize = table.values().map(|tally| tally.tried).sum();
    assert!(
        tried >= 50,
        "only {tried} fixes tried: the fixtures changed"
    );
    assert!(
        failures.is_empty(),
        "{} fixes failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
