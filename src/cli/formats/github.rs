//! `check --format github`: one GitHub Actions workflow command per finding,
//! `::error file=P,line=L,endLine=L,col=C,endColumn=E,title=CODE::message`, which GitHub shows as an
//! annotation on the line of the pull request and in the run's summary; the last line is the human
//! format's summary, which the log shows as it is.

use super::output::{CheckOutput, FileFindings, RunSummary, MAX_SHOWN_FINDINGS_PER_FILE};
use super::uri::slash_path;
use crate::cli::report;
use crate::diagnostics::{LineDiagnostic, Severity};
use std::io::{self, Write};

pub(super) struct GithubOutput;

impl CheckOutput for GithubOutput {
    fn begin(&mut self, _out: &mut dyn Write) -> io::Result<()> {
        Ok(())
    }

    fn file(&mut self, out: &mut dyn Write, file: &FileFindings<'_>) -> io::Result<()> {
        let path = escape_property(&slash_path(file.path_text));
        // GitHub shows only the first annotations of a step, and the log is read by people: a file
        // of junk is cut off as in the human format (the summary still counts everything).
        let (shown, hidden) = file.shown();
        for line_diagnostic in shown {
            write_command(out, &path, file, line_diagnostic)?;
        }
        if hidden > 0 {
            writeln!(
                out,
                "::warning file={path},title=more findings::{hidden} more findings not shown (the first {MAX_SHOWN_FINDINGS_PER_FILE} of each file are; --format sarif lists all)",
            )?;
        }
        Ok(())
    }

    fn end(&mut self, out: &mut dyn Write, summary: &RunSummary) -> io::Result<()> {
        writeln!(
            out,
            "{}",
            report::summary_line(summary.n_checked_files, summary.counts)
        )
    }
}

fn write_command(
    out: &mut dyn Write,
    escaped_path: &str,
    file: &FileFindings<'_>,
    line_diagnostic: &LineDiagnostic,
) -> io::Result<()> {
    let diagnostic = &line_diagnostic.diagnostic;
    let command = match diagnostic.severity {
        Severity::Error => "error",
        Severity::Warning => "warning",
        Severity::Information | Severity::Hint => "notice",
    };
    let line = line_diagnostic.line + 1;
    let (column, end_column) = file.lines.columns(line_diagnostic.line, diagnostic.span);
    // GitHub's end column is the last character's (inclusive); ours is the one after it.
    let last_column = end_column.saturating_sub(1).max(column);
    let mut message = diagnostic.message.clone();
    if let Some(fix) = &diagnostic.fix {
        message.push_str(&format!(" (fix: {})", fix.title));
    }
    writeln!(
        out,
        "::{command} file={escaped_path},line={line},endLine={line},col={column},endColumn={last_column},title={}::{}",
        escape_property(diagnostic.code.as_str()),
        escape_data(&message)
    )
}

/// The message of a command: a line break would end the command and start another line of the log
/// (where `::` could start a command of its own), so `%`, CR and LF are percent-encoded as the runner
/// decodes them.
fn escape_data(text: &str) -> String {
    text.replace('%', "%25")
        .replace('\r', "%0D")
        .replace('\n', "%0A")
}

/// A property value (`file=...`): also `:` and `,`, which separate the properties and the message.
fn escape_property(text: &str) -> String {
    escape_data(text).replace(':', "%3A").replace(',', "%2C")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cli::formats::output::render_one_file;
    use crate::diagnostics::{Code, Diagnostic, Fix, Span};

    /// The file's commands, without the summary line the end adds.
    fn render(path: &str, text: &str, diagnostics: &[LineDiagnostic]) -> String {
        let out = render_one_file(&mut GithubOutput, path, text, diagnostics, true);
        let out = String::from_utf8(out).unwrap();
        let summary_start = out.trim_end().rfind('\n').map_or(0, |at| at + 1);
        out[..summary_start].to_string()
    }

    fn finding(code: Code, severity: Severity, start: usize, end: usize) -> LineDiagnostic {
        let mut diagnostic = Diagnostic::new(code, Span::new(start, end), "a message");
        diagnostic.severity = severity;
        LineDiagnostic {
            line: 0,
            diagnostic,
        }
    }

    #[test]
    fn a_finding_becomes_one_workflow_command() {
        let mut item = finding(Code::ModifierWithoutParentheses, Severity::Error, 4, 10);
        item.diagnostic = item.diagnostic.with_fix(Fix::replace(
            "write `Z=AC(17)`",
            Span::new(4, 10),
            "Z=AC(17)",
        ));
        assert_eq!(
            render("./progs/P.MPF", "N20 Z=AC17", &[item]),
            "::error file=progs/P.MPF,line=1,endLine=1,col=5,endColumn=10,title=S101::a message (fix: write `Z=AC(17)`)\n"
        );
    }

    #[test]
    fn severities_map_to_commands_and_empty_spans_keep_one_column() {
        let rendered = render(
            "P.MPF",
            "N10 X",
            &[
                finding(Code::SameGroupTwice, Severity::Warning, 5, 5),
                finding(Code::SameGroupTwice, Severity::Information, 0, 3),
                finding(Code::SameGroupTwice, Severity::Hint, 0, 3),
            ],
        );
        let commands: Vec<&str> = rendered
            .lines()
            .map(|line| line.split(' ').next().unwrap())
            .collect();
        assert_eq!(commands, ["::warning", "::notice", "::notice"]);
        assert!(rendered.starts_with("::warning file=P.MPF,line=1,endLine=1,col=6,endColumn=6,"));
    }

    #[test]
    fn line_breaks_and_separators_cannot_escape_the_command() {
        let mut item = finding(Code::SameGroupTwice, Severity::Error, 0, 1);
        item.diagnostic.message = "50% off\n::error::forged\r".to_string();
        let rendered = render("a,b:c%.mpf", "X", &[item]);
        assert_eq!(rendered.lines().count(), 1, "{rendered}");
        assert!(rendered.contains("file=a%2Cb%3Ac%25.mpf,"), "{rendered}");
        assert!(
            rendered.ends_with("::50%25 off%0A::error::forged%0D\n"),
            "{rendered}"
        );
    }

    #[test]
    fn a_file_of_junk_is_cut_off() {
        let item = finding(Code::SameGroupTwice, Severity::Error, 0, 1);
        let many = vec![item; MAX_SHOWN_FINDINGS_PER_FILE + 5];
        let rendered = render("J.MPF", "X", &many);
        assert_eq!(rendered.lines().count(), MAX_SHOWN_FINDINGS_PER_FILE + 1);
        assert!(rendered.ends_with("5 more findings not shown (the first 1000 of each file are; --format sarif lists all)\n"));
    }
}
