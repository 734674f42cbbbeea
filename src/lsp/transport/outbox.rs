//! The one writer: every message the server sends (responses, its requests to the client, its own
//! notifications) is encoded by [`encode`] where it is made and queued here as a body; one writer
//! writes the bodies in queue order, each behind its header. Diagnostics are encoded by
//! `publish/` straight from the analysis's values (the framework's `Client` would first build a JSON
//! value tree of them), and their body comes in parts: the array's items are shared with the
//! document's `Publisher`, which takes them over for the next publication, so megabytes of items are
//! neither copied into a message nor written into fresh pages on every keystroke. On the process's
//! stdout the writer is a thread of its own with blocking writes (tokio's stdout copies every write
//! into its own buffer and hands it to the blocking pool, 2 MiB at a time), and the shared items, in
//! frozen pages of their own, are handed to a pipe rather than copied (`sys/stdout.rs`); in-process
//! (tests) it is a task.

use crate::lsp::transport::framing;
use crate::lsp::transport::stderr;
use crate::lsp::transport::sys::{FrozenBytes, OutputPiece, StdoutOutput};
use serde::Serialize;
use std::sync::Arc;
use std::time::Duration;
use tokio::io::{AsyncWrite, AsyncWriteExt};
use tokio::sync::mpsc;
use tower_lsp_server::ls_types::{
    Diagnostic, LogMessageParams, MessageType, PublishDiagnosticsParams, Uri,
};

/// A notification the server sends on its own.
pub enum Outgoing {
    Diagnostics {
        uri: Uri,
        version: Option<i32>,
        diagnostics: Vec<Diagnostic>,
    },
    Log {
        level: MessageType,
        message: String,
    },
}

/// A piece of a message's body.
pub enum Part {
    Owned(Vec<u8>),
    /// The first `length` bytes of frozen bytes shared with the sender.
    Shared(Arc<FrozenBytes>, usize),
}

impl Part {
    fn bytes(&self) -> &[u8] {
        match self {
            Part::Owned(bytes) => bytes,
            Part::Shared(bytes, length) => &bytes.as_slice()[..*length],
        }
    }

    fn piece(&self) -> OutputPiece<'_> {
        match self {
            Part::Owned(bytes) => OutputPiece::copied(bytes),
            Part::Shared(bytes, length) => OutputPiece::frozen(bytes, *length),
        }
    }
}

enum Queued {
    Body(Vec<Part>),
    /// Everything before this has been queued: flush and stop.
    End,
}

#[derive(Serialize)]
struct Notification<'a, P> {
    jsonrpc: &'static str,
    method: &'static str,
    params: &'a P,
}

/// The body of a notification.
pub fn encode_notification<P: Serialize>(method: &'static str, params: &P) -> Option<Vec<u8>> {
    encode(&Notification {
        jsonrpc: "2.0",
        method,
        params,
    })
}

/// The body of any message (a response, a request, a notification).
pub fn encode<M: Serialize>(message: &M) -> Option<Vec<u8>> {
    serde_json::to_vec(message).ok()
}

/// The sending side; sending never blocks and never fails (after the end the messages are dropped).
#[derive(Clone)]
pub struct OutgoingSender(mpsc::UnboundedSender<Queued>);

impl OutgoingSender {
    /// Encodes and queues a notification. Messages queued from one thread go out in that order.
    pub fn send(&self, message: Outgoing) {
        let body = match message {
            Outgoing::Diagnostics {
                uri,
                version,
                diagnostics,
            } => encode_notification(
                "textDocument/publishDiagnostics",
                &PublishDiagnosticsParams {
                    uri,
                    diagnostics,
                    version,
                },
            ),
            Outgoing::Log { level, message } => encode_notification(
                "window/logMessage",
                &LogMessageParams {
                    typ: level,
                    message,
                },
            ),
        };
        if let Some(body) = body {
            self.send_body(body);
        }
    }

    /// Encodes and queues any message.
    pub fn send_message<M: Serialize>(&self, message: &M) {
        if let Some(body) = encode(message) {
            self.send_body(body);
        }
    }

    /// Queues a body that is already encoded.
    pub fn send_body(&self, body: Vec<u8>) {
        let _ = self.0.send(Queued::Body(vec![Part::Owned(body)]));
    }

    /// Queues a body in parts (a publication of diagnostics).
    pub fn send_parts(&self, parts: Vec<Part>) {
        let _ = self.0.send(Queued::Body(parts));
    }

    /// Logs on stderr and as `window/logMessage`.
    pub fn log(&self, level: MessageType, message: String) {
        stderr::to_stderr(level, &message);
        self.send(Outgoing::Log { level, message });
    }

    pub fn log_warning(&self, message: String) {
        self.log(MessageType::WARNING, message);
    }

    pub fn log_error(&self, message: String) {
        self.log(MessageType::ERROR, message);
    }
}

/// Where the messages go.
pub enum Output<O> {
    /// A stream written by a task of the runtime (in-process use, the tests).
    Stream(O),
    /// The process's stdout, written with blocking calls by a thread of its own.
    Stdout,
}

/// The writer; [`Writer::finish`] waits until everything queued is out.
pub struct Writer {
    sender: OutgoingSender,
    done: tokio::sync::oneshot::Receiver<()>,
}

impl Writer {
    pub async fn finish(self) {
        let _ = self.sender.0.send(Queued::End);
        let _ = tokio::time::timeout(Duration::from_secs(5), self.done).await;
    }
}

/// Starts writing to `output`.
pub fn start<O>(output: Output<O>) -> (OutgoingSender, Writer)
where
    O: AsyncWrite + Unpin + Send + 'static,
{
    let (sender, receiver) = mpsc::unbounded_channel();
    let (done_sender, done) = tokio::sync::oneshot::channel();
    match output {
        Output::Stream(output) => {
            tokio::spawn(async move {
                write_stream(output, receiver).await;
                let _ = done_sender.send(());
            });
        }
        Output::Stdout => {
            let spawned = std::thread::Builder::new()
                .name("lsp-output".into())
                .spawn(move || {
                    write_blocking(StdoutOutput::new(), receiver);
                    let _ = done_sender.send(());
                });
            if let Err(error) = spawned {
                stderr::to_stderr(
                    MessageType::ERROR,
                    &format!("cannot start the output thread: {error}"),
                );
            }
        }
    }
    let sender = OutgoingSender(sender);
    (sender.clone(), Writer { sender, done })
}

fn body_length(parts: &[Part]) -> usize {
    parts.iter().map(|part| part.bytes().len()).sum()
}

async fn write_stream<O: AsyncWrite + Unpin>(
    mut output: O,
    mut receiver: mpsc::UnboundedReceiver<Queued>,
) {
    while let Some(Queued::Body(parts)) = receiver.recv().await {
        let written = async {
            output
                .write_all(&framing::header(body_length(&parts)))
                .await?;
            for part in &parts {
                output.write_all(part.bytes()).await?;
            }
            // Flushed when nothing else is waiting: a burst of messages goes out together.
            if receiver.is_empty() {
                output.flush().await?;
            }
            std::io::Result::Ok(())
        }
        .await;
        // The client has gone: nothing more can be written.
        if written.is_err() {
            return;
        }
    }
    let _ = output.flush().await;
}

fn write_blocking(mut output: StdoutOutput, mut receiver: mpsc::UnboundedReceiver<Queued>) {
    while let Some(Queued::Body(parts)) = receiver.blocking_recv() {
        let started = std::time::Instant::now();
        let length = body_length(&parts);
        let header = framing::header(length);
        let pieces: Vec<OutputPiece<'_>> = std::iter::once(OutputPiece::copied(&header))
            .chain(parts.iter().map(Part::piece))
            .collect();
        let written = output.write_message(&pieces);
        stderr::slow_with(
            || format!("writing a message of {length} bytes"),
            started.elapsed(),
        );
        if written.is_err() {
            return;
        }
    }
}
