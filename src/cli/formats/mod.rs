//! The output formats of `check`: how the findings of each file are written, and what comes before
//! the first file and after the last.
//!
//! - `plain.rs`: the human format (compiler style) and the JSON array.
//! - `sarif.rs`: SARIF 2.1.0, for code scanning (GitHub) and other SARIF viewers.
//! - `github.rs`: GitHub Actions workflow commands, which annotate the lines of a pull request.
//! - `gitlab.rs`: the GitLab Code Quality report (a Code Climate issue list).
//! - `output.rs`: what every format is handed, the interface they implement, what they share.
//!
//! `check` hands every format the same things: the file, its text and its findings, sorted by line and
//! column, then the totals of the run. The formats stream what they can, so a run over many files (or
//! a binary file with a million findings) does not keep its output in memory.

mod github;
mod gitlab;
mod output;
mod plain;
mod sarif;
mod uri;

use super::args::OutputFormat;

pub(crate) use output::{CheckOutput, FileFindings, RunSummary};

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
