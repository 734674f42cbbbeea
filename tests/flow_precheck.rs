//! The editor decides from a document's lines whether it runs in program order
//! (`analysis::execution::program::lines_have_flow`), so that a large CAM program is not copied into
//! one text only to learn that it needs no run. That decision must be the one the interpreter's own
//! flow index makes from the text: this test compares both on every fixture program, on every real
//! program of `../shared/corpus/real` (skipped with a message when the corpus is absent) and on the
//! cases where reading line by line could differ (a macro used before its definition, a program end
//! before the last block, structures that do not close).

#[path = "support/corpus_files.rs"]
mod corpus_files;

use corpus_files::{corpus_dir, program_files};
use sinumerik_lsp::analysis::document::{LineSource, TextLines};
use sinumerik_lsp::analysis::execution::program::{lines_have_flow, ProgramUnit};
use sinumerik_lsp::config::MachineConfig;
use sinumerik_lsp::io::source_file::read_source_file;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Both answers for one program text: (from the lines, from the interpreter's text).
fn both_answers(text: &str, config: &MachineConfig) -> (bool, bool) {
    let lines = TextLines::new(text);
    let from_lines = lines_have_flow(
        lines.line_count(),
        &|visit| lines.for_each_line(0, visit),
        config,
        std::iter::empty(),
    );
    // The text as the editor's run makes it: every line followed by a line feed.
    let mut joined = String::new();
    lines.for_each_line(0, &mut |_, line| {
        joined.push_str(line);
        joined.push('\n');
        true
    });
    let unit = ProgramUnit::new(String::new(), None, Arc::from(joined), config);
    (from_lines, unit.flow.has_flow)
}

#[test]
fn lines_tell_flow_as_the_interpreter_does_in_the_cases_that_could_differ() {
    let config = MachineConfig::default();
    for (text, expected) in [
        ("G0 X1\nG1 X2 Y3\nM30\n", false),
        ("G0 X1\nM30\nG1 X2\n", true),
        ("G0 X1\nMARK1: G1 X2\nM30\n", true),
        ("N10 G0 X1\nN20 GOTOB N10\n", true),
        ("WHILE R1<3\nR1=R1+1\n", true),
        ("G0 X1\nENDIF\n", true),
        ("G0 X1\nL100\n", true),
        // A macro used two lines before its definition is a macro, which the run expands like a
        // call, not an unknown word.
        ("G0 X1\nMYMAC\nDEFINE MYMAC AS G0 X5\n", true),
        ("DEF REAL A\nR1=5\nG1 X=R1\n", false),
        ("", false),
        ("G0 X1\r\nG1 X2\r\nM30", false),
    ] {
        let (from_lines, from_text) = both_answers(text, &config);
        assert_eq!(from_lines, from_text, "lines and text disagree on {text:?}");
        assert_eq!(from_text, expected, "flow of {text:?}");
    }
}

fn compare_all(paths: &[PathBuf]) -> (usize, usize) {
    let config = MachineConfig::default();
    let mut with_flow = 0;
    let mut compared = 0;
    for path in paths {
        let Ok(source) = read_source_file(path) else {
            continue;
        };
        let (from_lines, from_text) = both_answers(&source.text, &config);
        assert_eq!(
            from_lines,
            from_text,
            "lines and text disagree on the flow of {}",
            path.display()
        );
        compared += 1;
        with_flow += usize::from(from_text);
    }
    (compared, with_flow)
}

#[test]
fn lines_tell_flow_as_the_interpreter_does_in_every_fixture() {
    let mut paths = Vec::new();
    program_files(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures"),
        &mut paths,
    );
    let (compared, with_flow) = compare_all(&paths);
    println!("{compared} fixture programs, {with_flow} with flow");
    assert!(compared > 100, "only {compared} fixture programs found");
    // Both kinds must be among them, or the comparison says little.
    assert!(
        with_flow > 10 && compared - with_flow > 10,
        "{with_flow} of {compared}"
    );
}

#[test]
fn lines_tell_flow_as_the_interpreter_does_in_the_real_programs() {
    let dir = corpus_dir();
    if !dir.is_dir() {
        println!("corpus not found at {}; skipping", dir.display());
        return;
    }
    let mut paths = Vec::new();
    program_files(&dir, &mut paths);
    let (compared, with_flow) = compare_all(&paths);
    println!("{compared} real programs, {with_flow} with flow");
    assert!(compared > 100, "only {compared} real programs read");
}
