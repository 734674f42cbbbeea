//! Running a program again after an edit (`run_recorded` with the run of the earlier text) gives the
//! same moves, findings and pass counts as running the edited text from the start: after random
//! edits of programs with loops, jumps and calls, and of the execution fixtures. The tests also check
//! that the edits that should resume do resume, and rejoin the earlier run.

use sinumerik_lsp::analysis::execution::entry::RunSetup;
use sinumerik_lsp::analysis::execution::{run_recorded, ExecutionOptions, RecordedRun, RunStart};
use sinumerik_lsp::analysis::library::{MemoryLibrary, ProgramLibrary};
use sinumerik_lsp::analysis::ProgramKind;
use sinumerik_lsp::config::MachineConfig;
use std::path::Path;
use std::sync::Arc;

#[path = "support/generated.rs"]
mod generated;

/// A small deterministic generator of pseudo-random numbers.
struct Random(u64);

impl Random {
    fn below(&mut self, bound: usize) -> usize {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 % bound.max(1) as u64) as usize
    }
}

fn run(text: &str, library: &dyn ProgramLibrary, earlier: Option<&RecordedRun>) -> RecordedRun {
    run_recorded(
        Arc::from(text),
        &MachineConfig::mill(),
        ProgramKind::Main,
        library,
        &ExecutionOptions::default(),
        &RunSetup {
            entry: None,
            record_first_passes: true,
        },
        earlier,
    )
}

/// Whether a line has a part in the program's flow (a label, a structure, a jump, a call, an end).
fn is_flow_line(line: &str) -> bool {
    let upper = line.to_ascii_uppercase();
    upper.contains(':')
        || upper.contains('(') && !upper.contains("=AC(") && !upper.contains("=IC(")
        || [
            "IF", "ELSE", "WHILE", "FOR", "GOTO", "REPEAT", "UNTIL", "LOOP", "CASE", "M30", "M17",
            "M2", "RET", "PROC", "DEF", "CALL", "L1", "SAVE",
        ]
        .iter()
        .any(|word| upper.contains(word))
}

/// One random edit of a block without flow in `lines` (so that the program's structure stays sound
/// and later edits can resume): mostly a digit of a number changed or a comment added; one in five
/// replaces the line by another line, empties it, or adds or removes a line.
fn edit(lines: &mut Vec<String>, random: &mut Random) {
    let plain: Vec<usize> = (0..lines.len())
        .filter(|&line| !is_flow_line(&lines[line]))
        .collect();
    let Some(&index) = plain.get(random.below(plain.len())) else {
        return;
    };
    if random.below(5) > 0 {
        let digits: Vec<usize> = lines[index]
            .char_indices()
            .filter(|(_, character)| character.is_ascii_digit())
            .map(|(position, _)| position)
            .collect();
        if digits.is_empty() || random.below(4) == 0 {
            lines[index].push_str(" ; checked");
        } else {
            let position = digits[random.below(digits.len())];
            let digit = (b'0' + random.below(10) as u8) as char;
            lines[index].replace_range(position..position + 1, &digit.to_string());
        }
        return;
    }
    match random.below(4) {
        0 => {
            let other = lines[plain[random.below(plain.len())]].clone();
            lines[index] = other;
        }
        1 => lines[index].clear(),
        2 => lines.insert(index, "G1 X7 ; added".to_string()),
        _ => {
            if lines.len() > 2 {
                lines.remove(index);
            }
        }
    }
}

/// Applies `edits` random edits to `text`, one at a time, and checks after each that the run resumed
/// from the previous one equals a run from the start. Returns how the runs started.
fn check_random_edits(
    name: &str,
    text: &str,
    library: &dyn ProgramLibrary,
    edits: usize,
    seed: u64,
) -> Vec<RunStart> {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let mut random = Random(seed);
    let mut earlier = run(text, library, None);
    let mut starts = Vec::new();
    for step in 0..edits {
        edit(&mut lines, &mut random);
        let edited = lines.join("\n") + "\n";
        let again = run(&edited, library, Some(&earlier));
        let fresh = run(&edited, library, None);
        let (mine, theirs) = (&again.execution, &fresh.execution);
        let parts = [
            ("findings", mine.findings == theirs.findings),
            (
                "executed blocks",
                mine.executed_blocks == theirs.executed_blocks,
            ),
            (
                "pass counts",
                again.passes_by_program() == fresh.passes_by_program(),
            ),
            ("first passes", mine.first_passes == theirs.first_passes),
            ("assumptions", mine.assumed == theirs.assumed),
        ];
        // A short program is shown with the failure, to make it a case of its own.
        let shown = if edited.len() < 4000 {
            edited.as_str()
        } else {
            ""
        };
        for (part, same) in parts {
            assert!(
                same,
                "{name}, edit {step}: the {part} of the run from the earlier run differ from a fresh run's ({:?})\n{shown}",
                again.start
            );
        }
        if *again.moves != *fresh.moves {
            let first = again
                .moves
                .iter()
                .zip(fresh.moves.iter())
                .position(|(a, b)| a != b)
                .unwrap_or(again.moves.len().min(fresh.moves.len()));
            panic!(
                "{name}, edit {step}: the moves differ from move {first} on ({:?}; {} moves against {} fresh):\n{:?}\n{:?}",
                again.start,
                again.moves.len(),
                fresh.moves.len(),
                again.moves.get(first),
                fresh.moves.get(first)
            );
        }
        starts.push(again.start);
        earlier = again;
    }
    starts
}

fn fixtures() -> Vec<(String, String, MemoryLibrary)> {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/execution");
    let mut cases = Vec::new();
    let mut entries: Vec<_> = std::fs::read_dir(&folder)
        .expect("fixtures/execution")
        .flatten()
        .map(|entry| entry.path())
        .collect();
    entries.sort();
    for path in entries {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        if path.is_dir() {
            let mut library = MemoryLibrary::default();
            let mut main = None;
            for file in std::fs::read_dir(&path).expect("a case folder").flatten() {
                let file = file.path();
                let text = std::fs::read_to_string(&file).expect("a fixture");
                let stem = file.file_stem().unwrap().to_string_lossy().to_string();
                let extension = file
                    .extension()
                    .map(|extension| extension.to_string_lossy().to_ascii_uppercase());
                if extension.as_deref() == Some("MPF") && main.is_none() {
                    main = Some(text.clone());
                }
                library.insert(&stem, &file.to_string_lossy(), &text);
            }
            if let Some(main) = main {
                cases.push((name, main, library));
            }
        } else if name.to_ascii_uppercase().ends_with(".MPF") {
            let text = std::fs::read_to_string(&path).expect("a fixture");
            cases.push((name, text, MemoryLibrary::default()));
        }
    }
    cases
}

#[test]
fn runs_again_after_random_edits_of_the_fixtures_equal_fresh_runs() {
    let cases = fixtures();
    assert!(cases.len() >= 10, "the execution fixtures were not found");
    for (index, (name, text, library)) in cases.iter().enumerate() {
        check_random_edits(name, text, library, 40, 0x9E37_79B9 + index as u64);
    }
}

/// A program with loops of jumps, WHILE loops, a FOR loop, calls of a subprogram with a parameter and
/// an R parameter that adds up over the whole program, long enough for several checkpoints.
fn program_with_calls(groups: usize) -> (String, MemoryLibrary) {
    let mut text =
        String::from("DEF INT COUNT, I\nG17 G90 G71 G54\nT1 D1 M6\nR1=10 R2=0\nCOUNT=0\n");
    for group in 0..groups {
        text.push_str(&format!(
            "LOOP{group}:\nG1 X{}.5 Y{} F500\nG91 Z-1\nG90\nCOUNT=COUNT+1\nIF COUNT<{} GOTOB LOOP{group}\nWHILE COUNT>0\nCOUNT=COUNT-1\nG91 X=AC({}) Y2\nENDWHILE\nG90\nFOR I=1 TO 3\nPOCKET({}.5)\nENDFOR\nR2=R2+{}\nG0 Z50\nG1 Z=R2*0.01\n",
            group % 97,
            group % 13,
            2 + group % 5,
            group % 31,
            group % 7,
            group % 11
        ));
    }
    text.push_str("M30\n");
    let mut library = MemoryLibrary::default();
    library.insert(
        "POCKET",
        "/programs/POCKET.SPF",
        "PROC POCKET(REAL DEPTH)\nG91 G1 Z=-DEPTH\nX5 Y5\nG90\nM17\n",
    );
    (text, library)
}

#[test]
fn runs_again_after_random_edits_of_a_long_program_with_calls_equal_fresh_runs() {
    let (text, library) = program_with_calls(400);
    let starts = check_random_edits("calls", &text, &library, 60, 0x5EED);
    let rejoined = starts
        .iter()
        .filter(|start| {
            matches!(
                start,
                RunStart::Resumed {
                    rejoined: Some(_),
                    ..
                }
            )
        })
        .count();
    assert!(rejoined > 0, "no edit rejoined the earlier run: {starts:?}");
}

#[test]
fn runs_again_after_random_edits_of_the_generated_mixed_program_equal_fresh_runs() {
    let Some(text) = generated::generate("mixed", 4000) else {
        println!("../shared/bench/gen_program.py not found; skipping");
        return;
    };
    check_random_edits("mixed", &text, &MemoryLibrary::default(), 30, 0xC0FFEE);
}

#[test]
fn an_edit_in_a_loop_body_runs_that_loop_again_and_rejoins_after_it() {
    let (text, library) = program_with_calls(200);
    let earlier = run(&text, &library, None);
    // A coordinate in the loop of jumps of group 150: the run resumes before the loop, runs it
    // again and takes the rest from the earlier run once the state is the same again.
    let edited = text.replacen("G1 X53.5 Y7 F500", "G1 X53.25 Y7 F500", 1);
    assert_ne!(edited, text, "the line to edit is in the program");
    let again = run(&edited, &library, Some(&earlier));
    let RunStart::Resumed { from, rejoined } = again.start else {
        panic!("the edit did not resume the earlier run: {:?}", again.start);
    };
    assert!(from > 0, "it resumed from the start");
    let rejoined = rejoined.expect("the run rejoins the earlier run after the loop");
    assert!(
        rejoined - from < again.execution.executed_blocks / 4,
        "it ran {} of {} blocks again",
        rejoined - from,
        again.execution.executed_blocks
    );
    assert_eq!(*again.moves, *run(&edited, &library, None).moves);
    assert!(again.moves.iter().any(|executed| executed
        .movement
        .end
        .iter()
        .any(|(_, value)| *value == 53.25)));
}

#[test]
fn a_comment_edit_does_not_run_the_program_again() {
    let (text, library) = program_with_calls(50);
    let earlier = run(&text, &library, None);
    let edited = text.replacen("G0 Z50\n", "G0 Z50 ; retract\n", 1);
    let again = run(&edited, &library, Some(&earlier));
    assert!(
        matches!(
            again.start,
            RunStart::Resumed {
                rejoined: Some(_),
                ..
            }
        ),
        "{:?}",
        again.start
    );
}

#[test]
fn a_changed_jump_runs_the_program_from_the_start() {
    let (text, library) = program_with_calls(20);
    let earlier = run(&text, &library, None);
    let edited = text.replacen("IF COUNT<2 GOTOB LOOP0", "IF COUNT<3 GOTOB LOOP0", 1);
    assert_ne!(edited, text);
    let again = run(&edited, &library, Some(&earlier));
    assert_eq!(again.start, RunStart::Fresh);
}

#[test]
fn a_changed_subprogram_runs_the_program_from_the_start() {
    let (text, library) = program_with_calls(20);
    let earlier = run(&text, &library, None);
    let mut changed = MemoryLibrary::default();
    changed.insert(
        "POCKET",
        "/programs/POCKET.SPF",
        "PROC POCKET(REAL DEPTH)\nG91 G1 Z=-DEPTH\nX6 Y5\nG90\nM17\n",
    );
    let edited = text.replacen("G0 Z50\n", "G0 Z51\n", 1);
    let again = run(&edited, &changed, Some(&earlier));
    assert_eq!(again.start, RunStart::Fresh);
    assert_eq!(*again.moves, *run(&edited, &changed, None).moves);
}

#[test]
fn a_value_that_stays_different_runs_to_the_end() {
    let (text, library) = program_with_calls(100);
    let earlier = run(&text, &library, None);
    // R2 adds up over the whole program and every group moves to it: no later state is the same.
    let edited = text.replacen("R2=R2+5\n", "R2=R2+6\n", 1);
    assert_ne!(edited, text);
    let again = run(&edited, &library, Some(&earlier));
    assert!(
        matches!(again.start, RunStart::Resumed { rejoined: None, .. }),
        "{:?}",
        again.start
    );
    assert_eq!(*again.moves, *run(&edited, &library, None).moves);
}

/// `count` blocks that move X and Y absolutely, to put checkpoints between two parts of a program.
fn filler(count: usize) -> String {
    (0..count)
        .map(|index| format!("G1 X{} Y{}\n", index % 50, index % 7))
        .collect()
}

#[test]
fn an_edited_line_that_runs_again_later_is_run_again_there() {
    // The edited block runs in both passes of the outer loop of jumps: the run may not take the
    // second pass from the earlier run, although the state after the first pass's filler is equal.
    let text = format!(
        "G17 G90 G71 G54 F500\nR9=0\nOUTER:\nG1 X11.25 Y1\n{}R9=R9+1\nIF R9<2 GOTOB OUTER\nM30\n",
        filler(5000)
    );
    let library = MemoryLibrary::default();
    let earlier = run(&text, &library, None);
    let edited = text.replacen("G1 X11.25 Y1\n", "G1 X12.75 Y1\n", 1);
    let again = run(&edited, &library, Some(&earlier));
    assert!(
        matches!(again.start, RunStart::Resumed { .. }),
        "{:?}",
        again.start
    );
    let twelve = again
        .moves
        .iter()
        .filter(|executed| executed.movement.end.first() == Some(&(Arc::from("X"), 12.75)))
        .count();
    assert_eq!(twelve, 2, "both passes move to X12.75");
    assert_eq!(*again.moves, *run(&edited, &library, None).moves);
}

#[test]
fn a_block_that_runs_more_often_keeps_the_later_pass_numbers_right() {
    // The edited R5 sets how often the subprogram's loop runs; after the call R5 is 0 again, so the
    // state is the same, but the second call's passes of the loop's block are numbered on from
    // the first call's.
    let text = format!(
        "G17 G90 G71 G54 F500\nR5=3\nLOOPS\nR5=0\n{}R5=2\nLOOPS\nM30\n",
        filler(5000)
    );
    let mut library = MemoryLibrary::default();
    library.insert(
        "LOOPS",
        "/programs/LOOPS.SPF",
        "PROC LOOPS\nDEF INT I\nFOR I=1 TO R5\nG1 X=I Y0\nENDFOR\nM17\n",
    );
    let earlier = run(&text, &library, None);
    let edited = text.replacen("R5=3\n", "R5=4\n", 1);
    let again = run(&edited, &library, Some(&earlier));
    let fresh = run(&edited, &library, None);
    let passes: Vec<u32> = fresh
        .moves
        .iter()
        .filter(|executed| executed.path.is_some())
        .map(|executed| executed.pass)
        .collect();
    assert_eq!(passes, vec![1, 2, 3, 4, 5, 6]);
    assert_eq!(*again.moves, *fresh.moves);
    assert_eq!(again.execution.findings, fresh.execution.findings);
    assert_eq!(again.passes_by_program(), fresh.passes_by_program());
}
