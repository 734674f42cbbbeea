//! The `LanguageServer` implementation: it only dispatches. Notifications that change documents do
//! their work synchronously before any `.await` (tower-lsp-server runs up to four handlers at once,
//! so that is what keeps edits in order); requests run their feature on the analysis in the blocking
//! pool and answer "content modified" when the document changed meanwhile.

use crate::analysis::library::ProgramLibrary;
use crate::lsp::capabilities::{client_info, server_capabilities};
use crate::lsp::configuration::{apply_settings, request_configuration, watch_files};
use crate::lsp::convert::PositionEncoding;
use crate::lsp::documents::{Analysed, Documents, OpenDocument};
use crate::lsp::ext::{DocumentTextParams, DocumentTextResult, ModalStateParams, ModalStateResult};
use crate::lsp::handlers::code_action::code_actions;
use crate::lsp::handlers::config_fixes;
use crate::lsp::handlers::endpoint_preview;
use crate::lsp::handlers::hover::hover;
use crate::lsp::handlers::inlay::inlay_hints;
use crate::lsp::handlers::rewrite_commands;
use crate::lsp::handlers::{completion, navigation, outline, semantic, signature};
use crate::lsp::locks::lock;
use crate::lsp::log::HandlerTimer;
use crate::lsp::settings::Settings;
use crate::lsp::state::{not_open, ClientInfo, DocumentRequest, Shared};
use crate::lsp::text_document::ChangeError;
use crate::lsp::transport::outbox::OutgoingSender;
use crate::lsp::uris::{file_path, program_kind};
use crate::lsp::workspace::index::Workspace;
use crate::lsp::workspace::library::workspace_library;
use crate::lsp::workspace::updates;
use serde_json::Value;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use tower_lsp_server::jsonrpc::{Error, Result};
use tower_lsp_server::ls_types::*;
use tower_lsp_server::{Client, LanguageServer};

/// Set by `shutdown`: the process's exit code depends on it (the protocol asks for 1 when the client
/// exits without shutting the server down first). One server runs per process.
pub static SHUTDOWN_REQUESTED: std::sync::atomic::AtomicBool =
    std::sync::atomic::AtomicBool::new(false);

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
}

impl Backend {
    /// `sinumerik/modalState`.
    pub async fn modal_state(&self, params: ModalStateParams) -> Result<ModalStateResult> {
        let _timer = HandlerTimer::new("sinumerik/modalState", &self.outgoing);
        let line = params.line as usize;
        let library = self.library_of(&params.uri);
        let warm = Arc::clone(&library);
        self.on_analysis_after_times(&params.uri, warm, move |analysed| {
            crate::lsp::handlers::modal_state::modal_state_at(analysed, library.as_ref(), line)
        })
        .await
    }

    /// `sinumerik/documentText`.
    pub async fn document_text(&self, params: DocumentTextParams) -> Result<DocumentTextResult> {
        let document = self
            .documents
            .get(&params.uri)
            .ok_or_else(|| not_open(&params.uri))?;
        let (version, text) = document.text_now();
        Ok(DocumentTextResult { version, text })
    }

    /// What the features need of a request about the document at `uri`.
    fn request(&self, uri: Uri) -> DocumentRequest {
        DocumentRequest {
            shared: Arc::clone(&self.shared),
            uri,
            encoding: self.encoding(),
        }
    }

    /// The library through which the run of the document at `uri` finds the programs it calls.
    fn library_of(&self, uri: &Uri) -> Arc<dyn ProgramLibrary> {
        workspace_library(&self.shared, file_path(uri).as_deref())
    }

    /// A request about the document at `uri`, timed as `method`: `job` answers it on the document's
    /// up-to-date analysis in the blocking pool, or it fails with "content modified" when an edit
    /// came meanwhile.
    async fn answer<T: Send + 'static>(
        &self,
        method: &'static str,
        uri: Uri,
        job: impl FnOnce(&DocumentRequest, &Analysed) -> T + Send + 'static,
    ) -> Result<T> {
        let _timer = HandlerTimer::new(method, &self.outgoing);
        let request = self.request(uri);
        let uri = request.uri.clone();
        self.on_analysis(&uri, move |analysed| job(&request, analysed))
            .await
    }
}

impl LanguageServer for Backend {
    async fn initialize(&self, params: InitializeParams) -> Result<InitializeResult> {
        let _timer = HandlerTimer::new("initialize", &self.outgoing);
        let info = client_info(&params);
        let encoding = info.encoding.unwrap_or(PositionEncoding::Utf16);
        *lock(&self.info) = info;
        if let Some(options) = &params.initialization_options {
            if let Err(message) = lock(&self.settings).apply(options) {
                self.warn(format!("initializationOptions: {message}"));
            }
        }
        Ok(InitializeResult {
            capabilities: server_capabilities(encoding),
            server_info: Some(ServerInfo {
                name: "sinumerik-lsp".to_string(),
                version: Some(env!("CARGO_PKG_VERSION").to_string()),
            }),
            ..InitializeResult::default()
        })
    }

    async fn initialized(&self, _: InitializedParams) {
        if lock(&self.info).pulls_configuration {
            request_configuration(&self.shared);
        }
        if lock(&self.info).watches_files {
            watch_files(&self.shared);
        }
        updates::reindex(&self.shared);
    }

    async fn shutdown(&self) -> Result<()> {
        SHUTDOWN_REQUESTED.store(true, std::sync::atomic::Ordering::SeqCst);
        self.workspace.cancel();
        Ok(())
    }

    async fn did_open(&self, params: DidOpenTextDocumentParams) {
        let _timer = HandlerTimer::new("textDocument/didOpen", &self.outgoing);
        let mut item = params.text_document;
        // The first analysis reads the string; the rope is built from it afterwards (`opened_text.rs`).
        let text = std::mem::take(&mut item.text);
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
        updates::document_changed(&self.shared, &item.uri);
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
            Ok(()) => updates::document_changed(&self.shared, &uri),
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
                    updates::document_closed(&self.shared, &uri);
                }
            }
        }
    }

    async fn did_close(&self, params: DidCloseTextDocumentParams) {
        let uri = params.text_document.uri;
        match self.documents.remove(&uri) {
            Some(document) => {
                document.close(&self.context());
                updates::document_closed(&self.shared, &uri);
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
            apply_settings(&self.shared, &params.settings);
        } else if lock(&self.info).pulls_configuration {
            // The "pull" style: the notification only says that something changed.
            request_configuration(&self.shared);
        }
    }

    async fn did_change_watched_files(&self, params: DidChangeWatchedFilesParams) {
        updates::files_changed(&self.shared, params.changes);
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
        updates::reindex(&self.shared);
    }

    async fn hover(&self, params: HoverParams) -> Result<Option<Hover>> {
        let _timer = HandlerTimer::new("textDocument/hover", &self.outgoing);
        let at = params.text_document_position_params;
        let request = self.request(at.text_document.uri);
        let library = self.library_of(&request.uri);
        let warm = Arc::clone(&library);
        let line = at.position.line as usize;
        let uri = request.uri.clone();
        self.on_analysis_after_run(&uri, warm, line, move |analysed| {
            hover(
                analysed,
                library.as_ref(),
                at.position,
                request.encoding,
                |line_text, line, byte| {
                    navigation::documentation(&request, analysed, line_text, line, byte)
                },
            )
        })
        .await
    }

    async fn goto_definition(
        &self,
        params: GotoDefinitionParams,
    ) -> Result<Option<GotoDefinitionResponse>> {
        let at = params.text_document_position_params;
        let uri = at.text_document.uri;
        self.answer("textDocument/definition", uri, move |request, analysed| {
            let found = navigation::definition(request, analysed, at.position);
            (!found.is_empty()).then_some(GotoDefinitionResponse::Array(found))
        })
        .await
    }

    async fn references(&self, params: ReferenceParams) -> Result<Option<Vec<Location>>> {
        let at = params.text_document_position;
        let include_declaration = params.context.include_declaration;
        let uri = at.text_document.uri;
        self.answer("textDocument/references", uri, move |request, analysed| {
            Some(navigation::references(
                request,
                analysed,
                at.position,
                include_declaration,
            ))
        })
        .await
    }

    async fn document_highlight(
        &self,
        params: DocumentHighlightParams,
    ) -> Result<Option<Vec<DocumentHighlight>>> {
        let at = params.text_document_position_params;
        let uri = at.text_document.uri;
        self.answer(
            "textDocument/documentHighlight",
            uri,
            move |request, analysed| Some(navigation::highlights(request, analysed, at.position)),
        )
        .await
    }

    async fn prepare_rename(
        &self,
        params: TextDocumentPositionParams,
    ) -> Result<Option<PrepareRenameResponse>> {
        let uri = params.text_document.uri;
        self.answer(
            "textDocument/prepareRename",
            uri,
            move |request, analysed| navigation::prepare_rename(request, analysed, params.position),
        )
        .await
    }

    async fn rename(&self, params: RenameParams) -> Result<Option<WorkspaceEdit>> {
        let at = params.text_document_position;
        let new_name = params.new_name;
        self.answer(
            "textDocument/rename",
            at.text_document.uri,
            move |request, analysed| navigation::rename(request, analysed, at.position, &new_name),
        )
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
        let at = params.text_document_position;
        let snippets = lock(&self.info).snippets;
        let uri = at.text_document.uri;
        self.answer("textDocument/completion", uri, move |request, analysed| {
            let items = completion::completion_items(request, analysed, at.position, snippets);
            Some(CompletionResponse::Array(items))
        })
        .await
    }

    async fn signature_help(&self, params: SignatureHelpParams) -> Result<Option<SignatureHelp>> {
        let at = params.text_document_position_params;
        let uri = at.text_document.uri;
        self.answer(
            "textDocument/signatureHelp",
            uri,
            move |request, analysed| signature::signature(request, analysed, at.position),
        )
        .await
    }

    async fn semantic_tokens_full(
        &self,
        params: SemanticTokensParams,
    ) -> Result<Option<SemanticTokensResult>> {
        let uri = params.text_document.uri;
        self.answer(
            "textDocument/semanticTokens/full",
            uri,
            |request, analysed| {
                let tokens = semantic::tokens(request, analysed, None);
                Some(SemanticTokensResult::Tokens(tokens))
            },
        )
        .await
    }

    async fn semantic_tokens_range(
        &self,
        params: SemanticTokensRangeParams,
    ) -> Result<Option<SemanticTokensRangeResult>> {
        let uri = params.text_document.uri;
        self.answer(
            "textDocument/semanticTokens/range",
            uri,
            move |request, analysed| {
                let tokens = semantic::tokens(request, analysed, Some(params.range));
                Some(SemanticTokensRangeResult::Tokens(tokens))
            },
        )
        .await
    }

    async fn document_symbol(
        &self,
        params: DocumentSymbolParams,
    ) -> Result<Option<DocumentSymbolResponse>> {
        let uri = params.text_document.uri;
        self.answer("textDocument/documentSymbol", uri, |request, analysed| {
            let symbols = outline::document_symbols(analysed, request.encoding);
            Some(DocumentSymbolResponse::Nested(symbols))
        })
        .await
    }

    async fn folding_range(&self, params: FoldingRangeParams) -> Result<Option<Vec<FoldingRange>>> {
        let uri = params.text_document.uri;
        self.answer("textDocument/foldingRange", uri, |_, analysed| {
            Some(outline::folding_ranges(analysed))
        })
        .await
    }

    async fn formatting(&self, params: DocumentFormattingParams) -> Result<Option<Vec<TextEdit>>> {
        let uri = params.text_document.uri;
        self.answer("textDocument/formatting", uri, |request, analysed| {
            Some(rewrite_commands::formatting_edits(
                analysed,
                None,
                request.encoding,
            ))
        })
        .await
    }

    async fn range_formatting(
        &self,
        params: DocumentRangeFormattingParams,
    ) -> Result<Option<Vec<TextEdit>>> {
        let (uri, range) = (params.text_document.uri, params.range);
        self.answer(
            "textDocument/rangeFormatting",
            uri,
            move |request, analysed| {
                Some(rewrite_commands::formatting_edits(
                    analysed,
                    Some(range),
                    request.encoding,
                ))
            },
        )
        .await
    }

    async fn inlay_hint(&self, params: InlayHintParams) -> Result<Option<Vec<InlayHint>>> {
        let mode = lock(&self.settings).inlay_hints;
        let library = self.library_of(&params.text_document.uri);
        let (uri, range) = (params.text_document.uri, params.range);
        self.answer("textDocument/inlayHint", uri, move |request, analysed| {
            Some(inlay_hints(
                analysed,
                library.as_ref(),
                range,
                mode,
                request.encoding,
            ))
        })
        .await
    }

    async fn code_action(&self, params: CodeActionParams) -> Result<Option<CodeActionResponse>> {
        let range = params.range;
        let settings = lock(&self.settings).clone();
        let root = lock(&self.info).workspace_root.clone();
        let uri = params.text_document.uri;
        self.answer("textDocument/codeAction", uri, move |request, analysed| {
            let (uri, encoding) = (&request.uri, request.encoding);
            let path = file_path(uri);
            let mut actions = code_actions(analysed, uri, range, encoding);
            actions.extend(config_fixes::actions_for(
                analysed,
                range,
                path.as_deref(),
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
        endpoint_preview::execute(&self.shared, &params.command, &params.arguments).await
    }
}
