//! Parsing the command line into a [`Command`], without touching the filesystem.

use lexopt::prelude::*;
use std::ffi::OsString;
use std::fmt;
use std::path::PathBuf;

/// What the user asked for.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Command {
    /// No command at all: what an editor runs to start the language server.
    LanguageServer,
    Help,
    Version,
    Check(CheckOptions),
    Preview(PreviewOptions),
    Fmt(FmtOptions),
    Renumber(RenumberCliOptions),
}

/// The options of `fmt`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct FmtOptions {
    /// Report the files that would change (exit 1) instead of writing them.
    pub check: bool,
    pub config_path: Option<PathBuf>,
    pub paths: Vec<PathBuf>,
}

/// The options of `renumber`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct RenumberCliOptions {
    pub renumber: crate::ide::renumber::RenumberOptions,
    pub check: bool,
    pub config_path: Option<PathBuf>,
    pub paths: Vec<PathBuf>,
}

/// The options of `preview`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct PreviewOptions {
    pub format: PreviewFormat,
    /// Above this many segments the SVG picture thins runs of moves out.
    pub max_segments: usize,
    pub config_path: Option<PathBuf>,
    /// Folders of cycles and subprograms searched after the program's own folders, in this order.
    pub cycles: Vec<PathBuf>,
    pub path: PathBuf,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum PreviewFormat {
    Json,
    Csv,
    Svg,
}

/// The options of `check`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct CheckOptions {
    pub format: OutputFormat,
    /// One configuration file for every program, instead of the nearest `sinumerik.toml`.
    pub config_path: Option<PathBuf>,
    /// Extensions (lower case, without dot) that replace the configured ones when walking folders.
    pub extensions: Option<Vec<String>>,
    /// Folders of cycles and subprograms searched after the program's own folders, in this order.
    pub cycles: Vec<PathBuf>,
    pub paths: Vec<PathBuf>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum OutputFormat {
    Human,
    Json,
    /// SARIF 2.1.0 (code scanning).
    Sarif,
    /// GitHub Actions workflow commands (annotations).
    Github,
    /// GitLab's Code Quality report.
    Gitlab,
}

/// A command line that cannot be run, with the reason.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct UsageError(pub String);

impl fmt::Display for UsageError {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        formatter.write_str(&self.0)
    }
}

impl From<lexopt::Error> for UsageError {
    fn from(error: lexopt::Error) -> UsageError {
        UsageError(error.to_string())
    }
}

/// Parses the arguments; the first one is the program name, as in `std::env::args_os()`.
pub(crate) fn parse_args(args: impl IntoIterator<Item = OsString>) -> Result<Command, UsageError> {
    let mut parser = lexopt::Parser::from_iter(args);
    let Some(first) = parser.next()? else {
        return Ok(Command::LanguageServer);
    };
    match first {
        Short('h') | Long("help") => Ok(Command::Help),
        Short('V') | Long("version") => Ok(Command::Version),
        // Clients of vscode-languageclient pass `--stdio` when they talk over stdio.
        Long("stdio") => parse_serve(&mut parser),
        Value(command) if command == "serve" => parse_serve(&mut parser),
        Value(command) if command == "check" => parse_check(&mut parser),
        Value(command) if command == "preview" => parse_preview(&mut parser),
        Value(command) if command == "fmt" => parse_fmt(&mut parser),
        Value(command) if command == "renumber" => parse_renumber(&mut parser),
        Value(command) => Err(UsageError(format!(
            "unknown command {:?} (the commands are `serve`, `check`, `preview`, `fmt` and `renumber`)",
            command.to_string_lossy()
        ))),
        other => Err(other.unexpected().into()),
    }
}

fn parse_serve(parser: &mut lexopt::Parser) -> Result<Command, UsageError> {
    while let Some(arg) = parser.next()? {
        match arg {
            Long("stdio") => {}
            Short('h') | Long("help") => return Ok(Command::Help),
            other => return Err(other.unexpected().into()),
        }
    }
    Ok(Command::LanguageServer)
}

fn parse_check(parser: &mut lexopt::Parser) -> Result<Command, UsageError> {
    let mut options = CheckOptions {
        format: OutputFormat::Human,
        config_path: None,
        extensions: None,
        cycles: Vec::new(),
        paths: Vec::new(),
    };
    while let Some(arg) = parser.next()? {
        match arg {
            Short('h') | Long("help") => return Ok(Command::Help),
            Long("format") => {
                let format = parser.value()?;
                options.format = match format.to_str() {
                    Some("human") => OutputFormat::Human,
                    Some("json") => OutputFormat::Json,
                    Some("sarif") => OutputFormat::Sarif,
                    Some("github") => OutputFormat::Github,
                    Some("gitlab") => OutputFormat::Gitlab,
                    _ => {
                        return Err(UsageError(format!(
                            "unknown format {:?} for --format (expected human, json, sarif, github or gitlab)",
                            format.to_string_lossy()
                        )))
                    }
                };
            }
            Long("config") => options.config_path = Some(PathBuf::from(parser.value()?)),
            Long("extensions") => {
                let list = parser.value()?.string()?;
                options.extensions = Some(parse_extension_list(&list)?);
            }
            Long("cycles") => options.cycles.push(PathBuf::from(parser.value()?)),
            Value(path) => options.paths.push(PathBuf::from(path)),
            other => return Err(other.unexpected().into()),
        }
    }
    if options.paths.is_empty() {
        return Err(UsageError(
            "`check` needs at least one file or folder to check".to_string(),
        ));
    }
    Ok(Command::Check(options))
}

fn parse_preview(parser: &mut lexopt::Parser) -> Result<Command, UsageError> {
    let mut format = PreviewFormat::Json;
    let mut max_segments = 20_000;
    let mut config_path = None;
    let mut cycles = Vec::new();
    let mut paths = Vec::new();
    while let Some(arg) = parser.next()? {
        match arg {
            Short('h') | Long("help") => return Ok(Command::Help),
            Long("format") => {
                let value = parser.value()?;
                format = match value.to_str() {
                    Some("json") => PreviewFormat::Json,
                    Some("csv") => PreviewFormat::Csv,
                    Some("svg") => PreviewFormat::Svg,
                    _ => {
                        return Err(UsageError(format!(
                            "unknown format {:?} for --format (expected json, csv or svg)",
                            value.to_string_lossy()
                        )))
                    }
                };
            }
            Long("config") => config_path = Some(PathBuf::from(parser.value()?)),
            Long("cycles") => cycles.push(PathBuf::from(parser.value()?)),
            Long("max-segments") => {
                let value = parser.value()?.string()?;
                max_segments = value
                    .parse()
                    .ok()
                    .filter(|count: &usize| *count > 0)
                    .ok_or_else(|| {
                        UsageError(format!(
                            "--max-segments needs a positive whole number, not {value:?}"
                        ))
                    })?;
            }
            Value(path) => paths.push(PathBuf::from(path)),
            other => return Err(other.unexpected().into()),
        }
    }
    match paths.len() {
        1 => Ok(Command::Preview(PreviewOptions {
            format,
            max_segments,
            config_path,
            cycles,
            path: paths.remove(0),
        })),
        0 => Err(UsageError(
            "`preview` needs the program file to preview".to_string(),
        )),
        _ => Err(UsageError(
            "`preview` takes exactly one program file".to_string(),
        )),
    }
}

fn parse_fmt(parser: &mut lexopt::Parser) -> Result<Command, UsageError> {
    let mut options = FmtOptions {
        check: false,
        config_path: None,
        paths: Vec::new(),
    };
    while let Some(arg) = parser.next()? {
        match arg {
            Short('h') | Long("help") => return Ok(Command::Help),
            Long("check") => options.check = true,
            Long("config") => options.config_path = Some(PathBuf::from(parser.value()?)),
            Value(path) => options.paths.push(PathBuf::from(path)),
            other => return Err(other.unexpected().into()),
        }
    }
    if options.paths.is_empty() {
        return Err(UsageError(
            "`fmt` needs at least one file or folder".to_string(),
        ));
    }
    Ok(Command::Fmt(options))
}

fn parse_renumber(parser: &mut lexopt::Parser) -> Result<Command, UsageError> {
    use crate::ide::renumber::{NumberingMode, RenumberOptions};
    let mut options = RenumberCliOptions {
        renumber: RenumberOptions::default(),
        check: false,
        config_path: None,
        paths: Vec::new(),
    };
    let mut mode_flags = 0;
    while let Some(arg) = parser.next()? {
        match arg {
            Short('h') | Long("help") => return Ok(Command::Help),
            Long("check") => options.check = true,
            Long("config") => options.config_path = Some(PathBuf::from(parser.value()?)),
            Long(flag @ ("start" | "step")) => {
                let flag = flag.to_string();
                let value = parser.value()?.string()?;
                let number: u64 = value
                    .parse()
                    .ok()
                    .filter(|number| flag == "start" || *number > 0)
                    .ok_or_else(|| {
                        UsageError(format!(
                            "--{flag} needs a {} whole number, not {value:?}",
                            if flag == "start" {
                                "non-negative"
                            } else {
                                "positive"
                            }
                        ))
                    })?;
                if flag == "start" {
                    options.renumber.start = number;
                } else {
                    options.renumber.step = number;
                }
            }
            Long(flag @ ("keep" | "all" | "drop")) => {
                mode_flags += 1;
                options.renumber.mode = match flag {
                    "keep" => NumberingMode::Keep,
                    "all" => NumberingMode::All,
                    _ => NumberingMode::Drop,
                };
            }
            Value(path) => options.paths.push(PathBuf::from(path)),
            other => return Err(other.unexpected().into()),
        }
    }
    if mode_flags > 1 {
        return Err(UsageError(
            "choose one of --keep, --all and --drop".to_string(),
        ));
    }
    if options.paths.is_empty() {
        return Err(UsageError(
            "`renumber` needs at least one file or folder".to_string(),
        ));
    }
    Ok(Command::Renumber(options))
}

/// Reads `mpf,spf` (a leading dot is tolerated, `.mpf`, because that is how people often write
/// extensions on a command line).
fn parse_extension_list(list: &str) -> Result<Vec<String>, UsageError> {
    let mut extensions = Vec::new();
    for item in list.split(',') {
        let item = item.trim();
        let extension = item.strip_prefix('.').unwrap_or(item);
        if extension.is_empty() || extension.contains(['.', '/', '\\']) {
            return Err(UsageError(format!(
                "{item:?} in --extensions is not a file extension (expected a list like mpf,spf)"
            )));
        }
        extensions.push(extension.to_ascii_lowercase());
    }
    Ok(extensions)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(args: &[&str]) -> Result<Command, UsageError> {
        parse_args(
            std::iter::once("sinumerik-lsp")
                .chain(args.iter().copied())
                .map(OsString::from),
        )
    }

    fn check_options(args: &[&str]) -> CheckOptions {
        match parse(args) {
            Ok(Command::Check(options)) => options,
            other => panic!("expected check options for {args:?}, got {other:?}"),
        }
    }

    #[test]
    fn top_level_commands() {
        assert_eq!(parse(&[]), Ok(Command::LanguageServer));
        assert_eq!(parse(&["--help"]), Ok(Command::Help));
        assert_eq!(parse(&["-h"]), Ok(Command::Help));
        assert_eq!(parse(&["--version"]), Ok(Command::Version));
        assert_eq!(parse(&["check", "--help"]), Ok(Command::Help));
        assert!(parse(&["lint", "a.mpf"])
            .unwrap_err()
            .0
            .contains("unknown command"));
        assert!(parse(&["--frobnicate"])
            .unwrap_err()
            .0
            .contains("--frobnicate"));
    }

    #[test]
    fn check_options_are_read() {
        let options = check_options(&["check", "a.mpf", "dir"]);
        assert_eq!(options.format, OutputFormat::Human);
        assert_eq!(
            options.paths,
            vec![PathBuf::from("a.mpf"), PathBuf::from("dir")]
        );
        assert_eq!(options.config_path, None);
        assert_eq!(options.extensions, None);
        assert!(options.cycles.is_empty());

        let options = check_options(&[
            "check",
            "--format=json",
            "--config",
            "m.toml",
            "--extensions",
            "MPF, .spf,nc",
            "--",
            "-odd-name.mpf",
        ]);
        assert_eq!(options.format, OutputFormat::Json);
        assert_eq!(options.config_path, Some(PathBuf::from("m.toml")));
        assert_eq!(
            options.extensions,
            Some(vec!["mpf".to_string(), "spf".to_string(), "nc".to_string()])
        );
        assert_eq!(options.paths, vec![PathBuf::from("-odd-name.mpf")]);
    }

    #[test]
    fn cycle_folders_are_kept_in_the_order_given() {
        let options = check_options(&[
            "check",
            "--cycles",
            "cst",
            "a.mpf",
            "--cycles=cma",
            "--cycles",
            "cst",
        ]);
        assert_eq!(
            options.cycles,
            vec![
                PathBuf::from("cst"),
                PathBuf::from("cma"),
                PathBuf::from("cst")
            ]
        );
        assert_eq!(options.paths, vec![PathBuf::from("a.mpf")]);
        match parse(&["preview", "--cycles", "cus", "a.mpf", "--cycles", "cma"]) {
            Ok(Command::Preview(options)) => {
                assert_eq!(
                    options.cycles,
                    vec![PathBuf::from("cus"), PathBuf::from("cma")]
                );
                assert_eq!(options.path, PathBuf::from("a.mpf"));
            }
            other => panic!("{other:?}"),
        }
        assert!(parse(&["check", "a.mpf", "--cycles"])
            .unwrap_err()
            .0
            .contains("--cycles"));
    }

    #[test]
    fn fmt_and_renumber_options_are_read() {
        use crate::ide::renumber::NumberingMode;
        assert_eq!(
            parse(&["fmt", "--check", "a.mpf"]),
            Ok(Command::Fmt(FmtOptions {
                check: true,
                config_path: None,
                paths: vec![PathBuf::from("a.mpf")]
            }))
        );
        match parse(&["renumber", "--start", "100", "--step", "5", "--drop", "d"]) {
            Ok(Command::Renumber(options)) => {
                assert_eq!((options.renumber.start, options.renumber.step), (100, 5));
                assert_eq!(options.renumber.mode, NumberingMode::Drop);
                assert!(!options.check);
            }
            other => panic!("{other:?}"),
        }
        assert!(parse(&["renumber", "--step", "0", "a"])
            .unwrap_err()
            .0
            .contains("positive"));
        assert!(parse(&["renumber", "--keep", "--drop", "a"])
            .unwrap_err()
            .0
            .contains("one of"));
        assert!(parse(&["fmt"]).is_err());
    }

    #[test]
    fn check_usage_errors() {
        assert!(parse(&["check"]).unwrap_err().0.contains("at least one"));
        for (name, format) in [
            ("sarif", OutputFormat::Sarif),
            ("github", OutputFormat::Github),
            ("gitlab", OutputFormat::Gitlab),
        ] {
            assert_eq!(
                check_options(&["check", "--format", name, "a"]).format,
                format
            );
        }
        assert!(parse(&["check", "--format", "xml", "a"])
            .unwrap_err()
            .0
            .contains("xml"));
        assert!(parse(&["check", "a", "--format"])
            .unwrap_err()
            .0
            .contains("--format"));
        assert!(parse(&["check", "--extensions", "mpf,,spf", "a"]).is_err());
        assert!(parse(&["check", "--colour", "a"])
            .unwrap_err()
            .0
            .contains("--colour"));
    }
}
