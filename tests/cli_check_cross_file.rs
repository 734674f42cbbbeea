//! `check` reports the cross-file findings W301-W307 (as the server does): a jump to a missing label
//! or in the wrong direction and a DEF after the first executable block fail the run, and a call is
//! unknown only when none of the folders `check` searches for callees (the program's folder, its
//! parents up to the `sinumerik.toml`, the `--cycles` folders) has the program.

use std::ffi::OsStr;
use std::fs;
use std::path::PathBuf;
use std::process::Command;

/// A fresh folder with an empty `sinumerik.toml` (so the search for callees and configuration stops
/// here), removed afterwards.
struct TestDir {
    path: PathBuf,
}

impl TestDir {
    fn new(test_name: &str) -> TestDir {
        let path = std::env::temp_dir().join(format!(
            "sinumerik-lsp-cross-file-{}-{test_name}",
            std::process::id()
        ));
        let _ = fs::remove_dir_all(&path);
        fs::create_dir_all(&path).unwrap();
        fs::write(path.join("sinumerik.toml"), "").unwrap();
        TestDir { path }
    }

    fn write(&self, relative_path: &str, contents: &str) -> PathBuf {
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

/// `check --format json` with `args`: the exit code and the findings as (code, line, column,
/// severity).
fn check_json(args: &[&OsStr]) -> (i32, Vec<(String, u64, u64, String)>) {
    let output = Command::new(env!("CARGO_BIN_EXE_sinumerik-lsp"))
        .args(["check", "--format", "json"])
        .args(args)
        .output()
        .expect("the binary runs");
    let stdout = String::from_utf8(output.stdout).unwrap();
    let items: serde_json::Value =
        serde_json::from_str(&stdout).unwrap_or_else(|error| panic!("{error}: {stdout}"));
    let findings = items
        .as_array()
        .unwrap()
        .iter()
        .map(|item| {
            (
                item["code"].as_str().unwrap().to_string(),
                item["line"].as_u64().unwrap(),
                item["column"].as_u64().unwrap(),
                item["severity"].as_str().unwrap().to_string(),
            )
        })
        .collect();
    (output.status.code().expect("no signal"), findings)
}

fn cross_file(findings: &[(String, u64, u64, String)]) -> Vec<(String, u64, u64, String)> {
    findings
        .iter()
        .filter(|finding| finding.0.starts_with("W3"))
        .cloned()
        .collect()
}

fn finding(code: &str, line: u64, column: u64, severity: &str) -> (String, u64, u64, String) {
    (code.to_string(), line, column, severity.to_string())
}

#[test]
fn jumps_to_missing_labels_and_late_definitions_fail_the_run() {
    let dir = TestDir::new("jumps");
    let program = dir.write(
        "MAIN.MPF",
        "N10 G0 X0\nN20 GOTOF NOWHERE\nBACK:\nN30 GOTOF BACK\nN40 DEF REAL LATE\nN50 M30\n",
    );
    let (code, findings) = check_json(&[program.as_os_str()]);
    assert_eq!(code, 1, "{findings:?}");
    assert_eq!(
        cross_file(&findings),
        vec![
            finding("W304", 2, 11, "error"),
            finding("W305", 4, 11, "error"),
            finding("W307", 5, 14, "error"),
        ]
    );
}

#[test]
fn calls_are_found_in_the_folders_check_searches_and_unknown_elsewhere() {
    let dir = TestDir::new("calls");
    let program = dir.write(
        "parts/a/MAIN.MPF",
        "N10 PARENT\nN20 CYC()\nN30 OTHER\nN40 M30\n",
    );
    dir.write("parts/PARENT.SPF", "PROC PARENT\nM17\n");
    dir.write("cycles/deep/CYC.SPF", "PROC CYC(VAR REAL RESULT)\nM17\n");
    // A sibling folder is not searched: the control would not find OTHER there either.
    dir.write("parts/b/OTHER.SPF", "PROC OTHER\nM17\n");
    let cycles = dir.path.join("cycles");

    let (_, without_cycles) = check_json(&[program.as_os_str()]);
    assert_eq!(
        cross_file(&without_cycles),
        vec![
            finding("W301", 2, 5, "warning"),
            finding("W301", 3, 5, "warning"),
        ]
    );
    let (code, with_cycles) = check_json(&[
        OsStr::new("--cycles"),
        cycles.as_os_str(),
        program.as_os_str(),
    ]);
    // CYC is found, and its header says that the call leaves out a VAR parameter.
    assert_eq!(code, 0, "{with_cycles:?}");
    assert_eq!(
        cross_file(&with_cycles),
        vec![
            finding("W303", 2, 5, "warning"),
            finding("W301", 3, 5, "warning"),
        ]
    );
}

#[test]
fn the_programs_of_a_folder_share_the_folder_s_definitions() {
    let dir = TestDir::new("definitions");
    // A subprogram uses a global variable that a definition file of its folder defines, and one that
    // nothing defines; checking the folder gives each program its findings from the same index (the
    // folder's files in sorted order: MAIN.MPF's W304, then SUB.SPF's W306).
    dir.write("GUD.DEF", "DEF NCK REAL SHARED_VALUE\n");
    dir.write("SUB.SPF", "PROC SUB\nR1=SHARED_VALUE+MISSING_VALUE\nM17\n");
    dir.write("MAIN.MPF", "N10 SUB\nN20 GOTOF END_LABEL\nN30 M30\n");
    let (code, findings) = check_json(&[dir.path.as_os_str()]);
    assert_eq!(code, 1, "{findings:?}");
    assert_eq!(
        cross_file(&findings),
        vec![
            finding("W304", 2, 11, "error"),
            finding("W306", 2, 17, "warning"),
        ]
    );
}
