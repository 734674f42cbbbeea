//! The server's state, shared with the tasks it spawns: the open documents, the workspace index, the
//! settings and what the client told at initialize; and the way every request reaches the analysis
//! of its document (`on_analysis`: the revision it was asked about, or "content modified").

use crate::lsp::convert::PositionEncoding;
use crate::lsp::documents::{Analysed, Documents, OpenDocument, WorkerContext};
use crate::lsp::locks::lock;
use crate::lsp::settings::{machine_config_for, Settings};
use crate::lsp::transport::outbox::{Outgoing, OutgoingSender};
use crate::lsp::workspace::index::Workspace;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use tower_lsp_server::jsonrpc::{Error, ErrorCode, Result};
use tower_lsp_server::ls_types::{Diagnostic, DiagnosticSeverity, Position, Range, Uri};
use tower_lsp_server::Client;

/// What the client told at initialize.
#[derive(Debug, Clone, Default)]
pub struct ClientInfo {
    pub(crate) encoding: Option<PositionEncoding>,
    pub(crate) pulls_configuration: bool,
    pub(crate) refreshes_inlay_hints: bool,
    /// Whether workspace edits may carry document versions (`documentChanges`).
    pub(crate) versioned_edits: bool,
    /// Whether workspace edits may rename files (`resourceOperations` has `rename`). Such edits go
    /// as `documentChanges`, which a client that renames files takes whether or not it says so:
    /// Neovim 0.7 names the operations but not `documentChanges`.
    pub(crate) renames_files: bool,
    /// Whether the client shows `$/progress` for a token the server creates.
    pub(crate) work_done_progress: bool,
    /// Whether `workspace/didChangeWatchedFiles` can be registered dynamically.
    pub(crate) watches_files: bool,
    /// Whether completion items may be snippets.
    pub(crate) snippets: bool,
    pub(crate) workspace_root: Option<PathBuf>,
    /// Every workspace folder (the root URI when the client gave no folders).
    pub(crate) workspace_folders: Vec<PathBuf>,
}

/// The server's state, shared with the tasks it spawns.
pub struct Shared {
    pub(crate) client: Client,
    pub(crate) documents: Documents,
    pub(crate) workspace: Workspace,
    pub(crate) settings: Mutex<Settings>,
    pub(crate) info: Mutex<ClientInfo>,
    pub(crate) outgoing: OutgoingSender,
}

/// The document a request is about, with what every feature needs beside its analysis: the server's
/// state and the negotiated position encoding.
pub(crate) struct DocumentRequest {
    pub(crate) shared: Arc<Shared>,
    pub(crate) uri: Uri,
    pub(crate) encoding: PositionEncoding,
}

pub(crate) fn content_modified() -> Error {
    Error {
        code: ErrorCode::ServerError(-32801),
        message: "the document changed while the request was answered".into(),
        data: None,
    }
}

pub(crate) fn not_open(uri: &Uri) -> Error {
    Error::invalid_params(format!("the document {} is not open", uri.as_str()))
}

impl Shared {
    pub(crate) fn encoding(&self) -> PositionEncoding {
        lock(&self.info).encoding.unwrap_or(PositionEncoding::Utf16)
    }

    pub(crate) fn context(&self) -> WorkerContext {
        WorkerContext {
            outgoing: self.outgoing.clone(),
            encoding: self.encoding(),
            max_diagnostics: lock(&self.settings).max_diagnostics,
        }
    }

    pub(crate) fn settings_now(&self) -> Settings {
        lock(&self.settings).clone()
    }

    pub(crate) fn workspace_root(&self) -> Option<PathBuf> {
        lock(&self.info).workspace_root.clone()
    }

    /// The folders the index reads: the workspace folders and the configured cycle folders
    /// (relative ones taken from the first workspace folder).
    pub(crate) fn index_roots(&self) -> Vec<PathBuf> {
        let mut roots = lock(&self.info).workspace_folders.clone();
        roots.extend(self.cycle_folders());
        roots
    }

    /// The folders of the `cycleFolders` setting, in its order (relative ones taken from the first
    /// workspace folder).
    pub(crate) fn cycle_folders(&self) -> Vec<PathBuf> {
        let workspace_root = lock(&self.info).workspace_root.clone();
        lock(&self.settings)
            .cycle_folders
            .iter()
            .map(|folder| match (&workspace_root, folder.is_relative()) {
                (Some(root), true) => root.join(folder),
                _ => folder.clone(),
            })
            .collect()
    }

    /// Whether the client takes workspace edits with document versions.
    pub(crate) fn versioned_edits(&self) -> bool {
        lock(&self.info).versioned_edits
    }

    /// Whether the client renames files that a workspace edit asks it to rename.
    pub(crate) fn renames_files(&self) -> bool {
        lock(&self.info).renames_files
    }

    pub(crate) fn warn(&self, message: String) {
        self.outgoing.log_warning(message);
    }

    /// The machine configuration of a document; a configuration file that cannot be used is
    /// reported (the document is still checked, with the defaults).
    pub(crate) fn machine_config(&self, path: Option<&Path>) -> Arc<crate::config::MachineConfig> {
        let settings = lock(&self.settings).clone();
        let root = lock(&self.info).workspace_root.clone();
        let (config, error) = machine_config_for(path, &settings, root.as_deref());
        if let Some(error) = error {
            self.outgoing
                .log_error(format!("{error}; the defaults of a metric mill are used"));
            if let Some(uri) = Uri::from_file_path(&error.path) {
                let line = error.position.map_or(0, |(line, _)| line.saturating_sub(1)) as u32;
                let column = error
                    .position
                    .map_or(0, |(_, column)| column.saturating_sub(1))
                    as u32;
                self.outgoing.send(Outgoing::Diagnostics {
                    uri,
                    version: None,
                    diagnostics: vec![Diagnostic {
                        range: Range::new(
                            Position::new(line, column),
                            Position::new(line, column + 1),
                        ),
                        severity: Some(DiagnosticSeverity::ERROR),
                        source: Some("sinumerik".to_string()),
                        message: error.to_string(),
                        ..Diagnostic::default()
                    }],
                });
            }
        }
        config
    }

    /// Like [`Self::on_analysis`] for a request that shows the run of the program at `line`: when
    /// the block there is not read in program order (after a label, a jump or a loop, or in a
    /// subprogram), the run of the revision is made first without holding the analysis, so that
    /// edits meanwhile are analysed and published; the job then finds it made. With `times`, the
    /// revision's machining times (which every document needs, also one read in program order) are
    /// made the same way.
    pub(crate) async fn on_analysis_after_run<T: Send + 'static>(
        &self,
        uri: &Uri,
        library: Arc<dyn crate::analysis::library::ProgramLibrary>,
        line: usize,
        job: impl FnOnce(&Analysed) -> T + Send + 'static,
    ) -> Result<T> {
        // The common case, a hover on an up-to-date analysis of a block read in program order, is
        // answered here: a block's report replays at most one checkpoint interval (a tenth of a
        // millisecond), less than the two hand-overs to the blocking pool and back cost.
        if let Some(document) = self.documents.get(uri) {
            let revision = document.revision();
            if let Some(slot) = document.try_current(revision) {
                if let Some(analysed) = slot
                    .as_ref()
                    .filter(|analysed| !analysed.may_show_run(line))
                {
                    // A panic must not reach the service's task: it fails this request only, as
                    // one in the blocking pool does.
                    return caught(|| job(analysed))
                        .map_err(|message| self.request_failed(message));
                }
            }
        }
        self.on_analysis_after(uri, library, Some(line), job).await
    }

    /// Like [`Self::on_analysis_after_run`], making the run and the machining times of the
    /// revision first.
    pub(crate) async fn on_analysis_after_times<T: Send + 'static>(
        &self,
        uri: &Uri,
        library: Arc<dyn crate::analysis::library::ProgramLibrary>,
        job: impl FnOnce(&Analysed) -> T + Send + 'static,
    ) -> Result<T> {
        self.on_analysis_after(uri, library, None, job).await
    }

    /// The run (for a request at `Some(line)` that may show it) or the run and the times (`None`).
    /// One job of the blocking pool makes them and then answers: each hand-over between threads
    /// costs a hover tens of microseconds.
    pub(crate) async fn on_analysis_after<T: Send + 'static>(
        &self,
        uri: &Uri,
        library: Arc<dyn crate::analysis::library::ProgramLibrary>,
        line: Option<usize>,
        job: impl FnOnce(&Analysed) -> T + Send + 'static,
    ) -> Result<T> {
        self.in_blocking_pool(uri, move |document, revision| {
            let run = {
                let slot = document.catch_up();
                slot.as_ref()
                    .filter(|analysed| {
                        analysed.revision == revision
                            && line.is_none_or(|line| analysed.may_show_run(line))
                    })
                    .map(|analysed| analysed.execution_job())
            };
            // The analysis is let go while the run is made, so that edits meanwhile are analysed. A
            // run that panicked is not made here again: the job meets that when it asks for the run.
            let _ = caught(|| match (run, line) {
                (Some(run), Some(_)) => {
                    run.run(library.as_ref());
                }
                (Some(run), None) => {
                    run.times(library.as_ref());
                }
                (None, _) => {}
            });
            answer_on(document, revision, job)
        })
        .await
    }

    /// The open document, the revision it had when the request came, and a job that answers the
    /// request on the up-to-date analysis in the blocking pool.
    pub(crate) async fn on_analysis<T: Send + 'static>(
        &self,
        uri: &Uri,
        job: impl FnOnce(&Analysed) -> T + Send + 'static,
    ) -> Result<T> {
        self.in_blocking_pool(uri, move |document, revision| {
            answer_on(document, revision, job)
        })
        .await
    }

    /// `work` on the open document and the revision it had when the request came, in the blocking
    /// pool.
    async fn in_blocking_pool<T: Send + 'static>(
        &self,
        uri: &Uri,
        work: impl FnOnce(Arc<OpenDocument>, u64) -> Result<T> + Send + 'static,
    ) -> Result<T> {
        let document = self.documents.get(uri).ok_or_else(|| not_open(uri))?;
        let revision = document.revision();
        let answer = tokio::task::spawn_blocking(move || work(document, revision)).await;
        answer.unwrap_or_else(|join_error| Err(self.request_failed(join_error)))
    }

    /// The answer to a request whose work panicked, which is logged: the request fails, the server
    /// goes on.
    fn request_failed(&self, why: impl std::fmt::Display) -> Error {
        self.outgoing.log_error(format!("a request failed: {why}"));
        Error::internal_error()
    }

    /// Whether the client shows `$/progress` for a token the server creates.
    pub(crate) fn work_done_progress(&self) -> bool {
        lock(&self.info).work_done_progress
    }
}

/// `job` on the analysis of `document` brought up to date, when it is still of `revision`; the
/// content-modified error when an edit came since.
fn answer_on<T>(
    document: Arc<OpenDocument>,
    revision: u64,
    job: impl FnOnce(&Analysed) -> T,
) -> Result<T> {
    let slot = document.catch_up();
    match slot.as_ref() {
        Some(analysed) if analysed.revision == revision => Ok(job(analysed)),
        _ => Err(content_modified()),
    }
}

/// What `work` returns, or the message of its panic, caught.
fn caught<T>(work: impl FnOnce() -> T) -> std::result::Result<T, String> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(work)).map_err(|payload| {
        payload
            .downcast_ref::<&str>()
            .map(|text| text.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "a panic without a message".to_string())
    })
}

#[cfg(test)]
mod tests {
    use super::caught;

    #[test]
    fn a_panic_is_caught_with_its_message() {
        assert_eq!(caught(|| 7), Ok(7));
        assert_eq!(
            caught(|| -> u8 { panic!("a static text") }),
            Err("a static text".to_string())
        );
        let number = 12;
        assert_eq!(
            caught(|| -> u8 { panic!("a formatted text {number}") }),
            Err("a formatted text 12".to_string())
        );
        assert_eq!(
            caught(|| -> u8 { std::panic::panic_any(3_u32) }),
            Err("a panic without a message".to_string())
        );
    }
}
