//! Realistic mistakes put into the clean real programs of `../shared/corpus/real`, one mistake per
//! copy: `check` must report each on its line with the expected code. The test prints a table of the
//! catch rate per kind of mistake, and fails when a kind that is checked is missed in any program.
//!
//! A program is clean when `check` reports no error on it. The mistake is a block inserted after the
//! program's first G0/G1 block, where definitions are over and the modal state is the program's own.
//! The copies are checked in one run of the binary over a temporary folder, as a user checks a folder.
//!
//! When the corpus is not there, the test prints `corpus not found at ...; skipping` and passes.

#[path = "support/corpus_files.rs"]
mod corpus_files;

use corpus_files::{corpus_dir, glob_matches, known_invalid, program_files};
use sinumerik_lsp::cli::source_file::read_source_file;
use std::collections::{BTreeMap, HashSet};
use std::path::Path;
use std::process::Command;

/// One kind of mistake: the block inserted and the code `check` must report on it. A kind that is
/// not `checked` yet (the checker misses it in some or all programs) has its rate printed, and the
/// test fails once it is caught everywhere, so that the kind moves to the checked ones.
struct Mistake {
    name: &'static str,
    block: &'static str,
    code: &'static str,
    checked: bool,
}

const MISTAKES: &[Mistake] = &[
    // The ten classic mistakes.
    Mistake {
        name: "modifier without brackets",
        block: "X=AC 5",
        code: "S101",
        checked: true,
    },
    Mistake {
        name: "modifier not closed",
        block: "X=IC(3",
        code: "S102",
        checked: true,
    },
    Mistake {
        name: "G0 and G1 in one block",
        block: "G0 G1 X5",
        code: "S141",
        checked: true,
    },
    Mistake {
        name: "modifier on F",
        block: "F=IC(5)",
        code: "S107",
        checked: true,
    },
    Mistake {
        name: "G2 without centre",
        block: "G2 X5 Y5",
        code: "A209",
        checked: false,
    },
    Mistake {
        name: "unknown G function",
        block: "G999",
        code: "S144",
        checked: true,
    },
    Mistake {
        name: "string not closed",
        block: "MSG(\"CHECK)",
        code: "S132",
        checked: true,
    },
    Mistake {
        name: "two frame instructions",
        block: "TRANS X1 ROT Z45",
        code: "S141",
        checked: true,
    },
    Mistake {
        name: "CR on a G1 line",
        block: "G1 X5 CR=5",
        code: "none",
        checked: false,
    },
    Mistake {
        name: "GOTOF to a missing label",
        block: "GOTOF NO_SUCH_LABEL",
        code: "none",
        checked: false,
    },
    // The mistakes of issue 18's list.
    Mistake {
        name: "division by zero",
        block: "R1=1/0",
        code: "A205",
        checked: true,
    },
    Mistake {
        name: "SQRT of a negative number",
        block: "R1=SQRT(-1)",
        code: "A225",
        checked: true,
    },
    Mistake {
        name: "wrong argument count",
        block: "R1=POT(2,3)",
        code: "A226",
        checked: true,
    },
    Mistake {
        name: "value without =",
        block: "Z (R1+2)",
        code: "S151",
        checked: true,
    },
    Mistake {
        name: "I on a G0 line",
        block: "G0 X5 I5",
        code: "none",
        checked: false,
    },
    Mistake {
        name: "circle given two ways",
        block: "G2 X5 Y5 I5 J0 CR=5",
        code: "none",
        checked: false,
    },
    Mistake {
        name: "CIP without intermediate point",
        block: "CIP X5 Y5",
        code: "none",
        checked: false,
    },
    Mistake {
        name: "pole with one coordinate",
        block: "G111 X10",
        code: "none",
        checked: false,
    },
    Mistake {
        name: "AR without end point",
        block: "G3 AR=90",
        code: "none",
        checked: false,
    },
];

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
    let found: HashSet<(String, u64, String)> = findings
        .into_iter()
        .map(|(file, line, code, _)| (file, line, code))
        .collect();
    let mut caught: BTreeMap<usize, (usize, Vec<String>)> = BTreeMap::new();
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

    println!("{clean} clean programs, one mistake per copy:");
    println!("{:<34} {:>6} {:>8}  missed in", "mistake", "code", "caught");
    let mut failures = Vec::new();
    for (kind, mistake) in MISTAKES.iter().enumerate() {
        let (hits, missed) = &caught[&kind];
        let share = 100.0 * *hits as f64 / clean as f64;
        println!(
            "{:<34} {:>6} {:>7.1}%  {}",
            mistake.name,
            mistake.code,
            share,
            missed
                .iter()
                .take(3)
                .cloned()
                .collect::<Vec<_>>()
                .join(", ")
        );
        if mistake.checked && !missed.is_empty() {
            failures.push(format!(
                "{}: missed in {} programs",
                mistake.name,
                missed.len()
            ));
        }
        if !mistake.checked && missed.is_empty() {
            failures.push(format!(
                "{}: caught everywhere now; mark it checked",
                mistake.name
            ));
        }
    }
    let not_checked = MISTAKES.iter().filter(|mistake| !mistake.checked).count();
    println!("{not_checked} kinds are not fully checked yet");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
