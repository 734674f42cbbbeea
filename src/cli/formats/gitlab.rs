//! `check --format gitlab`: the GitLab Code Quality report, a JSON array of Code Climate issues with
//! the fields GitLab reads: `description`, `check_name`, `fingerprint`, `severity` and
//! `location.path` with `location.lines.begin`.
//!
//! GitLab compares the reports of two pipelines by fingerprint to show which findings a merge request
//! adds or fixes, so a fingerprint must stay the same while the finding does, even when lines are
//! inserted above it, and differ between two findings: it is a hash of the path, the code, the text
//! of the line (without surrounding white space) and how many findings of that code on the same line
//! text came before it in the file.

use super::output::{CheckOutput, FileFindings, RunSummary};
use super::uri::slash_path;
use crate::diagnostics::Severity;
use serde_json::json;
use std::collections::HashMap;
use std::io::{self, Write};

#[derive(Default)]
pub(super) struct GitlabOutput {
    n_written: usize,
}

impl CheckOutput for GitlabOutput {
    fn begin(&mut self, out: &mut dyn Write) -> io::Result<()> {
        write!(out, "[")
    }

    fn file(&mut self, out: &mut dyn Write, file: &FileFindings<'_>) -> io::Result<()> {
        let path = slash_path(file.path_text);
        let mut occurrences: HashMap<(&str, &str), usize> = HashMap::new();
        for line_diagnostic in file.diagnostics {
            let diagnostic = &line_diagnostic.diagnostic;
            let line_text = file.lines.line(line_diagnostic.line).trim();
            let occurrence = occurrences
                .entry((diagnostic.code.as_str(), line_text))
                .or_insert(0);
            let fingerprint = fingerprint(&[
                path.as_bytes(),
                diagnostic.code.as_str().as_bytes(),
                line_text.as_bytes(),
                occurrence.to_string().as_bytes(),
            ]);
            *occurrence += 1;
            let line = line_diagnostic.line + 1;
            let issue = json!({
                "type": "issue",
                "description": format!("{}: {}", diagnostic.code, diagnostic.message),
                "check_name": diagnostic.code.as_str(),
                "fingerprint": fingerprint,
                "severity": severity(diagnostic.severity),
                "location": {
                    "path": path,
                    "lines": { "begin": line, "end": line },
                },
            });
            let separator = if self.n_written == 0 { "\n" } else { ",\n" };
            write!(out, "{separator}")?;
            serde_json::to_writer(&mut *out, &issue)?;
            self.n_written += 1;
        }
        Ok(())
    }

    fn end(&mut self, out: &mut dyn Write, _summary: &RunSummary) -> io::Result<()> {
        if self.n_written == 0 {
            writeln!(out, "]")
        } else {
            writeln!(out, "\n]")
        }
    }
}

/// GitLab's scale is info, minor, major, critical, blocker; what the control rejects is major (the
/// program stops with an alarm), likely mistakes are minor.
fn severity(severity: Severity) -> &'static str {
    match severity {
        Severity::Error => "major",
        Severity::Warning => "minor",
        Severity::Information | Severity::Hint => "info",
    }
}

/// 128 bits as 32 hexadecimal digits (the length of the MD5 fingerprints most tools write): two
/// FNV-1a hashes of 64 bits with different offsets over the parts, each part followed by a zero byte so
/// that `ab`+`c` and `a`+`bc` differ. FNV is written here because it is fixed by its definition: the
/// fingerprints stay the same across versions of Rust and of this program.
fn fingerprint(parts: &[&[u8]]) -> String {
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    let mut hashes = [0xcbf2_9ce4_8422_2325_u64, 0x6c62_272e_07bb_0142_u64];
    for hash in &mut hashes {
        for part in parts {
            for byte in part.iter().chain(std::iter::once(&0)) {
                *hash ^= u64::from(*byte);
                *hash = hash.wrapping_mul(PRIME);
            }
        }
    }
    format!("{:016x}{:016x}", hashes[0], hashes[1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cli::formats::output::render_one_file;
    use crate::diagnostics::{Code, Diagnostic, LineDiagnostic, Span};
    use serde_json::Value;

    fn render(path: &str, text: &str, diagnostics: &[LineDiagnostic]) -> Vec<Value> {
        let out = render_one_file(&mut GitlabOutput::default(), path, text, diagnostics, true);
        serde_json::from_slice(&out).unwrap()
    }

    fn finding(line: usize, severity: Severity) -> LineDiagnostic {
        let mut diagnostic = Diagnostic::new(Code::SameGroupTwice, Span::new(0, 2), "G0 and G1");
        diagnostic.severity = severity;
        LineDiagnostic { line, diagnostic }
    }

    #[test]
    fn an_issue_has_the_fields_gitlab_reads() {
        let issues = render("./p/A.MPF", "G0 G1 X1\n", &[finding(0, Severity::Error)]);
        let issue = &issues[0];
        assert_eq!(issue["description"], "S140: G0 and G1");
        assert_eq!(issue["check_name"], "S140");
        assert_eq!(issue["severity"], "major");
        assert_eq!(issue["location"]["path"], "p/A.MPF");
        assert_eq!(issue["location"]["lines"]["begin"], 1);
        let fingerprint = issue["fingerprint"].as_str().unwrap();
        assert_eq!(fingerprint.len(), 32);
        assert!(fingerprint.bytes().all(|byte| byte.is_ascii_hexdigit()));
        assert_eq!(render("A.MPF", "", &[]), Vec::<Value>::new());
    }

    #[test]
    fn fingerprints_differ_between_findings_and_survive_moved_lines() {
        // The same finding twice on one line text (two identical blocks) and once elsewhere.
        let text = "G0 G1 X1\nG0 G1 X1\nG0 G1 X2\n";
        let issues = render(
            "A.MPF",
            text,
            &[
                finding(0, Severity::Warning),
                finding(1, Severity::Warning),
                finding(2, Severity::Hint),
            ],
        );
        let prints: Vec<&str> = issues
            .iter()
            .map(|issue| issue["fingerprint"].as_str().unwrap())
            .collect();
        assert_ne!(prints[0], prints[1]);
        assert_ne!(prints[0], prints[2]);
        assert_ne!(prints[1], prints[2]);
        assert_eq!(issues[0]["severity"], "minor");
        assert_eq!(issues[2]["severity"], "info");

        // Two comment lines inserted above: the same fingerprints on other lines.
        let moved = render(
            "A.MPF",
            &format!("; new\n; lines\n{text}"),
            &[
                finding(2, Severity::Warning),
                finding(3, Severity::Warning),
                finding(4, Severity::Hint),
            ],
        );
        let moved_prints: Vec<&str> = moved
            .iter()
            .map(|issue| issue["fingerprint"].as_str().unwrap())
            .collect();
        assert_eq!(prints, moved_prints);
        assert_eq!(moved[0]["location"]["lines"]["begin"], 3);
        // Another file: other fingerprints.
        let other = render("B.MPF", text, &[finding(0, Severity::Warning)]);
        assert_ne!(other[0]["fingerprint"], issues[0]["fingerprint"]);
    }

    #[test]
    fn fnv_is_the_published_function() {
        // FNV-1a 64 of "a" is 0xaf63dc4c8601ec8c; with the zero byte after each part it is the hash
        // of "a\0".
        let mut hash = 0xcbf2_9ce4_8422_2325_u64;
        for byte in b"a" {
            hash ^= u64::from(*byte);
            hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
        }
        assert_eq!(hash, 0xaf63_dc4c_8601_ec8c);
        // The zero byte after the part: XOR with 0 leaves the hash, the multiplication remains.
        assert!(fingerprint(&[b"a"]).starts_with(&format!(
            "{:016x}",
            hash.wrapping_mul(0x0000_0100_0000_01b3)
        )));
        assert_ne!(fingerprint(&[b"ab", b"c"]), fingerprint(&[b"a", b"bc"]));
    }
}
