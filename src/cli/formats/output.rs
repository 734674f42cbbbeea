//! What `check` hands every format (a file with its findings, the totals of the run), the interface
//! each format implements, and what several formats share: the cut-off of long lists of findings
//! and the alarm numbers named in a finding's summary.

use crate::cli::report::{ProgramLines, SeverityCounts};
use crate::diagnostics::LineDiagnostic;
use std::io::{self, Write};

/// How many findings of one file the formats that people read (human, GitHub) show: a file of junk
/// (a binary, an archive) can give a million findings, and a person reads the first ones.
pub(crate) const MAX_SHOWN_FINDINGS_PER_FILE: usize = 1_000;

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

impl FileFindings<'_> {
    /// The findings a person reads (the first [`MAX_SHOWN_FINDINGS_PER_FILE`]) and how many more
    /// there are; the rest are counted in the summary but not printed.
    pub(crate) fn shown(&self) -> (&[LineDiagnostic], usize) {
        let shown = self.diagnostics.len().min(MAX_SHOWN_FINDINGS_PER_FILE);
        (&self.diagnostics[..shown], self.diagnostics.len() - shown)
    }
}

/// The whole output of `output` for one file of `text` with `diagnostics` (for the formats' tests):
/// begin, the file, and the end with the findings counted; `complete` as the run would say.
#[cfg(test)]
pub(crate) fn render_one_file(
    output: &mut dyn CheckOutput,
    path: &str,
    text: &str,
    diagnostics: &[LineDiagnostic],
    complete: bool,
) -> Vec<u8> {
    let lines = ProgramLines::new(text);
    let mut out = Vec::new();
    let mut counts = SeverityCounts::default();
    for item in diagnostics {
        counts.add(item.diagnostic.severity);
    }
    let file = FileFindings {
        path_text: path,
        lines: &lines,
        diagnostics,
    };
    let summary = RunSummary {
        n_checked_files: 1,
        counts,
        complete,
    };
    output.begin(&mut out).expect("writing to memory");
    output.file(&mut out, &file).expect("writing to memory");
    output.end(&mut out, &summary).expect("writing to memory");
    out
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
