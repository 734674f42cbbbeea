//! The server's workspace index: a [`WorkspaceIndex`] over the program files of the workspace folders
//! (and the configured cycle folders), read from disk in the background with progress and
//! cancellation, kept up to date from `didChangeWatchedFiles`, and overridden by the open documents,
//! whose entries are rebuilt on the blocking pool once their edits pause (300 ms, plus 1 ms per
//! 1,000 lines: never per keystroke).
//! After every update the cross-file findings of the open documents are computed again
//! (`cross_file.rs` publishes them).
//!
//! Documents are identified by their path (for `file:` URIs, so the editor's URI and the one built
//! for a file on disk name the same document) or by their URI.
//!
//! Lock order: requests take the index's `state` lock inside a document's `analysis` lock; nothing
//! waits for a document's `analysis` lock while holding the index's, and nothing takes the index's
//! lock twice in one thread (a waiting writer would block the second reader).

use crate::config::MachineConfig;
use crate::ide::cross_file_diagnostics::cross_file_diagnostics;
use crate::ide::symbols::SymbolTable;
use crate::ide::{DocumentId, WorkspaceIndex};
use crate::io::source_file::read_source_file;
use crate::lsp::documents::{lock, Analysed, OpenDocument};
use crate::lsp::library::LibraryTexts;
use crate::lsp::server::{file_path, Shared};
use crate::lsp::settings::machine_config_for;
use crate::lsp::text_document::RopeLines;
use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, RwLock, RwLockReadGuard, RwLockWriteGuard};
use std::time::{Duration, Instant};
use tokio::sync::mpsc;
use tower_lsp_server::ls_types::notification::Progress;
use tower_lsp_server::ls_types::{
    FileChangeType, FileEvent, NumberOrString, ProgressParams, ProgressParamsValue, Uri,
    WorkDoneProgress, WorkDoneProgressBegin, WorkDoneProgressEnd, WorkDoneProgressReport,
};

/// How long after the last edit of a small document its index entry is rebuilt.
const DEBOUNCE: Duration = Duration::from_millis(300);

/// The quiet time added per line of the document: rebuilding costs about a third of a microsecond
/// per line, and a large program must not be rebuilt in every short pause of a burst of edits (on a
/// loaded machine each rebuild would slow the next analyses and so make the pauses longer). A
/// 1,000,000-line program waits 1.3 s.
const DEBOUNCE_PER_LINE: Duration = Duration::from_micros(1);

/// The quiet time after the last edit of a document of `line_count` lines.
fn quiet_time(line_count: usize) -> Duration {
    DEBOUNCE + DEBOUNCE_PER_LINE * u32::try_from(line_count).unwrap_or(u32::MAX)
}

/// The largest document whose entry a request made at every cursor move (highlights, hover) rebuilds
/// itself when it is older than the text: about 20 ms of work. A larger document waits for its
/// debounced update (a 1,000,000-line program takes a third of a second, under the analysis's lock).
const CHEAP_REBUILD_LINES: usize = 50_000;

/// The index and what the server knows about its entries.
#[derive(Default)]
pub struct IndexState {
    pub index: WorkspaceIndex,
    /// Documents whose entry comes from the editor, with the text revision it was built from.
    open: HashMap<DocumentId, u64>,
    /// The URI of each indexed document (the editor's for open documents).
    uris: HashMap<DocumentId, Uri>,
    /// Documents with text that is not all ASCII, whose byte offsets must be converted.
    non_ascii: HashSet<DocumentId>,
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

    fn insert(
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

    fn remove(&mut self, id: &str) {
        self.index.remove(id);
        self.uris.remove(id);
        self.non_ascii.remove(id);
    }
}

#[derive(Default)]
pub struct Workspace {
    state: RwLock<IndexState>,
    /// The documents waiting for their debounced update, with the time of their last edit.
    debounce: Mutex<HashMap<Uri, Instant>>,
    /// The cancellation flag of the indexing run in progress.
    run: Mutex<Option<Arc<AtomicBool>>>,
    /// Counts indexing runs, for unique progress tokens.
    runs: AtomicU64,
    /// The workspace folders and the cycle folders, as the last run indexed them.
    roots: Mutex<Vec<PathBuf>>,
    /// Held while the cross-file findings are computed: two computations at once could store the
    /// findings of the older index last.
    refreshing: Mutex<()>,
    /// The texts of called programs read from disk, dropped when the index sees their file change;
    /// every change of the index is told to it, so that the documents' libraries look up again.
    pub(super) library_texts: LibraryTexts,
}

/// The index's name for a document.
pub fn document_id(uri: &Uri) -> DocumentId {
    match file_path(uri) {
        Some(path) => Arc::from(path.to_string_lossy().as_ref()),
        None => Arc::from(uri.as_str()),
    }
}

/// The name the index takes the program name and kind from.
fn file_name(uri: &Uri) -> String {
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

fn is_config_file(path: &Path) -> bool {
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

    fn write(&self) -> RwLockWriteGuard<'_, IndexState> {
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
    fn update_open_document(&self, document: &OpenDocument) -> DocumentId {
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

    fn insert_open(
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
    fn update_from_disk(&self, path: &Path, configs: &mut ConfigCache) {
        let Some(uri) = Uri::from_file_path(path) else {
            return;
        };
        let id = document_id(&uri);
        if self.read().open.contains_key(&id) {
            return;
        }
        match read_source_file(path) {
            Ok(source) => {
                let config = configs.for_file(path);
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

    fn remove_from_disk(&self, id: &DocumentId) {
        let mut state = self.write();
        if !state.open.contains_key(id) {
            state.remove(id);
            drop(state);
            self.library_texts.file_changed(id);
        }
    }

    /// Whether a path lies in one of the indexed folders.
    fn in_roots(&self, path: &Path) -> bool {
        lock(&self.roots).iter().any(|root| path.starts_with(root))
    }

    /// Cancels the indexing run in progress (at shutdown).
    pub fn cancel(&self) {
        if let Some(run) = lock(&self.run).take() {
            run.store(true, Ordering::SeqCst);
        }
    }
}

/// The machine configuration of files on disk, read once per folder.
struct ConfigCache<'a> {
    shared: &'a Shared,
    by_folder: HashMap<PathBuf, Arc<MachineConfig>>,
}

impl ConfigCache<'_> {
    fn new(shared: &Shared) -> ConfigCache<'_> {
        ConfigCache {
            shared,
            by_folder: HashMap::new(),
        }
    }

    /// A configuration file that cannot be used gives the defaults here; the open documents
    /// report it.
    fn for_file(&mut self, path: &Path) -> Arc<MachineConfig> {
        let folder = path.parent().map(Path::to_path_buf).unwrap_or_default();
        let shared = self.shared;
        Arc::clone(self.by_folder.entry(folder).or_insert_with(|| {
            let settings = shared.settings_now();
            let root = shared.workspace_root();
            machine_config_for(Some(path), &settings, root.as_deref()).0
        }))
    }
}

/// Called after every edit of an open document: its entry is rebuilt once the edits pause (for a
/// time that grows with the document, see [`quiet_time`]).
pub fn document_changed(shared: &Arc<Shared>, uri: &Uri) {
    if lock(&shared.workspace.debounce)
        .insert(uri.clone(), Instant::now())
        .is_some()
    {
        // A task already waits for this document and will see the new time.
        return;
    }
    let shared = Arc::clone(shared);
    let uri = uri.clone();
    tokio::spawn(async move {
        let line_count = shared
            .documents
            .get(&uri)
            .map_or(0, |document| document.text_snapshot().rope.len_lines());
        let quiet = quiet_time(line_count);
        loop {
            let wait_until = {
                let mut pending = lock(&shared.workspace.debounce);
                match pending.get(&uri) {
                    None => return,
                    Some(last_edit) if *last_edit + quiet <= Instant::now() => {
                        pending.remove(&uri);
                        None
                    }
                    Some(last_edit) => Some(*last_edit + quiet),
                }
            };
            match wait_until {
                Some(due) => tokio::time::sleep_until(tokio::time::Instant::from_std(due)).await,
                None => break,
            }
        }
        let _ = tokio::task::spawn_blocking(move || {
            if let Some(document) = shared.documents.get(&uri) {
                shared.workspace.update_open_document(&document);
                refresh_diagnostics(&shared);
            }
        })
        .await;
    });
}

/// Called when a document is closed: the index goes back to the file on disk (if it is one of the
/// workspace's), and the other documents' findings are computed again.
pub fn document_closed(shared: &Arc<Shared>, uri: &Uri) {
    lock(&shared.workspace.debounce).remove(uri);
    let id = document_id(uri);
    shared.workspace.write().open.remove(&id);
    let shared = Arc::clone(shared);
    let uri = uri.clone();
    tokio::task::spawn_blocking(move || {
        match file_path(&uri) {
            Some(path)
                if is_program_file(&path) && shared.workspace.in_roots(&path) && path.is_file() =>
            {
                shared
                    .workspace
                    .update_from_disk(&path, &mut ConfigCache::new(&shared));
            }
            _ => shared.workspace.remove_from_disk(&id),
        }
        refresh_diagnostics(&shared);
    });
}

/// Computes the cross-file findings of every open document from the index, and the findings of
/// running it (E401-E408, with the programs it calls), and republishes those whose findings changed.
/// Runs on the blocking pool.
pub fn refresh_diagnostics(shared: &Arc<Shared>) {
    let _one_at_a_time = lock(&shared.workspace.refreshing);
    let context = shared.context();
    for document in shared.documents.all() {
        let id = document_id(&document.uri);
        let snapshot = document.text_snapshot();
        let (mut findings, built) = {
            let state = shared.workspace.read();
            let Some(built) = state.open.get(&id).copied() else {
                continue;
            };
            (
                cross_file_diagnostics(&state.index, &id, &snapshot.config),
                built,
            )
        };
        // The run's findings belong to the same revision as the index entry; a newer text gets them
        // at the next refresh, which its edit starts. The library takes the index's lock itself.
        if snapshot.revision == built {
            let library = crate::lsp::library::workspace_library(shared, document.path.as_deref());
            // The document's own run of this revision: the hover and the toolpath ask for the same
            // one, and it resumes the run of the previous revision where the edit allows it.
            let job = document
                .catch_up()
                .as_ref()
                .filter(|analysed| analysed.revision == built)
                .map(|analysed| analysed.execution_job());
            // The run does not hold the analysis: an edit meanwhile is analysed and published.
            let run = job.map_or_else(Vec::new, |job| {
                job.run(library.as_ref()).findings().to_vec()
            });
            if !run.is_empty() {
                findings.extend(run);
                findings.sort_by_key(|item| (item.line, item.diagnostic.span.start()));
            }
        }
        if lock(&document.extra).replace(findings, built) {
            document.republish(&context);
        }
    }
}

/// Makes the entries of every open document current (before a rename or a search for references).
pub fn update_all_open(shared: &Shared) {
    for document in shared.documents.all() {
        shared.workspace.update_open_document(&document);
    }
}

/// Progress of an indexing run, from the blocking pool to the task that tells the client.
enum RunEvent {
    Progress { done: usize, total: usize },
}

/// Indexes the program files of `roots` in the background, cancelling an earlier run; reports
/// progress with `$/progress` when the client supports it.
pub fn start_indexing(shared: &Arc<Shared>, roots: Vec<PathBuf>, progress: bool) {
    let cancel = Arc::new(AtomicBool::new(false));
    if let Some(earlier) = lock(&shared.workspace.run).replace(Arc::clone(&cancel)) {
        earlier.store(true, Ordering::SeqCst);
    }
    *lock(&shared.workspace.roots) = roots.clone();
    let run = shared.workspace.runs.fetch_add(1, Ordering::SeqCst) + 1;
    let shared = Arc::clone(shared);
    tokio::spawn(async move {
        let token = NumberOrString::String(format!("sinumerik/indexing/{run}"));
        let token = match progress {
            true => match shared.client.create_work_done_progress(token.clone()).await {
                Ok(()) => Some(token),
                Err(error) => {
                    shared.warn(format!("window/workDoneProgress/create failed: {error}"));
                    None
                }
            },
            false => None,
        };
        let notify = |value: WorkDoneProgress| {
            let shared = Arc::clone(&shared);
            let token = token.clone();
            async move {
                if let Some(token) = token {
                    shared
                        .client
                        .send_notification::<Progress>(ProgressParams {
                            token,
                            value: ProgressParamsValue::WorkDone(value),
                        })
                        .await;
                }
            }
        };
        notify(WorkDoneProgress::Begin(WorkDoneProgressBegin {
            title: "Indexing SINUMERIK programs".to_string(),
            cancellable: Some(false),
            message: Some("looking for program files".to_string()),
            percentage: Some(0),
        }))
        .await;
        let (events, mut received) = mpsc::unbounded_channel();
        let worker_shared = Arc::clone(&shared);
        let worker_cancel = Arc::clone(&cancel);
        let job = tokio::task::spawn_blocking(move || {
            index_roots(&worker_shared, &roots, &worker_cancel, &events)
        });
        while let Some(RunEvent::Progress { done, total }) = received.recv().await {
            notify(WorkDoneProgress::Report(WorkDoneProgressReport {
                cancellable: Some(false),
                message: Some(format!("{done}/{total} files")),
                percentage: Some(percentage(done, total)),
            }))
            .await;
        }
        let message = match job.await {
            Ok(Some(count)) => format!("{count} files indexed"),
            Ok(None) => "cancelled".to_string(),
            Err(error) => {
                shared.warn(format!("indexing the workspace failed: {error}"));
                "failed".to_string()
            }
        };
        notify(WorkDoneProgress::End(WorkDoneProgressEnd {
            message: Some(message),
        }))
        .await;
    });
}

fn percentage(done: usize, total: usize) -> u32 {
    (done * 100)
        .checked_div(total)
        .map_or(100, |share| u32::try_from(share).unwrap_or(100))
}

/// Reads every program file below `roots`; `None` when cancelled, else the number of files.
fn index_roots(
    shared: &Arc<Shared>,
    roots: &[PathBuf],
    cancel: &AtomicBool,
    events: &mpsc::UnboundedSender<RunEvent>,
) -> Option<usize> {
    // Any file may have changed while nobody watched (the folders or the settings changed).
    shared.workspace.library_texts.clear();
    let mut files = Vec::new();
    for root in roots {
        collect_program_files(root, &mut files, cancel);
    }
    files.sort();
    files.dedup();
    let total = files.len();
    let mut configs = ConfigCache::new(shared);
    let mut last_percentage = 0;
    for (done, path) in files.iter().enumerate() {
        if cancel.load(Ordering::SeqCst) {
            return None;
        }
        shared.workspace.update_from_disk(path, &mut configs);
        let now = percentage(done + 1, total);
        if now != last_percentage {
            last_percentage = now;
            let _ = events.send(RunEvent::Progress {
                done: done + 1,
                total,
            });
        }
    }
    if cancel.load(Ordering::SeqCst) {
        return None;
    }
    shared.workspace.write().index.set_complete(true);
    refresh_diagnostics(shared);
    Some(total)
}

/// The program files below `folder`, walked without following symbolic links.
fn collect_program_files(folder: &Path, files: &mut Vec<PathBuf>, cancel: &AtomicBool) {
    let mut pending = vec![folder.to_path_buf()];
    while let Some(folder) = pending.pop() {
        if cancel.load(Ordering::SeqCst) {
            return;
        }
        let Ok(entries) = std::fs::read_dir(&folder) else {
            continue;
        };
        for entry in entries.flatten() {
            let Ok(file_type) = entry.file_type() else {
                continue;
            };
            let path = entry.path();
            if file_type.is_dir() {
                pending.push(path);
            } else if file_type.is_file() && is_program_file(&path) {
                files.push(path);
            }
        }
    }
}

/// `workspace/didChangeWatchedFiles`: a changed `sinumerik.toml` gives the open documents their
/// configuration again and has the workspace indexed again (the configuration's axes decide how a
/// file reads); changed program files are read into the index (deleted ones leave it).
pub fn files_changed(shared: &Arc<Shared>, changes: Vec<FileEvent>) {
    let mut program_changes = Vec::new();
    let mut config_changed = false;
    for change in changes {
        let Some(path) = file_path(&change.uri) else {
            continue;
        };
        if is_config_file(&path) {
            config_changed = true;
        } else if is_program_file(&path) {
            program_changes.push((path, change.typ));
        }
    }
    if config_changed {
        let context = shared.context();
        for document in shared.documents.all() {
            let config = shared.machine_config(document.path.as_deref());
            document.set_config(config, &context);
            document_changed(shared, &document.uri);
        }
        // The new run reads every program file, the changed ones too.
        if shared.reindex() {
            return;
        }
    }
    if program_changes.is_empty() {
        return;
    }
    let shared = Arc::clone(shared);
    tokio::task::spawn_blocking(move || {
        let mut configs = ConfigCache::new(&shared);
        for (path, kind) in program_changes {
            if kind == FileChangeType::DELETED {
                if let Some(uri) = Uri::from_file_path(&path) {
                    shared.workspace.remove_from_disk(&document_id(&uri));
                }
            } else {
                shared.workspace.update_from_disk(&path, &mut configs);
            }
        }
        refresh_diagnostics(&shared);
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn program_files_are_recognised_in_any_case() {
        for name in ["a/PART.MPF", "b.spf", "GUD.Def", "_N_CYCLE_SPF"] {
            assert!(is_program_file(Path::new(name)), "{name}");
        }
        for name in ["notes.txt", "part.mpf.bak", "sinumerik.toml", "MPF"] {
            assert!(!is_program_file(Path::new(name)), "{name}");
        }
        assert!(is_config_file(Path::new("/x/SINUMERIK.TOML")));
    }

    #[test]
    fn large_documents_wait_longer_for_their_update() {
        assert_eq!(quiet_time(0), Duration::from_millis(300));
        assert_eq!(quiet_time(1_000_000), Duration::from_millis(1300));
    }

    #[test]
    fn percentages_stay_in_range() {
        assert_eq!(percentage(0, 0), 100);
        assert_eq!(percentage(1, 3), 33);
        assert_eq!(percentage(3, 3), 100);
    }
}
