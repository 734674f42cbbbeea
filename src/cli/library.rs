//! The programs a program on disk can call, found as the control finds them: in the program's own
//! folder, then in each parent folder up to the folder of the `sinumerik.toml` in use, then in each
//! `--cycles` folder (with its subfolders) in the order given. A call `PART2` runs `PART2.SPF`,
//! `PART2.MPF`, `_N_PART2_SPF` or `_N_PART2_MPF` (any letter case; the control's names also with an
//! extension after them, as archives carry them), subprograms before main programs.
//!
//! [`ProgramFiles`] holds what a whole run reads: each folder is listed once and each file read once,
//! whichever program asks, and from several threads at a time. [`FolderLibrary`] is one program's view
//! of it (its folders in lookup order) and implements the analysis's [`ProgramLibrary`].

use crate::analysis::library::{LibraryProgram, ProgramLibrary};
use crate::ide::workspace::{call_rank, macro_file_rank, program_name_and_kind, FileKind};
use crate::io::source_file::read_source_file;
use std::collections::{HashMap, HashSet};
use std::fs;
use std::path::{Component, Path, PathBuf};
use std::sync::{Arc, Mutex, MutexGuard, OnceLock};

/// A value computed once, by the first thread that asks; the others wait for it.
type Once<T> = Arc<OnceLock<T>>;

/// Listings by absolute folder and whether they include the subfolders.
type Listings = HashMap<(PathBuf, bool), Once<Arc<Listing>>>;

/// The folders and files of a run, each listed or read at most once.
#[derive(Debug, Default)]
pub struct ProgramFiles {
    /// The `--cycles` folders, as given.
    cycles: Vec<PathBuf>,
    listings: Mutex<Listings>,
    /// Texts by absolute file path; `None` for a file that could not be read.
    texts: Mutex<HashMap<PathBuf, Once<Option<Arc<str>>>>>,
}

/// The program and definition files of one folder (or of a folder and its subfolders), by the paths
/// relative to it.
#[derive(Debug, Default)]
struct Listing {
    /// The file each program name (upper case) resolves to in this folder.
    programs: HashMap<String, PathBuf>,
    /// Files that may define macros, in the order the control reads them.
    definitions: Vec<PathBuf>,
    /// Every program and definition file, in walking order: what `check` indexes for its
    /// cross-file findings.
    files: Vec<PathBuf>,
}

/// A folder searched for called programs.
#[derive(Debug, Clone, PartialEq, Eq)]
struct SearchFolder {
    /// Where it is: absolute, without `.` and `..`, so that one folder is listed once however a
    /// path names it.
    read: PathBuf,
    /// How the paths of its files are shown: as `check` shows the program's path, where that can be
    /// followed upwards.
    shown: PathBuf,
    recursive: bool,
}

impl ProgramFiles {
    /// The files of a run with these `--cycles` folders; an error (naming the folder) when one of them
    /// is not a folder that can be read: a run whose cycles are missing would check programs against
    /// something else than the user asked for.
    pub fn new(cycles: &[PathBuf]) -> Result<Arc<ProgramFiles>, String> {
        for folder in cycles {
            match fs::metadata(folder) {
                Ok(metadata) if metadata.is_dir() => {}
                Ok(_) => {
                    return Err(format!(
                        "{}: given with --cycles, but not a folder",
                        folder.display()
                    ));
                }
                Err(io_error) => {
                    return Err(format!(
                        "{}: the folder given with --cycles cannot be read: {io_error}",
                        folder.display()
                    ));
                }
            }
        }
        Ok(ProgramFiles::unchecked(cycles))
    }

    /// Like [`ProgramFiles::new`] without looking at the folders: a missing one finds nothing.
    pub fn unchecked(cycles: &[PathBuf]) -> Arc<ProgramFiles> {
        Arc::new(ProgramFiles {
            cycles: cycles.to_vec(),
            ..ProgramFiles::default()
        })
    }

    /// The library of the program at `program`, whose configuration file lies in `config_dir`.
    pub fn library_for(
        self: &Arc<Self>,
        program: &Path,
        config_dir: Option<&Path>,
    ) -> Arc<dyn ProgramLibrary> {
        Arc::new(FolderLibrary::new(self, program, config_dir))
    }

    fn listing(&self, folder: &SearchFolder) -> Arc<Listing> {
        let cell = Arc::clone(
            lock(&self.listings)
                .entry((folder.read.clone(), folder.recursive))
                .or_default(),
        );
        // The map's lock is not held while the folder is read, so other folders can be listed meanwhile.
        let listing = cell.get_or_init(|| Arc::new(list_folder(&folder.read, folder.recursive)));
        Arc::clone(listing)
    }

    fn text(&self, path: &Path) -> Option<Arc<str>> {
        let cell = Arc::clone(lock(&self.texts).entry(path.to_path_buf()).or_default());
        cell.get_or_init(|| {
            read_source_file(path)
                .ok()
                .map(|source| Arc::from(source.text))
        })
        .clone()
    }

    /// The text of `path` as the run reads it, without keeping it when no program has asked for it
    /// yet: the index of `check` reads every file of the folders searched once, and a folder of
    /// large programs must not stay in memory.
    pub(crate) fn text_once(&self, path: &Path) -> Option<Arc<str>> {
        let cached = lock(&self.texts)
            .get(path)
            .and_then(|cell| cell.get().cloned());
        match cached {
            Some(text) => text,
            None => read_source_file(path)
                .ok()
                .map(|source| Arc::from(source.text)),
        }
    }
}

/// The library of a program on disk through which the analysis finds the programs it calls.
#[derive(Debug)]
pub struct FolderLibrary {
    files: Arc<ProgramFiles>,
    /// The folders in lookup order.
    folders: Vec<SearchFolder>,
    /// What each name (upper case) found, misses included.
    found: Mutex<HashMap<String, Once<Option<Arc<LibraryProgram>>>>>,
    macro_files: OnceLock<Vec<Arc<LibraryProgram>>>,
}

impl FolderLibrary {
    /// The library of the program at `program` (a path as `check` was given it), whose configuration
    /// file lies in `config_dir`: the parent folders are searched up to that folder when it contains
    /// the program, else (and without a configuration file) only the program's own folder.
    pub fn new(files: &Arc<ProgramFiles>, program: &Path, config_dir: Option<&Path>) -> Self {
        let mut folders = own_and_parent_folders(program, config_dir);
        folders.extend(files.cycles.iter().map(|folder| SearchFolder {
            read: absolute_folder(folder),
            shown: folder.clone(),
            recursive: true,
        }));
        FolderLibrary {
            files: Arc::clone(files),
            folders,
            found: Mutex::default(),
            macro_files: OnceLock::new(),
        }
    }

    /// The folders searched, absolute, with whether their subfolders are: two programs with the
    /// same scope see the same programs, and `check` builds one index for them.
    pub(crate) fn scope(&self) -> Vec<(PathBuf, bool)> {
        self.folders
            .iter()
            .map(|folder| (folder.read.clone(), folder.recursive))
            .collect()
    }

    /// Every program and definition file of the folders searched (absolute paths, each once, in
    /// lookup order).
    pub(crate) fn indexed_files(&self) -> Vec<PathBuf> {
        let mut seen = HashSet::new();
        let mut files = Vec::new();
        for folder in &self.folders {
            let listing = self.files.listing(folder);
            for relative in &listing.files {
                let path = folder.read.join(relative);
                if seen.insert(path.clone()) {
                    files.push(path);
                }
            }
        }
        files
    }

    /// The run's files, shared with every program's library.
    pub(crate) fn program_files(&self) -> &ProgramFiles {
        &self.files
    }

    fn look_up(&self, name: &str) -> Option<Arc<LibraryProgram>> {
        let (folder, relative) = self.folders.iter().find_map(|folder| {
            let listing = self.files.listing(folder);
            let relative = listing.programs.get(name)?.clone();
            Some((folder, relative))
        })?;
        // A file that cannot be read leaves the call unknown: the control would run this file, not one
        // found further on.
        let text = self.files.text(&folder.read.join(&relative))?;
        Some(Arc::new(LibraryProgram {
            name: name.to_string(),
            path: Arc::from(folder.shown.join(&relative).display().to_string()),
            text,
        }))
    }

    fn read_macro_files(&self) -> Vec<Arc<LibraryProgram>> {
        let mut seen = HashSet::new();
        let mut programs = Vec::new();
        for folder in &self.folders {
            let listing = self.files.listing(folder);
            for relative in &listing.definitions {
                let path = folder.read.join(relative);
                if !seen.insert(path.clone()) {
                    continue;
                }
                let Some(text) = self.files.text(&path) else {
                    continue;
                };
                // Definition files of user data (`DEF NCK REAL ...`) are read by the control too, but
                // only files with a `DEFINE ... AS` change how a program reads.
                if crate::syntax::macro_names(&text).next().is_none() {
                    continue;
                }
                let file_name = relative.to_string_lossy();
                programs.push(Arc::new(LibraryProgram {
                    name: program_name_and_kind(&file_name).0,
                    path: Arc::from(folder.shown.join(relative).display().to_string()),
                    text,
                }));
            }
        }
        programs
    }
}

impl ProgramLibrary for FolderLibrary {
    fn find(&self, name: &str) -> Option<Arc<LibraryProgram>> {
        let name = name.to_ascii_uppercase();
        let cell = Arc::clone(lock(&self.found).entry(name.clone()).or_default());
        cell.get_or_init(|| self.look_up(&name)).clone()
    }

    /// The files that define macros, folder by folder in lookup order; in a folder the control's
    /// `_N_SMAC_DEF`, `_N_MMAC_DEF` and `_N_UMAC_DEF` in this order (system, machine manufacturer,
    /// user), then the other definition files by name.
    fn macro_files(&self) -> Vec<Arc<LibraryProgram>> {
        self.macro_files
            .get_or_init(|| self.read_macro_files())
            .clone()
    }
}

/// The library of the program at `program` with the configuration file in `config_dir` and the
/// `--cycles` folders `cycles`, reading for itself. [`ProgramFiles::library_for`] shares the reading
/// among the programs of a run.
pub fn library_for(
    program: &Path,
    config_dir: Option<&Path>,
    cycles: &[PathBuf],
) -> Arc<dyn ProgramLibrary> {
    ProgramFiles::unchecked(cycles).library_for(program, config_dir)
}

/// Locks a mutex, also after a panic elsewhere poisoned it: the maps behind these locks are
/// consistent at every unlock (only whole entries are added).
fn lock<T>(mutex: &Mutex<T>) -> MutexGuard<'_, T> {
    mutex
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// The absolute path of a file as the library names it (see [`absolute_folder`]).
pub(crate) fn absolute_file(path: &Path) -> PathBuf {
    match path.file_name() {
        Some(name) => absolute_folder(path.parent().unwrap_or(Path::new(""))).join(name),
        None => absolute_folder(path),
    }
}

/// `path` made absolute, with `.` and `..` resolved by the names alone (as the control's paths have
/// no links to follow); the empty path, which `Path::parent` gives for a bare file name, is the
/// current folder.
fn absolute_folder(path: &Path) -> PathBuf {
    let path = if path.as_os_str().is_empty() {
        Path::new(".")
    } else {
        path
    };
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let mut normal = PathBuf::new();
    for component in absolute.components() {
        match component {
            Component::CurDir => {}
            Component::ParentDir => {
                normal.pop();
            }
            other => normal.push(other),
        }
    }
    normal
}

/// The program's folder and its parents up to `config_dir`, when that folder contains the program.
/// The parents are shown as parts of the program's path while it has names to take off
/// (`a/b/p.mpf`: `a/b`, `a`, then the current folder as the empty path), and absolute beyond.
fn own_and_parent_folders(program: &Path, config_dir: Option<&Path>) -> Vec<SearchFolder> {
    let own = program.parent().unwrap_or(Path::new(""));
    let read = absolute_folder(own);
    let stop = config_dir
        .map(absolute_folder)
        .filter(|stop| read.starts_with(stop));
    let mut folders = Vec::new();
    let mut shown = Some(own.to_path_buf());
    let mut current = Some(read.as_path());
    while let Some(folder) = current {
        folders.push(SearchFolder {
            read: folder.to_path_buf(),
            shown: shown.clone().unwrap_or_else(|| folder.to_path_buf()),
            recursive: false,
        });
        match &stop {
            Some(stop) if folder != stop => {}
            _ => break,
        }
        shown = shown.and_then(|shown| match shown.components().next_back() {
            Some(Component::Normal(_)) => shown.parent().map(Path::to_path_buf),
            _ => None,
        });
        current = folder.parent();
    }
    folders
}

/// Lists `folder` (and with `recursive` its subfolders, after its own files, in sorted order). A
/// folder that cannot be read lists nothing: its programs stay unknown.
fn list_folder(folder: &Path, recursive: bool) -> Listing {
    let mut best: HashMap<String, (u8, PathBuf)> = HashMap::new();
    let mut definitions = Vec::new();
    let mut files = Vec::new();
    let mut pending = vec![PathBuf::new()];
    while let Some(relative_folder) = pending.pop() {
        let Ok(entries) = fs::read_dir(folder.join(&relative_folder)) else {
            continue;
        };
        let mut entries: Vec<fs::DirEntry> = entries.flatten().collect();
        entries.sort_by_key(|entry| entry.file_name());
        let mut subfolders = Vec::new();
        for entry in entries {
            let Ok(file_type) = entry.file_type() else {
                continue;
            };
            let relative = relative_folder.join(entry.file_name());
            // As in `check`, a linked folder is not walked (links can form cycles), a linked file is read.
            if file_type.is_dir() {
                subfolders.push(relative);
                continue;
            }
            let is_file = file_type.is_file()
                || (file_type.is_symlink()
                    && fs::metadata(entry.path()).is_ok_and(|metadata| metadata.is_file()));
            let Some(file_name) = entry.file_name().to_str().map(str::to_string) else {
                continue;
            };
            if !is_file {
                continue;
            }
            let (program, kind) = program_name_and_kind(&file_name);
            if kind == FileKind::Definitions {
                files.push(relative.clone());
                definitions.push((macro_file_rank(&program), relative));
            } else if let Some(rank) = call_rank(&file_name) {
                files.push(relative.clone());
                // The first file of the best rank wins: files of a folder before its subfolders'.
                if best.get(&program).is_none_or(|(known, _)| rank < *known) {
                    best.insert(program, (rank, relative));
                }
            }
        }
        if recursive {
            // Popped from the end: reversed, the subfolders are walked in sorted order.
            pending.extend(subfolders.into_iter().rev());
        }
    }
    // Stable: files of equal rank keep their walking order.
    definitions.sort_by_key(|(rank, _)| *rank);
    Listing {
        programs: best
            .into_iter()
            .map(|(program, (_, relative))| (program, relative))
            .collect(),
        definitions: definitions
            .into_iter()
            .map(|(_, relative)| relative)
            .collect(),
        files,
    }
}

#[cfg(test)]
#[path = "library_tests.rs"]
mod tests;
