//! Hostile files through the shipped binary (`check` and `preview`) and through the document model the
//! language server uses: each must give a clear answer (an exit code of 0 or 1, findings that name the
//! problem) in bounded time and memory, and never crash. The parser's behaviour on such lines is
//! tested in detail in `hostile_input.rs`; this file covers whole files end to end.
//!
//! Every test prints its figures (wall time, peak resident memory of the process, output size); the
//! bounds asserted are generous multiples of the input size, written down in docs/reliability.md.

use sinumerik_lsp::analysis::document::{DocumentAnalysis, TextLines};
use sinumerik_lsp::analysis::{diagnose_program, ProgramKind};
use sinumerik_lsp::config::MachineConfig;
use sinumerik_lsp::io::source_file::decode_source;
use std::io::Read;
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::sync::Arc;
use std::time::{Duration, Instant};

const MB: usize = 1024 * 1024;

/// A run that takes longer than this is a hang, whatever the machine's load.
const HANG: Duration = Duration::from_secs(120);

/// What one run of the binary did.
struct Run {
    exit_code: Option<i32>,
    stdout: Vec<u8>,
    stderr: String,
    elapsed: Duration,
    /// Peak resident memory of the process in bytes (VmHWM, sampled while it runs).
    peak_memory: usize,
}

/// A program file in the temporary folder, removed when dropped.
struct TempFile(PathBuf);

impl TempFile {
    /// Each file gets a folder of its own: `check` also reads the program files beside the one it
    /// checks (callees, definition files), and the other tests' large files in a shared folder would
    /// then count toward this file's memory bound.
    fn new(name: &str, bytes: &[u8]) -> TempFile {
        let folder =
            std::env::temp_dir().join(format!("sinumerik-hostile-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&folder).expect("the temporary folder can be made");
        let path = folder.join(name);
        std::fs::write(&path, bytes).expect("the temporary file can be written");
        TempFile(path)
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        if let Some(folder) = self.0.parent() {
            let _ = std::fs::remove_dir_all(folder);
        }
    }
}

/// Runs the binary with `args` and the file, reading its output while sampling its peak memory.
fn run(args: &[&str], file: &TempFile) -> Run {
    let started = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_sinumerik-lsp"))
        .args(args)
        .arg(&file.0)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary starts");
    let mut stdout_pipe = child.stdout.take().expect("piped");
    let mut stderr_pipe = child.stderr.take().expect("piped");
    let stdout_reader = std::thread::spawn(move || {
        let mut bytes = Vec::new();
        let _ = stdout_pipe.read_to_end(&mut bytes);
        bytes
    });
    let stderr_reader = std::thread::spawn(move || {
        let mut text = String::new();
        let _ = stderr_pipe.read_to_string(&mut text);
        text
    });
    let status_path = format!("/proc/{}/status", child.id());
    let mut peak_memory = 0;
    let status = loop {
        if let Ok(status) = std::fs::read_to_string(&status_path) {
            peak_memory = peak_memory.max(high_water_mark(&status));
        }
        if let Some(status) = child.try_wait().expect("the child can be waited for") {
            break status;
        }
        if started.elapsed() > HANG {
            let _ = child.kill();
            let _ = child.wait();
            panic!("`{}` on {} hangs", args.join(" "), file.0.display());
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let run = Run {
        exit_code: status.code(),
        stdout: stdout_reader.join().expect("stdout is read"),
        stderr: stderr_reader.join().expect("stderr is read"),
        elapsed: started.elapsed(),
        peak_memory,
    };
    eprintln!(
        "{:>24}: {:>7.2} s, {:>6.1} MB peak, {:>9} bytes of output, exit {:?}",
        args.join(" "),
        run.elapsed.as_secs_f64(),
        run.peak_memory as f64 / MB as f64,
        run.stdout.len(),
        run.exit_code
    );
    run
}

/// `VmHWM` of a `/proc/PID/status` text, in bytes.
fn high_water_mark(status: &str) -> usize {
    status
        .lines()
        .find_map(|line| line.strip_prefix("VmHWM:"))
        .and_then(|rest| {
            rest.trim()
                .trim_end_matches("kB")
                .trim()
                .parse::<usize>()
                .ok()
        })
        .map_or(0, |kilobytes| kilobytes * 1024)
}

/// The bounds every hostile file must keep, given the size of its input.
struct Bounds {
    /// Peak memory of one run: a base for the process plus so many bytes per input byte.
    memory_per_input_byte: usize,
    /// Output of one run, as a multiple of the input size plus a base.
    output_per_input_byte: usize,
}

const BASE_MEMORY: usize = 32 * MB;
const BASE_OUTPUT: usize = 4 * MB;

/// Runs `check` (human and JSON) and `preview` (JSON) on `bytes`, checks that each gives a clear
/// answer within the bounds, and returns the human output of `check`.
fn check_and_preview(name: &str, bytes: &[u8], bounds: Bounds) -> String {
    let file = TempFile::new(name, bytes);
    let mut human = String::new();
    for args in [
        &["check"][..],
        &["check", "--format", "json"][..],
        &["preview"][..],
    ] {
        let run = run(args, &file);
        assert!(
            matches!(run.exit_code, Some(0) | Some(1)),
            "`{}` on {name}: exit {:?}, stderr {}",
            args.join(" "),
            run.exit_code,
            run.stderr
        );
        assert!(run.stderr.is_empty(), "{name}: {}", run.stderr);
        let memory_bound = BASE_MEMORY + bounds.memory_per_input_byte * bytes.len();
        assert!(
            run.peak_memory <= memory_bound,
            "`{}` on {name} used {} MB, more than the bound of {} MB",
            args.join(" "),
            run.peak_memory / MB,
            memory_bound / MB
        );
        // The human format prints at most 1,000 findings per file; JSON and the preview list all.
        let output_bound = if args == ["check"] {
            BASE_OUTPUT
        } else {
            BASE_OUTPUT + bounds.output_per_input_byte * bytes.len()
        };
        assert!(
            run.stdout.len() <= output_bound,
            "`{}` on {name} printed {} bytes, more than {output_bound}",
            args.join(" "),
            run.stdout.len()
        );
        if args.len() > 1 {
            let json: serde_json::Value =
                serde_json::from_slice(&run.stdout).unwrap_or_else(|error| {
                    panic!("{name}: `{}` is not JSON: {error}", args.join(" "))
                });
            assert!(json.is_array() || json.is_object());
        }
        if args == ["check"] {
            human = String::from_utf8(run.stdout).expect("the output is UTF-8");
            assert!(human.contains("checked 1 file"), "{name}: no summary");
        }
    }
    human
}

/// The document model on the same bytes: a fresh analysis equals `check`'s, and an edit at the start
/// gives what a fresh analysis of the edited text gives.
fn document_model(name: &str, bytes: &[u8]) {
    let started = Instant::now();
    let text = decode_source(bytes).text;
    let config = Arc::new(MachineConfig::default());
    let source = TextLines::new(&text);
    let mut document = DocumentAnalysis::new(&source, config.clone(), ProgramKind::Main);
    assert!(
        document.diagnostics() == diagnose_program(&text, &config, ProgramKind::Main).as_slice(),
        "{name}: the document analysis differs from check"
    );
    let edited = format!("G0 X1\n{text}");
    let source = TextLines::new(&edited);
    document.update(&source, 0, 0, 1);
    let fresh = DocumentAnalysis::new(&source, config, ProgramKind::Main);
    assert!(
        document.diagnostics() == fresh.diagnostics(),
        "{name}: the edited document differs from a fresh analysis"
    );
    eprintln!(
        "{:>24}: {:>7.2} s for an analysis, an edit and a fresh analysis",
        "document model",
        started.elapsed().as_secs_f64()
    );
}

fn count(human: &str, code: &str) -> usize {
    human.matches(&format!("[{code}]")).count()
}

#[test]
fn ten_megabyte_single_line() {
    let bytes = "X1.5 Y2 Z-3 ".repeat(10 * MB / 12).into_bytes();
    let human = check_and_preview(
        "ten_mb_line.mpf",
        &bytes,
        Bounds {
            memory_per_input_byte: 48,
            output_per_input_byte: 1,
        },
    );
    assert_eq!(count(&human, "S163"), 1, "the block is too long, once");
    document_model("ten_mb_line", &bytes);
}

#[test]
fn hundred_thousand_nested_parentheses() {
    let bytes = format!(
        "G1 X={}1{} F100\n",
        "(".repeat(100_000),
        ")".repeat(100_000)
    )
    .into_bytes();
    let human = check_and_preview(
        "parentheses.mpf",
        &bytes,
        Bounds {
            memory_per_input_byte: 64,
            output_per_input_byte: 1,
        },
    );
    assert_eq!(count(&human, "S170"), 1, "{human}");
    document_model("parentheses", &bytes);
}

#[test]
fn hundred_thousand_nested_ifs() {
    let mut program = String::from("G0 X0\n");
    for _ in 0..100_000 {
        program.push_str("IF R1==1\n");
    }
    program.push_str("G1 X1 F100\n");
    for _ in 0..100_000 {
        program.push_str("ENDIF\n");
    }
    let human = check_and_preview(
        "nested_if.mpf",
        program.as_bytes(),
        Bounds {
            memory_per_input_byte: 64,
            output_per_input_byte: 4,
        },
    );
    // The structure check follows 256 levels and says so once; the closing ENDIFs still match.
    assert_eq!(
        count(&human, "S190"),
        1,
        "{}",
        &human[..human.len().min(2000)]
    );
    assert!(
        human.contains("checked 1 file: 0 errors, 1 warning"),
        "{human}"
    );
    document_model("nested_if", program.as_bytes());
}

#[test]
fn nul_and_control_bytes() {
    let mut bytes = Vec::new();
    for index in 0..100_000u32 {
        bytes.extend_from_slice(b"G1 X");
        bytes.push((index % 32) as u8);
        bytes.extend_from_slice(b"1 F100\x00\x07\x1B\x7F;\x00end\n");
    }
    check_and_preview(
        "control.mpf",
        &bytes,
        Bounds {
            memory_per_input_byte: 128,
            output_per_input_byte: 16,
        },
    );
    document_model("control", &bytes);
}

#[test]
fn invalid_utf8_and_mixed_encodings() {
    let mut bytes = Vec::new();
    for _ in 0..10_000 {
        bytes.extend_from_slice("; Bohrung Ø10 für Flansch\n".as_bytes());
        bytes.extend_from_slice(b"; Windows-1252: \xD8 f\xFCr \x80 \x81\n");
        bytes.extend_from_slice(b"G1 X\xC310 Y\xE2\x82 F100\n");
        bytes.extend_from_slice(b"\xEF\xBB\xBFG0 Z5\n");
    }
    let human = check_and_preview(
        "encodings.mpf",
        &bytes,
        Bounds {
            memory_per_input_byte: 128,
            output_per_input_byte: 40,
        },
    );
    // The file is not UTF-8, so it is read as Windows-1252: the stray bytes are characters that
    // have no meaning in a block (S100), the comments are comments.
    assert!(count(&human, "S100") >= 1, "the stray bytes are named");
    document_model("encodings", &bytes);
}

/// Bytes of a deterministic xorshift sequence: a binary file.
fn binary(length: usize) -> Vec<u8> {
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    (0..length)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state as u8
        })
        .collect()
}

#[test]
fn binary_file() {
    let bytes = binary(MB);
    let human = check_and_preview(
        "binary.mpf",
        &bytes,
        Bounds {
            memory_per_input_byte: 128,
            output_per_input_byte: 100,
        },
    );
    assert!(
        human.contains("more findings not shown"),
        "a binary gives many findings"
    );
    document_model("binary", &bytes);
}

#[test]
fn a_million_diagnostics() {
    // Every line lacks its value: 1,000,000 findings of S150.
    let bytes = "X\n".repeat(1_000_000).into_bytes();
    let file = TempFile::new("million.mpf", &bytes);
    let human = run(&["check"], &file);
    assert_eq!(human.exit_code, Some(1));
    let text = String::from_utf8(human.stdout).unwrap();
    // The human format prints the first 1,000 findings of a file and counts the rest.
    assert_eq!(text.matches(": error[").count(), 1_000);
    assert!(
        text.contains("999001 more findings not shown"),
        "{}",
        &text[text.len() - 300..]
    );
    assert!(text.contains("1000001 errors"));
    assert!(text.len() < 200_000);
    // JSON lists every finding: the output grows with them, about 200 bytes each.
    let json = run(&["check", "--format", "json"], &file);
    let findings = json.stdout.iter().filter(|byte| **byte == b'\n').count();
    assert!(findings >= 1_000_000, "{findings} lines of JSON");
    assert!(json.stdout.len() < 250 * 1_000_001);
    // Memory: about 240 bytes per finding while they are sorted and printed.
    assert!(
        json.peak_memory < BASE_MEMORY + 400 * 1_000_001,
        "{} MB",
        json.peak_memory / MB
    );
    // The preview lists the same findings after the moves (measured: 265 MB of JSON, 235 MB of
    // memory); it is left out here to keep the test short.
    document_model("million", &bytes);
}

#[test]
fn numbers_with_ten_thousand_digits() {
    let digits = "7".repeat(10_000);
    let program = format!("G0 X{digits}\nG1 Y={digits}.5 F{digits}\nZ=AC({digits}) X1EX99999\n");
    let file = TempFile::new("digits.mpf", program.as_bytes());
    let check = run(&["check"], &file);
    let human = String::from_utf8(check.stdout).unwrap();
    assert_eq!(count(&human, "S133"), 5, "{human}");
    assert!(human.contains("is too large for a number"));
    let preview = run(&["preview"], &file);
    let json: serde_json::Value = serde_json::from_slice(&preview.stdout).unwrap();
    // No position is made of such a number: X, Y and Z are unknown, and no value is null or infinite.
    for movement in json["moves"].as_array().unwrap() {
        for (axis, value) in movement["end"].as_object().unwrap() {
            assert!(value.is_number(), "{axis} is {value} in {movement}");
        }
    }
    let moves = json["moves"].as_array().unwrap();
    assert!(moves[0]["end"].get("X").is_none());
    assert!(moves[0]["uncertain"]
        .as_array()
        .unwrap()
        .contains(&"X".into()));
    document_model("digits", program.as_bytes());
}

#[test]
fn label_and_variable_names_of_one_megabyte() {
    let name = "A".repeat(MB);
    let program = format!("{name}:\nDEF REAL {name}\n{name}=5\nG1 X={name} F100\nGOTOB {name}\n");
    let human = check_and_preview(
        "names.mpf",
        program.as_bytes(),
        Bounds {
            memory_per_input_byte: 64,
            output_per_input_byte: 1,
        },
    );
    assert!(count(&human, "S162") >= 1, "the name is too long");
    // Messages quote at most a short piece of the name.
    assert!(
        human.lines().all(|line| line.len() < 2 * MB),
        "a message quotes the whole name"
    );
    document_model("names", program.as_bytes());
}

#[test]
fn only_carriage_returns_as_line_ends() {
    let program = "N10 G0 X0 Y0\rN20 G1 X10 F100\rN30 X\rN40 Y=IC(5)\r".repeat(25_000);
    let human = check_and_preview(
        "cr.mpf",
        program.as_bytes(),
        Bounds {
            memory_per_input_byte: 128,
            output_per_input_byte: 32,
        },
    );
    // Line 3 of the program lacks its value, on every repetition: the CR ends each block.
    assert!(human.contains("cr.mpf:3:"), "{}", &human[..500]);
    assert!(human.contains("cr.mpf:7:"));
    document_model("cr", program.as_bytes());
}

/// An archive as the control writes it (`.ARC`): a binary header of NUL-padded fields, then each
/// member's path, its length and its text, and binary blocks of machine data in between.
fn archive() -> Vec<u8> {
    let mut bytes = b"@@MMCIBN.002".to_vec();
    bytes.resize(256, 0);
    bytes.extend_from_slice(b"7\x00\x00\x00040703\x00\x0011704\x00\x00\x001476518605\x00\x00");
    bytes.resize(1024, 0);
    bytes.extend_from_slice(b";---components---\r\n\\_N_MPF_DIR\\_N_PART1_MPF\r\n");
    for member in 0..50 {
        bytes.extend_from_slice(
            format!("%_N_PART{member}_MPF\r\n;$PATH=/_N_MPF_DIR\r\n").as_bytes(),
        );
        for line in 0..200 {
            bytes
                .extend_from_slice(format!("N{line} G1 X{line}.5 Y-{member} F1000\r\n").as_bytes());
        }
        bytes.extend_from_slice(b"M30\r\n");
        bytes.extend_from_slice(&binary(2048));
    }
    bytes
}

#[test]
fn an_archive_opened_as_a_program() {
    let bytes = archive();
    let human = check_and_preview(
        "machine.arc",
        &bytes,
        Bounds {
            memory_per_input_byte: 128,
            output_per_input_byte: 40,
        },
    );
    // The programs inside are read as blocks; the binary parts give findings, never a crash.
    assert!(human.contains("errors"));
    document_model("archive", &bytes);
}

#[test]
fn coordinates_near_the_largest_double_give_a_valid_picture_and_table() {
    // Each value is a finite double, but the picture's extent from -1.7e308 to 1.7e308 is not: the
    // SVG once had `viewBox="-inf NaN inf inf"`. Such segments are left out and counted.
    let program = "G0 X-1.7EX308 Y0\nG1 X1.7EX308 Y1 F100\nG1 X10 Y10\nG1 X20 Y5\n";
    let file = TempFile::new("huge.mpf", program.as_bytes());
    let svg = run(&["preview", "--format", "svg"], &file);
    assert_eq!(svg.exit_code, Some(0), "{}", svg.stderr);
    let svg = String::from_utf8(svg.stdout).unwrap();
    assert!(!svg.contains("inf") && !svg.contains("NaN"), "{svg}");
    assert!(
        svg.contains("(1 segments, 2 left out: coordinates beyond 1e15)"),
        "{svg}"
    );
    let csv = run(&["preview", "--format", "csv"], &file);
    let csv = String::from_utf8(csv.stdout).unwrap();
    assert!(!csv.contains("inf") && !csv.contains("NaN"), "{csv}");
    assert_eq!(csv.lines().count(), 5, "{csv}");
}
