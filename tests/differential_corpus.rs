//! Differential check of the document model at scale: random edit steps across the conformance
//! fixtures and the real programs of the corpus (read from ../shared/corpus/real, skipped with a
//! message when absent), the incremental analysis compared with a from-scratch one after every step:
//! diagnostics exactly, block reports and moves with positions to 1e-6. `DIFFERENTIAL_STEPS` changes
//! the number of steps (2,000 by default; the run at scale is
//! `DIFFERENTIAL_STEPS=100000 cargo test --release --test differential_corpus -- --nocapture`, see
//! docs/reliability.md) and `DIFFERENTIAL_SEED` the seed.

#[path = "support/env_setting.rs"]
mod env_setting;
#[allow(dead_code)]
#[path = "support/fuzz.rs"]
mod fuzz;

use env_setting::setting;
use fuzz::{document, random, seeds};

use document::{check_document, random_edit, DocumentCase};
use random::Random;
use std::path::Path;

/// Edit steps in total (unless `DIFFERENTIAL_STEPS` says otherwise), and per document before the
/// next file is taken.
const STEPS: usize = 2_000;
const STEPS_PER_DOCUMENT: usize = 25;
/// A window of a long file, so that one step stays in the milliseconds.
const MAX_LINES: usize = 3_000;

/// The programs edited: the conformance fixtures and, when present, the corpus (NC files only).
/// Each program is (name, lines, whether it is from the corpus).
fn programs() -> (Vec<(String, Vec<String>, bool)>, usize) {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut programs = Vec::new();
    let mut from_corpus = 0;
    for (folder, is_corpus) in [
        (crate_dir.join("fixtures/conformance"), false),
        (seeds::corpus_dir(crate_dir), true),
    ] {
        for path in seeds::files_below(&folder) {
            let extension = path
                .extension()
                .and_then(|extension| extension.to_str())
                .unwrap_or("")
                .to_ascii_lowercase();
            if !matches!(extension.as_str(), "mpf" | "spf") {
                continue;
            }
            let bytes = std::fs::read(&path).expect("a program can be read");
            let text = sinumerik_lsp::io::source_file::decode_source(&bytes).text;
            let mut lines = seeds::split_lines(&text);
            lines.truncate(MAX_LINES);
            if lines.is_empty() {
                continue;
            }
            from_corpus += usize::from(is_corpus);
            programs.push((path.display().to_string(), lines, is_corpus));
        }
    }
    (programs, from_corpus)
}

#[test]
fn random_edits_of_fixtures_and_real_programs_match_a_fresh_analysis() {
    let (programs, from_corpus) = programs();
    assert!(programs.len() >= 10, "the conformance fixtures are missing");
    if from_corpus == 0 {
        eprintln!(
            "corpus not found (../shared/corpus/real): editing the conformance fixtures only"
        );
    }
    let total_steps = setting("DIFFERENTIAL_STEPS", STEPS as u64) as usize;
    let mut random = Random::new(setting("DIFFERENTIAL_SEED", 20_260_101));
    let started = std::time::Instant::now();
    let mut steps = 0;
    let mut documents = 0;
    let mut corpus_documents = 0;
    while steps < total_steps {
        let (name, lines, is_corpus) = &programs[random.below(programs.len())];
        let mut current = lines.clone();
        let mut edits = Vec::with_capacity(STEPS_PER_DOCUMENT);
        for _ in 0..STEPS_PER_DOCUMENT {
            let edit = random_edit(&mut random, &current, lines);
            document::apply(&mut current, &edit);
            edits.push(edit);
        }
        let lower = name.to_ascii_lowercase();
        let case = DocumentCase {
            turn: lower.contains("turn"),
            subprogram: lower.ends_with(".spf"),
            terminator: (documents % 3) as u8,
            lines: lines.clone(),
            edits,
        };
        match check_document(&case) {
            Ok(checked) => {
                steps += checked;
                corpus_documents += usize::from(*is_corpus);
            }
            Err(problem) => {
                let path = std::env::temp_dir().join(format!("differential-{documents}.fuzzdoc"));
                let _ = std::fs::write(&path, case.to_bytes());
                panic!(
                    "{name}: {problem}\nthe case is in {} (replay it with the fuzz example's --replay)",
                    path.display()
                );
            }
        }
        documents += 1;
    }
    eprintln!(
        "{steps} edit steps on {documents} documents ({corpus_documents} of them from the corpus; {} programs, {from_corpus} from the corpus) matched a fresh analysis in {:.1} s",
        programs.len(),
        started.elapsed().as_secs_f64()
    );
    assert!(steps >= total_steps);
}
