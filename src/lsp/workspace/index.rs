//! The server's workspace index and what it knows about its entries: which come from the editor, their
//! URIs, which are not ASCII; the documents waiting for their debounced update, the indexing run in
//! progress. Documents are identified by their path (for `file:` URIs, so the editor's URI and the
//! one built for a file on disk name the same document) or by their URI.
//!
//! Lock order: requests take the index's `state` lock inside a document's `analysis` lock; nothing
//! waits for a document's `analysis` lock while holding the index's, and nothing takes the index's
//! lock twice in one thread (a waiting writer would block the second reader).

use crate::analysis::document::RopeLines;
use crate::config::MachineConfig;
use crate::ide::symbols::SymbolTable;
use crate::ide::{DocumentId, WorkspaceIndex};
use crate::io::source_file::read_source_file;
use crate::lsp::documents::{Analysed, OpenDocument};
use crate::lsp::locks::lock;
use crate::lsp::uris::file_path;
use crate::lsp::workspace::library_texts::LibraryTexts;
use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, RwLock, RwLockReadGuard, RwLockWriteGuard};
use std::time::Instant;
use tower_lsp_server::ls_types::Uri;

/// The largest document whose entry a request made at every cursor move (highlights, hover) rebuilds
/// itself when it is older than the text: about 20 ms of work. A larger document waits for its
/// debounced update (a 1,000,000-line program takes a third of a second, under the analysis's lock).
const CHEAP_REBUILD_LINES: usize = 50_000;

/// The index and what the server knows about its entries.
#[derive(Default)]
pub struct IndexState {
    pub index: WorkspaceIndex,
    /// Documents whose entry comes from the editor, with the text revision it was built from.
    pub(crate) open: HashMap<DocumentId, u64>,
    /// The URI of each indexed document (the editor's for open documents).
    pub(crate) uris: HashMap<DocumentId, Uri>,
    /// Documents with text that is not all ASCII, whose byte offsets must be converted.
    pub(crate) non_ascii: HashSet<DocumentId>,
}

impl IndexState {
    pub fn uri(&self, id: &str) -> Option<&Uri> {
        self.uris.get(id)
    }

    /// Whether the document's byte offsets are its characters in every encoding.
    pub fn is_ascii(&self, id: &str) -> bool {
        !self.non_ascii.contains(id)
    }

    /// Whether the document's entry comes from the editor (its text there is the current one).
    pub fn is_open(&self, id: &str) -> bool {
        self.open.contains_key(id)
    }

    pub(crate) fn insert(
        &mut self,
        id: DocumentId,
        uri: Uri,
        file_name: &str,
        symbols: SymbolTable,
        ascii: bool,
    ) {
        self.index
            .insert(Arc::clone(&id), file_name, Arc::new(symbols));
        if ascii {
            self.non_ascii.remove(&id);
        } else {
            self.non_ascii.insert(Arc::clone(&id));
        }
        self.uris.insert(id, uri);
    }

    pub(crate) fn remove(&mut self, id: &str) {
        self.index.remove(id);
        self.uris.remove(id);
        self.non_ascii.remove(id);
    }
}

#[derive(Default)]
pub struct Workspace {
    pub(crate) state: RwLock<IndexState>,
    /// The documents waiting for their debounced update, with the time of their last edit.
    pub(crate) debounce: Mutex<HashMap<Uri, Instant>>,
    /// The cancellation flag of the indexing run in progress.
    pub(crate) run: Mutex<Option<Arc<AtomicBool>>>,
    /// Counts indexing runs, for unique progress tokens.
    pub(crate) runs: AtomicU64,
    /// The workspace folders and the cycle folders, as the last run indexed them.
    pub(crate) roots: Mutex<Vec<PathBuf>>,
    /// Held while the cross-file findings are computed: two computations at once could store the
    /// findings of the older index last.
    pub(crate) refreshing: Mutex<()>,
    /// The texts of called programs read from disk, dropped when the index sees their file change;
    /// every change of the index is told to it, so that the documents' libraries look up again.
    pub(crate) library_texts: LibraryTexts,
}

/// The index's name for a document.
pub fn document_id(uri: &Uri) -> DocumentId {
    match file_path(uri) {
        Some(path) => Arc::from(path.to_string_lossy().as_ref()),
        None => Arc::from(uri.as_str()),
    }
}

/// The name the index takes the program name and kind from.
pub(crate) fn file_name(uri: &Uri) -> String {
    match file_path(uri) {
        Some(path) => path.to_string_lossy().into_owned(),
        None => uri.path().as_str().to_string(),
    }
}

/// Whether a path names a program file the index reads: `.MPF`, `.SPF`, `.DEF` in any case, or a
/// control file name such as `_N_PART2_SPF`.
pub fn is_program_file(path: &Path) -> bool {
    let Some(name) = path.file_name().and_then(|name| name.to_str()) else {
        return false;
    };
    let upper = name.to_ascii_uppercase();
    let by_extension = Path::new(&upper)
        .extension()
        .and_then(|extension| extension.to_str())
        .is_some_and(|extension| matches!(extension, "MPF" | "SPF" | "DEF"));
    let control_name = upper.starts_with("_N_")
        && (upper.ends_with("_MPF") || upper.ends_with("_SPF") || upper.ends_with("_DEF"));
    by_extension || control_name
}

pub(crate) fn is_config_file(path: &Path) -> bool {
    path.file_name()
        .and_then(|name| name.to_str())
        .is_some_and(|name| name.eq_ignore_ascii_case("sinumerik.toml"))
}

impl Workspace {
    /// The index for reading (features hold it while they run).
    pub fn read(&self) -> RwLockReadGuard<'_, IndexState> {
        self.state
            .read()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    pub(crate) fn write(&self) -> RwLockWriteGuard<'_, IndexState> {
        self.state
            .write()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    /// Makes the entry of an open document describe `analysed`, building its symbol table if the
    /// entry is older; returns the document's id. Used by requests that must answer for exactly
    /// the text they were asked about.
    pub fn ensure_current(&self, uri: &Uri, analysed: &Analysed) -> DocumentId {
        let id = document_id(uri);
        if self.read().open.get(&id) == Some(&analysed.revision) {
            return id;
        }
        let symbols = SymbolTable::build(&analysed.lines(), analysed.analysis.config());
        let ascii = analysed.rope.len_bytes() == analysed.rope.len_chars();
        self.insert_open(&id, uri, symbols, analysed.revision, ascii);
        id
    }

    /// Like [`Workspace::ensure_current`] for requests made at every cursor move: `None` when the
    /// entry is older than `analysed` and the document too large to rebuild it now.
    pub fn current_if_cheap(&self, uri: &Uri, analysed: &Analysed) -> Option<DocumentId> {
        let id = document_id(uri);
        if self.read().open.get(&id) == Some(&analysed.revision) {
            return Some(id);
        }
        let line_count = crate::analysis::document::LineSource::line_count(&analysed.lines());
        (line_count <= CHEAP_REBUILD_LINES).then(|| self.ensure_current(uri, analysed))
    }

    /// Makes sure an open document has an entry (possibly a few edits old, which completion and
    /// highlighting accept rather than rebuilding per keystroke); returns its id.
    pub fn ensure_present(&self, uri: &Uri, analysed: &Analysed) -> DocumentId {
        let id = document_id(uri);
        if self.read().open.contains_key(&id) {
            return id;
        }
        self.ensure_current(uri, analysed)
    }

    /// Brings the entry of an open document up to date with its text now (the other open
    /// documents of a rename or a search for references).
    pub(crate) fn update_open_document(&self, document: &OpenDocument) -> DocumentId {
        let id = document_id(&document.uri);
        let snapshot = document.text_snapshot();
        if self.read().open.get(&id) == Some(&snapshot.revision) {
            return id;
        }
        let symbols = SymbolTable::build(&RopeLines::new(&snapshot.rope), &snapshot.config);
        let ascii = snapshot.rope.len_bytes() == snapshot.rope.len_chars();
        self.insert_open(&id, &document.uri, symbols, snapshot.revision, ascii);
        id
    }

    pub(crate) fn insert_open(
        &self,
        id: &DocumentId,
        uri: &Uri,
        symbols: SymbolTable,
        revision: u64,
        ascii: bool,
    ) {
        let mut state = self.write();
        if state.open.get(id).is_some_and(|built| *built > revision) {
            return;
        }
        state.open.insert(Arc::clone(id), revision);
        state.insert(Arc::clone(id), uri.clone(), &file_name(uri), symbols, ascii);
        // Told after the index changed: a lookup that saw the old entry is not kept.
        self.library_texts.index_changed();
    }

    /// Reads a file that is not open into the index (or removes it when it cannot be read).
    pub(crate) fn update_from_disk(
        &self,
        path: &Path,
        config_for: &mut dyn FnMut(&Path) -> Arc<MachineConfig>,
    ) {
        let Some(uri) = Uri::from_file_path(path) else {
            return;
        };
        let id = document_id(&uri);
        if self.read().open.contains_key(&id) {
            return;
        }
        match read_source_file(path) {
            Ok(source) => {
                let config = config_for(path);
                let symbols = SymbolTable::of_text(&source.text, &config);
                let mut state = self.write();
                // The document may have been opened meanwhile: the editor's text wins.
                if !state.open.contains_key(&id) {
                    let ascii = source.text.is_ascii();
                    state.insert(
                        Arc::clone(&id),
                        uri,
                        &path.to_string_lossy(),
                        symbols,
                        ascii,
                    );
                    drop(state);
                    self.library_texts.file_changed(&id);
                }
            }
            Err(_) => self.remove_from_disk(&id),
        }
    }

    pub(crate) fn remove_from_disk(&self, id: &DocumentId) {
        let mut state = self.write();
        if !state.open.contains_key(id) {
            state.remove(id);
            drop(state);
            self.library_texts.file_changed(id);
        }
    }

    /// Whether a path lies in one of the indexed folders.
    pub(crate) fn in_roots(&self, path: &Path) -> bool {
        lock(&self.roots).iter().any(|root| path.starts_with(root))
    }

    /// Cancels the indexing run in progress (at shutdown).
    pub fn cancel(&self) {
        if let Some(run) = lock(&self.run).take() {
            run.store(true, Ordering::SeqCst);
        }
    }
}
