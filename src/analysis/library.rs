//! The programs a running program can call: subprograms, cycles and macro definition files found the
//! way the control finds them. The analysis asks by name and never reads files itself: the command
//! line (the program's folder, its parents, `--cycles`) and the server (the workspace index and the
//! cycle folders) implement [`ProgramLibrary`] and do the reading.

use crate::analysis::execution::entry::CallerEntry;
use std::sync::Arc;

/// One program file as the library found it.
#[derive(Debug, Clone, PartialEq)]
pub struct LibraryProgram {
    /// The program's name in upper case, as a call names it (`PART2`, `L123`, `CYCLE81`).
    pub name: String,
    /// Where it was found, as the caller should show it (a path or a URI).
    pub path: Arc<str>,
    /// The whole text of the file, already decoded.
    pub text: Arc<str>,
}

/// Finds called programs by name. Implementations cache what they read: the analysis may ask for the
/// same name many times.
pub trait ProgramLibrary: Send + Sync {
    /// The program a call of `name` (upper case, without extension: `PART2`, `L123`) runs, or `None`
    /// when it cannot be found (the call then stays unknown).
    fn find(&self, name: &str) -> Option<Arc<LibraryProgram>>;

    /// Macro definition files (`.DEF` with `DEFINE ... AS ...`) that apply to every program, in the
    /// order their definitions are read.
    fn macro_files(&self) -> Vec<Arc<LibraryProgram>> {
        Vec::new()
    }

    /// For a subprogram analysed on its own: the entry state its call sites agree on (`None`: they
    /// do not agree, none is known, or the caller does not look; the reset state is assumed then).
    fn caller_entry(&self) -> Option<Arc<CallerEntry>> {
        None
    }

    /// Changes whenever what the library finds may have changed: a run made with an older value may
    /// be out of date.
    fn generation(&self) -> u64 {
        0
    }
}

/// A library that finds nothing: every call stays unknown.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoLibrary;

impl ProgramLibrary for NoLibrary {
    fn find(&self, _name: &str) -> Option<Arc<LibraryProgram>> {
        None
    }
}

/// A library of programs held in memory, by upper-case name: tests and callers that already have
/// the texts.
#[derive(Debug, Clone, Default)]
pub struct MemoryLibrary {
    programs: std::collections::HashMap<String, Arc<LibraryProgram>>,
    macros: Vec<Arc<LibraryProgram>>,
}

impl MemoryLibrary {
    /// Adds a program; `name` may be given in any case.
    pub fn insert(&mut self, name: &str, path: &str, text: &str) {
        let name = name.to_ascii_uppercase();
        self.programs.insert(
            name.clone(),
            Arc::new(LibraryProgram {
                name,
                path: Arc::from(path),
                text: Arc::from(text),
            }),
        );
    }

    /// Adds a macro definition file.
    pub fn insert_macro_file(&mut self, path: &str, text: &str) {
        self.macros.push(Arc::new(LibraryProgram {
            name: String::new(),
            path: Arc::from(path),
            text: Arc::from(text),
        }));
    }
}

impl ProgramLibrary for MemoryLibrary {
    fn find(&self, name: &str) -> Option<Arc<LibraryProgram>> {
        self.programs.get(&name.to_ascii_uppercase()).cloned()
    }

    fn macro_files(&self) -> Vec<Arc<LibraryProgram>> {
        self.macros.clone()
    }
}
