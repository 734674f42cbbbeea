//! The `LanguageServer` implementation: it only dispatches. Notifications that change documents do
//! their work synchronously before any `.await` (tower-lsp-server runs up to four handlers at once,
//! so that is what keeps edits in order); requests run their feature on the analysis in the blocking
//! pool and answer "content modified" when the document changed meanwhile.

use crate::analysis::ProgramKind;
use crate::lsp::code_action::code_actions;
use crate::lsp::config_fixes;
use crate::lsp::convert::PositionEncoding;
use crate::lsp::documents::{lock, Analysed, Documents, OpenDocument, WorkerContext};
use crate::lsp::endpoint_preview;
use crate::lsp::ext::{
    DocumentTextParams, DocumentTextResult, EndpointPreviewParams, ModalStateParams,
    ModalStateResult, ENDPOINT_PREVIEW_COMMAND,
};
use crate::lsp::hover::hover;
use crate::lsp::inlay::inlay_hints;
use crate::lsp::log::HandlerTimer;
use crate::lsp::rewrite_commands::{self, FORMAT_COMMAND, RENUMBER_COMMAND};
use crate::lsp::settings::{machine_config_for, Settings};
use crate::lsp::text_document::ChangeError;
use crate::lsp::transport::outbox::{Outgoing, OutgoingSender};
use crate::lsp::workspace::{self, Workspace};
use crate::lsp::{completion, navigation, semantic, signature};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::Duration;
use tower_lsp_server::jsonrpc::{Error, ErrorCode, Result};
use tower_lsp_server::ls_types::*;
use tower_lsp_server::{Client, LanguageServer};

/// How long the server waits for the client's answer to `workspace/configuration`.
const CONFIGURATION_TIMEOUT: Duration = Duration::from_secs(10);

/// Set by `shutdown`: the process's exit code depends on it (the protocol asks for 1 when the client
/// exits without shutting the server down first). One server runs per process.
pub static SHUTDOWN_REQUESTED: std::sync::atomic::AtomicBool =
    std::sync::atomic::AtomicBool::new(false);

/// What the client told at initialize.
#[derive(Debug, Clone, Default)]
struct ClientInfo {
    encoding: Option<PositionEncoding>,
    pulls_configuration: bool,
    refreshes_inlay_hints: bool,
    /// Whether workspace edits may carry document versions (`documentChanges`).
    versioned_edits: bool,
    /// Whether workspace edits may rename files (`resourceOperations` has `rename`). Such edits go
    /// as `documentChanges`, which a client that renames files takes whether or not it says so:
    /// Neovim 0.7 names the operations but not `documentChanges`.
    renames_files: bool,
    /// Whether the client shows `$/progress` for a token the server creates.
    work_done_progress: bool,
    /// Whether `workspace/didChangeWatchedFiles` can be registered dynamically.
    watches_files: bool,
    /// Whether completion items may be snippets.
    snippets: bool,
    workspace_root: Option<PathBuf>,
    /// Every workspace folder (the root URI when the client gave no folders).
    workspace_folders: Vec<PathBuf>,
}

/// The server's state, shared with the tasks it spawns.
pub struct Shared {
    pub(super) client: Client,
    pub(super) documents: Documents,
    pub(super) workspace: Workspace,
    settings: Mutex<Settings>,
    info: Mutex<ClientInfo>,
    outgoing: OutgoingSender,
}

fn content_modified() -> Error {
    Error {
        code: ErrorCode::ServerError(-32801),
        message: "the document changed while the request was answered".into(),
        data: None,
    }
}

fn not_open(uri: &Uri) -> Error {
    Error::invalid_params(format!("the document {} is not open", uri.as_str()))
}

/// The file of a `file:` URI.
pub fn file_path(uri: &Uri) -> Option<PathBuf> {
    let is_file = uri.scheme().as_str().eq_ignore_ascii_case("file");
    if !is_file {
        return None;
    }
    uri.to_file_path().map(|path| path.into_owned())
}

/// The kind of a document by its file name (`_N_PART1_MPF` and `PART1.MPF` are main programs), or by
/// the last segment of its URI when it is not a file.
fn program_kind(uri: &Uri, path: Option<&Path>) -> ProgramKind {
    match path {
        Some(path) => ProgramKind::from_file_name(&path.to_string_lossy()),
        None => ProgramKind::from_file_name(uri.path().as_str()),
    }
}

/// The language server: a handle on the shared state.
pub struct Backend {
    shared: Arc<Shared>,
}

impl std::ops::Deref for Backend {
    type Target = Shared;

    fn deref(&self) -> &Shared {
        &self.shared
    }
}

impl Backend {
    pub fn new(client: Client, outgoing: OutgoingSender) -> Backend {
        let shared = Shared {
            client,
            documents: Documents::default(),
            workspace: Workspace::default(),
            settings: Mutex::new(Settings::default()),
            info: Mutex::new(ClientInfo::default()),
            outgoing,
        };
        Backend {
            shared: Arc::new(shared),
        }
    }

    /// Sends `workspace/configuration` from a task of its own, bounded by a timeout, so no handler
    /// waits for the client (a client that answers late cannot stall the server's input).
    fn request_configuration(&self) {
        let shared = Arc::clone(&self.shared);
        tokio::spawn(async move {
            let request = shared.client.configuration(vec![ConfigurationItem {
                scope_uri: None,
                section: Some("sinumerik".to_string()),
            }]);
            match tokio::time::timeout(CONFIGURATION_TIMEOUT, request).await {
                Ok(Ok(values)) => {
                    if let Some(value) = values.first() {
                        shared.apply_settings(value);
                    }
                }
                Ok(Err(error)) => shared
                    .outgoing
                    .log_warning(format!("workspace/configuration failed: {error}")),
                Err(_) => shared.outgoing.log_warning(
                    "the client did not answer workspace/configuration in time".to_string(),
                ),
            }
        });
    }
}

impl Backend {
    /// `sinumerik/documentText`.
    /// `sinumerik/modalState`.
    pub async fn modal_state(&self, params: ModalStateParams) -> Result<ModalStateResult> {
        let _timer = HandlerTimer::new("sinumerik/modalState", &self.outgoing);
        let line = params.line as usize;
        let library =
            crate::lsp::library::workspace_library(&self.shared, file_path(&params.uri).as_deref());
        let warm = Arc::clone(&library);
        self.on_analysis_after_times(&params.uri, warm, move |analysed| {
            crate::lsp::modal_state::modal_state_at(analysed, library.as_ref(), line)
        })
        .await
    }

    pub async fn document_text(&self, params: DocumentTextParams) -> Result<DocumentTextResult> {
        let document = self
            .documents
            .get(&params.uri)
            .ok_or_else(|| not_open(&params.uri))?;
        let (version, text) = document.text_now();
        Ok(DocumentTextResult { version, text })
    }
}

impl Shared {
    pub(super) fn encoding(&self) -> PositionEncoding {
        lock(&self.info).encoding.unwrap_or(PositionEncoding::Utf16)
    }

    pub(super) fn context(&self) -> WorkerContext {
        WorkerContext {
            outgoing: self.outgoing.clone(),
            encoding: self.encoding(),
            max_diagnostics: lock(&self.settings).max_diagnostics,
        }
    }

    pub(super) fn settings_now(&self) -> Settings {
        lock(&self.settings).clone()
    }

    pub(super) fn workspace_root(&self) -> Option<PathBuf> {
        lock(&self.info).workspace_root.clone()
    }

    /// The folders the index reads: the workspace folders and the configured cycle folders
    /// (relative ones taken from the first workspace folder).
    fn index_roots(&self) -> Vec<PathBuf> {
        let mut roots = lock(&self.info).workspace_folders.clone();
        roots.extend(self.cycle_folders());
        roots
    }

    /// The folders of the `cycleFolders` setting, in its order (relative ones taken from the first
    /// workspace folder).
    pub(super) fn cycle_folders(&self) -> Vec<PathBuf> {
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

    /// Starts indexing the workspace again (at start, and when folders, settings or a
    /// `sinumerik.toml` change); `false` when there is nothing to index (no folder).
    pub(super) fn reindex(self: &Arc<Self>) -> bool {
        let roots = self.index_roots();
        if roots.is_empty() {
            return false;
        }
        let progress = lock(&self.info).work_done_progress;
        workspace::start_indexing(self, roots, progress);
        true
    }

    /// Asks the client to tell about changed program files and configuration files.
    fn watch_files(&self) {
        let client = self.client.clone();
        let outgoing = self.outgoing.clone();
        tokio::spawn(async move {
            let watcher = |pattern: &str| FileSystemWatcher {
                glob_pattern: GlobPattern::String(pattern.to_string()),
                kind: None,
            };
            let options = DidChangeWatchedFilesRegistrationOptions {
                watchers: vec![
                    watcher("**/*.{mpf,spf,def,MPF,SPF,DEF}"),
                    watcher("**/sinumerik.toml"),
                ],
            };
            let registration = Registration {
                id: "sinumerik/watchedFiles".to_string(),
                method: "workspace/didChangeWatchedFiles".to_string(),
                register_options: serde_json::to_value(options).ok(),
            };
            if let Err(error) = client.register_capability(vec![registration]).await {
                outgoing.log_warning(format!("cannot watch the workspace's files: {error}"));
            }
        });
    }

    /// Whether the client takes workspace edits with document versions.
    pub(super) fn versioned_edits(&self) -> bool {
        lock(&self.info).versioned_edits
    }

    /// Whether the client renames files that a workspace edit asks it to rename.
    pub(super) fn renames_files(&self) -> bool {
        lock(&self.info).renames_files
    }

    pub(super) fn warn(&self, message: String) {
        self.outgoing.log_warning(message);
    }

    /// The machine configuration of a document; a configuration file that cannot be used is
    /// reported (the document is still checked, with the defaults).
    pub(super) fn machine_config(&self, path: Option<&Path>) -> Arc<crate::config::MachineConfig> {
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

    /// Applies new settings: documents whose configuration changed are analysed again.
    fn apply_settings(self: &Arc<Self>, value: &Value) {
        let (old, new) = {
            let mut settings = lock(&self.settings);
            let old = settings.clone();
            if let Err(message) = settings.apply(value) {
                self.warn(format!("settings: {message}"));
            }
            (old, settings.clone())
        };
        if old.config_file != new.config_file || old.machine_kind != new.machine_kind {
            let context = self.context();
            for document in self.documents.all() {
                let config = self.machine_config(document.path.as_deref());
                document.set_config(config, &context);
            }
        }
        if old.cycle_folders != new.cycle_folders {
            self.reindex();
        }
        if old.max_diagnostics != new.max_diagnostics {
            let context = self.context();
            for document in self.documents.all() {
                document.republish(&context);
            }
        }
        if old.inlay_hints != new.inlay_hints && lock(&self.info).refreshes_inlay_hints {
            let client = self.client.clone();
            tokio::spawn(async move {
                let _ = client.inlay_hint_refresh().await;
            });
        }
    }

    /// Like [`Self::on_analysis`] for a request that shows the run of the program at `line`: when
    /// the block there is not read in program order (after a label, a jump or a loop, or in a
    /// subprogram), the run of the revision is made first without holding the analysis, so that
    /// edits meanwhile are analysed and published; the job then finds it made. With `times`, the
    /// revision's machining times (which every document needs, also one read in program order) are
    /// made the same way.
    pub(super) async fn on_analysis_after_run<T: Send + 'static>(
        &self,
        uri: &Uri,
        library: Arc<dyn crate::analysis::library::ProgramLibrary>,
        line: usize,
        job: impl FnOnce(&Analysed) -> T + Send + 'static,
    ) -> Result<T> {
        self.on_analysis_after(uri, library, Some(line), job).await
    }

    /// Like [`Self::on_analysis_after_run`], making the run and the machining times of the
    /// revision first.
    pub(super) async fn on_analysis_after_times<T: Send + 'static>(
        &self,
        uri: &Uri,
        library: Arc<dyn crate::analysis::library::ProgramLibrary>,
        job: impl FnOnce(&Analysed) -> T + Send + 'static,
    ) -> Result<T> {
        self.on_analysis_after(uri, library, None, job).await
    }

    /// The run (for a request at `Some(line)` that may show it) or the run and the times (`None`).
    async fn on_analysis_after<T: Send + 'static>(
        &self,
        uri: &Uri,
        library: Arc<dyn crate::analysis::library::ProgramLibrary>,
        line: Option<usize>,
        job: impl FnOnce(&Analysed) -> T + Send + 'static,
    ) -> Result<T> {
        if let Some(document) = self.documents.get(uri) {
            let revision = document.revision();
            let _ = tokio::task::spawn_blocking(move || {
                let run = {
                    let slot = document.catch_up();
                    slot.as_ref()
                        .filter(|analysed| {
                            analysed.revision == revision
                                && line.is_none_or(|line| analysed.may_show_run(line))
                        })
                        .map(|analysed| analysed.execution_job())
                };
                match (run, line) {
                    (Some(run), Some(_)) => {
                        run.run(library.as_ref());
                    }
                    (Some(run), None) => {
                        run.times(library.as_ref());
                    }
                    (None, _) => {}
                }
            })
            .await;
        }
        self.on_analysis(uri, job).await
    }

    /// The open document, the revision it had when the request came, and a job that answers the
    /// request on the up-to-date analysis in the blocking pool.
    pub(super) async fn on_analysis<T: Send + 'static>(
        &self,
        uri: &Uri,
        job: impl FnOnce(&Analysed) -> T + Send + 'static,
    ) -> Result<T> {
        let document = self.documents.get(uri).ok_or_else(|| not_open(uri))?;
        let revision = document.revision();
        let answer = tokio::task::spawn_blocking(move || {
            let slot = document.catch_up();
            match slot.as_ref() {
                Some(analysed) if analysed.revision == revision => Ok(job(analysed)),
                _ => Err(content_modified()),
            }
        })
        .await;
        match answer {
            Ok(result) => result,
            Err(join_error) => {
                self.outgoing
                    .log_error(format!("a request failed: {join_error}"));
                Err(Error::internal_error())
            }
        }
    }
}

impl LanguageServer for Backend {
    async fn initialize(&self, params: InitializeParams) -> Result<InitializeResult> {
        let _timer = HandlerTimer::new("initialize", &self.outgoing);
        let encoding = PositionEncoding::negotiate(
            params
                .capabilities
                .general
                .as_ref()
                .and_then(|general| general.position_encodings.as_deref()),
        );
        let workspace = params.capabilities.workspace.as_ref();
        #[allow(deprecated)]
        let root_uri = params.root_uri.clone();
        let workspace_root = params
            .workspace_folders
            .as_ref()
            .and_then(|folders| folders.first())
            .map(|folder| folder.uri.clone())
            .or(root_uri.clone())
            .as_ref()
            .and_then(file_path);
        let workspace_folders: Vec<PathBuf> = match &params.workspace_folders {
            Some(folders) if !folders.is_empty() => folders
                .iter()
                .filter_map(|folder| file_path(&folder.uri))
                .collect(),
            _ => root_uri.as_ref().and_then(file_path).into_iter().collect(),
        };
        *lock(&self.info) = ClientInfo {
            encoding: Some(encoding),
            pulls_configuration: workspace
                .and_then(|workspace| workspace.configuration)
                .unwrap_or(false),
            refreshes_inlay_hints: workspace
                .and_then(|workspace| workspace.inlay_hint.as_ref())
                .and_then(|inlay| inlay.refresh_support)
                .unwrap_or(false),
            versioned_edits: workspace
                .and_then(|workspace| workspace.workspace_edit.as_ref())
                .and_then(|edit| edit.document_changes)
                .unwrap_or(false),
            renames_files: workspace
                .and_then(|workspace| workspace.workspace_edit.as_ref())
                .and_then(|edit| edit.resource_operations.as_ref())
                .is_some_and(|operations| operations.contains(&ResourceOperationKind::Rename)),
            work_done_progress: params
                .capabilities
                .window
                .as_ref()
                .and_then(|window| window.work_done_progress)
                .unwrap_or(false),
            snippets: params
                .capabilities
                .text_document
                .as_ref()
                .and_then(|text| text.completion.as_ref())
                .and_then(|completion| completion.completion_item.as_ref())
                .and_then(|item| item.snippet_support)
                .unwrap_or(false),
            watches_files: workspace
                .and_then(|workspace| workspace.did_change_watched_files.as_ref())
                .and_then(|watched| watched.dynamic_registration)
                .unwrap_or(false),
            workspace_root,
            workspace_folders,
        };
        if let Some(options) = &params.initialization_options {
            if let Err(message) = lock(&self.settings).apply(options) {
                self.warn(format!("initializationOptions: {message}"));
            }
        }
        Ok(InitializeResult {
            capabilities: ServerCapabilities {
                position_encoding: Some(encoding.kind()),
                text_document_sync: Some(TextDocumentSyncCapability::Options(
                    TextDocumentSyncOptions {
                        open_close: Some(true),
                        change: Some(TextDocumentSyncKind::INCREMENTAL),
                        ..TextDocumentSyncOptions::default()
                    },
                )),
                hover_provider: Some(HoverProviderCapability::Simple(true)),
                code_action_provider: Some(CodeActionProviderCapability::Options(
                    CodeActionOptions {
                        code_action_kinds: Some(vec![CodeActionKind::QUICKFIX]),
                        ..CodeActionOptions::default()
                    },
                )),
                inlay_hint_provider: Some(OneOf::Left(true)),
                document_symbol_provider: Some(OneOf::Left(true)),
                folding_range_provider: Some(FoldingRangeProviderCapability::Simple(true)),
                definition_provider: Some(OneOf::Left(true)),
                references_provider: Some(OneOf::Left(true)),
                document_highlight_provider: Some(OneOf::Left(true)),
                rename_provider: Some(OneOf::Right(RenameOptions {
                    prepare_provider: Some(true),
                    work_done_progress_options: WorkDoneProgressOptions::default(),
                })),
                workspace_symbol_provider: Some(OneOf::Left(true)),
                completion_provider: Some(CompletionOptions {
                    trigger_characters: Some(
                        completion::TRIGGER_CHARACTERS
                            .iter()
                            .map(|character| character.to_string())
                            .collect(),
                    ),
                    ..CompletionOptions::default()
                }),
                signature_help_provider: Some(SignatureHelpOptions {
                    trigger_characters: Some(
                        signature::TRIGGER_CHARACTERS
                            .iter()
                            .map(|character| character.to_string())
                            .collect(),
                    ),
                    ..SignatureHelpOptions::default()
                }),
                semantic_tokens_provider: Some(
                    SemanticTokensServerCapabilities::SemanticTokensOptions(
                        SemanticTokensOptions {
                            legend: semantic::legend(),
                            range: Some(true),
                            full: Some(SemanticTokensFullOptions::Bool(true)),
                            ..SemanticTokensOptions::default()
                        },
                    ),
                ),
                workspace: Some(WorkspaceServerCapabilities {
                    workspace_folders: Some(WorkspaceFoldersServerCapabilities {
                        supported: Some(true),
                        change_notifications: Some(OneOf::Left(true)),
                    }),
                    file_operations: None,
                }),
                document_formatting_provider: Some(OneOf::Left(true)),
                document_range_formatting_provider: Some(OneOf::Left(true)),
                execute_command_provider: Some(ExecuteCommandOptions {
                    commands: vec![
                        ENDPOINT_PREVIEW_COMMAND.to_string(),
                        RENUMBER_COMMAND.to_string(),
                        FORMAT_COMMAND.to_string(),
                    ],
                    ..ExecuteCommandOptions::default()
                }),
                ..ServerCapabilities::default()
            },
            server_info: Some(ServerInfo {
                name: "sinumerik-lsp".to_string(),
                version: Some(env!("CARGO_PKG_VERSION").to_string()),
            }),
            ..InitializeResult::default()
        })
    }

    async fn initialized(&self, _: InitializedParams) {
        if lock(&self.info).pulls_configuration {
            self.request_configuration();
        }
        if lock(&self.info).watches_files {
            self.watch_files();
        }
        self.shared.reindex();
    }

    async fn shutdown(&self) -> Result<()> {
        SHUTDOWN_REQUESTED.store(true, std::sync::atomic::Ordering::SeqCst);
        self.workspace.cancel();
        Ok(())
    }

    async fn did_open(&self, params: DidOpenTextDocumentParams) {
        let _timer = HandlerTimer::new("textDocument/didOpen", &self.outgoing);
        let mut item = params.text_document;
        // The string goes as soon as the rope holds the text: a large program is not kept twice.
        let text = ropey::Rope::from_str(&std::mem::take(&mut item.text));
        let path = file_path(&item.uri);
        let kind = program_kind(&item.uri, path.as_deref());
        let config = self.machine_config(path.as_deref());
        let document = Arc::new(OpenDocument::new(
            item.uri.clone(),
            path,
            kind,
            text,
            item.version,
            config,
        ));
        let context = self.context();
        if let Some(replaced) = self.documents.insert(Arc::clone(&document)) {
            self.warn(format!(
                "{} was opened again without being closed; the new text replaces the old",
                item.uri.as_str()
            ));
            replaced.close(&context);
        }
        document.start(&context);
        workspace::document_changed(&self.shared, &item.uri);
    }

    async fn did_change(&self, params: DidChangeTextDocumentParams) {
        let _timer = HandlerTimer::new("textDocument/didChange", &self.outgoing);
        let uri = params.text_document.uri;
        let Some(document) = self.documents.get(&uri) else {
            self.warn(format!(
                "an edit of {}, which is not open, is ignored",
                uri.as_str()
            ));
            return;
        };
        let context = self.context();
        match document.change(
            &params.content_changes,
            params.text_document.version,
            &context,
        ) {
            Ok(()) => workspace::document_changed(&self.shared, &uri),
            Err(error @ ChangeError::StaleVersion { .. }) => {
                self.warn(format!("{}: {error}", uri.as_str()));
            }
            Err(error @ ChangeError::ReversedRange { .. }) => {
                self.outgoing.log_error(format!(
                    "{}: {error}; the document is out of step with the editor and is dropped until it is opened again",
                    uri.as_str()
                ));
                if let Some(document) = self.documents.remove(&uri) {
                    document.close(&context);
                    workspace::document_closed(&self.shared, &uri);
                }
            }
        }
    }

    async fn did_close(&self, params: DidCloseTextDocumentParams) {
        let uri = params.text_document.uri;
        match self.documents.remove(&uri) {
            Some(document) => {
                document.close(&self.context());
                workspace::document_closed(&self.shared, &uri);
            }
            None => self.warn(format!("{} was closed but was not open", uri.as_str())),
        }
    }

    async fn did_change_configuration(&self, params: DidChangeConfigurationParams) {
        let has_settings = match &params.settings {
            Value::Null => false,
            Value::Object(map) => !map.is_empty(),
            _ => true,
        };
        if has_settings {
            self.shared.apply_settings(&params.settings);
        } else if lock(&self.info).pulls_configuration {
            // The "pull" style: the notification only says that something changed.
            self.request_configuration();
        }
    }

    async fn did_change_watched_files(&self, params: DidChangeWatchedFilesParams) {
        workspace::files_changed(&self.shared, params.changes);
    }

    async fn did_change_workspace_folders(&self, params: DidChangeWorkspaceFoldersParams) {
        {
            let mut info = lock(&self.info);
            let removed: Vec<PathBuf> = params
                .event
                .removed
                .iter()
                .filter_map(|folder| file_path(&folder.uri))
                .collect();
            info.workspace_folders
                .retain(|folder| !removed.contains(folder));
            info.workspace_folders.extend(
                params
                    .event
                    .added
                    .iter()
                    .filter_map(|folder| file_path(&folder.uri)),
            );
        }
        self.shared.reindex();
    }

    async fn hover(&self, params: HoverParams) -> Result<Option<Hover>> {
        let _timer = HandlerTimer::new("textDocument/hover", &self.outgoing);
        let position = params.text_document_position_params.position;
        let encoding = self.encoding();
        let uri = params.text_document_position_params.text_document.uri;
        let shared = Arc::clone(&self.shared);
        let document_uri = uri.clone();
        let library = crate::lsp::library::workspace_library(&shared, file_path(&uri).as_deref());
        let warm = Arc::clone(&library);
        let line = position.line as usize;
        self.on_analysis_after_run(&uri, warm, line, move |analysed| {
            hover(
                analysed,
                library.as_ref(),
                position,
                encoding,
                |line_text, line, byte| {
                    navigation::documentation(
                        &shared,
                        analysed,
                        &document_uri,
                        line_text,
                        line,
                        byte,
                    )
                },
            )
        })
        .await
    }

    async fn goto_definition(
        &self,
        params: GotoDefinitionParams,
    ) -> Result<Option<GotoDefinitionResponse>> {
        let _timer = HandlerTimer::new("textDocument/definition", &self.outgoing);
        let position = params.text_document_position_params.position;
        let uri = params.text_document_position_params.text_document.uri;
        let (shared, encoding, document_uri) =
            (Arc::clone(&self.shared), self.encoding(), uri.clone());
        self.on_analysis(&uri, move |analysed| {
            let found =
                navigation::definition(&shared, analysed, &document_uri, position, encoding);
            (!found.is_empty()).then_some(GotoDefinitionResponse::Array(found))
        })
        .await
    }

    async fn references(&self, params: ReferenceParams) -> Result<Option<Vec<Location>>> {
        let _timer = HandlerTimer::new("textDocument/references", &self.outgoing);
        let position = params.text_document_position.position;
        let uri = params.text_document_position.text_document.uri;
        let include_declaration = params.context.include_declaration;
        let (shared, encoding, document_uri) =
            (Arc::clone(&self.shared), self.encoding(), uri.clone());
        self.on_analysis(&uri, move |analysed| {
            Some(navigation::references(
                &shared,
                analysed,
                &document_uri,
                position,
                include_declaration,
                encoding,
            ))
        })
        .await
    }

    async fn document_highlight(
        &self,
        params: DocumentHighlightParams,
    ) -> Result<Option<Vec<DocumentHighlight>>> {
        let _timer = HandlerTimer::new("textDocument/documentHighlight", &self.outgoing);
        let position = params.text_document_position_params.position;
        let uri = params.text_document_position_params.text_document.uri;
        let (shared, encoding, document_uri) =
            (Arc::clone(&self.shared), self.encoding(), uri.clone());
        self.on_analysis(&uri, move |analysed| {
            Some(navigation::highlights(
                &shared,
                analysed,
                &document_uri,
                position,
                encoding,
            ))
        })
        .await
    }

    async fn prepare_rename(
        &self,
        params: TextDocumentPositionParams,
    ) -> Result<Option<PrepareRenameResponse>> {
        let _timer = HandlerTimer::new("textDocument/prepareRename", &self.outgoing);
        let position = params.position;
        let uri = params.text_document.uri;
        let (shared, encoding, document_uri) =
            (Arc::clone(&self.shared), self.encoding(), uri.clone());
        self.on_analysis(&uri, move |analysed| {
            navigation::prepare_rename(&shared, analysed, &document_uri, position, encoding)
        })
        .await
    }

    async fn rename(&self, params: RenameParams) -> Result<Option<WorkspaceEdit>> {
        let _timer = HandlerTimer::new("textDocument/rename", &self.outgoing);
        let position = params.text_document_position.position;
        let uri = params.text_document_position.text_document.uri;
        let new_name = params.new_name;
        let (shared, encoding, document_uri) =
            (Arc::clone(&self.shared), self.encoding(), uri.clone());
        self.on_analysis(&uri, move |analysed| {
            navigation::rename(
                &shared,
                analysed,
                &document_uri,
                position,
                &new_name,
                encoding,
            )
        })
        .await?
        .map(Some)
    }

    async fn symbol(
        &self,
        params: WorkspaceSymbolParams,
    ) -> Result<Option<WorkspaceSymbolResponse>> {
        let _timer = HandlerTimer::new("workspace/symbol", &self.outgoing);
        let (shared, encoding) = (Arc::clone(&self.shared), self.encoding());
        let found = tokio::task::spawn_blocking(move || {
            navigation::workspace_symbols(&shared, &params.query, encoding)
        })
        .await
        .map_err(|_| Error::internal_error())?;
        Ok(Some(WorkspaceSymbolResponse::Flat(found)))
    }

    async fn completion(&self, params: CompletionParams) -> Result<Option<CompletionResponse>> {
        let _timer = HandlerTimer::new("textDocument/completion", &self.outgoing);
        let position = params.text_document_position.position;
        let uri = params.text_document_position.text_document.uri;
        let snippets = lock(&self.info).snippets;
        let (shared, encoding, document_uri) =
            (Arc::clone(&self.shared), self.encoding(), uri.clone());
        self.on_analysis(&uri, move |analysed| {
            Some(CompletionResponse::Array(completion::completion_items(
                &shared,
                analysed,
                &document_uri,
                position,
                snippets,
                encoding,
            )))
        })
        .await
    }

    async fn signature_help(&self, params: SignatureHelpParams) -> Result<Option<SignatureHelp>> {
        let _timer = HandlerTimer::new("textDocument/signatureHelp", &self.outgoing);
        let position = params.text_document_position_params.position;
        let uri = params.text_document_position_params.text_document.uri;
        let (shared, encoding, document_uri) =
            (Arc::clone(&self.shared), self.encoding(), uri.clone());
        self.on_analysis(&uri, move |analysed| {
            signature::signature(&shared, analysed, &document_uri, position, encoding)
        })
        .await
    }

    async fn semantic_tokens_full(
        &self,
        params: SemanticTokensParams,
    ) -> Result<Option<SemanticTokensResult>> {
        let _timer = HandlerTimer::new("textDocument/semanticTokens/full", &self.outgoing);
        let uri = params.text_document.uri;
        let (shared, encoding, document_uri) =
            (Arc::clone(&self.shared), self.encoding(), uri.clone());
        self.on_analysis(&uri, move |analysed| {
            Some(SemanticTokensResult::Tokens(semantic::tokens(
                &shared,
                analysed,
                &document_uri,
                None,
                encoding,
            )))
        })
        .await
    }

    async fn semantic_tokens_range(
        &self,
        params: SemanticTokensRangeParams,
    ) -> Result<Option<SemanticTokensRangeResult>> {
        let _timer = HandlerTimer::new("textDocument/semanticTokens/range", &self.outgoing);
        let uri = params.text_document.uri;
        let range = params.range;
        let (shared, encoding, document_uri) =
            (Arc::clone(&self.shared), self.encoding(), uri.clone());
        self.on_analysis(&uri, move |analysed| {
            Some(SemanticTokensRangeResult::Tokens(semantic::tokens(
                &shared,
                analysed,
                &document_uri,
                Some(range),
                encoding,
            )))
        })
        .await
    }

    async fn document_symbol(
        &self,
        params: DocumentSymbolParams,
    ) -> Result<Option<DocumentSymbolResponse>> {
        let _timer = HandlerTimer::new("textDocument/documentSymbol", &self.outgoing);
        let encoding = self.encoding();
        self.on_analysis(&params.text_document.uri, move |analysed| {
            Some(DocumentSymbolResponse::Nested(
                crate::lsp::outline::document_symbols(analysed, encoding),
            ))
        })
        .await
    }

    async fn folding_range(&self, params: FoldingRangeParams) -> Result<Option<Vec<FoldingRange>>> {
        let _timer = HandlerTimer::new("textDocument/foldingRange", &self.outgoing);
        self.on_analysis(&params.text_document.uri, |analysed| {
            Some(crate::lsp::outline::folding_ranges(analysed))
        })
        .await
    }

    async fn formatting(&self, params: DocumentFormattingParams) -> Result<Option<Vec<TextEdit>>> {
        let _timer = HandlerTimer::new("textDocument/formatting", &self.outgoing);
        let encoding = self.encoding();
        self.on_analysis(&params.text_document.uri, move |analysed| {
            Some(rewrite_commands::formatting_edits(analysed, None, encoding))
        })
        .await
    }

    async fn range_formatting(
        &self,
        params: DocumentRangeFormattingParams,
    ) -> Result<Option<Vec<TextEdit>>> {
        let _timer = HandlerTimer::new("textDocument/rangeFormatting", &self.outgoing);
        let encoding = self.encoding();
        let range = params.range;
        self.on_analysis(&params.text_document.uri, move |analysed| {
            Some(rewrite_commands::formatting_edits(
                analysed,
                Some(range),
                encoding,
            ))
        })
        .await
    }

    async fn inlay_hint(&self, params: InlayHintParams) -> Result<Option<Vec<InlayHint>>> {
        let _timer = HandlerTimer::new("textDocument/inlayHint", &self.outgoing);
        let mode = lock(&self.settings).inlay_hints;
        let encoding = self.encoding();
        let range = params.range;
        let library = crate::lsp::library::workspace_library(
            &self.shared,
            file_path(&params.text_document.uri).as_deref(),
        );
        self.on_analysis(&params.text_document.uri, move |analysed| {
            Some(inlay_hints(
                analysed,
                library.as_ref(),
                range,
                mode,
                encoding,
            ))
        })
        .await
    }

    async fn code_action(&self, params: CodeActionParams) -> Result<Option<CodeActionResponse>> {
        let _timer = HandlerTimer::new("textDocument/codeAction", &self.outgoing);
        let encoding = self.encoding();
        let uri = params.text_document.uri.clone();
        let range = params.range;
        let settings = lock(&self.settings).clone();
        let root = lock(&self.info).workspace_root.clone();
        let document_path = file_path(&uri);
        self.on_analysis(&params.text_document.uri, move |analysed| {
            let mut actions = code_actions(analysed, &uri, range, encoding);
            actions.extend(config_fixes::actions_for(
                analysed,
                range,
                document_path.as_deref(),
                &settings,
                root.as_deref(),
                encoding,
            ));
            Some(actions)
        })
        .await
    }

    async fn execute_command(&self, params: ExecuteCommandParams) -> Result<Option<Value>> {
        let _timer = HandlerTimer::new("workspace/executeCommand", &self.outgoing);
        if rewrite_commands::is_rewrite_command(&params.command) {
            return rewrite_commands::execute(&self.shared, &params.command, &params.arguments)
                .await;
        }
        if params.command != ENDPOINT_PREVIEW_COMMAND {
            return Err(Error::invalid_params(format!(
                "unknown command {}",
                params.command
            )));
        }
        let [argument] = params.arguments.as_slice() else {
            return Err(Error::invalid_params(format!(
                "{ENDPOINT_PREVIEW_COMMAND} takes one argument {{\"uri\", \"startLine\"?, \"endLine\"?}}"
            )));
        };
        let preview: EndpointPreviewParams =
            serde_json::from_value(argument.clone()).map_err(|error| {
                Error::invalid_params(format!("{ENDPOINT_PREVIEW_COMMAND}: {error}"))
            })?;
        let lines = endpoint_preview::LineSelection {
            start: preview.start_line,
            end: preview.end_line,
        };
        let label = file_path(&preview.uri)
            .map(|path| path.display().to_string())
            .unwrap_or_else(|| preview.uri.as_str().to_string());
        let library = crate::lsp::library::workspace_library(
            &self.shared,
            file_path(&preview.uri).as_deref(),
        );
        if self.documents.get(&preview.uri).is_some() {
            let result = self
                .on_analysis(&preview.uri, move |analysed| {
                    endpoint_preview::preview_open(analysed, &label, lines, library.as_ref())
                })
                .await?;
            return result.map(Some).map_err(Error::invalid_params);
        }
        let path = file_path(&preview.uri).ok_or_else(|| {
            Error::invalid_params(format!(
                "{} is neither open nor a file: URI",
                preview.uri.as_str()
            ))
        })?;
        let config = self.machine_config(Some(&path));
        let kind = program_kind(&preview.uri, Some(&path));
        let result = tokio::task::spawn_blocking(move || {
            endpoint_preview::preview_file(&path, &label, config, kind, lines, library.as_ref())
        })
        .await
        .map_err(|_| Error::internal_error())?;
        result.map(Some).map_err(Error::invalid_params)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::str::FromStr;

    #[test]
    fn a_document_s_kind_comes_from_its_file_name() {
        let kind = |uri: &str| {
            let uri = Uri::from_str(uri).unwrap();
            program_kind(&uri, file_path(&uri).as_deref())
        };
        assert_eq!(kind("file:///nc/_N_MAIN_MPF"), ProgramKind::Main);
        assert_eq!(kind("file:///nc/_N_MAIN_SPF"), ProgramKind::Subprogram);
        assert_eq!(kind("file:///nc/main.mpf"), ProgramKind::Main);
        assert_eq!(kind("untitled:_N_MAIN_MPF"), ProgramKind::Main);
        assert_eq!(kind("untitled:Untitled-1"), ProgramKind::Subprogram);
    }
}
