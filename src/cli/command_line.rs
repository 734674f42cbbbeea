//! The command line's entry: the usage text, the dispatch to each command, the exit code when the
//! output cannot be written.

use super::args::{parse_args, Command};
use super::exit_codes::{EXIT_OK, EXIT_TROUBLE};
use super::{check, fmt, preview, renumber};
use std::ffi::OsString;
use std::io::{self, Write};

const USAGE: &str = "\
Usage:
  sinumerik-lsp [serve]                  the language server on stdin and stdout
  sinumerik-lsp check [OPTIONS] PATH...  check programs (folders recursively)
  sinumerik-lsp preview [--format json|csv|svg] [--max-segments N] [--config FILE]
                        [--cycles DIR]... FILE
                                         the resolved end point of every move
  sinumerik-lsp fmt [--check] [--config FILE] PATH...
                                         normalise spacing and letter case in place
  sinumerik-lsp renumber [--start N] [--step N] [--keep|--all|--drop] [--check]
                         [--config FILE] PATH...
                                         renumber blocks in place (default 10, 10, --keep)
  sinumerik-lsp --help                   show this help
  sinumerik-lsp --version                show the version

Options of check:
  --format FORMAT       output format: human (default), json, sarif (SARIF 2.1.0),
                        github (workflow commands that annotate a pull request),
                        gitlab (Code Quality report)
  --config FILE         use this configuration for every program
  --extensions LIST     extensions read from folders (default: mpf,spf)
  --cycles DIR          a folder of cycles and subprograms (with its subfolders)
                        where called programs are looked for; repeatable, searched
                        in the order given (also for preview)

Without --config, each program uses the sinumerik.toml in its folder or the
nearest folder above it, else the defaults of a metric milling machine.
A called program is looked for in the caller's folder, then in the folders
above it up to the one of its sinumerik.toml, then in the --cycles folders.

Exit codes: 0 no errors found, 1 errors found, 2 usage, file or configuration
problem. fmt and renumber: 0 done (or nothing to change), 1 with --check when a
file would change, 2 a file that could not be read, rewritten or written.
";

/// Whether the arguments (the first is the program name) ask for the language server, which
/// `main.rs` starts instead of the command line: the server owns stdin and stdout, so it must start
/// before anything locks them.
pub fn wants_language_server(args: &[OsString]) -> bool {
    matches!(parse_args(args.to_vec()), Ok(Command::LanguageServer))
}

/// Runs a command with the process's arguments (the first is the program name) on the real stdout
/// and stderr, and returns the exit code.
pub fn run(args: impl IntoIterator<Item = OsString>) -> u8 {
    let stdout = io::stdout();
    let mut stdout = io::BufWriter::new(stdout.lock());
    let stderr = io::stderr();
    let mut stderr = stderr.lock();
    run_with_output(args, &mut stdout, &mut stderr)
}

/// [`run`] with the output streams passed in, so that tests can capture them.
pub fn run_with_output(
    args: impl IntoIterator<Item = OsString>,
    stdout: &mut dyn Write,
    stderr: &mut dyn Write,
) -> u8 {
    let command = match parse_args(args) {
        Ok(command) => command,
        Err(usage_error) => {
            let _ = writeln!(
                stderr,
                "error: {usage_error}\nRun `sinumerik-lsp --help` for usage."
            );
            return EXIT_TROUBLE;
        }
    };
    let result = match command {
        Command::LanguageServer => {
            // `main.rs` starts the server on the process's stdio before this; with other streams (tests)
            // there is nothing to serve on.
            let _ = write!(
                stderr,
                "sinumerik-lsp: the language server needs stdin and stdout.\n\n{USAGE}"
            );
            return EXIT_TROUBLE;
        }
        Command::Help => write!(stdout, "{}\n\n{USAGE}", version_line()).map(|()| EXIT_OK),
        Command::Version => writeln!(stdout, "{}", version_line()).map(|()| EXIT_OK),
        Command::Check(options) => check::run_check(&options, stdout, stderr),
        Command::Preview(options) => preview::run_preview(&options, stdout, stderr),
        Command::Fmt(options) => fmt::run_fmt(&options, stdout, stderr),
        Command::Renumber(options) => renumber::run_renumber(&options, stdout, stderr),
    };
    match result.and_then(|exit_code| stdout.flush().map(|()| exit_code)) {
        Ok(exit_code) => exit_code,
        // A closed pipe (`check ... | head`) means the reader has seen enough; that is not worth a message.
        Err(io_error) if io_error.kind() == io::ErrorKind::BrokenPipe => EXIT_TROUBLE,
        Err(io_error) => {
            let _ = writeln!(stderr, "error: cannot write the output: {io_error}");
            EXIT_TROUBLE
        }
    }
}

fn version_line() -> String {
    format!("sinumerik-lsp {}", env!("CARGO_PKG_VERSION"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run_captured(args: &[&str]) -> (u8, String, String) {
        let mut stdout = Vec::new();
        let mut stderr = Vec::new();
        let args = std::iter::once("sinumerik-lsp")
            .chain(args.iter().copied())
            .map(OsString::from);
        let exit_code = run_with_output(args, &mut stdout, &mut stderr);
        (
            exit_code,
            String::from_utf8(stdout).unwrap(),
            String::from_utf8(stderr).unwrap(),
        )
    }

    #[test]
    fn no_command_prints_usage_on_stderr() {
        let (exit_code, stdout, stderr) = run_captured(&[]);
        assert_eq!(exit_code, EXIT_TROUBLE);
        assert_eq!(stdout, "");
        assert!(stderr.contains("Usage:"), "{stderr}");
    }

    #[test]
    fn help_and_version_go_to_stdout() {
        let (exit_code, stdout, _) = run_captured(&["--help"]);
        assert_eq!(exit_code, EXIT_OK);
        assert!(stdout.contains("--extensions"), "{stdout}");
        assert!(stdout.contains("--cycles DIR"), "{stdout}");
        let (exit_code, stdout, _) = run_captured(&["--version"]);
        assert_eq!(exit_code, EXIT_OK);
        assert_eq!(
            stdout,
            format!("sinumerik-lsp {}\n", env!("CARGO_PKG_VERSION"))
        );
    }

    #[test]
    fn usage_errors_exit_2() {
        let (exit_code, stdout, stderr) = run_captured(&["check", "--bogus", "x"]);
        assert_eq!(exit_code, EXIT_TROUBLE);
        assert_eq!(stdout, "");
        assert!(stderr.contains("--bogus"), "{stderr}");
    }

    #[test]
    fn a_failing_writer_does_not_panic() {
        struct BrokenPipe;
        impl Write for BrokenPipe {
            fn write(&mut self, _: &[u8]) -> io::Result<usize> {
                Err(io::ErrorKind::BrokenPipe.into())
            }
            fn flush(&mut self) -> io::Result<()> {
                Err(io::ErrorKind::BrokenPipe.into())
            }
        }
        let mut stderr = Vec::new();
        let args = ["sinumerik-lsp", "--version"].map(OsString::from);
        assert_eq!(
            run_with_output(args, &mut BrokenPipe, &mut stderr),
            EXIT_TROUBLE
        );
        assert!(stderr.is_empty());
    }
}
