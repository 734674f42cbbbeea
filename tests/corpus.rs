//! The checker over the real-world corpus in `../shared/corpus/real` (public programs, see its
//! PROVENANCE.md): it must never panic, and it must report no error on a file that is not listed in
//! `tests/corpus_known_invalid.txt` with the reason why the file is invalid.
//!
//! The findings are those of `check` that the program's folder decides: the analysis's, and the
//! cross-file findings W301-W307 over the program and definition files of its folder.
//!
//! Every file is read like the command line reads it (UTF-8, else Windows-1252; the binary `.arc`
//! archives included) and checked with `MachineConfig::mill()`; a lathe program (one the mill reports
//! for diameter programming or G96 without a transverse axis) is checked with `MachineConfig::turn()`
//! too, and must get no error either way.
//!
//! When the corpus is not there, the tests print `corpus not found at ...; skipping` and pass.
//! `cargo test --test corpus -- --nocapture` shows a one-line summary of the run.

use sinumerik_lsp::analysis::{analyze_program, ProgramKind};
use sinumerik_lsp::config::MachineConfig;
use sinumerik_lsp::diagnostics::{Code, LineDiagnostic, Severity};
use sinumerik_lsp::ide::cross_file_diagnostics::cross_file_diagnostics;
use sinumerik_lsp::ide::workspace::{call_rank, program_name_and_kind, FileKind};
use sinumerik_lsp::ide::{TextLines, WorkspaceIndex};
use sinumerik_lsp::io::source_file::read_source_file;
use sinumerik_lsp::syntax::lines::line_ranges;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// Files of the corpus folder that describe the corpus rather than belong to it.
const CORPUS_DOCUMENTS: &[&str] = &["PROVENANCE.md", "STATS.md"];

/// How many errors of an offending file are shown.
const ERRORS_SHOWN_PER_FILE: usize = 5;

/// Source lines are cut to this many characters in messages (the archives have megabyte-long lines).
const MAX_SHOWN_LINE_CHARS: usize = 160;

fn manifest_dir() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn corpus_dir() -> PathBuf {
    manifest_dir().join("../shared/corpus/real")
}

fn known_invalid_list_path() -> PathBuf {
    manifest_dir().join("tests/corpus_known_invalid.txt")
}

/// One entry of `corpus_known_invalid.txt`.
struct KnownInvalid {
    /// Relative to the corpus folder, `/`-separated; `*` matches any run of characters.
    pattern: String,
    reason: String,
    line_number: usize,
}

fn load_known_invalid() -> Vec<KnownInvalid> {
    let path = known_invalid_list_path();
    let text =
        fs::read_to_string(&path).unwrap_or_else(|error| panic!("{}: {error}", path.display()));
    let mut entries = Vec::new();
    for (index, line) in text.lines().enumerate() {
        let line = line.trim_end();
        if line.trim().is_empty() || line.trim_start().starts_with('#') {
            continue;
        }
        let Some((pattern, reason)) = line.split_once('\t') else {
            panic!(
                "{}:{}: expected `path<TAB>reason`, found {line:?}",
                path.display(),
                index + 1
            );
        };
        assert!(
            !pattern.trim().is_empty() && !reason.trim().is_empty(),
            "{}:{}: both the path and the reason are needed",
            path.display(),
            index + 1
        );
        entries.push(KnownInvalid {
            pattern: pattern.trim().to_string(),
            reason: reason.trim().to_string(),
            line_number: index + 1,
        });
    }
    entries
}

/// Whether `text` matches `pattern`, where `*` stands for any run of characters (none included).
fn glob_matches(pattern: &str, text: &str) -> bool {
    let mut parts = pattern.split('*');
    let first = parts.next().unwrap_or("");
    let Some(mut rest) = text.strip_prefix(first) else {
        return false;
    };
    let parts: Vec<&str> = parts.collect();
    let Some((last, middle)) = parts.split_last() else {
        return rest.is_empty();
    };
    for part in middle {
        match rest.find(part) {
            Some(position) => rest = &rest[position + part.len()..],
            None => return false,
        }
    }
    rest.len() >= last.len() && rest.ends_with(last)
}

/// All files under `dir`, as paths relative to it with `/` separators, sorted.
fn corpus_files(dir: &Path) -> Vec<String> {
    fn walk(dir: &Path, prefix: &str, out: &mut Vec<String>) {
        let entries =
            fs::read_dir(dir).unwrap_or_else(|error| panic!("{}: {error}", dir.display()));
        for entry in entries {
            let entry = entry.expect("readable folder entry");
            let name = entry.file_name().to_string_lossy().into_owned();
            let relative = if prefix.is_empty() {
                name
            } else {
                format!("{prefix}/{name}")
            };
            let path = entry.path();
            if path.is_dir() {
                walk(&path, &relative, out);
            } else {
                out.push(relative);
            }
        }
    }
    let mut files = Vec::new();
    walk(dir, "", &mut files);
    files.retain(|file| !CORPUS_DOCUMENTS.contains(&file.as_str()));
    files.sort();
    files
}

/// The outcome of checking one corpus file.
enum Outcome {
    Checked {
        text: String,
        diagnostics: Vec<LineDiagnostic>,
        /// For a lathe program (one the mill configuration reports for diameter programming or G96
        /// without a transverse axis, A235/A236): its findings with `MachineConfig::turn()`.
        turn: Option<Vec<LineDiagnostic>>,
    },
    Unreadable(String),
    Panicked(String),
}

struct FileResult {
    path: String,
    outcome: Outcome,
}

impl FileResult {
    fn errors(&self) -> Vec<&LineDiagnostic> {
        match &self.outcome {
            Outcome::Checked { diagnostics, .. } => diagnostics
                .iter()
                .filter(|item| item.diagnostic.severity == Severity::Error)
                .collect(),
            _ => Vec::new(),
        }
    }

    /// The first errors of the file with their source lines, for a failure message.
    fn describe_errors(&self) -> String {
        let Outcome::Checked { text, .. } = &self.outcome else {
            return String::new();
        };
        let lines: Vec<(usize, usize)> = line_ranges(text).collect();
        let errors = self.errors();
        let mut out = format!("{} ({} errors)\n", self.path, errors.len());
        for item in errors.iter().take(ERRORS_SHOWN_PER_FILE) {
            let source_line = lines
                .get(item.line)
                .map(|&(start, end)| &text[start..end])
                .unwrap_or("");
            let column = source_line
                .get(..item.diagnostic.span.start())
                .map_or(0, |before| before.chars().count())
                + 1;
            let _ = writeln!(
                out,
                "  {}:{}: {} {}",
                item.line + 1,
                column,
                item.diagnostic.code,
                item.diagnostic.message
            );
            let _ = writeln!(out, "      | {}", shown_line(source_line));
        }
        if errors.len() > ERRORS_SHOWN_PER_FILE {
            let _ = writeln!(
                out,
                "  ... and {} more",
                errors.len() - ERRORS_SHOWN_PER_FILE
            );
        }
        out
    }
}

fn shown_line(line: &str) -> String {
    let mut shown: String = line
        .trim_end()
        .chars()
        .take(MAX_SHOWN_LINE_CHARS)
        .map(|character| {
            if character.is_control() && character != '\t' {
                '?'
            } else {
                character
            }
        })
        .collect();
    if line.trim_end().chars().count() > MAX_SHOWN_LINE_CHARS {
        shown.push_str(" ...");
    }
    shown
}

fn check_file(corpus: &Path, relative: &str) -> Outcome {
    let source = match read_source_file(&corpus.join(relative)) {
        Ok(source) => source,
        Err(error) => return Outcome::Unreadable(error.to_string()),
    };
    let config = MachineConfig::mill();
    // The whole analysis, as `check` runs it: syntax and the semantic findings of the modal state.
    let kind = ProgramKind::from_extension(
        Path::new(relative)
            .extension()
            .and_then(|extension| extension.to_str()),
    );
    let turn = MachineConfig::turn();
    let run = || {
        let diagnostics = analyze_program(&source.text, &config, kind).diagnostics;
        let lathe = diagnostics.iter().any(|item| {
            matches!(
                item.diagnostic.code,
                Code::DiameterWithoutTransverseAxis | Code::CuttingSpeedWithoutTransverseAxis
            )
        });
        let turn = lathe.then(|| analyze_program(&source.text, &turn, kind).diagnostics);
        (diagnostics, turn)
    };
    match std::panic::catch_unwind(run) {
        Ok((diagnostics, turn)) => Outcome::Checked {
            text: source.text,
            diagnostics,
            turn,
        },
        Err(payload) => Outcome::Panicked(
            payload
                .downcast_ref::<&str>()
                .map(|message| message.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "(no message)".to_string()),
        ),
    }
}

/// Adds the cross-file findings (W301-W307) as `check` reports them: over an index of the program
/// and definition files of each file's folder (the folder `check` searches for callees when no
/// `sinumerik.toml` is in use), complete.
fn add_cross_file_findings(results: &mut [FileResult]) {
    let config = MachineConfig::mill();
    let folder_of = |path: &str| {
        path.rsplit_once('/')
            .map_or("", |(folder, _)| folder)
            .to_string()
    };
    let mut indexes: BTreeMap<String, WorkspaceIndex> = BTreeMap::new();
    for result in results.iter() {
        let Outcome::Checked { text, .. } = &result.outcome else {
            continue;
        };
        let name = result.path.rsplit('/').next().unwrap_or(&result.path);
        if call_rank(name).is_some() || program_name_and_kind(name).1 == FileKind::Definitions {
            let index = indexes.entry(folder_of(&result.path)).or_default();
            index.update(
                result.path.as_str().into(),
                &result.path,
                &TextLines::new(text),
                &config,
            );
        }
    }
    for result in results.iter_mut() {
        let Outcome::Checked {
            text, diagnostics, ..
        } = &mut result.outcome
        else {
            continue;
        };
        let mut index = indexes
            .get(&folder_of(&result.path))
            .cloned()
            .unwrap_or_default();
        index.set_complete(true);
        if index.document(&result.path).is_none() {
            index.update(
                result.path.as_str().into(),
                &result.path,
                &TextLines::new(text),
                &config,
            );
        }
        diagnostics.extend(cross_file_diagnostics(&index, &result.path, &config));
    }
}

struct CorpusRun {
    known_invalid: Vec<KnownInvalid>,
    results: Vec<FileResult>,
}

impl CorpusRun {
    fn known_invalid_entry(&self, path: &str) -> Option<&KnownInvalid> {
        self.known_invalid
            .iter()
            .find(|entry| glob_matches(&entry.pattern, path))
    }

    fn summary(&self) -> String {
        let mut known_invalid_files = 0;
        let mut known_invalid_errors = 0;
        let mut other_errors = 0;
        let mut warnings: BTreeMap<Code, usize> = BTreeMap::new();
        for result in &self.results {
            let errors = result.errors().len();
            if self.known_invalid_entry(&result.path).is_some() {
                known_invalid_files += 1;
                known_invalid_errors += errors;
                continue;
            }
            other_errors += errors;
            if let Outcome::Checked { diagnostics, .. } = &result.outcome {
                for item in diagnostics {
                    if item.diagnostic.severity == Severity::Warning {
                        *warnings.entry(item.diagnostic.code).or_default() += 1;
                    }
                }
            }
        }
        let warnings: Vec<String> = warnings
            .iter()
            .map(|(code, count)| format!("{code} {count}"))
            .collect();
        format!(
            "corpus: {} files checked; {known_invalid_errors} errors on {known_invalid_files} known-invalid files; \
             {other_errors} errors elsewhere; warnings on the other files by code: {}",
            self.results.len(),
            if warnings.is_empty() {
                "none".to_string()
            } else {
                warnings.join(", ")
            }
        )
    }
}

/// The corpus is checked once and shared by the tests of this file; `None` when it is not there.
fn corpus_run() -> Option<&'static CorpusRun> {
    static RUN: OnceLock<Option<CorpusRun>> = OnceLock::new();
    RUN.get_or_init(|| {
        let corpus = corpus_dir();
        if !corpus.is_dir() {
            println!("corpus not found at {}; skipping", corpus.display());
            return None;
        }
        let results: Vec<FileResult> = corpus_files(&corpus)
            .into_iter()
            .map(|path| FileResult {
                outcome: check_file(&corpus, &path),
                path,
            })
            .collect();
        let mut results = results;
        add_cross_file_findings(&mut results);
        assert!(
            !results.is_empty(),
            "the corpus at {} is empty",
            corpus.display()
        );
        let run = CorpusRun {
            known_invalid: load_known_invalid(),
            results,
        };
        println!("{}", run.summary());
        Some(run)
    })
    .as_ref()
}

#[test]
fn every_corpus_file_is_read_and_checked_without_panic() {
    let Some(run) = corpus_run() else {
        return;
    };
    let mut failures = String::new();
    for result in &run.results {
        match &result.outcome {
            Outcome::Panicked(message) => {
                let _ = writeln!(failures, "{}: the checker panicked: {message}", result.path);
            }
            Outcome::Unreadable(error) => {
                let _ = writeln!(failures, "{}: cannot be read: {error}", result.path);
            }
            Outcome::Checked { .. } => {}
        }
    }
    assert!(failures.is_empty(), "{failures}");
}

#[test]
fn no_errors_outside_the_known_invalid_files() {
    let Some(run) = corpus_run() else {
        return;
    };
    let offending: Vec<&FileResult> = run
        .results
        .iter()
        .filter(|result| {
            !result.errors().is_empty() && run.known_invalid_entry(&result.path).is_none()
        })
        .collect();
    let mut message = String::new();
    for result in &offending {
        message.push_str(&result.describe_errors());
    }
    assert!(
        offending.is_empty(),
        "{} corpus files that are not listed in tests/corpus_known_invalid.txt get errors \
         (fix the parser, or list a file there with the reason why it is really invalid):\n{message}",
        offending.len()
    );
}

#[test]
fn the_known_invalid_list_has_no_stale_entries() {
    let Some(run) = corpus_run() else {
        return;
    };
    let mut stale = String::new();
    for entry in &run.known_invalid {
        let matched: Vec<&FileResult> = run
            .results
            .iter()
            .filter(|result| glob_matches(&entry.pattern, &result.path))
            .collect();
        if matched.is_empty() {
            let _ = writeln!(
                stale,
                "line {}: `{}` matches no corpus file",
                entry.line_number, entry.pattern
            );
        }
        for result in matched {
            if result.errors().is_empty() {
                let _ = writeln!(
                    stale,
                    "line {}: `{}` is listed as invalid ({}) but gets no error; remove it from the list",
                    entry.line_number, result.path, entry.reason
                );
            }
        }
    }
    assert!(
        stale.is_empty(),
        "stale entries in tests/corpus_known_invalid.txt:\n{stale}"
    );
}

#[test]
fn glob_patterns_match_like_the_list_expects() {
    assert!(glob_matches("a/sin840d*.spf", "a/sin840d.spf"));
    assert!(glob_matches("a/sin840d*.spf", "a/sin840d_T_CHANGE.spf"));
    assert!(!glob_matches("a/sin840d*.spf", "a/sin840d.mpf"));
    assert!(!glob_matches("a/test.arc", "a/test.arc.d/X.MPF"));
    assert!(glob_matches("a/*", "a/b"));
    assert!(glob_matches("*x*x", "xx"));
    assert!(!glob_matches("*x*x", "x"));
}

#[test]
fn lathe_programs_get_no_errors_with_the_turn_configuration() {
    let Some(run) = corpus_run() else {
        return;
    };
    let mut lathe_programs = 0;
    let mut codes: BTreeMap<Code, usize> = BTreeMap::new();
    let mut offending = String::new();
    for result in &run.results {
        let Outcome::Checked {
            text,
            turn: Some(turn),
            ..
        } = &result.outcome
        else {
            continue;
        };
        if run.known_invalid_entry(&result.path).is_some() {
            continue;
        }
        lathe_programs += 1;
        for item in turn {
            *codes.entry(item.diagnostic.code).or_default() += 1;
        }
        let turn_result = FileResult {
            path: result.path.clone(),
            outcome: Outcome::Checked {
                text: text.clone(),
                diagnostics: turn.clone(),
                turn: None,
            },
        };
        if !turn_result.errors().is_empty() {
            offending.push_str(&turn_result.describe_errors());
        }
    }
    let codes: Vec<String> = codes
        .iter()
        .map(|(code, count)| format!("{code} {count}"))
        .collect();
    println!(
        "corpus with kind = \"turn\": {lathe_programs} valid lathe programs; findings by code: {}",
        codes.join(", ")
    );
    assert!(
        offending.is_empty(),
        "lathe programs that get errors with the turn configuration:\n{offending}"
    );
}
