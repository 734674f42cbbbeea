//! End-to-end tests of `sinumerik-lsp check`: the real binary on real files, checking exit codes,
//! both output formats, decoding, configuration files and folder walking.

use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

/// A program with a modifier written without parentheses: one S101 error.
/// Under G91, so that `AC` is not redundant and S101 is the only finding.
const PROGRAM_WITH_ERROR: &[u8] = b"N10 G91 G0 Z=AC17\n";
/// A program the checker has nothing against.
const CLEAN_PROGRAM: &[u8] = b"N10 G0 X10 Y20\nN20 G1 Z-5 F100\nN30 M30\n";

/// A fresh folder per test, removed afterwards. It holds an empty `sinumerik.toml`, so the search for
/// a configuration file stops here and a stray file higher up in the temp folder cannot change results.
struct TestDir {
    path: PathBuf,
}

impl TestDir {
    fn new(test_name: &str) -> TestDir {
        let path = std::env::temp_dir().join(format!(
            "sinumerik-lsp-cli-{}-{test_name}",
            std::process::id()
        ));
        let _ = fs::remove_dir_all(&path);
        fs::create_dir_all(&path).unwrap();
        fs::write(path.join("sinumerik.toml"), "").unwrap();
        TestDir { path }
    }

    fn write(&self, relative_path: &str, contents: &[u8]) -> PathBuf {
        let path = self.path.join(relative_path);
        fs::create_dir_all(path.parent().unwrap()).unwrap();
        fs::write(&path, contents).unwrap();
        path
    }
}

impl Drop for TestDir {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.path);
    }
}

struct RunResult {
    exit_code: i32,
    stdout: String,
    stderr: String,
}

fn run<I, S>(args: I) -> RunResult
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    let output = Command::new(env!("CARGO_BIN_EXE_sinumerik-lsp"))
        .args(args)
        .output()
        .expect("the binary runs");
    // A missing exit code means the process died from a signal, which a checker must never do.
    let exit_code = output
        .status
        .code()
        .unwrap_or_else(|| panic!("killed by a signal: {:?}", output.status));
    RunResult {
        exit_code,
        stdout: String::from_utf8(output.stdout).expect("stdout is UTF-8"),
        stderr: String::from_utf8(output.stderr).expect("stderr is UTF-8"),
    }
}

fn check(paths: &[&Path]) -> RunResult {
    let mut args = vec![OsStr::new("check")];
    args.extend(paths.iter().map(|path| path.as_os_str()));
    run(args)
}

fn check_json(paths: &[&Path]) -> (RunResult, Vec<serde_json::Value>) {
    let mut args = vec![
        OsStr::new("check"),
        OsStr::new("--format"),
        OsStr::new("json"),
    ];
    args.extend(paths.iter().map(|path| path.as_os_str()));
    let result = run(args);
    let parsed: serde_json::Value = serde_json::from_str(&result.stdout)
        .unwrap_or_else(|error| panic!("not JSON ({error}): {}", result.stdout));
    let diagnostics = parsed.as_array().expect("a JSON array").clone();
    (result, diagnostics)
}

#[test]
fn clean_file_exits_0() {
    let dir = TestDir::new("clean");
    let program = dir.write("CLEAN.MPF", CLEAN_PROGRAM);
    let result = check(&[&program]);
    assert_eq!(result.exit_code, 0, "{}{}", result.stdout, result.stderr);
    assert_eq!(result.stderr, "");
    assert!(
        result
            .stdout
            .ends_with("checked 1 file: 0 errors, 0 warnings, 0 infos\n"),
        "{}",
        result.stdout
    );
}

#[test]
fn error_exits_1_in_compiler_format() {
    let dir = TestDir::new("error");
    let program = dir.write("ERR.MPF", PROGRAM_WITH_ERROR);
    let result = check(&[&program]);
    assert_eq!(result.exit_code, 1, "{}{}", result.stdout, result.stderr);
    assert_eq!(result.stderr, "");
    let lines: Vec<&str> = result.stdout.lines().collect();
    let header_prefix = format!("{}:1:", program.display());
    assert!(lines[0].starts_with(&header_prefix), "{}", result.stdout);
    assert!(lines[0].contains(": error[S101]: "), "{}", result.stdout);
    assert_eq!(lines[1], "    1 | N10 G91 G0 Z=AC17");
    assert!(
        lines[2].starts_with("      | ") && lines[2].contains('^'),
        "{}",
        result.stdout
    );
    assert!(
        result
            .stdout
            .ends_with("checked 1 file: 1 error, 0 warnings, 0 infos\n"),
        "{}",
        result.stdout
    );
}

#[test]
fn json_output_has_all_fields() {
    let dir = TestDir::new("json");
    let program = dir.write("ERR.MPF", PROGRAM_WITH_ERROR);
    let (result, diagnostics) = check_json(&[&program]);
    assert_eq!(result.exit_code, 1, "{}", result.stderr);
    let s101 = diagnostics
        .iter()
        .find(|diagnostic| diagnostic["code"] == "S101")
        .unwrap_or_else(|| panic!("no S101 in {}", result.stdout));
    assert_eq!(s101["file"], program.display().to_string());
    assert_eq!(s101["line"], 1);
    assert_eq!(s101["end_line"], 1);
    assert_eq!(s101["severity"], "error");
    assert!(s101["message"]
        .as_str()
        .is_some_and(|message| !message.is_empty()));
    let column = s101["column"].as_u64().expect("a column");
    let end_column = s101["end_column"].as_u64().expect("an end column");
    assert!(column >= 1 && end_column > column, "{s101}");
    let fix = &s101["fix"];
    assert!(
        fix.is_null() || (fix["title"].is_string() && fix["edits"].is_array()),
        "{s101}"
    );
    for edit in fix["edits"].as_array().into_iter().flatten() {
        for field in ["line", "column", "end_line", "end_column"] {
            assert!(edit[field].is_u64(), "{edit}");
        }
        assert!(edit["new_text"].is_string(), "{edit}");
    }
}

#[test]
fn json_output_of_a_clean_file_is_an_empty_array() {
    let dir = TestDir::new("json-clean");
    let program = dir.write("CLEAN.MPF", CLEAN_PROGRAM);
    let (result, diagnostics) = check_json(&[&program]);
    assert_eq!(result.exit_code, 0, "{}", result.stdout);
    assert!(diagnostics.is_empty(), "{}", result.stdout);
}

#[test]
fn missing_path_exits_2_but_other_files_are_checked() {
    let dir = TestDir::new("missing");
    let program = dir.write("ERR.MPF", PROGRAM_WITH_ERROR);
    let missing = dir.path.join("NOPE.MPF");
    let result = check(&[&missing, &program]);
    assert_eq!(result.exit_code, 2);
    assert!(result.stderr.contains("NOPE.MPF"), "{}", result.stderr);
    assert!(result.stdout.contains("error[S101]"), "{}", result.stdout);
}

#[test]
fn usage_errors_exit_2() {
    // No arguments at all start the language server (tests/lsp_stdio.rs).
    for args in [
        vec!["check"],
        vec!["check", "--format", "xml", "x.mpf"],
        vec!["check", "--no-such-option", "x.mpf"],
        vec!["frobnicate"],
        vec!["serve", "--bogus"],
    ] {
        let result = run(&args);
        assert_eq!(result.exit_code, 2, "{args:?}");
        assert_eq!(result.stdout, "", "{args:?}");
        assert!(!result.stderr.is_empty(), "{args:?}");
    }
    let help = run(["--help"]);
    assert_eq!(help.exit_code, 0);
    assert!(help.stdout.contains("check"), "{}", help.stdout);
    let version = run(["--version"]);
    assert_eq!(version.exit_code, 0);
    assert!(
        version.stdout.starts_with("sinumerik-lsp "),
        "{}",
        version.stdout
    );
}

#[test]
fn windows_1252_is_read_without_error() {
    let dir = TestDir::new("cp1252");
    let clean = dir.write("UMLAUT.MPF", b"N10 G0 X10 ; \xC4nderung\r\n");
    let result = check(&[&clean]);
    assert_eq!(result.exit_code, 0, "{}{}", result.stdout, result.stderr);
    assert_eq!(result.stderr, "");

    // The line is echoed decoded, and the column counts characters, not bytes.
    let with_error = dir.write(
        "UMLAUT_ERR.MPF",
        b"; \xC4\xD6\xDC\nN10 G0 Z=AC17 ; \xC4nderung\r\n",
    );
    let result = check(&[&with_error]);
    assert_eq!(result.exit_code, 1, "{}{}", result.stdout, result.stderr);
    assert!(
        result.stdout.contains("    2 | N10 G0 Z=AC17 ; Änderung\n"),
        "{}",
        result.stdout
    );
}

#[test]
fn byte_order_mark_is_dropped() {
    let dir = TestDir::new("bom");
    let plain = dir.write("PLAIN.MPF", PROGRAM_WITH_ERROR);
    let with_bom = dir.write(
        "BOM.MPF",
        &[b"\xEF\xBB\xBF".as_slice(), PROGRAM_WITH_ERROR].concat(),
    );
    let (_, plain_diagnostics) = check_json(&[&plain]);
    let (result, bom_diagnostics) = check_json(&[&with_bom]);
    assert_eq!(result.exit_code, 1);
    let columns = |diagnostics: &[serde_json::Value]| -> Vec<(u64, u64)> {
        diagnostics
            .iter()
            .map(|diagnostic| {
                (
                    diagnostic["column"].as_u64().unwrap(),
                    diagnostic["end_column"].as_u64().unwrap(),
                )
            })
            .collect()
    };
    assert_eq!(columns(&bom_diagnostics), columns(&plain_diagnostics));

    let result = check(&[&with_bom]);
    assert!(!result.stdout.contains('\u{FEFF}'), "{}", result.stdout);
    assert!(
        result.stdout.contains("    1 | N10 G91 G0 Z=AC17\n"),
        "{}",
        result.stdout
    );
}

#[test]
fn config_file_with_a_bad_key_exits_2_and_names_the_key() {
    let dir = TestDir::new("bad-config");
    dir.write("sinumerik.toml", b"[machine]\nkinds = \"turn\"\n");
    let program = dir.write("CLEAN.MPF", CLEAN_PROGRAM);
    let result = check(&[&program]);
    assert_eq!(result.exit_code, 2, "{}{}", result.stdout, result.stderr);
    assert!(result.stderr.contains("machine.kinds"), "{}", result.stderr);
    assert!(
        result.stderr.contains("sinumerik.toml:2:1"),
        "{}",
        result.stderr
    );

    let explicit = dir.write("other.toml", b"[axes]\nX = \"lineer\"\n");
    let result = run([
        OsStr::new("check"),
        OsStr::new("--config"),
        explicit.as_os_str(),
        program.as_os_str(),
    ]);
    assert_eq!(result.exit_code, 2);
    assert!(result.stderr.contains("axes.X"), "{}", result.stderr);
    assert!(result.stderr.contains("lineer"), "{}", result.stderr);
}

#[test]
fn config_file_is_found_in_a_parent_folder() {
    let dir = TestDir::new("config-parent");
    // The nested program's error is turned into a warning by the configuration two folders up.
    dir.write("sinumerik.toml", b"[diagnostics]\nS101 = \"warning\"\n");
    let program = dir.write("a/b/ERR.MPF", PROGRAM_WITH_ERROR);
    let result = check(&[&program]);
    assert_eq!(result.exit_code, 0, "{}{}", result.stdout, result.stderr);
    assert!(result.stdout.contains("warning[S101]"), "{}", result.stdout);

    // --config replaces the discovered file.
    let explicit = dir.write("strict.toml", b"");
    let result = run([
        OsStr::new("check"),
        OsStr::new("--config"),
        explicit.as_os_str(),
        program.as_os_str(),
    ]);
    assert_eq!(result.exit_code, 1, "{}{}", result.stdout, result.stderr);
}

#[test]
fn folders_are_walked_by_extension_in_sorted_order() {
    let dir = TestDir::new("walk");
    dir.write("programs/B.MPF", PROGRAM_WITH_ERROR);
    dir.write("programs/a.spf", PROGRAM_WITH_ERROR);
    dir.write("programs/notes.txt", PROGRAM_WITH_ERROR);
    dir.write("programs/no_extension", PROGRAM_WITH_ERROR);
    dir.write("programs/sub/C.Mpf", PROGRAM_WITH_ERROR);
    let folder = dir.path.join("programs");
    let (result, diagnostics) = check_json(&[&folder]);
    assert_eq!(result.exit_code, 1, "{}", result.stderr);
    let mut files: Vec<String> = diagnostics
        .iter()
        .map(|diagnostic| diagnostic["file"].as_str().unwrap().to_string())
        .collect();
    files.dedup();
    let expected: Vec<String> = ["B.MPF", "a.spf", "sub/C.Mpf"]
        .iter()
        .map(|name| folder.join(name).display().to_string())
        .collect();
    assert_eq!(files, expected);

    // --extensions replaces the list; a file named directly is checked whatever its extension.
    let result = run([
        OsStr::new("check"),
        OsStr::new("--extensions"),
        OsStr::new("txt"),
        folder.as_os_str(),
    ]);
    assert!(result.stdout.contains("notes.txt"), "{}", result.stdout);
    assert!(!result.stdout.contains("B.MPF"), "{}", result.stdout);
    let result = check(&[&folder.join("no_extension")]);
    assert_eq!(result.exit_code, 1, "{}", result.stdout);
}

#[test]
fn folder_without_programs_exits_2() {
    let dir = TestDir::new("empty-folder");
    dir.write("docs/readme.txt", b"nothing here");
    let result = check(&[&dir.path.join("docs")]);
    assert_eq!(result.exit_code, 2);
    assert!(
        result.stderr.contains("no program files"),
        "{}",
        result.stderr
    );
}

#[cfg(unix)]
#[test]
fn symlinked_folders_are_not_followed() {
    let dir = TestDir::new("symlink");
    dir.write("real/ERR.MPF", PROGRAM_WITH_ERROR);
    dir.write("walked/CLEAN.MPF", CLEAN_PROGRAM);
    std::os::unix::fs::symlink(dir.path.join("real"), dir.path.join("walked/link")).unwrap();
    // A link back up would make an endless walk if links were followed.
    std::os::unix::fs::symlink(&dir.path, dir.path.join("walked/loop")).unwrap();
    let result = check(&[&dir.path.join("walked")]);
    assert_eq!(result.exit_code, 0, "{}{}", result.stdout, result.stderr);
    assert!(
        result.stdout.contains("checked 1 file:"),
        "{}",
        result.stdout
    );
}

#[test]
fn binary_garbage_does_not_crash() {
    let dir = TestDir::new("garbage");
    // A fixed pseudo-random sequence (a linear congruential generator) keeps the test repeatable.
    let mut state: u32 = 0x5eed;
    let mut garbage: Vec<u8> = (0..200_000)
        .map(|_| {
            state = state.wrapping_mul(1_103_515_245).wrapping_add(12_345);
            (state >> 16) as u8
        })
        .collect();
    garbage.extend_from_slice(b"\0\0\0N10 G0 X1\0\xFF\xFE\n\r\x1b[2J");
    let program = dir.write("GARBAGE.MPF", &garbage);
    for format in ["human", "json"] {
        let result = run([
            OsStr::new("check"),
            OsStr::new("--format"),
            OsStr::new(format),
            program.as_os_str(),
        ]);
        assert!(
            result.exit_code == 0 || result.exit_code == 1,
            "{format}: {}",
            result.stderr
        );
        assert!(
            !result.stdout.contains('\u{1b}'),
            "escape codes must not reach the terminal"
        );
    }
}

#[test]
fn oversized_file_is_refused_and_the_others_checked() {
    let dir = TestDir::new("oversized");
    let huge = dir.path.join("HUGE.MPF");
    // A sparse file: the size is reported by the filesystem without writing 257 MiB.
    fs::File::create(&huge)
        .unwrap()
        .set_len(257 * 1024 * 1024)
        .unwrap();
    let program = dir.write("ERR.MPF", PROGRAM_WITH_ERROR);
    let result = check(&[&huge, &program]);
    assert_eq!(result.exit_code, 2);
    assert!(
        result.stderr.contains("HUGE.MPF") && result.stderr.contains("too large"),
        "{}",
        result.stderr
    );
    assert!(result.stdout.contains("error[S101]"), "{}", result.stdout);
}

#[test]
fn cycle_folders_must_exist_and_leave_the_findings_unchanged() {
    let dir = TestDir::new("cycles");
    let program = dir.write("ERR.MPF", PROGRAM_WITH_ERROR);
    let cycles = dir.path.join("cycles");
    fs::create_dir_all(&cycles).unwrap();
    let without = check(&[&program]);

    let with = run([
        OsStr::new("check"),
        OsStr::new("--cycles"),
        cycles.as_os_str(),
        OsStr::new("--cycles"),
        dir.path.as_os_str(),
        program.as_os_str(),
    ]);
    assert_eq!(with.exit_code, 1, "{}{}", with.stdout, with.stderr);
    assert_eq!(with.stdout, without.stdout);
    assert_eq!(with.stderr, "");

    let missing = dir.path.join("no-such-cycles");
    let result = run([
        OsStr::new("check"),
        OsStr::new("--cycles"),
        cycles.as_os_str(),
        OsStr::new("--cycles"),
        missing.as_os_str(),
        program.as_os_str(),
    ]);
    assert_eq!(result.exit_code, 2, "{}{}", result.stdout, result.stderr);
    // Nothing is checked: the programs would be read without the cycles the user named.
    assert_eq!(result.stdout, "");
    assert!(
        result.stderr.starts_with(&format!(
            "error: {}: the folder given with --cycles cannot be read: ",
            missing.display()
        )),
        "{}",
        result.stderr
    );

    let result = run([
        OsStr::new("check"),
        OsStr::new("--cycles"),
        program.as_os_str(),
        program.as_os_str(),
    ]);
    assert_eq!(result.exit_code, 2, "{}{}", result.stdout, result.stderr);
    assert!(
        result
            .stderr
            .contains("given with --cycles, but not a folder"),
        "{}",
        result.stderr
    );
}

#[test]
fn the_control_s_file_names_say_whether_a_program_is_a_main_program() {
    let dir = TestDir::new("control-names");
    // A feed move without F: an error in a main program, which starts without a feed; none in a
    // subprogram, which inherits the caller's.
    let text: &[u8] = b"N10 G1 X10\nN20 M30\n";
    let main = dir.write("_N_MAIN_MPF", text);
    let sub = dir.write("_N_MAIN_SPF", text);
    let archived_main = dir.write("_N_PART_MPF.txt", text);
    let (result, diagnostics) = check_json(&[&main, &sub, &archived_main]);
    assert_eq!(result.exit_code, 1, "{}{}", result.stdout, result.stderr);
    let files: Vec<&str> = diagnostics
        .iter()
        .filter(|diagnostic| diagnostic["code"] == "A203")
        .map(|diagnostic| diagnostic["file"].as_str().unwrap())
        .collect();
    assert_eq!(
        files,
        [
            main.display().to_string(),
            archived_main.display().to_string()
        ]
    );
}

#[test]
fn macros_of_definition_files_are_no_unknown_g_functions() {
    let dir = TestDir::new("library-macros");
    let program = dir.write(
        "parts/MAIN.MPF",
        b"N10 G90 G0 X0 Y0 Z0\nN20 R210=25\nN30 G300\nN40 M30\n",
    );
    let without = check(&[&program]);
    assert_eq!(
        without.exit_code, 1,
        "G300 is no G function: {}",
        without.stdout
    );
    assert!(without.stdout.contains("S144"), "{}", without.stdout);
    // A macro definition file next to the program defines G300 (reference §8.10).
    dir.write("parts/_N_SMAC_DEF", b"DEFINE G300 AS G90 G0 Z=R210\n");
    let with = check(&[&program]);
    assert_eq!(with.exit_code, 0, "{}", with.stdout);
    assert!(!with.stdout.contains("S144"), "{}", with.stdout);
}
