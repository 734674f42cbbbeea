//! Every reproducer of a fuzz finding (fixtures/fuzz) runs through all five fuzz targets: the block
//! parser, the full analysis, the document model under edits, the command line's output formats and
//! the configuration reader. Each one failed once; they must pass now, with the same checks the fuzzer
//! applies (examples/fuzz/targets.rs, document.rs, cli.rs and config.rs).

#[allow(dead_code)]
#[path = "support/fuzz.rs"]
mod fuzz;

use fuzz::{cases, document, random, seeds, targets};

use cases::{run_case, Case, Target};
use std::path::Path;

#[test]
fn every_fuzz_reproducer_passes_every_target() {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/fuzz");
    let files = seeds::files_below(&folder);
    assert!(
        files.len() >= 5,
        "expected the reproducers of the fixed fuzz findings in {}",
        folder.display()
    );
    let mut failures = Vec::new();
    for path in &files {
        let case = Case::from_file(path).expect("a reproducer can be read");
        for target in [
            Target::Parser,
            Target::Analysis,
            Target::Document,
            Target::Cli,
            Target::Config,
        ] {
            if let Err(problem) = run_case(target, &case) {
                failures.push(format!("{} ({}): {problem}", path.display(), target.name()));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn a_document_case_survives_writing_and_reading() {
    // The reproducer format must keep any text: line ends inside lines are impossible, but empty
    // lines, control bytes and non-ASCII text are common.
    let mut random = random::Random::new(11);
    for _ in 0..200 {
        let case = document::generate_case(&mut random, &[], 6);
        let bytes = case.to_bytes();
        assert_eq!(document::DocumentCase::from_bytes(&bytes), Some(case));
    }
}

#[test]
fn the_checks_find_an_infinite_position() {
    // The property the first reproducers broke: a move must never show infinity as a number.
    let text = "G0 X1\n";
    let mut movement = sinumerik_lsp::analysis::analyze(text, &Default::default()).moves[0].clone();
    assert!(targets::check_move_numbers(&movement).is_ok());
    movement.end[0].1 = f64::INFINITY;
    assert!(targets::check_move_numbers(&movement).is_err());
}

#[test]
fn the_checks_find_infinity_and_nan_in_a_block_report() {
    assert!(document::check_finite_debug(&(Some(1.5), "information", vec![2.0])).is_ok());
    assert!(document::check_finite_debug(&(Some(f64::INFINITY), "X")).is_err());
    assert!(document::check_finite_debug(&[f64::NAN]).is_err());
    assert!(document::check_finite_debug(&-f64::INFINITY).is_err());
}
