//! `check --format sarif`: one SARIF 2.1.0 log with one run. The rules are every finding code (its
//! summary as the help text, the control's alarm numbers as a property); each result has its region in
//! 1-based lines and columns counted in Unicode code points, end exclusive (the run says so with
//! `columnKind`), and the finding's fix as a SARIF fix where it has one.

use super::output::{alarm_numbers, CheckOutput, FileFindings, RunSummary};
use super::uri::{folder_uri, is_absolute, path_uri};
use crate::cli::report::ProgramLines;
use crate::diagnostics::{Code, LineDiagnostic, Severity, Span};
use serde_json::{json, Map, Value};
use std::io::{self, Write};
use std::path::Path;

/// The base that relative paths are resolved against, as SARIF viewers and GitHub code scanning
/// expect it (`%SRCROOT%`, the root of the sources).
const SOURCE_ROOT: &str = "%SRCROOT%";

pub(super) struct SarifOutput {
    /// The working folder as a `file:` URI ending in `/`, when it is known.
    source_root: Option<String>,
    n_written: usize,
}

impl SarifOutput {
    pub(super) fn new(working_dir: Option<&Path>) -> SarifOutput {
        SarifOutput {
            source_root: working_dir.and_then(folder_uri),
            n_written: 0,
        }
    }
}

impl CheckOutput for SarifOutput {
    fn begin(&mut self, out: &mut dyn Write) -> io::Result<()> {
        // The log is written in pieces, so that results stream: everything up to the opening of the
        // results array now, the array's items per file, the rest at the end.
        let mut run = Map::new();
        run.insert("tool".into(), tool());
        if let Some(source_root) = &self.source_root {
            run.insert(
                "originalUriBaseIds".into(),
                json!({ SOURCE_ROOT: { "uri": source_root } }),
            );
        }
        run.insert("columnKind".into(), json!("unicodeCodePoints"));
        let run = serde_json::to_string(&Value::Object(run))?;
        // The object's closing brace is left off: the results follow as its last member.
        let run = run.strip_suffix('}').unwrap_or(&run);
        write!(
            out,
            "{{\"$schema\":\"https://json.schemastore.org/sarif-2.1.0.json\",\"version\":\"2.1.0\",\"runs\":[{run},\"results\":["
        )
    }

    fn file(&mut self, out: &mut dyn Write, file: &FileFindings<'_>) -> io::Result<()> {
        let location = artifact_location(file.path_text);
        for line_diagnostic in file.diagnostics {
            let separator = if self.n_written == 0 { "\n" } else { ",\n" };
            write!(out, "{separator}")?;
            serde_json::to_writer(&mut *out, &result(&location, file.lines, line_diagnostic))?;
            self.n_written += 1;
        }
        Ok(())
    }

    fn end(&mut self, out: &mut dyn Write, summary: &RunSummary) -> io::Result<()> {
        // The exit code of `check`, as SARIF's consumers read it: 2 for an incomplete run.
        let exit_code = if !summary.complete {
            2
        } else if summary.counts.errors > 0 {
            1
        } else {
            0
        };
        let invocation = json!({
            "executionSuccessful": summary.complete,
            "exitCode": exit_code,
        });
        writeln!(out, "\n],\"invocations\":[{invocation}]}}]}}")
    }
}

fn tool() -> Value {
    let rules: Vec<Value> = Code::ALL.iter().map(|code| rule(*code)).collect();
    json!({
        "driver": {
            "name": "sinumerik-lsp",
            "fullName": "sinumerik-lsp, the checker of SINUMERIK NC programs",
            "version": env!("CARGO_PKG_VERSION"),
            "semanticVersion": env!("CARGO_PKG_VERSION"),
            "rules": rules,
        }
    })
}

/// One finding code as a SARIF rule. The rules are in the order of `Code::ALL`, which is what the
/// results' `ruleIndex` points into.
fn rule(code: Code) -> Value {
    let summary = code.summary();
    let alarms = alarm_numbers(summary);
    let mut help = format!("{summary}\n\n");
    match alarms.as_slice() {
        [] => {}
        [alarm] => help.push_str(&format!("The control's alarm: {alarm}.\n")),
        alarms => help.push_str(&format!("The control's alarms: {}.\n", alarms.join(", "))),
    }
    help.push_str(&format!(
        "{} is described with every other code in docs/diagnostics.md of sinumerik-lsp; its severity can be changed in sinumerik.toml ([diagnostics] {} = \"warning\").",
        code.as_str(),
        code.as_str()
    ));
    json!({
        "id": code.as_str(),
        "name": format!("{code:?}"),
        "shortDescription": { "text": summary },
        "fullDescription": { "text": summary },
        "help": { "text": help },
        "defaultConfiguration": { "level": level(code.default_severity()) },
        "properties": {
            "alarms": alarms,
            "tags": [family(code)],
        },
    })
}

/// The family of checks a code belongs to, by its letter: what a viewer can filter by.
fn family(code: Code) -> &'static str {
    match code.as_str().as_bytes().first() {
        Some(b'S') => "syntax",
        Some(b'A') => "analysis",
        Some(b'E') => "execution",
        Some(b'W') => "workspace",
        _ => "other",
    }
}

fn level(severity: Severity) -> &'static str {
    match severity {
        Severity::Error => "error",
        Severity::Warning => "warning",
        // SARIF has no level below `note`: infos and hints are both notes.
        Severity::Information | Severity::Hint => "note",
    }
}

fn artifact_location(path_text: &str) -> Value {
    if is_absolute(path_text) {
        json!({ "uri": path_uri(path_text) })
    } else {
        json!({ "uri": path_uri(path_text), "uriBaseId": SOURCE_ROOT })
    }
}

fn region(lines: &ProgramLines<'_>, line_idx: usize, span: Span) -> Value {
    let (start_column, end_column) = lines.columns(line_idx, span);
    json!({
        "startLine": line_idx + 1,
        "startColumn": start_column,
        "endLine": line_idx + 1,
        "endColumn": end_column,
    })
}

fn result(location: &Value, lines: &ProgramLines<'_>, line_diagnostic: &LineDiagnostic) -> Value {
    let diagnostic = &line_diagnostic.diagnostic;
    let line_idx = line_diagnostic.line;
    let rule_index = Code::ALL
        .iter()
        .position(|code| *code == diagnostic.code)
        .unwrap_or(0);
    let mut result = json!({
        "ruleId": diagnostic.code.as_str(),
        "ruleIndex": rule_index,
        "level": level(diagnostic.severity),
        "message": { "text": diagnostic.message },
        "locations": [{
            "physicalLocation": {
                "artifactLocation": location,
                "region": region(lines, line_idx, diagnostic.span),
            }
        }],
    });
    // A SARIF fix needs at least one replacement; a fix without edits only names an intent.
    if let Some(fix) = diagnostic.fix.as_ref().filter(|fix| !fix.edits.is_empty()) {
        let replacements: Vec<Value> = fix
            .edits
            .iter()
            .map(|edit| {
                // Edits are relative to the diagnostic's line, like its span.
                json!({
                    "deletedRegion": region(lines, line_idx, edit.span),
                    "insertedContent": { "text": edit.new_text },
                })
            })
            .collect();
        result["fixes"] = json!([{
            "description": { "text": fix.title },
            "artifactChanges": [{
                "artifactLocation": location,
                "replacements": replacements,
            }],
        }]);
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cli::formats::output::render_one_file;
    use crate::diagnostics::{Diagnostic, Fix};

    fn render(path: &str, text: &str, diagnostics: &[LineDiagnostic], complete: bool) -> Value {
        let mut output = SarifOutput::new(Some(Path::new("/work/repo")));
        let out = render_one_file(&mut output, path, text, diagnostics, complete);
        serde_json::from_slice(&out).expect("the log is one JSON document")
    }

    fn s101_with_fix() -> LineDiagnostic {
        LineDiagnostic {
            line: 1,
            diagnostic: Diagnostic::new(
                Code::ModifierWithoutParentheses,
                Span::new(3, 9),
                "modifier AC needs its value in parentheses",
            )
            .with_fix(Fix::replace(
                "write `Z=AC(17)`",
                Span::new(3, 9),
                "Z=AC(17)",
            )),
        }
    }

    #[test]
    fn a_result_has_its_rule_region_and_fix() {
        let log = render(
            "./progs/Ä 1.MPF",
            "; Ä\nÄ Z=AC17\n",
            &[s101_with_fix()],
            true,
        );
        let run = &log["runs"][0];
        assert_eq!(log["version"], "2.1.0");
        assert_eq!(run["columnKind"], "unicodeCodePoints");
        assert_eq!(
            run["originalUriBaseIds"]["%SRCROOT%"]["uri"],
            "file:///work/repo/"
        );
        let result = &run["results"][0];
        assert_eq!(result["ruleId"], "S101");
        let rule_index = result["ruleIndex"].as_u64().unwrap() as usize;
        assert_eq!(run["tool"]["driver"]["rules"][rule_index]["id"], "S101");
        assert_eq!(result["level"], "error");
        let location = &result["locations"][0]["physicalLocation"];
        assert_eq!(location["artifactLocation"]["uri"], "progs/%C3%84%201.MPF");
        assert_eq!(location["artifactLocation"]["uriBaseId"], "%SRCROOT%");
        // Byte offsets 3..9 of `Ä Z=AC17` are the characters 3..9 (1-based, end exclusive).
        assert_eq!(
            location["region"],
            json!({"startLine": 2, "startColumn": 3, "endLine": 2, "endColumn": 9})
        );
        let fix = &result["fixes"][0];
        assert_eq!(fix["description"]["text"], "write `Z=AC(17)`");
        let replacement = &fix["artifactChanges"][0]["replacements"][0];
        assert_eq!(replacement["insertedContent"]["text"], "Z=AC(17)");
        assert_eq!(replacement["deletedRegion"]["startColumn"], 3);
        assert_eq!(run["invocations"][0]["exitCode"], 1);
        assert_eq!(run["invocations"][0]["executionSuccessful"], true);
    }

    #[test]
    fn rules_carry_help_and_alarm_numbers() {
        let log = render("A.MPF", "", &[], false);
        let rules = log["runs"][0]["tool"]["driver"]["rules"]
            .as_array()
            .unwrap();
        assert_eq!(rules.len(), Code::ALL.len());
        let s140 = rules.iter().find(|rule| rule["id"] == "S140").unwrap();
        assert_eq!(s140["properties"]["alarms"], json!(["12060"]));
        assert_eq!(s140["properties"]["tags"], json!(["syntax"]));
        assert_eq!(s140["defaultConfiguration"]["level"], "error");
        let help = s140["help"]["text"].as_str().unwrap();
        assert!(help.contains("The control's alarm: 12060."), "{help}");
        let s143 = rules.iter().find(|rule| rule["id"] == "S143").unwrap();
        assert!(s143["help"]["text"]
            .as_str()
            .unwrap()
            .contains("alarms: 12010, 16420."));
        // No results and an incomplete run: still a valid log, and it says the run failed.
        assert_eq!(log["runs"][0]["results"], json!([]));
        assert_eq!(log["runs"][0]["invocations"][0]["exitCode"], 2);
        assert_eq!(
            log["runs"][0]["invocations"][0]["executionSuccessful"],
            false
        );
    }

    #[test]
    fn absolute_paths_are_file_uris_and_notes_are_notes() {
        if !cfg!(unix) {
            return;
        }
        let mut hint = s101_with_fix();
        hint.diagnostic.severity = Severity::Hint;
        hint.diagnostic.fix = None;
        let log = render("/data/P.MPF", "\nZ=AC17", &[hint], true);
        let result = &log["runs"][0]["results"][0];
        let location = &result["locations"][0]["physicalLocation"]["artifactLocation"];
        assert_eq!(location, &json!({"uri": "file:///data/P.MPF"}));
        assert_eq!(result["level"], "note");
        assert!(result.get("fixes").is_none());
        assert_eq!(log["runs"][0]["invocations"][0]["exitCode"], 0);
    }
}
