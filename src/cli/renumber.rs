//! The `renumber` command: renumbers the blocks of program files in place, or with `--check` tells
//! which would change.

use super::args::RenumberCliOptions;
use super::rewrite::{run_rewrite, RewriteRun};
use crate::ide::renumber::renumber_text;
use std::io::{self, Write};

pub(crate) fn run_renumber(
    options: &RenumberCliOptions,
    stdout: &mut dyn Write,
    stderr: &mut dyn Write,
) -> io::Result<u8> {
    let run = RewriteRun {
        paths: &options.paths,
        config_path: options.config_path.as_deref(),
        check: options.check,
        done_verb: "renumbered",
    };
    run_rewrite(
        &run,
        &|text, config| {
            renumber_text(text, config, options.renumber).map_err(|error| error.to_string())
        },
        stdout,
        stderr,
    )
}
