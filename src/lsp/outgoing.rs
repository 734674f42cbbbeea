//! Everything the server writes goes through here: the framework's responses and requests, and the
//! notifications the server sends itself (diagnostics from the analysis workers, log lines), which
//! are serialized straight to text in the sending thread. The framework would first build a JSON
//! value tree of every notification, which for 24,000 diagnostics took more than ten times as long.

use crate::lsp::diagnostics_array::JsonArray;
use crate::lsp::log;
use crate::lsp::stdio::{MessageOutput, Piece};
use serde::Serialize;
use std::time::Duration;
use tokio::io::{
    AsyncBufReadExt, AsyncReadExt, AsyncWrite, AsyncWriteExt, BufReader, DuplexStream,
};
use tokio::sync::{mpsc, oneshot};
use tokio::task::JoinHandle;
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

enum Frame {
    /// A whole message with its header.
    Message(Vec<u8>),
    /// A message around a JSON array in shared pieces (a large diagnostics array, kept for the next
    /// publication), so that it is written without being copied.
    Parts {
        head: Vec<u8>,
        body: JsonArray,
        tail: Vec<u8>,
    },
    /// Everything before this has been queued: flush and stop.
    End,
}

impl Frame {
    /// The bytes of a message, piece by piece (none for the end).
    fn pieces(&self) -> Vec<Piece<'_>> {
        match self {
            Frame::Message(bytes) => vec![Piece::copied(bytes)],
            Frame::Parts { head, body, tail } => std::iter::once(Piece::copied(head))
                .chain(body.pieces())
                .chain(std::iter::once(Piece::copied(tail)))
                .collect(),
            Frame::End => Vec::new(),
        }
    }
}

#[derive(Serialize)]
struct Notification<'a, P> {
    jsonrpc: &'static str,
    method: &'static str,
    params: &'a P,
}

fn framed<P: Serialize>(method: &'static str, params: &P) -> Option<Vec<u8>> {
    let body = serde_json::to_vec(&Notification {
        jsonrpc: "2.0",
        method,
        params,
    })
    .ok()?;
    Some(with_header(&body))
}

fn with_header(body: &[u8]) -> Vec<u8> {
    let mut message = format!("Content-Length: {}\r\n\r\n", body.len()).into_bytes();
    message.extend_from_slice(body);
    message
}

/// The sending side; sending never blocks and never fails (after the end the messages are dropped).
#[derive(Clone)]
pub struct OutgoingSender(mpsc::UnboundedSender<Frame>);

impl OutgoingSender {
    /// Serializes and queues a notification. Messages queued from one thread go out in that order.
    pub fn send(&self, message: Outgoing) {
        let started = std::time::Instant::now();
        let frame = match message {
            Outgoing::Diagnostics {
                uri,
                version,
                diagnostics,
            } => {
                let count = diagnostics.len();
                let frame = framed(
                    "textDocument/publishDiagnostics",
                    &PublishDiagnosticsParams {
                        uri,
                        diagnostics,
                        version,
                    },
                );
                log::slow_with(
                    || format!("serializing {count} diagnostics"),
                    started.elapsed(),
                );
                frame
            }
            Outgoing::Log { level, message } => framed(
                "window/logMessage",
                &LogMessageParams {
                    typ: level,
                    message,
                },
            ),
        };
        if let Some(frame) = frame {
            let _ = self.0.send(Frame::Message(frame));
        }
    }

    /// Queues a message that is already written, header included.
    pub fn send_message(&self, message: Vec<u8>) {
        let _ = self.0.send(Frame::Message(message));
    }

    /// Queues a message written in three parts: `head` (with the header), `body` and `tail`.
    pub fn send_parts(&self, head: Vec<u8>, body: JsonArray, tail: Vec<u8>) {
        let _ = self.0.send(Frame::Parts { head, body, tail });
    }

    /// Logs on stderr and as `window/logMessage`.
    pub fn log(&self, level: MessageType, message: String) {
        log::to_stderr(level, &message);
        self.send(Outgoing::Log { level, message });
    }

    pub fn log_warning(&self, message: String) {
        self.log(MessageType::WARNING, message);
    }

    pub fn log_error(&self, message: String) {
        self.log(MessageType::ERROR, message);
    }
}

/// Where the messages are written.
pub enum Sink<O> {
    /// A stream written by a task of the runtime (the in-process tests).
    Stream(O),
    /// A blocking writer with a thread of its own (the process's stdout, see `stdio.rs`): a full pipe
    /// then holds up that thread only, and large messages go out without a copy.
    Thread(Box<dyn MessageOutput>),
}

enum Writer {
    Task(JoinHandle<()>),
    /// Fires when the thread has written everything queued before the end.
    Thread(oneshot::Receiver<()>),
}

/// The tasks that write the output; [`OutputTasks::finish`] waits until everything queued is out.
pub struct OutputTasks {
    sender: OutgoingSender,
    forwarder: JoinHandle<()>,
    writer: Writer,
}

impl OutputTasks {
    pub async fn finish(self) {
        let _ = self.forwarder.await;
        let _ = self.sender.0.send(Frame::End);
        let wait = Duration::from_secs(5);
        match self.writer {
            Writer::Task(task) => {
                let _ = tokio::time::timeout(wait, task).await;
            }
            Writer::Thread(done) => {
                let _ = tokio::time::timeout(wait, done).await;
            }
        }
    }
}

/// Starts writing to `sink`. Returns the sender for the server's own notifications, the stream the
/// framework writes its messages to, and the tasks.
pub fn start<O>(sink: Sink<O>) -> (OutgoingSender, DuplexStream, OutputTasks)
where
    O: AsyncWrite + Unpin + Send + 'static,
{
    let (sender, receiver) = mpsc::unbounded_channel();
    let sender = OutgoingSender(sender);
    let (framework_side, forwarder_side) = tokio::io::duplex(1 << 20);
    let framework_sender = sender.clone();
    let forwarder = tokio::spawn(async move {
        let mut reader = BufReader::new(forwarder_side);
        while let Some(frame) = read_frame(&mut reader).await {
            let _ = framework_sender.0.send(Frame::Message(frame));
        }
    });
    let writer = match sink {
        Sink::Stream(output) => Writer::Task(tokio::spawn(write_to_stream(output, receiver))),
        Sink::Thread(output) => {
            let (done, finished) = oneshot::channel();
            let spawned = std::thread::Builder::new()
                .name("lsp-output".to_string())
                .spawn(move || {
                    write_blocking(output, receiver);
                    let _ = done.send(());
                });
            if let Err(error) = spawned {
                log::to_stderr(
                    MessageType::ERROR,
                    &format!("the output thread cannot start: {error}"),
                );
            }
            Writer::Thread(finished)
        }
    };
    (
        sender.clone(),
        framework_side,
        OutputTasks {
            sender,
            forwarder,
            writer,
        },
    )
}

async fn write_to_stream<O: AsyncWrite + Unpin>(
    mut output: O,
    mut receiver: mpsc::UnboundedReceiver<Frame>,
) {
    while let Some(frame) = receiver.recv().await {
        if matches!(frame, Frame::End) {
            break;
        }
        let mut written = Ok(());
        for piece in frame.pieces() {
            written = output.write_all(piece.bytes).await;
            if written.is_err() {
                break;
            }
        }
        if written.is_err() || (receiver.is_empty() && output.flush().await.is_err()) {
            return;
        }
    }
    let _ = output.flush().await;
}

/// The output thread: writes each message as it comes, until the end or until the output fails (the
/// client has gone; what is still queued is dropped with the channel).
fn write_blocking(
    mut output: Box<dyn MessageOutput>,
    mut receiver: mpsc::UnboundedReceiver<Frame>,
) {
    while let Some(frame) = receiver.blocking_recv() {
        if matches!(frame, Frame::End) || output.write_message(&frame.pieces()).is_err() {
            return;
        }
    }
}

/// One message as the framework wrote it, header included; `None` when the framework has stopped.
async fn read_frame(reader: &mut BufReader<DuplexStream>) -> Option<Vec<u8>> {
    let mut frame = Vec::new();
    let mut length = None;
    loop {
        let start = frame.len();
        if reader.read_until(b'\n', &mut frame).await.ok()? == 0 {
            return None;
        }
        let line = String::from_utf8_lossy(&frame[start..]);
        let line = line.trim_end();
        if line.is_empty() {
            break;
        }
        if let Some((name, value)) = line.split_once(':') {
            if name.trim().eq_ignore_ascii_case("content-length") {
                length = value.trim().parse::<usize>().ok();
            }
        }
    }
    let start = frame.len();
    frame.resize(start + length?, 0);
    reader.read_exact(&mut frame[start..]).await.ok()?;
    Some(frame)
}
