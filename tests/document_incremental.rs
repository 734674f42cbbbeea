//! The incremental analysis of a document must equal a from-scratch analysis of the same text after
//! any sequence of edits: diagnostics, moves and block reports. Random edits (a small deterministic
//! generator, so a failure names its seed) replace line ranges with lines drawn from a pool of blocks
//! that change the modal state, open and close structures, define macros and move axes.

use sinumerik_lsp::analysis::document::{
    DocumentAnalysis, LineSource, TextLines, CHECKPOINT_INTERVAL,
};
use sinumerik_lsp::analysis::{diagnose_program, ProgramKind};
use sinumerik_lsp::config::MachineConfig;
use sinumerik_lsp::diagnostics::LineDiagnostic;
use std::sync::Arc;

#[path = "support/generated.rs"]
mod generated;

/// A xorshift generator: deterministic, no dependency.
struct Random(u64);

impl Random {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, bound: usize) -> usize {
        (self.next() % bound.max(1) as u64) as usize
    }
}

/// Blocks an edit may insert: every kind of state change the analysis follows, and mistakes.
const POOL: &[&str] = &[
    "N10 G90 G0 X10 Y20 Z30",
    "G91",
    "G90",
    "X=IC(5) Y=AC(2)",
    "Z=IC(-32)",
    "G1 X1 F100",
    "G1 X2",
    "G2 X10 Y0 I5 J0",
    "G3 X0 Y0 CR=5",
    "G70",
    "G71",
    "G700 F10",
    "G18 DIAMON",
    "G17 DIAMOF",
    "R1=5",
    "R2=R1*2 X=R2",
    "IF R1==5 GOTOF END1",
    "END1:",
    "WHILE R1>0",
    "ENDWHILE",
    "IF R1>2",
    "ELSE",
    "ENDIF",
    "TRANS X10",
    "AROT RPL=30",
    "G111 X0 Y0",
    "G1 AP=45 RP=10",
    "L100",
    "M6",
    "Z=AC17",
    "X=IC(",
    "; a comment",
    "",
    "   ",
    "DEF REAL DEPTH",
    "DEPTH=-5",
    "G1 Z=DEPTH",
    "F0",
    "R3=1/0",
    "X1 X2",
    "G54",
    "G500",
    "G53 X0",
    "SUPA Z0",
    "G1 Z=IC(1)",
    "X0.5 Y-0.25",
    "G91 X0.125",
    "CT X5 Y5",
    "CIP X1 Y1 I1=0.5 J1=0.5",
    "G2 X2 Y0 AR=90",
    "A=DC(10)",
    "$P_UIFR[1]=CTRANS(X,200)",
];

/// Rare blocks that change how the whole document reads.
const RARE: &[&str] = &["DEFINE RETRACT AS G0 Z100", "RETRACT", "PROC SUB1"];

fn random_line(random: &mut Random) -> String {
    if random.below(60) == 0 {
        return RARE[random.below(RARE.len())].to_string();
    }
    POOL[random.below(POOL.len())].to_string()
}

fn joined(lines: &[String]) -> String {
    let mut text = String::new();
    for line in lines {
        text.push_str(line);
        text.push('\n');
    }
    text
}

/// The debug form of a value with every decimal number rounded to six places: an edit may carry a
/// difference of positions across blocks instead of adding the increments again, which gives the same
/// positions up to the last bits of a double.
fn rounded_debug(value: &impl std::fmt::Debug) -> String {
    let text = format!("{value:?}");
    let mut out = String::with_capacity(text.len());
    let bytes = text.as_bytes();
    let mut index = 0;
    while index < bytes.len() {
        let starts_number = bytes[index].is_ascii_digit()
            && (index == 0
                || !(bytes[index - 1].is_ascii_alphanumeric() || bytes[index - 1] == b'_'));
        if !starts_number {
            out.push(bytes[index] as char);
            index += 1;
            continue;
        }
        let mut end = index;
        while end < bytes.len()
            && (bytes[end].is_ascii_digit() || matches!(bytes[end], b'.' | b'e' | b'-'))
        {
            if bytes[end] == b'-' && bytes[end - 1] != b'e' {
                break;
            }
            end += 1;
        }
        let literal = &text[index..end];
        match literal.parse::<f64>() {
            Ok(number) if literal.contains('.') || literal.contains('e') => {
                let rounded = (number * 1e6).round() / 1e6;
                out.push_str(&format!("{}", if rounded == 0.0 { 0.0 } else { rounded }))
            }
            _ => out.push_str(literal),
        }
        index = end;
    }
    out
}

/// Fails with the first difference of two diagnostic lists, not with both lists in full.
fn assert_same_diagnostics(actual: &[LineDiagnostic], expected: &[LineDiagnostic], context: &str) {
    let first_difference = actual
        .iter()
        .zip(expected)
        .position(|(actual, expected)| actual != expected);
    match first_difference {
        Some(index) => panic!(
            "{context}: diagnostic {index} differs:\n  incremental {:?}\n  expected    {:?}",
            actual[index], expected[index]
        ),
        None => assert_eq!(
            actual.len(),
            expected.len(),
            "{context}: different counts; extra: {:?}",
            if actual.len() > expected.len() {
                &actual[expected.len()..]
            } else {
                &expected[actual.len()..]
            }
        ),
    }
}

/// Applies `steps` random edits to `lines` and checks the incremental analysis after each.
fn check_random_edits(seed: u64, mut lines: Vec<String>, steps: usize, config: MachineConfig) {
    let config = Arc::new(config);
    let mut random = Random(seed);
    let text = joined(&lines);
    let mut analysis =
        DocumentAnalysis::new(&TextLines::new(&text), config.clone(), ProgramKind::Main);
    for step in 0..steps {
        let first = random.below(lines.len() + 1);
        let removed = random.below((lines.len() - first).min(4) + 1);
        let inserted_count = if random.below(8) == 0 {
            random.below(40)
        } else {
            random.below(3)
        };
        let inserted: Vec<String> = (0..inserted_count)
            .map(|_| random_line(&mut random))
            .collect();
        lines.splice(first..first + removed, inserted);
        let text = joined(&lines);
        let source = TextLines::new(&text);
        analysis.update(&source, first, removed, inserted_count);
        let fresh = DocumentAnalysis::new(&source, config.clone(), ProgramKind::Main);
        assert_same_diagnostics(
            analysis.diagnostics(),
            fresh.diagnostics(),
            &format!("seed {seed}, step {step}: after replacing {removed} lines at {first} by {inserted_count}"),
        );
        if step % 10 == 0 {
            assert_same_diagnostics(
                analysis.diagnostics(),
                &diagnose_program(&text, &config, ProgramKind::Main),
                &format!("seed {seed}, step {step}: the document and the checker"),
            );
            let line = random.below(lines.len() + 1);
            assert_eq!(
                rounded_debug(&analysis.block_report(&source, line)),
                rounded_debug(&fresh.block_report(&source, line)),
                "seed {seed}, step {step}: block report of line {line}"
            );
            let range = line..(line + 700).min(lines.len());
            let incremental_moves = analysis.moves(&source, range.clone());
            let fresh_moves = fresh.moves(&source, range);
            assert_eq!(
                incremental_moves.len(),
                fresh_moves.len(),
                "seed {seed}, step {step}: moves"
            );
            for (incremental, fresh) in incremental_moves.iter().zip(&fresh_moves) {
                assert_eq!(
                    rounded_debug(incremental),
                    rounded_debug(fresh),
                    "seed {seed}, step {step}: move of line {}",
                    fresh.line
                );
            }
        }
    }
}

#[test]
fn random_edits_of_a_small_program_match_a_fresh_analysis() {
    for seed in 1..=20u64 {
        let mut random = Random(seed * 7919);
        let lines: Vec<String> = (0..60).map(|_| random_line(&mut random)).collect();
        check_random_edits(seed, lines, 150, MachineConfig::mill());
    }
}

#[test]
fn random_edits_across_checkpoints_match_a_fresh_analysis() {
    // Programs longer than a few checkpoint intervals, so that passes stop early at checkpoints.
    let mut random = Random(42);
    let lines: Vec<String> = (0..3000).map(|_| random_line(&mut random)).collect();
    check_random_edits(42, lines, 120, MachineConfig::mill());
}

#[test]
fn random_edits_of_generated_programs_match_a_fresh_analysis() {
    for (style, config) in [
        ("inc", MachineConfig::mill()),
        ("turning", MachineConfig::turn()),
        ("mixed", MachineConfig::mill()),
    ] {
        let Some(text) = generated::generate(style, 4000) else {
            eprintln!("skipped: ../shared/bench/gen_program.py is not available");
            return;
        };
        let lines: Vec<String> = text.lines().map(str::to_string).collect();
        check_random_edits(style.len() as u64, lines, 60, config);
    }
}

#[test]
fn an_edit_far_from_the_end_stops_at_a_checkpoint() {
    // A comment edit leaves the state unchanged: the diagnostics of the rest are kept, and they are
    // still the right ones (the syntax error on the last line stays where it is).
    let config = Arc::new(MachineConfig::mill());
    let mut lines: Vec<String> = (0..5000)
        .map(|index| format!("N{index} G1 X{index} F100"))
        .collect();
    lines.push("Z=AC17".to_string());
    let text = joined(&lines);
    let mut analysis =
        DocumentAnalysis::new(&TextLines::new(&text), config.clone(), ProgramKind::Main);
    let codes: Vec<&str> = analysis
        .diagnostics()
        .iter()
        .map(|item| item.diagnostic.code.as_str())
        .collect();
    assert_eq!(codes, ["S101", "A202"]);
    lines.insert(10, "; inserted".to_string());
    let text = joined(&lines);
    analysis.update(&TextLines::new(&text), 10, 0, 1);
    assert_same_diagnostics(
        analysis.diagnostics(),
        &diagnose_program(&text, &config, ProgramKind::Main),
        "after the comment",
    );
    assert_eq!(analysis.diagnostics()[0].line, 5001);
    assert!(
        analysis.lines_read_by_last_update() <= 2 * CHECKPOINT_INTERVAL,
        "the edit re-read {} lines",
        analysis.lines_read_by_last_update()
    );
}

#[test]
fn a_changed_increment_is_carried_to_the_end_without_reading_it_again() {
    // Every later position moves by the same amount, and every later block reads X incrementally:
    // the edit re-reads one interval, and the result is that of a fresh analysis.
    let config = Arc::new(MachineConfig::mill());
    let mut lines = vec!["G0 X0 Y0 Z0".to_string(), "G91 G1 F100".to_string()];
    for index in 0..6000 {
        lines.push(match index % 50 {
            0 => "G2 X2 Y0 I1 J0".to_string(),
            7 => "Y=AC(3) X1".to_string(),
            13 => "X1 Y1 Z=IC(1)".to_string(),
            _ => format!("X0.{} Y-0.1", index % 7),
        });
    }
    lines.push("G90 G0 Z100".to_string());
    let text = joined(&lines);
    let mut analysis =
        DocumentAnalysis::new(&TextLines::new(&text), config.clone(), ProgramKind::Main);
    lines[100] = "X0.5 Y-0.1 Z0.25".to_string();
    let text = joined(&lines);
    let source = TextLines::new(&text);
    analysis.update(&source, 100, 1, 1);
    assert!(
        analysis.lines_read_by_last_update() <= 2 * CHECKPOINT_INTERVAL,
        "the edit re-read {} lines",
        analysis.lines_read_by_last_update()
    );
    let fresh = DocumentAnalysis::new(&source, config.clone(), ProgramKind::Main);
    assert_same_diagnostics(
        analysis.diagnostics(),
        fresh.diagnostics(),
        "after the edit",
    );
    for line in [99, 100, 101, 3000, 6001, 6002] {
        assert_eq!(
            rounded_debug(&analysis.block_report(&source, line)),
            rounded_debug(&fresh.block_report(&source, line)),
            "line {line}"
        );
    }
    // A second edit after the first starts from the moved checkpoints.
    lines[5000] = "X0.7 Y-0.1".to_string();
    let text = joined(&lines);
    let source = TextLines::new(&text);
    analysis.update(&source, 5000, 1, 1);
    let fresh = DocumentAnalysis::new(&source, config, ProgramKind::Main);
    assert_eq!(
        rounded_debug(&analysis.block_report(&source, 6001)),
        rounded_debug(&fresh.block_report(&source, 6001))
    );
}

/// Checks that the two-thread analysis of `text` is the one-thread analysis; returns the lines the
/// two-thread analysis read.
fn check_parallel_analysis(text: &str, context: &str) -> usize {
    let config = Arc::new(MachineConfig::mill());
    let source = TextLines::new(text);
    let mut helper_source = TextLines::new(text);
    let parallel = DocumentAnalysis::new_in_parallel(
        &source,
        &mut helper_source,
        config.clone(),
        ProgramKind::Main,
    );
    let sequential = DocumentAnalysis::new(&source, config, ProgramKind::Main);
    assert_same_diagnostics(parallel.diagnostics(), sequential.diagnostics(), context);
    let line_count = source.line_count();
    let mut random = Random(0x5EED ^ line_count as u64);
    for _ in 0..20 {
        let line = random.below(line_count + 1);
        assert_eq!(
            rounded_debug(&parallel.block_report(&source, line)),
            rounded_debug(&sequential.block_report(&source, line)),
            "{context}: block report of line {line}"
        );
        let range = line..(line + 600).min(line_count);
        assert_eq!(
            rounded_debug(&parallel.moves(&source, range.clone())),
            rounded_debug(&sequential.moves(&source, range.clone())),
            "{context}: moves of lines {range:?}"
        );
    }
    parallel.lines_read_by_last_update()
}

fn program(header: &[&str], body: impl Fn(usize) -> String, line_count: usize) -> String {
    let mut text: String = header.iter().map(|line| format!("{line}\n")).collect();
    for index in header.len()..line_count {
        text.push_str(&body(index));
        text.push('\n');
    }
    text
}

#[test]
fn a_program_analysed_on_two_threads_reads_each_line_once_when_the_middle_is_guessed_right() {
    let lines = 40 * CHECKPOINT_INTERVAL;
    let text = program(
        &[
            "G17 G90 G71 G54",
            "T1 D1",
            "M6",
            "G0 X0 Y0 Z50",
            "G1 Z5 F2500",
        ],
        |index| {
            format!(
                "N{index} X{}.5 Y{} Z-{}.25",
                index % 97,
                index % 13,
                index % 7
            )
        },
        lines,
    );
    let read = check_parallel_analysis(&text, "absolute program");
    assert_eq!(read, lines, "each line is read once");
}

#[test]
fn facts_of_the_whole_document_read_on_two_threads_are_those_of_one() {
    // A G-function macro defined in the second half is used in the first (an unknown G function
    // without the definition), and a `PROC` header in the second half
    // makes the whole program a subprogram: the two halves are read on different threads, so each
    // half's facts must reach the other's analysis.
    let lines = 40 * CHECKPOINT_INTERVAL;
    let late = 30 * CHECKPOINT_INTERVAL;
    let with_both = |index: usize| match index {
        _ if index == late => "DEFINE G300 AS G0".to_string(),
        _ if index == late + 1 => "PROC LATE".to_string(),
        _ if index % 100 == 7 => format!("G300 X{} Y1", index % 11),
        _ => format!("N{index} G1 X{}.5 Y{}", index % 97, index % 13),
    };
    let text = program(&["G90 G71 F100"], with_both, lines);
    check_parallel_analysis(&text, "late macro and PROC header");
    let macro_only = |index: usize| match index {
        _ if index == late + 1 => "N1 G1 X1".to_string(),
        _ => with_both(index),
    };
    let text = program(&["G90 G71 F100"], macro_only, lines);
    check_parallel_analysis(&text, "late macro");
}

#[test]
fn an_incremental_program_analysed_on_two_threads_carries_the_shift_into_the_second_half() {
    let lines = 40 * CHECKPOINT_INTERVAL;
    let text = program(
        &["G17 G91 G71 G54", "G0 X0 Y0 Z0", "G1 F100"],
        |index| format!("X0.{} Y-0.{}", index % 9 + 1, index % 7 + 1),
        lines,
    );
    let read = check_parallel_analysis(&text, "incremental program");
    assert!(
        read < lines + 2 * CHECKPOINT_INTERVAL,
        "the second half is not read again ({read} lines read)"
    );
}

#[test]
fn programs_whose_middle_state_cannot_be_guessed_are_read_again_from_the_true_state() {
    let lines = 40 * CHECKPOINT_INTERVAL;
    let middle = lines / 2;
    // A variable defined early and changed in the first half, an IF open across the middle, and
    // a change of units in the first half that the guess does not see.
    let text = program(
        &["DEF REAL DEPTH", "DEPTH=-1", "G90 G1 F100 X0 Y0 Z0"],
        |index| match index {
            5000 => "G70".to_string(),
            6000 => "DEPTH=-2".to_string(),
            index if index == middle - 700 => "IF R1==0".to_string(),
            index if index == middle + 700 => "ENDIF".to_string(),
            index if index % 1000 == 0 => "G1 Z=DEPTH".to_string(),
            index => format!("X{} Y{}", index % 50, index % 30),
        },
        lines,
    );
    check_parallel_analysis(&text, "program with state from the first half");
}

#[test]
fn random_and_generated_programs_analysed_on_two_threads_match_one_thread() {
    let mut random = Random(77);
    for round in 0..3 {
        let lines: Vec<String> = (0..30 * CHECKPOINT_INTERVAL)
            .map(|_| random_line(&mut random))
            .collect();
        check_parallel_analysis(&joined(&lines), &format!("random program {round}"));
    }
    for style in ["cam3d", "inc", "turning", "mixed"] {
        match generated::generate(style, 40_000) {
            Some(text) => {
                check_parallel_analysis(&text, style);
            }
            None => eprintln!("skipped {style}: ../shared/bench/gen_program.py is not available"),
        }
    }
}

#[test]
fn an_interrupted_update_is_finished_by_the_next_one_as_if_it_had_run_to_the_end() {
    use sinumerik_lsp::analysis::document::INTERRUPTIBLE_AFTER_LINES;
    let config = Arc::new(MachineConfig::mill());
    let line_count = 3 * INTERRUPTIBLE_AFTER_LINES;
    let mut lines: Vec<String> = (0..line_count)
        .map(|index| match index {
            0 => "G17 G90 G71 G54 G1 F500".to_string(),
            index if index % 997 == 0 => "Z=AC17".to_string(),
            index if index % 1999 == 0 => "G2 X10 Y0 I5 J0".to_string(),
            // Pairs of moves that cancel under G91, so that positions stay small (a sum of
            // increments and a carried shift of them agree to the last digits printed).
            index => {
                let sign = if index % 2 == 0 { "" } else { "-" };
                format!("X{sign}{}.5 Y{sign}{}", index / 2 % 83, index / 2 % 29)
            }
        })
        .collect();
    // Blocks that change how every later block reads, so that updates read far.
    let far_reaching = ["G91", "G90", "G70", "TRANS X10", "G1 X=IC(3)", "X7 Y7"];
    let mut analysis = DocumentAnalysis::new(
        &TextLines::new(&joined(&lines)),
        config.clone(),
        ProgramKind::Main,
    );
    let mut random = Random(2024);
    let mut interruptions = 0;
    for step in 0..24 {
        let first = random.below(lines.len() / 2);
        let removed = random.below(2);
        let inserted: Vec<String> = (0..random.below(3))
            .map(|_| far_reaching[random.below(far_reaching.len())].to_string())
            .collect();
        let inserted_count = inserted.len();
        lines.splice(first..first + removed, inserted);
        let text = joined(&lines);
        let source = TextLines::new(&text);
        let interrupt = step % 3 != 2;
        let finished =
            analysis.update_interruptible(&source, first, removed, inserted_count, &|| interrupt);
        if finished {
            let fresh = DocumentAnalysis::new(&source, config.clone(), ProgramKind::Main);
            assert_same_diagnostics(
                analysis.diagnostics(),
                fresh.diagnostics(),
                &format!("step {step}: after a finished update"),
            );
            let line = random.below(lines.len());
            assert_eq!(
                rounded_debug(&analysis.block_report(&source, line)),
                rounded_debug(&fresh.block_report(&source, line)),
                "step {step}: block report of line {line}"
            );
        } else {
            assert!(interrupt, "step {step}: only an interrupted update stops");
            interruptions += 1;
        }
    }
    // The last edit: a line replaced by itself, finishing whatever was left.
    let text = joined(&lines);
    let source = TextLines::new(&text);
    assert!(analysis.update_interruptible(&source, 5, 1, 1, &|| false));
    let fresh = DocumentAnalysis::new(&source, config, ProgramKind::Main);
    assert_same_diagnostics(analysis.diagnostics(), fresh.diagnostics(), "at the end");
    assert!(
        interruptions >= 2,
        "updates were interrupted ({interruptions} times)"
    );
}
