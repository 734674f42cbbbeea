//! The cross-file findings of `check` (W301-W307, `ide::cross_file_diagnostics`), computed over a
//! [`WorkspaceIndex`] as the server computes them over its own: the index holds the checked program
//! and every program and definition file of the folders `check` searches for its callees (its own
//! folder, the parents up to the `sinumerik.toml` in use, the `--cycles` folders). `check` has read
//! all of them, so the index is complete and names found nowhere are reported, as the server does
//! once its indexing has finished.
//!
//! Programs with the same folders to search share one index per run, and each file's symbol table
//! is built once: a folder of 1,000 programs builds 1,000 tables, not a million. The folders are
//! read only for a program that calls programs or uses names it does not define itself.

use super::library::{absolute_file, FolderLibrary};
use crate::config::MachineConfig;
use crate::diagnostics::{Code, LineDiagnostic};
use crate::ide::cross_file_diagnostics::cross_file_diagnostics;
use crate::ide::{SymbolTable, WorkspaceIndex};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::sync::Arc;

/// The folders a program's library searches, with whether their subfolders are searched too.
type Scope = Vec<(PathBuf, bool)>;

/// The indexes of one `check` run.
#[derive(Default)]
pub(super) struct CheckIndexes {
    /// The complete index of each scope, with the files of its folders.
    by_scope: HashMap<Scope, WorkspaceIndex>,
    /// The symbol table of each file read for an index, by absolute path; `None` for a file that
    /// could not be read (it stays out of the index, as in the server).
    tables: HashMap<PathBuf, Option<Arc<SymbolTable>>>,
}

impl CheckIndexes {
    /// The W3xx findings of the program at `program` (its `text`, read with `config`), with the
    /// configured severities, sorted by line. `config_of_folder` gives the configuration of the
    /// files of another folder (a `--cycles` folder may have its own `sinumerik.toml`).
    pub(super) fn findings(
        &mut self,
        library: &FolderLibrary,
        program: &Path,
        text: &str,
        config: &MachineConfig,
        config_of_folder: impl FnMut(&Path) -> Rc<MachineConfig>,
    ) -> Vec<LineDiagnostic> {
        // The program's entry is the one read from its text now, with its own configuration (a
        // program named on the command line may have an extension the library does not list, or
        // differ from the copy read for the index).
        let name = absolute_file(program).to_string_lossy().into_owned();
        let id: Arc<str> = Arc::from(name.as_str());
        let own = Arc::new(SymbolTable::of_text(text, config));
        // Jumps and the order of definitions need the program alone. The other files matter only
        // for calls and for names the program does not define itself (more files only resolve
        // more names), so a program without either does not have its folders read: a file in a
        // large folder (a temporary folder, an archive) is checked without reading its neighbours.
        let mut alone = WorkspaceIndex::new();
        alone.insert(Arc::clone(&id), &name, Arc::clone(&own));
        alone.set_complete(true);
        let findings = cross_file_diagnostics(&alone, &id, config);
        let needs_folders = !own.calls.is_empty()
            || findings
                .iter()
                .any(|item| item.diagnostic.code == Code::UndefinedVariable);
        if !needs_folders {
            return findings;
        }
        let index = self.scope_index(library, config_of_folder);
        // The index's entry of the program comes back afterwards, for the next program of the scope.
        let earlier = index
            .document(&id)
            .map(|document| Arc::clone(&document.symbols));
        index.insert(Arc::clone(&id), &name, own);
        let findings = cross_file_diagnostics(index, &id, config);
        match earlier {
            Some(symbols) => index.insert(Arc::clone(&id), &name, symbols),
            None => index.remove(&id),
        }
        findings
    }

    /// The complete index of the library's folders, built on first use.
    fn scope_index(
        &mut self,
        library: &FolderLibrary,
        mut config_of_folder: impl FnMut(&Path) -> Rc<MachineConfig>,
    ) -> &mut WorkspaceIndex {
        let tables = &mut self.tables;
        self.by_scope.entry(library.scope()).or_insert_with(|| {
            let mut index = WorkspaceIndex::new();
            for path in library.indexed_files() {
                let table = tables
                    .entry(path.clone())
                    .or_insert_with(|| {
                        let config = config_of_folder(path.parent().unwrap_or(Path::new("")));
                        let text = library.program_files().text_once(&path)?;
                        Some(Arc::new(SymbolTable::of_text(&text, &config)))
                    })
                    .clone();
                if let Some(table) = table {
                    let name = path.to_string_lossy();
                    index.insert(Arc::from(name.as_ref()), &name, table);
                }
            }
            index.set_complete(true);
            index
        })
    }
}
