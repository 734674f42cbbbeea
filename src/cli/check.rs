//! The `check` command: collects the program files, finds the configuration of each, runs the checker
//! and prints what it reports.

use super::args::CheckOptions;
use super::check_index::CheckIndexes;
use super::exit_codes::{EXIT_ERRORS_FOUND, EXIT_OK, EXIT_TROUBLE};
use super::formats::{self, FileFindings, RunSummary};
use super::library::{FolderLibrary, ProgramFiles};
use super::report::{ProgramLines, SeverityCounts};
use crate::config::{discover_config_file, load_config_file, MachineConfig};
use crate::io::source_file::read_source_file;
use std::collections::HashMap;
use std::fmt::Display;
use std::fs;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::sync::Arc;

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

    let Some(mut configs) = run_configs(
        options.config_path.as_deref(),
        options.extensions.clone(),
        &mut problems,
    ) else {
        return Ok(EXIT_TROUBLE);
    };
    // Like a configuration given explicitly, the cycle folders apply to every program: without
    // them no program would be checked as asked.
    let program_files = match ProgramFiles::new(&options.cycles) {
        Ok(program_files) => program_files,
        Err(message) => {
            problems.report(message);
            return Ok(EXIT_TROUBLE);
        }
    };

    let files = collect_program_files(&options.paths, &mut configs, &mut problems);
    let mut indexes = CheckIndexes::default();

    let mut counts = SeverityCounts::default();
    let mut n_checked_files = 0;
    let working_dir = std::env::current_dir().ok();
    let mut output = formats::output_for(options.format, working_dir.as_deref());
    output.begin(stdout)?;
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
        // The programs this one calls are found through its library, which lists folders and reads
        // files only when asked.
        let library = Arc::new(FolderLibrary::new(
            &program_files,
            path,
            configs.config_dir_for(folder).as_deref(),
        ));

        // The checker returns the diagnostics sorted by line and column, the order people read in:
        // those of reading the program block by block, and those of running it.
        let kind = crate::analysis::ProgramKind::from_file_name(&path.to_string_lossy());
        // Macros of the library's definition files read as the run reads them.
        let macros = crate::analysis::execution::library_macros::LibraryMacros::read(
            library.as_ref(),
            &config,
        );
        let mut line_diagnostics = if macros.definitions.is_empty() {
            crate::analysis::diagnose_program(&source.text, &config, kind)
        } else {
            crate::analysis::diagnose_program_with_macros(&source.text, &config, kind, &macros)
        };
        let run_findings = crate::analysis::execution::execution_findings(
            &source.text,
            &config,
            kind,
            library.as_ref(),
            &config.execution,
        );
        // The findings that need the symbol tables of the program and of the files it can call
        // (W301-W307), as the server publishes them.
        let cross_file = indexes.findings(&library, path, &source.text, &config, |other| {
            configs
                .for_folder(other, &mut problems)
                .unwrap_or_else(|| Rc::new(MachineConfig::default()))
        });
        if !run_findings.is_empty() || !cross_file.is_empty() {
            line_diagnostics.extend(run_findings);
            line_diagnostics.extend(cross_file);
            line_diagnostics.sort_by_key(|item| (item.line, item.diagnostic.span.start()));
        }
        let lines = ProgramLines::new(&source.text);
        for line_diagnostic in &line_diagnostics {
            counts.add(line_diagnostic.diagnostic.severity);
        }
        output.file(
            stdout,
            &FileFindings {
                path_text: &path.display().to_string(),
                lines: &lines,
                diagnostics: &line_diagnostics,
            },
        )?;
    }
    output.end(
        stdout,
        &RunSummary {
            n_checked_files,
            counts,
            complete: !problems.any_problem,
        },
    )?;

    Ok(if problems.any_problem {
        EXIT_TROUBLE
    } else if counts.errors > 0 {
        EXIT_ERRORS_FOUND
    } else {
        EXIT_OK
    })
}

/// The configurations of a run: the file given with `--config` for every program, else each
/// folder's own. `None` when the given file cannot be used (it is reported): a configuration given
/// explicitly applies to every file, so nothing can be processed.
pub(super) fn run_configs(
    config_path: Option<&Path>,
    extensions: Option<Vec<String>>,
    problems: &mut ProblemReporter<'_>,
) -> Option<ConfigCache> {
    let fixed_config = match config_path {
        None => None,
        Some(config_path) => match load_config_file(config_path) {
            Ok(config) => Some(config),
            Err(config_error) => {
                problems.report(config_error);
                return None;
            }
        },
    };
    Some(ConfigCache::new(
        fixed_config.map(|config| (config_path.unwrap_or(Path::new("")), config)),
        extensions,
    ))
}

/// The files named on the command line and the program files below the folders named there, in
/// order; paths that cannot be read and folders without program files are reported.
pub(super) fn collect_program_files(
    paths: &[PathBuf],
    configs: &mut ConfigCache,
    problems: &mut ProblemReporter<'_>,
) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for path in paths {
        let metadata = match fs::metadata(path) {
            Ok(metadata) => metadata,
            Err(io_error) => {
                problems.report(format_args!("{}: {io_error}", path.display()));
                continue;
            }
        };
        if metadata.is_dir() {
            let n_files_before = files.len();
            walk_folder(path, configs, problems, &mut files);
            if files.len() == n_files_before {
                if let Some(config) = configs.for_folder(path, problems) {
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
    files
}

/// Collects the files below `folder` whose extension the folder's configuration accepts, in sorted
/// order so that the output is the same on every run and every filesystem.
pub(super) fn walk_folder(
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
pub(super) struct ConfigCache {
    fixed: Option<Rc<MachineConfig>>,
    /// The folder of the file given with `--config`.
    fixed_dir: Option<PathBuf>,
    extensions_override: Option<Vec<String>>,
    default: Rc<MachineConfig>,
    config_file_by_folder: HashMap<PathBuf, Option<PathBuf>>,
    /// `None` for a file that could not be used; its error has been reported.
    config_by_file: HashMap<PathBuf, Option<Rc<MachineConfig>>>,
}

impl ConfigCache {
    /// `fixed`: the file given with `--config` and its configuration.
    fn new(
        fixed: Option<(&Path, MachineConfig)>,
        extensions_override: Option<Vec<String>>,
    ) -> ConfigCache {
        let fixed_dir = fixed
            .as_ref()
            .map(|(path, _)| path.parent().unwrap_or(Path::new("")).to_path_buf());
        ConfigCache {
            fixed: fixed.map(|(_, config)| Rc::new(with_extensions(config, &extensions_override))),
            fixed_dir,
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
    pub(super) fn for_folder(
        &mut self,
        folder: &Path,
        problems: &mut ProblemReporter<'_>,
    ) -> Option<Rc<MachineConfig>> {
        if let Some(fixed) = &self.fixed {
            return Some(Rc::clone(fixed));
        }
        let Some(config_file) = self.config_file_for(folder) else {
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

    /// The folder of the configuration file the programs in `folder` use (the one given with
    /// `--config`, or the nearest `sinumerik.toml`), or `None` when they use the defaults. The search
    /// for called programs goes up to this folder.
    pub(super) fn config_dir_for(&mut self, folder: &Path) -> Option<PathBuf> {
        if self.fixed.is_some() {
            return self.fixed_dir.clone();
        }
        let config_file = self.config_file_for(folder)?;
        config_file.parent().map(Path::to_path_buf)
    }

    /// The nearest `sinumerik.toml` of `folder`, searched once per folder.
    fn config_file_for(&mut self, folder: &Path) -> Option<PathBuf> {
        self.config_file_by_folder
            .entry(folder.to_path_buf())
            .or_insert_with(|| discover_config_file(folder))
            .clone()
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
pub(super) struct ProblemReporter<'a> {
    pub(super) stderr: &'a mut dyn Write,
    pub(super) any_problem: bool,
}

impl ProblemReporter<'_> {
    pub(super) fn report(&mut self, message: impl Display) {
        self.any_problem = true;
        // If stderr itself cannot be written there is nobody left to tell; the exit code still says it.
        let _ = writeln!(self.stderr, "error: {message}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_configuration_s_folder_is_the_nearest_sinumerik_toml_s_or_that_of_config() {
        let root =
            std::env::temp_dir().join(format!("sinumerik-lsp-config-dir-{}", std::process::id()));
        let _ = fs::remove_dir_all(&root);
        fs::create_dir_all(root.join("a/b")).unwrap();
        fs::write(root.join("sinumerik.toml"), "").unwrap();
        fs::write(root.join("a/other.toml"), "").unwrap();
        let mut stderr = Vec::new();
        let mut problems = ProblemReporter {
            stderr: &mut stderr,
            any_problem: false,
        };

        let mut configs = run_configs(None, None, &mut problems).unwrap();
        let nearest = configs.config_dir_for(&root.join("a/b"));
        let given = root.join("a/other.toml");
        let mut fixed = run_configs(Some(&given), None, &mut problems).unwrap();
        let fixed_dir = fixed.config_dir_for(&root.join("a/b"));
        fs::remove_dir_all(&root).unwrap();

        assert_eq!(nearest.as_deref(), Some(root.as_path()));
        assert_eq!(fixed_dir, Some(root.join("a")));
        assert!(!problems.any_problem);
    }
}
