//! The human format (compiler style, with a summary line) and the JSON array of `check`.

use super::output::{CheckOutput, FileFindings, RunSummary, MAX_SHOWN_FINDINGS_PER_FILE};
use crate::cli::report::{self, JsonDiagnostic};
use std::io::{self, Write};

/// Compiler-style findings with the source line and a caret underline, then a summary line.
pub(super) struct HumanOutput;

impl CheckOutput for HumanOutput {
    fn begin(&mut self, _out: &mut dyn Write) -> io::Result<()> {
        Ok(())
    }

    fn file(&mut self, out: &mut dyn Write, file: &FileFindings<'_>) -> io::Result<()> {
        let (shown, hidden) = file.shown();
        for line_diagnostic in shown {
            report::write_human(out, file.path_text, file.lines, line_diagnostic)?;
        }
        if hidden > 0 {
            writeln!(
                out,
                "{}: {hidden} more findings not shown (the first {MAX_SHOWN_FINDINGS_PER_FILE} of each file are; --format json lists all)",
                file.path_text,
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

/// One JSON array of every finding, one object per line inside it: valid JSON that is still easy to
/// grep.
#[derive(Default)]
pub(super) struct JsonOutput {
    n_written: usize,
}

impl CheckOutput for JsonOutput {
    fn begin(&mut self, out: &mut dyn Write) -> io::Result<()> {
        write!(out, "[")
    }

    fn file(&mut self, out: &mut dyn Write, file: &FileFindings<'_>) -> io::Result<()> {
        for line_diagnostic in file.diagnostics {
            let separator = if self.n_written == 0 { "\n" } else { ",\n" };
            write!(out, "{separator}")?;
            serde_json::to_writer(
                &mut *out,
                &JsonDiagnostic::new(file.path_text, file.lines, line_diagnostic),
            )?;
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
