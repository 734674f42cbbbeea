//! The `fmt` command: formats program files in place, or with `--check` tells which would change.

use super::args::FmtOptions;
use super::rewrite::{run_rewrite, RewriteRun};
use crate::ide::format::{format_text, FormatOptions};
use std::io::{self, Write};

pub(crate) fn run_fmt(
    options: &FmtOptions,
    stdout: &mut dyn Write,
    stderr: &mut dyn Write,
) -> io::Result<u8> {
    let run = RewriteRun {
        paths: &options.paths,
        config_path: options.config_path.as_deref(),
        check: options.check,
        done_verb: "reformatted",
    };
    run_rewrite(
        &run,
        &|text, config| Ok(format_text(text, config, FormatOptions::default())),
        stdout,
        stderr,
    )
}
