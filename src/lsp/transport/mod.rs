//! The server's transport: one reader, one framing parser, one writer, around tower-lsp-server's
//! `LspService`, which dispatches each request to the `LanguageServer` implementation.
//!
//! - `framing.rs`: the `Content-Length` framing, without IO (fuzzed, `examples/fuzz`).
//! - `message.rs`: a body read once into the framework's `Request` or `Response`, or dropped with the
//!   error response JSON-RPC asks for.
//! - `open_in_place.rs`: a large `didOpen` read in its own buffer (its text unescaped in place), its
//!   text's literal checked and unescaped a word at a time by `json_literal.rs` (both fuzzed).
//! - `outbox.rs`: the queue every outgoing message goes through, and the task that writes it.
//! - `framing_reader.rs`: input -> framer -> message; `stderr.rs`: the lines the transport logs;
//!   `measure.rs`: the switch of the side-by-side measurements.
//! - `sys/`: the crate's only `unsafe` code: the allocator and pipe settings, frozen pages and the
//!   stdout writer that hands them to a pipe.
//!
//! The framework's own `Server` is not used: its reader stops for good at the first body it cannot
//! read (which ends the server on one bad message), and its writer serializes every notification
//! through a JSON value tree. The loop here is the framework's, with these two ends replaced: requests
//! are started in arrival order and run up to four at once, responses are written as they finish.

pub mod framing;
mod framing_reader;
pub mod json_literal;
pub mod measure;
pub mod message;
pub mod open_in_place;
pub mod outbox;
pub mod stderr;
// The crate's only `unsafe` code: what the server does through the C library.
#[allow(unsafe_code)]
mod sys;

pub use sys::FrozenBytes;

use futures::{SinkExt, StreamExt};
use message::{Incoming, InitializeGate};
use outbox::OutgoingSender;
use tokio::io::{AsyncRead, AsyncWrite};
use tower::Service;
use tower_lsp_server::jsonrpc::{Request, Response};
use tower_lsp_server::ls_types::MessageType;
use tower_lsp_server::{ClientSocket, LspService};

/// Requests the framework runs at once (its own default).
const MAX_CONCURRENCY: usize = 4;

/// Serves the protocol on `input` and `output` until the client sends `exit` or closes the input;
/// `build` makes the service, given the sender every outgoing message goes through.
pub async fn serve<I, O, S>(
    input: I,
    output: O,
    build: impl FnOnce(OutgoingSender) -> (LspService<S>, ClientSocket),
) where
    I: AsyncRead + Unpin + Send + 'static,
    O: AsyncWrite + Unpin + Send + 'static,
    S: tower_lsp_server::LanguageServer,
{
    serve_on(input, outbox::Output::Stream(output), build).await;
}

async fn serve_on<I, O, S>(
    input: I,
    output: outbox::Output<O>,
    build: impl FnOnce(OutgoingSender) -> (LspService<S>, ClientSocket),
) where
    I: AsyncRead + Unpin + Send + 'static,
    O: AsyncWrite + Unpin + Send + 'static,
    S: tower_lsp_server::LanguageServer,
{
    let (outgoing, writer) = outbox::start(output);
    let (service, socket) = build(outgoing.clone());
    run(input, service, socket, outgoing).await;
    writer.finish().await;
}

async fn run<I, S>(
    input: I,
    mut service: LspService<S>,
    socket: ClientSocket,
    outgoing: OutgoingSender,
) where
    I: AsyncRead + Unpin + Send + 'static,
    S: tower_lsp_server::LanguageServer,
{
    let (client_requests, mut client_responses) = socket.split();
    let (client_requests, client_abort) = futures::stream::abortable(client_requests);
    let (mut tasks, task_queue) = futures::channel::mpsc::channel(100);

    let answer = {
        let outgoing = outgoing.clone();
        task_queue
            .buffer_unordered(MAX_CONCURRENCY)
            .for_each(move |response: Option<Response>| {
                if let Some(response) = response {
                    outgoing.send_message(&response);
                }
                std::future::ready(())
            })
    };
    let ask = {
        let outgoing = outgoing.clone();
        client_requests.for_each(move |request: Request| {
            outgoing.send_message(&request);
            std::future::ready(())
        })
    };
    let read = async {
        let mut reader = framing_reader::MessageReader::new(input);
        let mut gate = InitializeGate::default();
        while let Some(incoming) = reader.next(&mut gate).await {
            match incoming {
                Incoming::Request(request) => {
                    if futures::future::poll_fn(|context| service.poll_ready(context))
                        .await
                        .is_err()
                    {
                        break;
                    }
                    let will_exit = request.method() == "exit";
                    let call = service.call(request);
                    let task = async move { call.await.unwrap_or(None) };
                    if tasks.send(task).await.is_err() || will_exit {
                        break;
                    }
                }
                Incoming::Response(response) => {
                    if client_responses.send(response).await.is_err() {
                        break;
                    }
                }
                Incoming::Invalid { response, reason } => {
                    stderr::to_stderr(MessageType::WARNING, &reason);
                    outgoing.send_message(&response);
                }
            }
        }
        tasks.disconnect();
        client_abort.abort();
    };
    futures::join!(answer, ask, read);
}

/// Runs the server on the process's stdin and stdout; `false` when it could not start.
pub fn serve_stdio<S>(build: impl FnOnce(OutgoingSender) -> (LspService<S>, ClientSocket)) -> bool
where
    S: tower_lsp_server::LanguageServer,
{
    sys::configure_allocator();
    // Analyses run in the blocking pool. Few threads keep few allocator arenas holding freed memory
    // (a 1,000,000-line analysis allocates hundreds of MB).
    let runtime = match tokio::runtime::Builder::new_multi_thread()
        .max_blocking_threads(8)
        .enable_all()
        .build()
    {
        Ok(runtime) => runtime,
        Err(error) => {
            eprintln!("sinumerik-lsp: cannot start the language server: {error}");
            return false;
        }
    };
    sys::enlarge_stdio_buffers();
    runtime.block_on(serve_on(
        tokio::io::stdin(),
        outbox::Output::<tokio::io::Stdout>::Stdout,
        build,
    ));
    // Analyses still running in the blocking pool are not waited for: the client has gone.
    runtime.shutdown_timeout(std::time::Duration::from_millis(100));
    true
}
