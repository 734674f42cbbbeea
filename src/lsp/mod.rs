//! The language server: the only module that knows the Language Server Protocol. Everything below
//! it (`analysis`, `syntax`, `config`, `diagnostics`) speaks in lines, byte spans and plain values;
//! this module converts at its edge (`convert.rs`).
//!
//! - `server.rs`: the `LanguageServer` implementation, which only dispatches; `state.rs`: the state
//!   it shares with its tasks; `capabilities.rs`: `initialize`; `configuration.rs`: the settings.
//! - `handlers/`: one file per feature, converting the core's answers to LSP types.
//! - `workspace/`: the workspace index, its updates, the libraries of open documents.
//! - `documents.rs`: open documents, their analysis on snapshots, the worker that publishes;
//!   `execution_job.rs`: the run of a revision; `text_document.rs`: rope text, `apply_changes`;
//!   `convert.rs`: positions in the negotiated encoding, spans to ranges, diagnostics;
//!   `cross_file.rs`: the W3xx findings joined to the published diagnostics.
//! - `diagnostics_array.rs`, `diagnostics_limit.rs`: the published diagnostics' JSON.
//! - `outgoing.rs`, `log.rs`, `framing.rs`, `arriving_open.rs`, `open_texts.rs`, `json_string.rs`,
//!   `stdio.rs`, `frozen_bytes.rs`, `memory.rs`: the transport (input guard, output, stdio).
//! - `settings.rs`, `ext.rs`, `uris.rs`, `locks.rs`: settings, own protocol types, URIs, locks.

mod arriving_open;
mod capabilities;
mod configuration;
mod convert;
mod cross_file;
mod diagnostics_array;
mod diagnostics_limit;
mod documents;
mod execution_job;
mod ext;
mod framing;
mod frozen_bytes;
mod handlers;
mod json_string;
mod locks;
mod log;
mod memory;
mod open_texts;
mod outgoing;
mod server;
mod settings;
mod state;
mod stdio;
mod text_document;
mod uris;
mod workspace;

pub use convert::PositionEncoding;
pub use ext::{EndpointPreviewParams, ENDPOINT_PREVIEW_COMMAND};
pub use handlers::rewrite_commands::{FORMAT_COMMAND, RENUMBER_COMMAND};
pub use text_document::{apply_changes, DocumentText, LineChange, RopeLineChange, RopeLines};

use tokio::io::{AsyncRead, AsyncWrite};
use tower_lsp_server::{LspService, Server};

/// Serves the protocol on `input` and `output` until the client sends `exit` or closes the input.
pub async fn serve<I, O>(input: I, output: O)
where
    I: AsyncRead + Unpin + Send + 'static,
    O: AsyncWrite + Unpin + Send + 'static,
{
    serve_on(input, outgoing::Sink::Stream(output)).await;
}

async fn serve_on<I, O>(input: I, output: outgoing::Sink<O>)
where
    I: AsyncRead + Unpin + Send + 'static,
    O: AsyncWrite + Unpin + Send + 'static,
{
    let open_texts = std::sync::Arc::new(open_texts::OpenTexts::default());
    let (outgoing, framework_output, output_tasks) = outgoing::start(output);
    let input = framing::guard_input(input, outgoing.clone(), std::sync::Arc::clone(&open_texts));
    let (service, socket) =
        LspService::build(move |client| server::Backend::new(client, outgoing, open_texts))
            .custom_method(ext::DOCUMENT_TEXT_REQUEST, server::Backend::document_text)
            .custom_method(ext::MODAL_STATE_REQUEST, server::Backend::modal_state)
            .finish();
    Server::new(input, framework_output, socket)
        .serve(service)
        .await;
    output_tasks.finish().await;
}

/// Runs the server on the process's stdin and stdout; returns the exit code.
pub fn serve_stdio() -> u8 {
    memory::configure_allocator();
    // Analyses run in the blocking pool. Few threads keep few allocator arenas holding freed memory
    // (a 1,000,000-line analysis allocates hundreds of MB); stdin and stdout need one thread each.
    let runtime = match tokio::runtime::Builder::new_multi_thread()
        .max_blocking_threads(8)
        .enable_all()
        .build()
    {
        Ok(runtime) => runtime,
        Err(error) => {
            eprintln!("sinumerik-lsp: cannot start the language server: {error}");
            return 2;
        }
    };
    stdio::enlarge_stdio_buffers();
    runtime.block_on(serve_on(
        tokio::io::stdin(),
        outgoing::Sink::<tokio::io::Stdout>::Thread(stdio::stdout_output()),
    ));
    // Analyses still running in the blocking pool are not waited for: the client has gone.
    runtime.shutdown_timeout(std::time::Duration::from_millis(100));
    // The protocol's exit code: 0 after `shutdown`, 1 when the client left without it.
    if server::SHUTDOWN_REQUESTED.load(std::sync::atomic::Ordering::SeqCst) {
        0
    } else {
        1
    }
}
