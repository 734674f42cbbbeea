//! The language server: the only module that knows the Language Server Protocol. Everything below
//! it (`analysis`, `syntax`, `config`, `diagnostics`) speaks in lines, byte spans and plain values;
//! this module converts at its edge (`convert.rs`).
//!
//! - `server.rs`: the `LanguageServer` implementation; dispatch, settings, capabilities.
//! - `documents.rs`: open documents, their analysis on snapshots, the worker that publishes.
//! - `text_document.rs`: rope text, `apply_changes`, the lines an edit touched, `LineSource`.
//! - `convert.rs`: positions in the negotiated encoding, spans to ranges, diagnostics.
//! - `publish/`: diagnostics publication (the `maxDiagnostics` limit, the one JSON encoder of
//!   diagnostics, reuse of the unchanged items from one publication to the next).
//! - `hover.rs`, `inlay.rs`, `code_action.rs`, `endpoint_preview.rs`: one feature each.
//! - `words.rs`: where the words of a block are, for the cursor.
//! - `settings.rs`: settings and each document's machine configuration; `ext.rs`: own protocol types.
//! - `library.rs`: the programs a document calls, found through the workspace index.
//! - `log.rs`: logging and slow-handler reports.
//! - `transport/`: one reader, one framing parser, one writer around the framework's dispatch; the
//!   process's stdio and allocator settings (the crate's only `unsafe`).

mod call_sites;
mod code_action;
mod completion;
mod config_fixes;
mod convert;
mod cross_file;
mod documents;
mod endpoint_preview;
mod ext;
mod hover;
mod hover_resolution;
mod inlay;
mod library;
mod log;
mod modal_state;
mod navigation;
mod numbers;
mod outline;
mod publish;
mod rewrite_commands;
mod semantic;
mod server;
mod settings;
mod signature;
mod text_document;
mod transport;
mod words;
mod workspace;
mod workspace_edit;

pub use convert::PositionEncoding;
pub use ext::{EndpointPreviewParams, ENDPOINT_PREVIEW_COMMAND};
pub use rewrite_commands::{FORMAT_COMMAND, RENUMBER_COMMAND};
// For the fuzzer (examples/fuzz): the framing parser and the encoding of diagnostics.
pub use publish::{publication as publication_body, ranges as diagnostic_ranges, Publisher};
pub use text_document::{apply_changes, DocumentText, LineChange, RopeLineChange, RopeLines};
pub use transport::framing::{Frame, Framer};
pub use transport::message::{read_message, Incoming, InitializeGate};

use tokio::io::{AsyncRead, AsyncWrite};
use tower_lsp_server::LspService;

/// The service: the `LanguageServer` implementation with the server's own methods.
fn service(
    outgoing: transport::outbox::OutgoingSender,
) -> (LspService<server::Backend>, tower_lsp_server::ClientSocket) {
    LspService::build(move |client| server::Backend::new(client, outgoing))
        .custom_method(ext::DOCUMENT_TEXT_REQUEST, server::Backend::document_text)
        .custom_method(ext::MODAL_STATE_REQUEST, server::Backend::modal_state)
        .finish()
}

/// Serves the protocol on `input` and `output` until the client sends `exit` or closes the input.
pub async fn serve<I, O>(input: I, output: O)
where
    I: AsyncRead + Unpin + Send + 'static,
    O: AsyncWrite + Unpin + Send + 'static,
{
    transport::serve(input, output, service).await;
}

/// Runs the server on the process's stdin and stdout; returns the exit code.
pub fn serve_stdio() -> u8 {
    if !transport::serve_stdio(service) {
        return 2;
    }
    // The protocol's exit code: 0 after `shutdown`, 1 when the client left without it.
    if server::SHUTDOWN_REQUESTED.load(std::sync::atomic::Ordering::SeqCst) {
        0
    } else {
        1
    }
}
