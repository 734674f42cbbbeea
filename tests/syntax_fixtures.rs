//! Data-driven syntax tests over the programs in `fixtures/syntax/`.
//!
//! - `fixtures/syntax/ok/*.mpf|*.spf`: valid programs; they must produce no diagnostic of any severity.
//! - `fixtures/syntax/err/*.mpf|*.spf`: programs with mistakes; each has a snapshot `NAME.mpf.expected`
//!   next to it that lists exactly the diagnostics, one per line:
//!
//!   ```text
//!   3:9-3:15 error S101 the value of AC must be in parentheses [fix: Write `AC(17)` => 3:9-3:15 "AC(17)"]
//!   ```
//!
//!   Positions are `line:column`, both 1-based, columns counted in characters, the end exclusive.
//!
//! A file whose name starts with `turn_` is checked with `MachineConfig::turn()`, every other file with
//! `MachineConfig::mill()`.
//!
//! Snapshots: `UPDATE_SNAPSHOTS=1 cargo test --test syntax_fixtures` (re)writes them. A missing snapshot
//! is written on a normal run too, but the test then fails and says so, so that a snapshot is never
//! accepted without somebody reading it.

use sinumerik_lsp::config::MachineConfig;
use sinumerik_lsp::diagnostics::{Code, LineDiagnostic, Span};
use sinumerik_lsp::io::source_file::read_source_file;
use sinumerik_lsp::syntax::check_program;
use sinumerik_lsp::syntax::lines::line_ranges;
use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};

const SNAPSHOT_EXTENSION: &str = "expected";

/// Codes that no fixture is expected to produce, with the reason. Empty: every code has a fixture.
const CODES_WITHOUT_FIXTURE: &[(&str, &str)] = &[];

fn fixtures_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/syntax")
}

fn updating_snapshots() -> bool {
    std::env::var_os("UPDATE_SNAPSHOTS").is_some_and(|value| value == "1")
}

/// The program files (`.mpf`, `.spf`, any case) of a fixture folder, sorted by name.
fn program_files(dir: &Path) -> Vec<PathBuf> {
    let entries = fs::read_dir(dir).unwrap_or_else(|error| panic!("{}: {error}", dir.display()));
    let mut files: Vec<PathBuf> = entries
        .map(|entry| entry.expect("readable folder entry").path())
        .filter(|path| {
            path.is_file()
                && path.extension().is_some_and(|extension| {
                    extension.eq_ignore_ascii_case("mpf") || extension.eq_ignore_ascii_case("spf")
                })
        })
        .collect();
    files.sort();
    assert!(
        !files.is_empty(),
        "no fixture programs in {}: the test would prove nothing",
        dir.display()
    );
    files
}

fn file_name(path: &Path) -> String {
    path.file_name()
        .expect("a file name")
        .to_string_lossy()
        .into_owned()
}

fn config_for(path: &Path) -> MachineConfig {
    if file_name(path).to_ascii_lowercase().starts_with("turn_") {
        MachineConfig::turn()
    } else {
        MachineConfig::mill()
    }
}

fn snapshot_path(program: &Path) -> PathBuf {
    let mut name = program.as_os_str().to_owned();
    name.push(".");
    name.push(SNAPSHOT_EXTENSION);
    PathBuf::from(name)
}

/// A program and its diagnostics.
struct Checked {
    text: String,
    lines: Vec<(usize, usize)>,
    diagnostics: Vec<LineDiagnostic>,
}

fn check_file(path: &Path) -> Checked {
    let source =
        read_source_file(path).unwrap_or_else(|error| panic!("{}: {error}", path.display()));
    let diagnostics = check_program(&source.text, &config_for(path));
    let lines = line_ranges(&source.text).collect();
    Checked {
        text: source.text,
        lines,
        diagnostics,
    }
}

impl Checked {
    fn line_text(&self, line: usize) -> Option<&str> {
        self.lines
            .get(line)
            .map(|&(start, end)| &self.text[start..end])
    }

    /// `line:column`, 1-based, the column counted in characters. An offset outside the line or inside
    /// a character is shown as `line:?byteN`, so that the snapshot shows the bad span instead of hiding it.
    fn position(&self, line: usize, byte_offset: usize) -> String {
        match self.line_text(line) {
            Some(text) if text.is_char_boundary(byte_offset) => {
                format!("{}:{}", line + 1, text[..byte_offset].chars().count() + 1)
            }
            _ => format!("{}:?byte{}", line + 1, byte_offset),
        }
    }

    fn range(&self, line: usize, span: Span) -> String {
        format!(
            "{}-{}",
            self.position(line, span.start()),
            self.position(line, span.end())
        )
    }

    /// One diagnostic in the snapshot format.
    fn render_one(&self, item: &LineDiagnostic) -> String {
        let diagnostic = &item.diagnostic;
        let mut out = format!(
            "{} {} {} {}",
            self.range(item.line, diagnostic.span),
            diagnostic.severity,
            diagnostic.code,
            one_line(&diagnostic.message)
        );
        if let Some(fix) = &diagnostic.fix {
            let edits: Vec<String> = fix
                .edits
                .iter()
                .map(|edit| format!("{} {:?}", self.range(item.line, edit.span), edit.new_text))
                .collect();
            let _ = write!(
                out,
                " [fix: {} => {}]",
                one_line(&fix.title),
                edits.join(", ")
            );
        }
        out
    }

    fn render(&self) -> String {
        self.diagnostics
            .iter()
            .map(|item| self.render_one(item) + "\n")
            .collect()
    }

    /// Spans that do not fit their line: a bug whatever the snapshot says.
    fn span_problems(&self) -> Vec<String> {
        let mut problems = Vec::new();
        for item in &self.diagnostics {
            let Some(text) = self.line_text(item.line) else {
                problems.push(format!(
                    "line {} does not exist (the file has {} lines): {}",
                    item.line + 1,
                    self.lines.len(),
                    self.render_one(item)
                ));
                continue;
            };
            let mut spans = vec![item.diagnostic.span];
            if let Some(fix) = &item.diagnostic.fix {
                spans.extend(fix.edits.iter().map(|edit| edit.span));
            }
            for span in spans {
                if span.start() > span.end()
                    || !text.is_char_boundary(span.start())
                    || !text.is_char_boundary(span.end())
                {
                    problems.push(format!(
                        "span {}..{} does not fit line {} ({} bytes): {}",
                        span.start(),
                        span.end(),
                        item.line + 1,
                        text.len(),
                        self.render_one(item)
                    ));
                }
            }
        }
        problems
    }
}

fn one_line(text: &str) -> String {
    text.replace('\r', "\\r").replace('\n', "\\n")
}

/// A line diff (longest common subsequence) of two short texts: `-` expected only, `+` actual only.
fn diff(expected: &str, actual: &str) -> String {
    let old: Vec<&str> = expected.lines().collect();
    let new: Vec<&str> = actual.lines().collect();
    let mut common = vec![vec![0usize; new.len() + 1]; old.len() + 1];
    for i in (0..old.len()).rev() {
        for j in (0..new.len()).rev() {
            common[i][j] = if old[i] == new[j] {
                common[i + 1][j + 1] + 1
            } else {
                common[i + 1][j].max(common[i][j + 1])
            };
        }
    }
    let mut out = String::from("--- expected\n+++ actual\n");
    let (mut i, mut j) = (0, 0);
    while i < old.len() || j < new.len() {
        if i < old.len() && j < new.len() && old[i] == new[j] {
            let _ = writeln!(out, "  {}", old[i]);
            i += 1;
            j += 1;
        } else if i < old.len() && (j == new.len() || common[i + 1][j] >= common[i][j + 1]) {
            let _ = writeln!(out, "- {}", old[i]);
            i += 1;
        } else {
            let _ = writeln!(out, "+ {}", new[j]);
            j += 1;
        }
    }
    out
}

fn relative(path: &Path) -> String {
    path.strip_prefix(env!("CARGO_MANIFEST_DIR"))
        .unwrap_or(path)
        .display()
        .to_string()
}

#[test]
fn ok_fixtures_have_no_diagnostics() {
    let mut failures = String::new();
    for path in program_files(&fixtures_dir().join("ok")) {
        let checked = check_file(&path);
        if !checked.diagnostics.is_empty() {
            let _ = writeln!(
                failures,
                "{} ({} diagnostics):",
                relative(&path),
                checked.diagnostics.len()
            );
            for item in &checked.diagnostics {
                let source_line = checked.line_text(item.line).unwrap_or("");
                let _ = writeln!(failures, "  {}", checked.render_one(item));
                let _ = writeln!(failures, "      | {}", source_line.trim_end());
            }
        }
    }
    assert!(
        failures.is_empty(),
        "valid programs got diagnostics:\n{failures}"
    );
}

#[test]
fn err_fixtures_match_their_snapshots() {
    let update = updating_snapshots();
    let mut failures = String::new();
    for path in program_files(&fixtures_dir().join("err")) {
        let checked = check_file(&path);
        let actual = checked.render();
        let snapshot = snapshot_path(&path);
        for problem in checked.span_problems() {
            let _ = writeln!(failures, "{}: {problem}", relative(&path));
        }
        if checked.diagnostics.is_empty() {
            let _ = writeln!(
                failures,
                "{}: no diagnostic at all; an err fixture must produce at least one",
                relative(&path)
            );
        }
        match fs::read_to_string(&snapshot) {
            Ok(expected) if expected.replace("\r\n", "\n") == actual => {}
            Ok(expected) => {
                if update {
                    fs::write(&snapshot, &actual).expect("snapshot written");
                    eprintln!("updated {}", relative(&snapshot));
                } else {
                    let _ = writeln!(
                        failures,
                        "{} does not match (run with UPDATE_SNAPSHOTS=1 to accept):\n{}",
                        relative(&snapshot),
                        diff(&expected.replace("\r\n", "\n"), &actual)
                    );
                }
            }
            Err(error) if error.kind() == std::io::ErrorKind::NotFound => {
                fs::write(&snapshot, &actual).expect("snapshot written");
                if update {
                    eprintln!("created {}", relative(&snapshot));
                } else {
                    let _ = writeln!(
                        failures,
                        "{} was missing and has been created; read it, then run the test again:\n{}",
                        relative(&snapshot),
                        actual
                    );
                }
            }
            Err(error) => panic!("{}: {error}", snapshot.display()),
        }
    }
    assert!(failures.is_empty(), "snapshot failures:\n{failures}");
}

#[test]
fn every_snapshot_has_its_program() {
    let dir = fixtures_dir().join("err");
    let mut orphans = Vec::new();
    for entry in fs::read_dir(&dir).expect("the err fixture folder") {
        let path = entry.expect("readable folder entry").path();
        if path
            .extension()
            .is_some_and(|extension| extension == SNAPSHOT_EXTENSION)
            && !path.with_extension("").is_file()
        {
            orphans.push(relative(&path));
        }
    }
    assert!(
        orphans.is_empty(),
        "snapshots without a program (delete them): {orphans:?}"
    );
}

#[test]
fn every_diagnostic_code_has_an_err_fixture() {
    let mut produced = BTreeSet::new();
    for path in program_files(&fixtures_dir().join("err")) {
        produced.extend(
            check_file(&path)
                .diagnostics
                .iter()
                .map(|item| item.diagnostic.code),
        );
    }
    let exempt: BTreeSet<&str> = CODES_WITHOUT_FIXTURE
        .iter()
        .map(|(code, _)| *code)
        .collect();
    // Syntax codes start with S; the semantic (A) codes are covered by the analysis tests.
    let missing: Vec<&str> = Code::ALL
        .iter()
        .filter(|code| code.as_str().starts_with('S'))
        .filter(|code| !produced.contains(*code) && !exempt.contains(code.as_str()))
        .map(|code| code.as_str())
        .collect();
    assert!(
        missing.is_empty(),
        "no err fixture produces these codes: {missing:?}"
    );
}

#[test]
fn the_diff_marks_changed_lines() {
    let shown = diff("a\nb\nc\n", "a\nx\nc\nd\n");
    assert_eq!(shown, "--- expected\n+++ actual\n  a\n- b\n+ x\n  c\n+ d\n");
}
