//! The language server: the only module that knows the Language Server Protocol. Everything below
//! it (`analysis`, `syntax`, `config`, `diagnostics`) speaks in lines, byte spans and plain values;
//! this module converts at its edge (`convert.rs`).
//!
//! - `server.rs`: the `LanguageServer` implementation, which only dispatches; `state.rs`: the state
//!   it shares with its tasks; `capabilities.rs`: `initialize`; `configuration.rs`: the settings.
//! - `handlers/`: one file per feature, converting the core's answers to LSP types.
//! - `workspace/`: the workspace index, its updates, the libraries of open documents.
//! - `documents/`: open documents, their analysis on snapshots, the worker that publishes (a
//!   `didOpen`'s first analysis read from its string, `opened_text.rs`, before the rope is built);
//!   `execution_job.rs`: the run of a revision; `text_document.rs`: rope text, `apply_changes`;
//!   `convert.rs`: positions in the negotiated encoding, spans to ranges, diagnostics;
//!   `cross_file.rs`: the W3xx findings joined to the published diagnostics.
//! - `publish/`: diagnostics publication (the `maxDiagnostics` limit, the one JSON encoder of
//!   diagnostics, reuse of the unchanged items from one publication to the next).
//! - `transport/`: one reader, one framing parser, one writer around the framework's dispatch; in
//!   `sys/`, the crate's only `unsafe`: the process's stdio and allocator settings, and frozen pages
//!   handed to the stdout pipe; `log.rs`: logging and slow-handler reports.
//! - `settings.rs`, `ext.rs`, `uris.rs`, `locks.rs`: settings, own protocol types, URIs, locks.

mod capabilities;
mod configuration;
mod convert;
mod cross_file;
mod documents;
mod execution_job;
mod ext;
mod handlers;
mod locks;
mod log;
mod opened_text;
mod publish;
mod server;
mod settings;
mod state;
mod text_document;
mod transport;
mod uris;
mod workspace;

pub use convert::PositionEncoding;
pub use ext::{EndpointPreviewParams, ENDPOINT_PREVIEW_COMMAND};
pub use handlers::rewrite_commands::{FORMAT_COMMAND, RENUMBER_COMMAND};
// For the fuzzer (examples/fuzz): the framing parser and the encoding of diagnostics.
pub use publish::{publication as publication_body, ranges as diagnostic_ranges, Publisher};
pub use text_document::{apply_changes, DocumentText, LineChange, RopeLineChange};
pub use transport::framing::{Frame, Framer};
pub use transport::message::{read_message, read_owned_message, Incoming, InitializeGate};

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
