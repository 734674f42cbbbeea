//! The server's [`ProgramLibrary`]: the programs an open document calls, found through the workspace
//! index (program names from file names, `_N_PART2_SPF` as `PART2`). Where several files hold a
//! program of the name, the one the control would run wins: in the caller's folder, then in the
//! folders above it, then in the cycle folders in the order of the `cycleFolders` setting; after them
//! the rest of the workspace, whose programs the cross-file checks also know. A subprogram comes
//! before a main program, a file named as on a PC (`PART2.SPF`) before the control's own name.
//!
//! A found file that is open gives its text as the editor has it now; any other is read from disk
//! when first asked for and kept until the index sees the file change ([`LibraryTexts`]). A library
//! forgets what it found whenever the index changes, so that a document never runs a callee's
//! replaced text for longer than the index's own debounce.
//!
//! Lock order: a lookup takes the index's `state` lock for reading, and a document's `text` lock
//! after releasing it; it must not be called while the caller holds the index's lock.

use crate::analysis::library::{LibraryProgram, ProgramLibrary};
use crate::ide::call_lookup::{folders_above, LookupOrder};
use crate::ide::workspace::IndexedDocument;
use crate::ide::DocumentId;
use crate::io::source_file::read_source_file;
use crate::lsp::locks::lock;
use crate::lsp::state::Shared;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, Weak};
use tower_lsp_server::ls_types::Uri;

/// The library of one open document. Cheap to create: it holds the folders above the document and
/// looks everything else up when asked.
pub struct WorkspaceLibrary {
    shared: Weak<Shared>,
    /// The document's folder and the folders above it, nearest first; empty when it is no file.
    folders: Vec<PathBuf>,
    /// The document's file, whose call sites give a subprogram's entry state.
    path: Option<PathBuf>,
    cache: Mutex<FoundCache>,
}

/// What a library found since the index's generation `generation`.
#[derive(Default)]
struct FoundCache {
    generation: u64,
    found: HashMap<String, Option<Arc<LibraryProgram>>>,
    macro_files: Option<Vec<Arc<LibraryProgram>>>,
}

/// A file the lookup chose, with what is needed to get its text once the index's lock is released.
struct Chosen {
    id: DocumentId,
    uri: Option<Uri>,
    name: String,
}

/// The library through which the analysis of the document at `path` (`None` when it is not a file)
/// finds the programs it calls.
pub fn workspace_library(shared: &Arc<Shared>, path: Option<&Path>) -> Arc<dyn ProgramLibrary> {
    Arc::new(WorkspaceLibrary::new(shared, path))
}

impl WorkspaceLibrary {
    pub fn new(shared: &Arc<Shared>, path: Option<&Path>) -> WorkspaceLibrary {
        WorkspaceLibrary {
            shared: Arc::downgrade(shared),
            folders: folders_above(path),
            path: path.map(Path::to_path_buf),
            cache: Mutex::default(),
        }
    }

    fn look_up(&self, shared: &Shared, name: &str) -> Option<Arc<LibraryProgram>> {
        let cycles = shared.cycle_folders();
        let chosen = {
            let state = shared.workspace.read();
            let order = LookupOrder {
                folders: &self.folders,
                cycles: &cycles,
            };
            order
                .best_program(&state.index, name, |id| state.is_open(id))
                .map(|document| chosen(&state, document))
        }?;
        self.program(shared, chosen)
    }

    fn read_macro_files(&self, shared: &Shared) -> Vec<Arc<LibraryProgram>> {
        let cycles = shared.cycle_folders();
        let chosen: Vec<Chosen> = {
            let state = shared.workspace.read();
            let order = LookupOrder {
                folders: &self.folders,
                cycles: &cycles,
            };
            order
                .macro_files(&state.index)
                .into_iter()
                .map(|document| chosen(&state, document))
                .collect()
        };
        chosen
            .into_iter()
            .filter_map(|chosen| self.program(shared, chosen))
            .collect()
    }

    /// The program of a chosen file with its current text.
    fn program(&self, shared: &Shared, chosen: Chosen) -> Option<Arc<LibraryProgram>> {
        // An open document's entry may still be the file's until its edits pause: the editor's text
        // is asked for whatever the entry says.
        let open_text = chosen
            .uri
            .as_ref()
            .and_then(|uri| shared.documents.get(uri))
            .map(|document| Arc::<str>::from(document.text_snapshot().rope.to_string()));
        let text = match open_text {
            Some(text) => text,
            None => shared.workspace.library_texts.text(&chosen.id, || {
                read_source_file(Path::new(chosen.id.as_ref()))
                    .ok()
                    .map(|source| Arc::from(source.text))
            })?,
        };
        let path = match &chosen.uri {
            Some(uri) => Arc::from(uri.as_str()),
            None => Arc::clone(&chosen.id),
        };
        Some(Arc::new(LibraryProgram {
            name: chosen.name,
            path,
            text,
        }))
    }
}

/// Runs `look_up` unless `cache` holds a result from the index's generation `generation`, and keeps
/// its result unless the index changed meanwhile (`current_generation`).
fn cached<T: Clone>(
    cache: &Mutex<FoundCache>,
    generation: u64,
    current_generation: impl FnOnce() -> u64,
    get: impl FnOnce(&FoundCache) -> Option<T>,
    put: impl FnOnce(&mut FoundCache, T),
    look_up: impl FnOnce() -> T,
) -> T {
    {
        let mut cache = lock(cache);
        if cache.generation != generation {
            *cache = FoundCache {
                generation,
                ..FoundCache::default()
            };
        }
        if let Some(value) = get(&cache) {
            return value;
        }
    }
    // The cache is not locked during the lookup, which may read files.
    let value = look_up();
    if current_generation() == generation {
        let mut cache = lock(cache);
        if cache.generation == generation {
            put(&mut cache, value.clone());
        }
    }
    value
}

fn chosen(state: &crate::lsp::workspace::index::IndexState, document: &IndexedDocument) -> Chosen {
    Chosen {
        id: Arc::clone(&document.id),
        uri: state.uri(&document.id).cloned(),
        name: document.program_name.clone(),
    }
}

impl ProgramLibrary for WorkspaceLibrary {
    fn find(&self, name: &str) -> Option<Arc<LibraryProgram>> {
        let shared = self.shared.upgrade()?;
        let name = name.to_ascii_uppercase();
        let texts = &shared.workspace.library_texts;
        cached(
            &self.cache,
            texts.generation(),
            || texts.generation(),
            |cache| cache.found.get(&name).cloned(),
            |cache, found| {
                cache.found.insert(name.clone(), found);
            },
            || self.look_up(&shared, &name),
        )
    }

    /// The definition files of the index that define macros (`.DEF`, `_N_SMAC_DEF`, ...): those of the
    /// document's folder and the folders above it first, then the cycle folders', then the rest; in
    /// a folder `_N_SMAC_DEF`, `_N_MMAC_DEF`, `_N_UMAC_DEF`, then the others by path.
    fn macro_files(&self) -> Vec<Arc<LibraryProgram>> {
        let Some(shared) = self.shared.upgrade() else {
            return Vec::new();
        };
        let texts = &shared.workspace.library_texts;
        cached(
            &self.cache,
            texts.generation(),
            || texts.generation(),
            |cache| cache.macro_files.clone(),
            |cache, files| cache.macro_files = Some(files),
            || self.read_macro_files(&shared),
        )
    }

    /// The entry state the workspace's call sites of this subprogram agree on (`call_sites.rs`).
    fn caller_entry(&self) -> Option<Arc<crate::analysis::execution::entry::CallerEntry>> {
        self.entry_from_call_sites()
    }

    /// The index's generation: every change of an indexed file (a caller or a callee) advances it.
    fn generation(&self) -> u64 {
        self.index_generation()
    }
}

/// What a library says beyond finding programs: the entry state from the call sites, and the
/// generation of what it finds.
impl WorkspaceLibrary {
    fn entry_from_call_sites(&self) -> Option<Arc<crate::analysis::execution::entry::CallerEntry>> {
        let shared = self.shared.upgrade()?;
        crate::lsp::workspace::call_sites::caller_entry(&shared, self.path.as_deref()?)
    }

    fn index_generation(&self) -> u64 {
        self.shared
            .upgrade()
            .map_or(0, |shared| shared.workspace.library_texts.generation())
    }
}

#[cfg(test)]
#[path = "library_tests.rs"]
mod tests;
