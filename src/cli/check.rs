//! The `check` command: collects the program files, finds the configuration of each, runs the checker
//! and prints what it reports.

use super::args::{CheckOptions, OutputFormat};
use super::report::{self, JsonDiagnostic, ProgramLines, SeverityCounts};
use super::source_file::read_source_file;
use super::{EXIT_ERRORS_FOUND, EXIT_OK, EXIT_TROUBLE};
use crate::config::{discover_config_file, load_config_file, MachineConfig};
use std::collections::HashMap;
use std::fmt::Display;
use std::fs;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// The most findings the human format prints for one file; the summary still counts all of them.
pub(crate) const MAX_HUMAN_FINDINGS_PER_FILE: usize = 1_000;

/// Runs `check` and returns the exit code. Problems with inputs (unreadable paths, bad configuration
/// files) go to `stderr` and do not stop the run, so one bad file does not hide the findings in the
/// others; the `Err` case is only a failure to write the output itself.
pub(crate) fn run_check(
    options: &CheckOptions,
    stdout: &mut dyn Write,
    stderr: &mut dyn Write,
) -> io::Result<u8> {
    let mut problems = ProblemReporter {
        stderr,
        any_problem: false,
    };

    let fixed_config = match &options.config_path {
        None => None,
        Some(config_path) => match load_config_file(config_path) {
            Ok(config) => Some(config),
            Err(config_error) => {
                // A configuration given explicitly applies to every file, so nothing can be checked.
                problems.report(config_error);
                return Ok(EXIT_TROUBLE);
            }
        },
    };
    let mut configs = ConfigCache::new(fixed_config, options.extensions.clone());

    let mut files = Vec::new();
    for path in &options.paths {
        let metadata = match fs::metadata(path) {
            Ok(metadata) => metadata,
            Err(io_error) => {
                problems.report(format_args!("{}: {io_error}", path.display()));
                continue;
            }
        };
        if metadata.is_dir() {
            let n_files_before = files.len();
            walk_folder(path, &mut configs, &mut problems, &mut files);
            if files.len() == n_files_before {
                if let Some(config) = configs.for_folder(path, &mut problems) {
                    problems.report(format_args!(
                        "{}: no program files found in this folder (looking for the extensions {})",
                        path.display(),
                        config.extensions.join(", ")
                    ));
                }
            }
        } else {
            // A file named on the command line is checked whatever its extension: the user chose it.
            files.push(path.clone());
        }
    }

    let mut counts = SeverityCounts::default();
    let mut n_checked_files = 0;
    let mut n_json_diagnostics = 0;
    if options.format == OutputFormat::Json {
        write!(stdout, "[")?;
    }
    for path in &files {
        let folder = path.parent().unwrap_or(Path::new(""));
        let Some(config) = configs.for_folder(folder, &mut problems) else {
            continue;
        };
        let source = match read_source_file(path) {
            Ok(source) => source,
            Err(io_error) => {
                problems.report(format_args!("{}: {io_error}", path.display()));
                continue;
            }
        };
        n_checked_files += 1;

        // The checker returns the diagnostics sorted by line and column, the order people read in.
        let kind = crate::analysis::ProgramKind::from_extension(
            path.extension().and_then(|extension| extension.to_str()),
        );
        let line_diagnostics = crate::analysis::diagnose_program(&source.text, &config, kind);
        let lines = ProgramLines::new(&source.text);
        let path_text = path.display().to_string();
        for (index, line_diagnostic) in line_diagnostics.iter().enumerate() {
            counts.add(line_diagnostic.diagnostic.severity);
            match options.format {
                // A file of junk (a binary, an archive) can give a million findings: a person reads
                // the first ones, so the rest are counted in the summary but not printed.
                OutputFormat::Human if index >= MAX_HUMAN_FINDINGS_PER_FILE => {}
                OutputFormat::Human => {
                    report::write_human(stdout, &path_text, &lines, line_diagnostic)?
                }
                OutputFormat::Json => {
                    // One object per line inside the array: valid JSON that is still easy to grep.
                    let separator = if n_json_diagnostics == 0 { "\n" } else { ",\n" };
                    write!(stdout, "{separator}")?;
                    serde_json::to_writer(
                        &mut *stdout,
                        &JsonDiagnostic::new(&path_text, &lines, line_diagnostic),
                    )?;
                    n_json_diagnostics += 1;
                }
            }
        }
        if options.format == OutputFormat::Human
            && line_diagnostics.len() > MAX_HUMAN_FINDINGS_PER_FILE
        {
            writeln!(
                stdout,
                "{path_text}: {} more findings not shown (the first {MAX_HUMAN_FINDINGS_PER_FILE} of each file are; --format json lists all)",
                line_diagnostics.len() - MAX_HUMAN_FINDINGS_PER_FILE
            )?;
        }
    }
    match options.format {
        OutputFormat::Human => {
            writeln!(stdout, "{}", report::summary_line(n_checked_files, counts))?
        }
        OutputFormat::Json if n_json_diagnostics == 0 => writeln!(stdout, "]")?,
        OutputFormat::Json => writeln!(stdout, "\n]")?,
    }

    Ok(if problems.any_problem {
        EXIT_TROUBLE
    } else if counts.errors > 0 {
        EXIT_ERRORS_FOUND
    } else {
        EXIT_OK
    })
}

/// Collects the files below `folder` whose extension the folder's configuration accepts, in sorted
/// order so that the output is the same on every run and every filesystem.
fn walk_folder(
    folder: &Path,
    configs: &mut ConfigCache,
    problems: &mut ProblemReporter<'_>,
    files: &mut Vec<PathBuf>,
) {
    let entries = match fs::read_dir(folder) {
        Ok(entries) => entries,
        Err(io_error) => {
            problems.report(format_args!(
                "{}: cannot read the folder: {io_error}",
                folder.display()
            ));
            return;
        }
    };
    let mut entries: Vec<fs::DirEntry> = entries
        .filter_map(|entry| match entry {
            Ok(entry) => Some(entry),
            Err(io_error) => {
                problems.report(format_args!(
                    "{}: cannot read the folder: {io_error}",
                    folder.display()
                ));
                None
            }
        })
        .collect();
    entries.sort_by_key(|entry| entry.file_name());

    for entry in entries {
        let path = entry.path();
        // `DirEntry::file_type` does not follow symbolic links, so a linked folder is seen as a
        // link and not walked: links can form cycles and lead far outside the folder the user named.
        let Ok(file_type) = entry.file_type() else {
            continue;
        };
        let is_file = if file_type.is_dir() {
            walk_folder(&path, configs, problems, files);
            continue;
        } else if file_type.is_symlink() {
            fs::metadata(&path).is_ok_and(|metadata| metadata.is_file())
        } else {
            file_type.is_file()
        };
        if !is_file {
            continue;
        }
        let Some(extension) = path.extension().and_then(|extension| extension.to_str()) else {
            continue;
        };
        // A broken configuration file has already been reported; the files it governs are skipped.
        let Some(config) = configs.for_folder(folder, problems) else {
            continue;
        };
        if config.accepts_extension(extension) {
            files.push(path);
        }
    }
}

/// The configuration of each folder: the one given with `--config`, or the nearest `sinumerik.toml`,
/// or the defaults. Both the search and the parsing are cached, and a broken file is reported once.
struct ConfigCache {
    fixed: Option<Rc<MachineConfig>>,
    extensions_override: Option<Vec<String>>,
    default: Rc<MachineConfig>,
    config_file_by_folder: HashMap<PathBuf, Option<PathBuf>>,
    /// `None` for a file that could not be used; its error has been reported.
    config_by_file: HashMap<PathBuf, Option<Rc<MachineConfig>>>,
}

impl ConfigCache {
    fn new(fixed: Option<MachineConfig>, extensions_override: Option<Vec<String>>) -> ConfigCache {
        ConfigCache {
            fixed: fixed.map(|config| Rc::new(with_extensions(config, &extensions_override))),
            default: Rc::new(with_extensions(
                MachineConfig::default(),
                &extensions_override,
            )),
            extensions_override,
            config_file_by_folder: HashMap::new(),
            config_by_file: HashMap::new(),
        }
    }

    /// The configuration for programs in `folder`, or `None` when its configuration file is broken.
    fn for_folder(
        &mut self,
        folder: &Path,
        problems: &mut ProblemReporter<'_>,
    ) -> Option<Rc<MachineConfig>> {
        if let Some(fixed) = &self.fixed {
            return Some(Rc::clone(fixed));
        }
        let config_file = self
            .config_file_by_folder
            .entry(folder.to_path_buf())
            .or_insert_with(|| discover_config_file(folder))
            .clone();
        let Some(config_file) = config_file else {
            return Some(Rc::clone(&self.default));
        };
        if let Some(cached) = self.config_by_file.get(&config_file) {
            return cached.clone();
        }
        let loaded = match load_config_file(&config_file) {
            Ok(config) => Some(Rc::new(with_extensions(config, &self.extensions_override))),
            Err(config_error) => {
                problems.report(config_error);
                None
            }
        };
        self.config_by_file.insert(config_file, loaded.clone());
        loaded
    }
}

/// `--extensions` wins over the extensions of every configuration file.
fn with_extensions(
    mut config: MachineConfig,
    extensions_override: &Option<Vec<String>>,
) -> MachineConfig {
    if let Some(extensions) = extensions_override {
        config.extensions = extensions.clone();
    }
    config
}

/// Reports problems with the inputs on stderr and remembers that there was one, for the exit code.
struct ProblemReporter<'a> {
    stderr: &'a mut dyn Write,
    any_problem: bool,
}

impl ProblemReporter<'_> {
    fn report(&mut self, message: impl Display) {
        self.any_problem = true;
        // If stderr itself cannot be written there is nobody left to tell; the exit code still says it.
        let _ = writeln!(self.stderr, "error: {message}");
    }
}
