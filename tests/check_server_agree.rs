//! `check` and the server report the same findings: every program of `fixtures/` (`.mpf`, `.spf`) is
//! checked by the binary (`check --format json`) and opened in the server (in this process, with its
//! folder as the workspace), and the two lists must have the same codes, lines, columns, severities
//! and messages. A folder of `fixtures/execution` is one workspace of several files; every other
//! program is a workspace of its own. The configuration a fixture's header gives (`; toml:`,
//! `; config: turn`, `; options:`) is written as the folder's `sinumerik.toml`, which both read (an
//! empty one for the defaults).
//!
//! The server publishes the analysis's findings first and the cross-file and run findings once its
//! index is complete and the document's entry is built (after the edit pause). The test waits for
//! that with a probe: a document outside the workspace whose only finding (W304) comes from the same
//! computation, opened after the programs; once the probe's finding is published, the publications
//! of the programs are read until the server has been quiet for a while.

#[path = "support/lsp_client.rs"]
mod lsp_client;

use lsp_client::{file_uri, temp_folder, TestClient};
use serde_json::{json, Value};
use sinumerik_lsp::io::source_file::read_source_file;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

/// How long the server must stay quiet after the probe's findings before its publications count
/// as final.
const QUIET: Duration = Duration::from_millis(1000);

/// Cases run at the same time (each with a server of its own; most of the time they wait).
const PARALLEL_CASES: usize = 12;

/// Differences known and explained, which must still occur (so that the entry goes when the cause
/// is fixed): (case, file, side, code, 1-based line, why).
const KNOWN_DIFFERENCES: &[(&str, &str, &str, &str, u64, &str)] = &[(
    "execution/macro_files",
    "main.mpf",
    "server only",
    "S144",
    7,
    "the server's document analysis does not read the macros of the definition files of the \
     workspace (`check` does, and the run of both does): `G300`, which UMAC.DEF defines, reads \
     as an unknown G function there",
)];

/// One workspace: the fixture files copied into it and the configuration its header gives.
struct Case {
    name: String,
    files: Vec<PathBuf>,
    toml: String,
}

/// A finding as both sides can write it: code, LSP line, UTF-16 start and end (line, column),
/// severity and message.
type Finding = (String, u64, u64, u64, u64, String, String);

fn is_program(path: &Path) -> bool {
    path.extension()
        .and_then(|extension| extension.to_str())
        .is_some_and(|extension| {
            extension.eq_ignore_ascii_case("mpf") || extension.eq_ignore_ascii_case("spf")
        })
}

fn sorted_entries(folder: &Path) -> Vec<PathBuf> {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(folder)
        .unwrap_or_else(|error| panic!("{}: {error}", folder.display()))
        .map(|entry| entry.unwrap().path())
        .collect();
    entries.sort();
    entries
}

/// The cases below `folder`: each program alone, or each folder of `fixtures/execution` as one.
fn collect_cases(root: &Path, folder: &Path, cases: &mut Vec<Case>) {
    for entry in sorted_entries(folder) {
        let name = entry.strip_prefix(root).unwrap().display().to_string();
        if entry.is_dir() {
            if entry
                .parent()
                .is_some_and(|parent| parent.ends_with("execution"))
            {
                let files = sorted_entries(&entry);
                let main = files
                    .iter()
                    .find(|file| {
                        file.file_stem()
                            .is_some_and(|stem| stem.eq_ignore_ascii_case("main"))
                    })
                    .unwrap_or_else(|| panic!("{name} has no main program"));
                let toml = configuration_of(&std::fs::read_to_string(main).unwrap());
                cases.push(Case { name, files, toml });
            } else {
                collect_cases(root, &entry, cases);
            }
        } else if is_program(&entry) {
            let text = String::from_utf8_lossy(&std::fs::read(&entry).unwrap()).into_owned();
            cases.push(Case {
                name,
                toml: configuration_of(&text),
                files: vec![entry],
            });
        }
    }
}

/// The `sinumerik.toml` a fixture's header asks for (empty for the defaults): `; toml:` lines as
/// written, `; config: turn` as the lathe kind, `; options:` as the `[execution]` table.
fn configuration_of(text: &str) -> String {
    let mut toml: String = text
        .lines()
        .filter_map(|line| line.strip_prefix("; toml: "))
        .flat_map(|line| [line, "\n"])
        .collect();
    if toml.is_empty() && text.starts_with("; config: turn") {
        toml.push_str("[machine]\nkind = \"turn\"\n");
    }
    for settings in text
        .lines()
        .filter_map(|line| line.strip_prefix("; options: "))
    {
        toml.push_str("[execution]\n");
        for setting in settings.split_whitespace() {
            let (key, value) = setting.split_once('=').expect("key=value");
            let line = match key {
                "max_blocks" | "max_loop_passes" | "m30_ends_subprogram" => {
                    format!("{key} = {value}")
                }
                "entry" => format!("subprogram_entry = \"{value}\""),
                "gotos" => format!(
                    "gotos_restart = \"{}\"",
                    match value {
                        "true" => "always",
                        "false" => "never",
                        _ => "unknown",
                    }
                ),
                other => panic!("unknown option {other}"),
            };
            toml.push_str(&line);
            toml.push('\n');
        }
    }
    toml
}

/// The UTF-16 column of 1-based character column `column` of `line`.
fn utf16_column(line: &str, column: u64) -> u64 {
    line.chars()
        .take(column.saturating_sub(1) as usize)
        .map(|character| character.len_utf16() as u64)
        .sum()
}

/// The lines of a text as the checker splits them (LF, CRLF, lone CR).
fn text_lines(text: &str) -> Vec<&str> {
    sinumerik_lsp::syntax::lines::line_ranges(text)
        .map(|(start, end)| &text[start..end])
        .collect()
}

/// `check --format json` of the case's programs: findings by file name.
async fn check_findings(
    files: &[PathBuf],
    texts: &HashMap<String, String>,
) -> HashMap<String, Vec<Finding>> {
    let output = tokio::process::Command::new(env!("CARGO_BIN_EXE_sinumerik-lsp"))
        .args(["check", "--format", "json"])
        .args(files)
        .output()
        .await
        .expect("check runs");
    assert!(
        matches!(output.status.code(), Some(0 | 1)),
        "check failed on {files:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let items: Value = serde_json::from_slice(&output.stdout).expect("check writes JSON");
    let mut by_file: HashMap<String, Vec<Finding>> = HashMap::new();
    for item in items.as_array().expect("an array") {
        let file = Path::new(item["file"].as_str().unwrap())
            .file_name()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        let lines = text_lines(&texts[&file]);
        let number = |key: &str| item[key].as_u64().unwrap();
        let (line, end_line) = (number("line") - 1, number("end_line") - 1);
        let text_of = |line: u64| lines.get(line as usize).copied().unwrap_or("");
        by_file.entry(file).or_default().push((
            item["code"].as_str().unwrap().to_string(),
            line,
            utf16_column(text_of(line), number("column")),
            end_line,
            utf16_column(text_of(end_line), number("end_column")),
            item["severity"].as_str().unwrap().to_string(),
            item["message"].as_str().unwrap().to_string(),
        ));
    }
    by_file
}

fn server_finding(diagnostic: &Value) -> Finding {
    let position = |point: &str, part: &str| diagnostic["range"][point][part].as_u64().unwrap();
    let severity = match diagnostic["severity"].as_u64() {
        Some(1) => "error",
        Some(2) => "warning",
        Some(3) => "info",
        _ => "hint",
    };
    (
        diagnostic["code"].as_str().unwrap_or_default().to_string(),
        position("start", "line"),
        position("start", "character"),
        position("end", "line"),
        position("end", "character"),
        severity.to_string(),
        diagnostic["message"]
            .as_str()
            .unwrap_or_default()
            .to_string(),
    )
}

/// The findings the server publishes for the case's programs, by file name.
async fn server_findings(
    folder: &Path,
    probe_folder: &Path,
    texts: &HashMap<String, String>,
) -> HashMap<String, Vec<Finding>> {
    let mut client = TestClient::in_process();
    let folder_uri = file_uri(folder);
    client
        .request(
            "initialize",
            json!({
                "processId": null,
                "rootUri": folder_uri,
                "workspaceFolders": [{"uri": folder_uri, "name": "case"}],
                "capabilities": {"window": {"workDoneProgress": true}}
            }),
        )
        .await
        .expect("initialize succeeds");
    client.notify("initialized", json!({})).await;
    // The index is complete when the indexing's progress ends.
    client
        .notification("$/progress", |params| params["value"]["kind"] == "end")
        .await;
    let mut names_by_uri = HashMap::new();
    let mut names: Vec<&String> = texts.keys().collect();
    names.sort();
    for name in names {
        let uri = file_uri(&folder.join(name));
        client.open(&uri, 1, &texts[name]).await;
        names_by_uri.insert(uri, name.clone());
    }
    std::fs::write(probe_folder.join("sinumerik.toml"), "").unwrap();
    let probe = file_uri(&probe_folder.join("probe.txt"));
    client.open(&probe, 1, "GOTOF PROBE_TARGET\n").await;
    let mut latest: HashMap<String, Vec<Finding>> = HashMap::new();
    let mut probe_seen = false;
    loop {
        let wanted = |params: &Value| {
            let uri = params["uri"].as_str().unwrap_or_default();
            uri == probe || names_by_uri.contains_key(uri)
        };
        let waiting = client.notification("textDocument/publishDiagnostics", wanted);
        let params = if probe_seen {
            match tokio::time::timeout(QUIET, waiting).await {
                Ok(params) => params,
                Err(_) => break,
            }
        } else {
            waiting.await
        };
        let uri = params["uri"].as_str().unwrap_or_default();
        let diagnostics = params["diagnostics"]
            .as_array()
            .cloned()
            .unwrap_or_default();
        if uri == probe {
            probe_seen |= diagnostics
                .iter()
                .any(|diagnostic| diagnostic["code"] == "W304");
        } else {
            latest.insert(
                names_by_uri[uri].clone(),
                diagnostics.iter().map(server_finding).collect(),
            );
        }
    }
    client.shutdown().await;
    latest
}

/// The differences of one case as table rows: (case, file, side, finding).
async fn compare_case(
    index: usize,
    case: Arc<Case>,
) -> Vec<(String, String, &'static str, Finding)> {
    let folder = temp_folder(&format!("agree-{index}"));
    let probe_folder = temp_folder(&format!("agree-probe-{index}"));
    let mut texts = HashMap::new();
    let mut programs = Vec::new();
    for file in &case.files {
        let name = file.file_name().unwrap().to_string_lossy().into_owned();
        let copy = folder.join(&name);
        std::fs::copy(file, &copy).unwrap();
        if is_program(file) {
            texts.insert(name, read_source_file(file).expect("readable fixture").text);
            programs.push(copy);
        }
    }
    // Always a file, empty for the defaults: the search for a configuration (and for callees) stops
    // in the case's folder, whatever lies above it in the temporary folder.
    std::fs::write(folder.join("sinumerik.toml"), &case.toml).unwrap();
    let from_check = check_findings(&programs, &texts).await;
    let from_server = server_findings(&folder, &probe_folder, &texts).await;
    let _ = std::fs::remove_dir_all(&folder);
    let _ = std::fs::remove_dir_all(&probe_folder);
    let mut rows = Vec::new();
    let mut names: Vec<&String> = texts.keys().collect();
    names.sort();
    for name in names {
        let mut checked = from_check.get(name).cloned().unwrap_or_default();
        let Some(published) = from_server.get(name) else {
            rows.push((
                case.name.clone(),
                name.clone(),
                "server published nothing",
                Finding::default(),
            ));
            continue;
        };
        let mut published = published.clone();
        checked.sort();
        published.sort();
        for finding in &checked {
            if let Some(position) = published.iter().position(|other| other == finding) {
                published.remove(position);
            } else {
                rows.push((
                    case.name.clone(),
                    name.clone(),
                    "check only",
                    finding.clone(),
                ));
            }
        }
        for finding in published {
            rows.push((case.name.clone(), name.clone(), "server only", finding));
        }
    }
    rows
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn check_and_the_server_report_the_same_findings_on_every_fixture_program() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures");
    let mut cases = Vec::new();
    collect_cases(&root, &root, &mut cases);
    assert!(cases.len() > 100, "only {} cases found", cases.len());
    let n_programs: usize = cases
        .iter()
        .map(|case| case.files.iter().filter(|file| is_program(file)).count())
        .sum();
    let started = std::time::Instant::now();
    let limit = Arc::new(tokio::sync::Semaphore::new(PARALLEL_CASES));
    let mut tasks = Vec::new();
    for (index, case) in cases.into_iter().enumerate() {
        let limit = Arc::clone(&limit);
        tasks.push(tokio::spawn(async move {
            let _permit = limit.acquire_owned().await.unwrap();
            compare_case(index, Arc::new(case)).await
        }));
    }
    let mut rows = Vec::new();
    for task in tasks {
        rows.extend(task.await.expect("the case ran"));
    }
    let mut unseen = Vec::new();
    for (case, file, side, code, line, why) in KNOWN_DIFFERENCES {
        let before = rows.len();
        let (row_case, row_file, row_side) = (case.to_string(), file.to_string(), *side);
        rows.retain(|(case, file, side, finding)| {
            let known = *case == row_case
                && *file == row_file
                && *side == row_side
                && finding.0 == *code
                && finding.1 + 1 == *line;
            !known
        });
        if rows.len() == before {
            unseen.push(format!("{case} {file} {side} {code} line {line} ({why})"));
        }
    }
    println!(
        "{n_programs} programs compared in {:.1} s",
        started.elapsed().as_secs_f64()
    );
    if !rows.is_empty() {
        println!("{:<44} {:<22} {:<12} finding", "case", "file", "side");
        for (case, file, side, (code, line, column, end_line, end_column, severity, message)) in
            &rows
        {
            println!(
                "{case:<44} {file:<22} {side:<12} {code} {}:{column}-{}:{end_column} {severity} {message}",
                line + 1,
                end_line + 1
            );
        }
    }
    assert!(rows.is_empty(), "{} differences (table above)", rows.len());
    assert!(
        unseen.is_empty(),
        "known differences that no longer occur (remove them from KNOWN_DIFFERENCES):\n{}",
        unseen.join("\n")
    );
}
