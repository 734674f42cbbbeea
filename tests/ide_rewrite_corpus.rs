//! Formatting and renumbering round trips over every valid program of the real corpus
//! (`../shared/corpus/real`, without the files listed in `tests/corpus_known_invalid.txt`): the
//! rewritten text must resolve to exactly the same end points (`analysis::visit_moves`), keep every
//! comment and string byte for byte, and formatting must be idempotent. Files are read as the CLI
//! reads them. The W3xx findings of the workspace index report no error on a valid program either.
//! When the corpus is absent, the tests print a message and pass.

use sinumerik_lsp::analysis::{visit_moves, Move, ProgramKind};
use sinumerik_lsp::config::MachineConfig;
use sinumerik_lsp::ide::format::{format_text, FormatOptions};
use sinumerik_lsp::ide::renumber::{renumber_text, NumberingMode, RenumberOptions};
use sinumerik_lsp::io::source_file::read_source_file;
use sinumerik_lsp::syntax::lexer::{lex_line_into, Token};
use sinumerik_lsp::syntax::lines::line_ranges;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

fn corpus_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/corpus/real")
}

/// The `path<TAB>reason` patterns of the known-invalid list (`*` matches any run of characters).
fn known_invalid_patterns() -> Vec<String> {
    let list = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus_known_invalid.txt"),
    )
    .expect("tests/corpus_known_invalid.txt is readable");
    list.lines()
        .filter(|line| !line.trim().is_empty() && !line.trim_start().starts_with('#'))
        .filter_map(|line| {
            line.split('\t')
                .next()
                .map(|pattern| pattern.trim().to_string())
        })
        .collect()
}

fn wildcard_match(pattern: &str, text: &str) -> bool {
    match pattern.split_once('*') {
        None => pattern == text,
        Some((head, tail)) => {
            text.starts_with(head)
                && (0..=text.len() - head.len()).any(|skip| {
                    text.is_char_boundary(head.len() + skip)
                        && wildcard_match(tail, &text[head.len() + skip..])
                })
        }
    }
}

/// The valid corpus programs as (relative path, text, kind); `None` when the corpus is absent.
fn valid_corpus_programs() -> Option<Vec<(String, String, ProgramKind)>> {
    let root = corpus_dir();
    if !root.is_dir() {
        println!("corpus not found at {}; skipping", root.display());
        return None;
    }
    let patterns = known_invalid_patterns();
    let mut files = Vec::new();
    let mut pending = vec![root.clone()];
    while let Some(folder) = pending.pop() {
        for entry in std::fs::read_dir(&folder).expect("readable corpus folder") {
            let path = entry.expect("folder entry").path();
            if path.is_dir() {
                pending.push(path);
            } else {
                files.push(path);
            }
        }
    }
    files.sort();
    let mut programs = Vec::new();
    for path in files {
        let relative = path
            .strip_prefix(&root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        if matches!(relative.as_str(), "PROVENANCE.md" | "STATS.md")
            || patterns
                .iter()
                .any(|pattern| wildcard_match(pattern, &relative))
        {
            continue;
        }
        let source = read_source_file(&path).unwrap_or_else(|error| panic!("{relative}: {error}"));
        let kind =
            ProgramKind::from_extension(path.extension().and_then(|extension| extension.to_str()));
        programs.push((relative, source.text, kind));
    }
    assert!(!programs.is_empty(), "no valid corpus programs found");
    Some(programs)
}

/// The end points of a program, without the block numbers (which renumbering changes on purpose).
fn end_points(text: &str, config: &MachineConfig, kind: ProgramKind) -> Vec<Move> {
    let mut moves = Vec::new();
    visit_moves(text, config, kind, |movement| {
        let mut movement = movement.clone();
        movement.block_number = None;
        moves.push(movement);
    });
    moves
}

/// Every comment and string of the text with its line, as written.
fn comments_and_strings(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut lexemes = Vec::new();
    for (line_index, (start, end)) in line_ranges(text).enumerate() {
        let line = &text[start..end];
        lex_line_into(line, &mut lexemes);
        for lexeme in &lexemes {
            if matches!(
                lexeme.token,
                Some(Token::Comment | Token::String | Token::UnterminatedString)
            ) {
                out.push((
                    line_index,
                    line[lexeme.span.start()..lexeme.span.end()].to_string(),
                ));
            }
        }
    }
    out
}

fn first_difference(before: &[Move], after: &[Move]) -> String {
    match before.iter().zip(after).find(|(left, right)| left != right) {
        Some((left, right)) => format!("line {}: before {left:?}\n after {right:?}", left.line + 1),
        None => format!("{} moves before, {} after", before.len(), after.len()),
    }
}

#[test]
fn formatting_keeps_end_points_comments_and_strings_of_every_corpus_program() {
    let Some(programs) = valid_corpus_programs() else {
        return;
    };
    let config = MachineConfig::mill();
    let mut failures = String::new();
    let mut changed_files = 0;
    for (path, text, kind) in &programs {
        let formatted = format_text(text, &config, FormatOptions::default());
        if &formatted != text {
            changed_files += 1;
        }
        let before = end_points(text, &config, *kind);
        let after = end_points(&formatted, &config, *kind);
        if before != after {
            let _ = writeln!(
                failures,
                "{path}: formatting changed the end points: {}",
                first_difference(&before, &after)
            );
        }
        if comments_and_strings(text) != comments_and_strings(&formatted) {
            let _ = writeln!(failures, "{path}: formatting changed a comment or string");
        }
        if format_text(&formatted, &config, FormatOptions::default()) != formatted {
            let _ = writeln!(
                failures,
                "{path}: formatting twice differs from formatting once"
            );
        }
        if line_ranges(text).count() != line_ranges(&formatted).count() {
            let _ = writeln!(failures, "{path}: formatting changed the number of lines");
        }
    }
    println!(
        "fmt round trip: {} programs, {changed_files} changed by formatting",
        programs.len()
    );
    assert!(
        changed_files > 0,
        "formatting changed no corpus program, so the round trip tested nothing"
    );
    assert!(failures.is_empty(), "{failures}");
}

#[test]
fn renumbering_keeps_end_points_comments_and_strings_of_every_corpus_program() {
    let Some(programs) = valid_corpus_programs() else {
        return;
    };
    let config = MachineConfig::mill();
    let mut failures = String::new();
    let mut changed_files = 0;
    for mode in [NumberingMode::Keep, NumberingMode::All, NumberingMode::Drop] {
        let options = RenumberOptions {
            start: 10,
            step: 10,
            mode,
        };
        for (path, text, kind) in &programs {
            let renumbered = match renumber_text(text, &config, options) {
                Ok(renumbered) => renumbered,
                Err(error) => {
                    let _ = writeln!(failures, "{path} ({mode:?}): {error}");
                    continue;
                }
            };
            if &renumbered != text {
                changed_files += 1;
            }
            let before = end_points(text, &config, *kind);
            let after = end_points(&renumbered, &config, *kind);
            if before != after {
                let _ = writeln!(
                    failures,
                    "{path} ({mode:?}): renumbering changed the end points: {}",
                    first_difference(&before, &after)
                );
            }
            if comments_and_strings(text) != comments_and_strings(&renumbered) {
                let _ = writeln!(
                    failures,
                    "{path} ({mode:?}): renumbering changed a comment or string"
                );
            }
        }
    }
    println!(
        "renumber round trip: {} programs in 3 modes, {changed_files} rewrites changed the text",
        programs.len()
    );
    assert!(
        changed_files > 0,
        "renumbering changed no corpus program, so the round trip tested nothing"
    );
    assert!(failures.is_empty(), "{failures}");
}

/// Errors the W3xx findings report on corpus programs that the checker otherwise accepts (path,
/// 1-based line, code, why). None: `check` reports the W3xx findings too, so the programs with real
/// mistakes of this kind (jumps to missing labels or the wrong way, DEF after the first executable
/// block) are listed in `tests/corpus_known_invalid.txt` with the reason and are not valid programs.
const KNOWN_WORKSPACE_ERRORS: &[(&str, usize, &str, &str)] = &[];

#[test]
fn workspace_findings_give_no_error_on_valid_corpus_programs() {
    use sinumerik_lsp::analysis::document::TextLines;
    use sinumerik_lsp::diagnostics::Severity;
    use sinumerik_lsp::ide::cross_file_diagnostics::cross_file_diagnostics;
    use sinumerik_lsp::ide::WorkspaceIndex;
    use std::collections::BTreeMap;
    let Some(programs) = valid_corpus_programs() else {
        return;
    };
    let config = MachineConfig::mill();
    // One workspace per project folder of the corpus, as an editor would open it.
    let mut projects: BTreeMap<String, Vec<&(String, String, ProgramKind)>> = BTreeMap::new();
    for program in &programs {
        projects
            .entry(program.0.split('/').next().unwrap().to_string())
            .or_default()
            .push(program);
    }
    let mut errors: Vec<(String, usize, String, String)> = Vec::new();
    let mut findings = 0;
    for members in projects.values() {
        let mut index = WorkspaceIndex::new();
        for (path, text, _) in members {
            index.update(
                std::sync::Arc::from(path.as_str()),
                path,
                &TextLines::new(text),
                &config,
            );
        }
        for (path, _, _) in members {
            for item in cross_file_diagnostics(&index, path, &config) {
                findings += 1;
                if item.diagnostic.severity == Severity::Error {
                    errors.push((
                        path.clone(),
                        item.line + 1,
                        item.diagnostic.code.to_string(),
                        item.diagnostic.message,
                    ));
                }
            }
        }
    }
    println!(
        "workspace findings on valid corpus programs: {findings}, {} errors",
        errors.len()
    );
    let found: Vec<(String, usize, String)> = errors
        .iter()
        .map(|(path, line, code, _)| (path.clone(), *line, code.clone()))
        .collect();
    let expected: Vec<(String, usize, String)> = KNOWN_WORKSPACE_ERRORS
        .iter()
        .map(|(path, line, code, _)| (path.to_string(), *line, code.to_string()))
        .collect();
    let messages: String = errors
        .iter()
        .map(|(path, line, code, message)| format!("{path}:{line}: {code} {message}\n"))
        .collect();
    assert_eq!(
        found, expected,
        "the errors of the workspace findings on valid corpus programs changed:\n{messages}"
    );
}
