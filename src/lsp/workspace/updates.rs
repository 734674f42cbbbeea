//! Keeping the workspace index current: background indexing of the workspace and cycle folders
//! (progress, cancellation), watched files, and the open documents, whose entries are rebuilt on the
//! blocking pool once their edits pause (300 ms, plus 1 ms per 1,000 lines: never per keystroke).
//! After every update the cross-file findings of the open documents are computed again
//! (`cross_file.rs` publishes them).

use crate::config::MachineConfig;
use crate::ide::cross_file_diagnostics::cross_file_diagnostics;
use crate::lsp::locks::lock;
use crate::lsp::settings::machine_config_for;
use crate::lsp::state::Shared;
use crate::lsp::uris::file_path;
use crate::lsp::workspace::index::{document_id, is_config_file, is_program_file};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};
use tokio::sync::mpsc;
use tower_lsp_server::ls_types::notification::Progress;
use tower_lsp_server::ls_types::{
    FileChangeType, FileEvent, NumberOrString, ProgressParams, ProgressParamsValue, Uri,
    WorkDoneProgress, WorkDoneProgressBegin, WorkDoneProgressEnd, WorkDoneProgressReport,
};

/// Starts indexing the workspace again (at start, and when folders, settings or a
/// `sinumerik.toml` change); `false` when there is nothing to index (no folder).
pub fn reindex(shared: &Arc<Shared>) -> bool {
    let roots = shared.index_roots();
    if roots.is_empty() {
        return false;
    }
    let progress = shared.work_done_progress();
    start_indexing(shared, roots, progress);
    true
}

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
            .map_or(0, |document| document.line_count());
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
                    .update_from_disk(&path, &mut |path: &Path| {
                        ConfigCache::new(&shared).for_file(path)
                    });
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
            let library =
                crate::lsp::workspace::library::workspace_library(shared, document.path.as_deref());
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
        shared
            .workspace
            .update_from_disk(path, &mut |path: &Path| configs.for_file(path));
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
        if reindex(shared) {
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
                shared
                    .workspace
                    .update_from_disk(&path, &mut |path: &Path| configs.for_file(path));
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
