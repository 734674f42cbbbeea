//! The output formats of `check`: how the findings of each file are written, and what comes before
//! the first file and after the last.
//!
//! - `plain.rs`: the human format (compiler style) and the JSON array.
//! - `sarif.rs`: SARIF 2.1.0, for code scanning (GitHub) and other SARIF viewers.
//! - `github.rs`: GitHub Actions workflow commands, which annotate the lines of a pull request.
//! - `gitlab.rs`: the GitLab Code Quality report (a Code Climate issue list).
//!
//! `check` hands every format the same things: the file, its text and its findings, sorted by line and
//! column, then the totals of the run. The formats stream what they can, so a run over many files (or
//! a binary file with a million findings) does not keep its output in memory.

mod github;
mod gitlab;
mod plain;
mod sarif;
mod uri;

use super::args::OutputFormat;
use super::report::{ProgramLines, SeverityCounts};
use crate::diagnostics::LineDiagnostic;
use std::io::{self, Write};

/// One checked file as the formats see it.
pub(crate) struct FileFindings<'a> {
    /// The path as given on the command line or found below a folder named there.
    pub path_text: &'a str,
    pub lines: &'a ProgramLines<'a>,
    pub diagnostics: &'a [LineDiagnostic],
}

/// What a format may say after the last file.
pub(crate) struct RunSummary {
    pub n_checked_files: usize,
    pub counts: SeverityCounts,
    /// False when a path, a configuration file or a file could not be used (exit code 2).
    pub complete: bool,
}

/// An output format of `check`.
pub(crate) trait CheckOutput {
    /// Written before the first file (the opening of a JSON document, say).
    fn begin(&mut self, out: &mut dyn Write) -> io::Result<()>;
    /// The findings of one file.
    fn file(&mut self, out: &mut dyn Write, file: &FileFindings<'_>) -> io::Result<()>;
    /// Written after the last file.
    fn end(&mut self, out: &mut dyn Write, summary: &RunSummary) -> io::Result<()>;
}

/// The writer of a format. `working_dir` is where relative paths are relative to: SARIF states it
/// (as `%SRCROOT%`) so that a viewer can find the files.
pub(crate) fn output_for(
    format: OutputFormat,
    working_dir: Option<&std::path::Path>,
) -> Box<dyn CheckOutput> {
    match format {
        OutputFormat::Human => Box::new(plain::HumanOutput),
        OutputFormat::Json => Box::new(plain::JsonOutput::default()),
        OutputFormat::Sarif => Box::new(sarif::SarifOutput::new(working_dir)),
        OutputFormat::Github => Box::new(github::GithubOutput),
        OutputFormat::Gitlab => Box::new(gitlab::GitlabOutput::default()),
    }
}

/// The alarm numbers of the control that a finding's summary names (`(alarm 12060)`,
/// `(alarms 12010, 16420)`), in the order written: the same numbers the control shows, so that a
/// reader of a CI report can look them up in the control's alarm list.
pub(crate) fn alarm_numbers(summary: &str) -> Vec<&str> {
    let mut numbers = Vec::new();
    let mut rest = summary;
    while let Some(found) = rest.find("alarm") {
        rest = &rest[found + "alarm".len()..];
        rest = rest.strip_prefix('s').unwrap_or(rest);
        // A list of numbers follows: `12010, 16420` or `12010 and 16420`; anything else ends it.
        loop {
            let trimmed = rest.trim_start_matches([' ', ',']);
            let trimmed = trimmed.strip_prefix("and ").unwrap_or(trimmed);
            let digits = trimmed.bytes().take_while(u8::is_ascii_digit).count();
            if digits < 4 {
                break;
            }
            numbers.push(&trimmed[..digits]);
            rest = &trimmed[digits..];
        }
    }
    numbers
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostics::Code;

    #[test]
    fn alarm_numbers_are_read_from_the_summaries() {
        assert_eq!(alarm_numbers(Code::SameGroupTwice.summary()), vec!["12060"]);
        assert_eq!(
            alarm_numbers(Code::AddressTwice.summary()),
            vec!["12010", "16420"]
        );
        assert_eq!(
            alarm_numbers("the control stops with alarm 14012 if it takes that way"),
            vec!["14012"]
        );
        // "the alarm is not documented" names no number.
        assert!(alarm_numbers(Code::AngleDirectionMismatch.summary()).is_empty());
        assert!(alarm_numbers("alarms").is_empty());
    }

    #[test]
    fn most_error_codes_name_their_alarm() {
        // The summaries are written by hand; this keeps the reading of them honest: a change of
        // wording that hid the numbers would empty the rules' alarm lists.
        let with_alarm = Code::ALL
            .iter()
            .filter(|code| !alarm_numbers(code.summary()).is_empty())
            .count();
        assert!(with_alarm >= 30, "{with_alarm} codes name an alarm");
    }
}
