//! Realistic mistakes put into the clean real programs of `../shared/corpus/real`, one mistake per
//! copy: `check` must report each on its line with the expected code. The test prints a table of the
//! catch rate per kind of mistake, and fails when any kind is missed in any program.
//!
//! A program is clean when `check` reports no error on it. The mistake is a block inserted after the
//! program's first G0/G1 block, where definitions are over and the modal state is the program's own.
//! The copies are checked in one run of the binary over a temporary folder, as a user checks a folder.
//!
//! When the corpus is not there, the test prints `corpus not found at ...; skipping` and passes.

#[path = "support/corpus_files.rs"]
mod corpus_files;

use corpus_files::{corpus_dir, glob_matches, known_invalid, program_files};
use sinumerik_lsp::io::source_file::read_source_file;
use std::collections::{BTreeMap, HashSet};
use std::path::Path;
use std::process::Command;

/// One kind of mistake: the block inserted and the code `check` must report on it.
struct Mistake {
    name: &'static str,
    block: &'static str,
    code: &'static str,
}

/// The codes of which one finding is reported per program, at the first block that needs a lathe
/// (A235 for DIAMON and the like, A236 for G96; both say to configure a lathe, which is one fix): in
/// a program whose original already has one of them (a lathe program read with the mill's axes that
/// writes DIAMON or G96 before its first linear block) the inserted block repeats what the user has
/// been told at the program's first use, so it is no new mistake and that program does not count for
/// these kinds. Every other program must report it on the inserted line.
const ONCE_PER_PROGRAM: &[&str] = &["A235", "A236"];

const MISTAKES: &[Mistake] = &[
    // The ten classic mistakes.
    mistake("modifier without brackets", "X=AC 5", "S101"),
    mistake("modifier not closed", "X=IC(3", "S102"),
    mistake("G0 and G1 in one block", "G0 G1 X5", "S141"),
    mistake("modifier on F", "F=IC(5)", "S107"),
    mistake("G2 without centre", "G2 X5 Y5", "A209"),
    mistake("unknown G function", "G999", "S144"),
    mistake("string not closed", "MSG(\"CHECK)", "S132"),
    mistake("two frame instructions", "TRANS X1 ROT Z45", "S141"),
    mistake("CR on a G1 line", "G1 X5 CR=5", "A229"),
    mistake("GOTOF to a missing label", "GOTOF NO_SUCH_LABEL", "W304"),
    // The mistakes of issue 18's list.
    mistake("division by zero", "R1=1/0", "A205"),
    mistake("SQRT of a negative number", "R1=SQRT(-1)", "A225"),
    mistake("wrong argument count", "R1=POT(2,3)", "A226"),
    mistake("value without =", "Z (R1+2)", "S151"),
    mistake("AC value not in brackets", "X=AC 1.2+SIN(30)", "S101"),
    mistake("frame value without =", "TRANS X _CPA", "S151"),
    mistake("I on a G0 line", "G0 X5 I5", "A229"),
    mistake("circle given two ways", "G2 X5 Y5 I5 J0 CR=5", "A230"),
    mistake("radius zero", "G2 X=IC(0) Y=IC(0) I0 J0", "A231"),
    mistake("CIP without intermediate point", "CIP X5 Y5", "A232"),
    mistake("pole with one coordinate", "G111 X10", "A233"),
    mistake("AR without end point", "G3 AR=90", "A209"),
    mistake("DIAMON on a mill", "DIAMON", "A235"),
    mistake("G96 on a mill", "G96 S100", "A236"),
];

/// A kind of mistake, which the checker must catch in every clean program.
const fn mistake(name: &'static str, block: &'static str, code: &'static str) -> Mistake {
    Mistake { name, block, code }
}

/// The 0-based index of the first line that is a G0 or G1 block, if any.
fn first_linear_block(lines: &[&str]) -> Option<usize> {
    lines.iter().position(|line| {
        let code = line.split(';').next().unwrap_or("").to_ascii_uppercase();
        code.split(|c: char| !c.is_ascii_alphanumeric())
            .any(|word| matches!(word, "G0" | "G00" | "G1" | "G01"))
    })
}

/// The findings of `check --format json` over `folder`, as (file name, 1-based line, code, severity).
fn check_folder(folder: &Path) -> Vec<(String, u64, String, String)> {
    let output = Command::new(env!("CARGO_BIN_EXE_sinumerik-lsp"))
        .args(["check", "--format", "json"])
        .arg(folder)
        .output()
        .expect("the binary runs");
    let findings: serde_json::Value =
        serde_json::from_slice(&output.stdout).expect("check --format json prints JSON");
    findings
        .as_array()
        .expect("an array of findings")
        .iter()
        .map(|finding| {
            let file = finding["file"].as_str().unwrap_or_default();
            let name = Path::new(file)
                .file_name()
                .map(|name| name.to_string_lossy().into_owned())
                .unwrap_or_default();
            (
                name,
                finding["line"].as_u64().unwrap_or_default(),
                finding["code"].as_str().unwrap_or_default().to_string(),
                finding["severity"].as_str().unwrap_or_default().to_string(),
            )
        })
        .collect()
}

#[test]
fn check_reports_every_mistake_put_into_clean_real_programs() {
    let dir = corpus_dir();
    if !dir.is_dir() {
        println!("corpus not found at {}; skipping", dir.display());
        return;
    }
    let invalid = known_invalid();
    let mut files = Vec::new();
    program_files(&dir, &mut files);
    let folder = std::env::temp_dir().join(format!("sinumerik-mutation-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&folder);
    std::fs::create_dir_all(&folder).expect("the temporary folder can be made");

    // Every candidate program and its copies, each a file of its own: `P<n>_K0` is the original.
    let mut programs = Vec::new();
    for path in &files {
        let relative = path
            .strip_prefix(&dir)
            .unwrap_or(path)
            .to_string_lossy()
            .replace('\\', "/");
        if invalid
            .iter()
            .any(|pattern| glob_matches(pattern, &relative))
        {
            continue;
        }
        let Ok(source) = read_source_file(path) else {
            continue;
        };
        let lines: Vec<&str> = source.text.lines().collect();
        let Some(after) = first_linear_block(&lines) else {
            continue;
        };
        let index = programs.len();
        let extension = path
            .extension()
            .map(|extension| extension.to_string_lossy().to_ascii_uppercase())
            .unwrap_or_else(|| "MPF".to_string());
        std::fs::write(
            folder.join(format!("P{index}_K0.{extension}")),
            lines.join("\n"),
        )
        .expect("the copy can be written");
        for (kind, mistake) in MISTAKES.iter().enumerate() {
            let mut mutated = lines.clone();
            mutated.insert(after + 1, mistake.block);
            std::fs::write(
                folder.join(format!("P{index}_K{}.{extension}", kind + 1)),
                mutated.join("\n"),
            )
            .expect("the mutated copy can be written");
        }
        programs.push((relative, after, extension));
    }
    let findings = check_folder(&folder);
    let _ = std::fs::remove_dir_all(&folder);

    // Clean programs: `check` reports no error on the original.
    let unclean: HashSet<String> = findings
        .iter()
        .filter(|(file, _, _, severity)| file.contains("_K0.") && severity == "error")
        .map(|(file, ..)| file.split('_').next().unwrap_or_default().to_string())
        .collect();
    // The original programs that already have a finding reported once per program.
    let reported_before: HashSet<String> = findings
        .iter()
        .filter(|(file, _, code, _)| {
            file.contains("_K0.") && ONCE_PER_PROGRAM.contains(&code.as_str())
        })
        .map(|(file, ..)| file.split('_').next().unwrap_or_default().to_string())
        .collect();
    let found: HashSet<(String, u64, String)> = findings
        .into_iter()
        .map(|(file, line, code, _)| (file, line, code))
        .collect();
    let mut caught: BTreeMap<usize, (usize, Vec<String>)> = BTreeMap::new();
    let mut not_applicable: BTreeMap<usize, usize> = BTreeMap::new();
    let mut clean = 0;
    for (index, (relative, after, extension)) in programs.iter().enumerate() {
        if unclean.contains(&format!("P{index}")) {
            continue;
        }
        clean += 1;
        for (kind, mistake) in MISTAKES.iter().enumerate() {
            let file = format!("P{index}_K{}.{extension}", kind + 1);
            let line = *after as u64 + 2;
            let entry = caught.entry(kind).or_default();
            let once = ONCE_PER_PROGRAM.contains(&mistake.code);
            if once && reported_before.contains(&format!("P{index}")) {
                *not_applicable.entry(kind).or_default() += 1;
                continue;
            }
            let reported = found.contains(&(file, line, mistake.code.to_string()));
            if reported {
                entry.0 += 1;
            } else {
                entry.1.push(relative.clone());
            }
        }
    }
    assert!(
        clean >= 30,
        "only {clean} clean programs: the corpus or the checker changed"
    );

    println!("{clean} clean programs, one mistake per copy (n/a: the original reports the code already, once per program):");
    println!(
        "{:<34} {:>6} {:>8} {:>4}  missed in",
        "mistake", "code", "caught", "n/a"
    );
    let mut failures = Vec::new();
    for (kind, mistake) in MISTAKES.iter().enumerate() {
        let (hits, missed) = &caught[&kind];
        let skipped = not_applicable.get(&kind).copied().unwrap_or(0);
        let share = 100.0 * *hits as f64 / (hits + missed.len()).max(1) as f64;
        println!(
            "{:<34} {:>6} {:>7.1}% {:>4}  {}",
            mistake.name,
            mistake.code,
            share,
            skipped,
            missed
                .iter()
                .take(3)
                .cloned()
                .collect::<Vec<_>>()
                .join(", ")
        );
        if !missed.is_empty() {
            failures.push(format!(
                "{}: missed in {} programs",
                mistake.name,
                missed.len()
            ));
        }
        // Programs left out must stay few: the kind is to be checked where it is a mistake.
        if skipped * 4 > clean {
            failures.push(format!(
                "{}: {skipped} of {clean} programs report it already",
                mistake.name
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
