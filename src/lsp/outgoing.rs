//! Everything the server writes goes through here: the framework's responses and requests, and the
//! notifications the server sends itself (diagnostics from the analysis workers, log lines), which
//! are serialized straight to text in the sending thread. The framework would first build a JSON
//! value tree of every notification, which for 24,000 diagnostics took more than ten times as long.

use crate::lsp::log;
use serde::Serialize;
use std::sync::Arc;
use std::time::Duration;
use tokio::io::{
    AsyncBufReadExt, AsyncReadExt, AsyncWrite, AsyncWriteExt, BufReader, DuplexStream,
};
use tokio::sync::mpsc;
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
    /// A message in three pieces, the middle one shared (a large diagnostics array, kept for the next
    /// publication), so that it is written without being copied.
    Parts {
        head: Vec<u8>,
        body: Arc<Vec<u8>>,
        tail: Vec<u8>,
    },
    /// Everything before this has been queued: flush and stop.
    End,
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

    /// Queues a message written in three pieces: `head` (with the header), `body` and `tail`.
    pub fn send_parts(&self, head: Vec<u8>, body: Arc<Vec<u8>>, tail: Vec<u8>) {
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

/// The tasks that write the output; [`OutputTasks::finish`] waits until everything queued is out.
pub struct OutputTasks {
    sender: OutgoingSender,
    forwarder: JoinHandle<()>,
    writer: JoinHandle<()>,
}

impl OutputTasks {
    pub async fn finish(self) {
        let _ = self.forwarder.await;
        let _ = self.sender.0.send(Frame::End);
        let _ = tokio::time::timeout(Duration::from_secs(5), self.writer).await;
    }
}

/// Starts writing to `output`. Returns the sender for the server's own notifications, the stream the
/// framework writes its messages to, and the tasks.
pub fn start<O>(output: O) -> (OutgoingSender, DuplexStream, OutputTasks)
where
    O: AsyncWrite + Unpin + Send + 'static,
{
    let (sender, mut receiver) = mpsc::unbounded_channel();
    let sender = OutgoingSender(sender);
    let (framework_side, forwarder_side) = tokio::io::duplex(1 << 20);
    let framework_sender = sender.clone();
    let forwarder = tokio::spawn(async move {
        let mut reader = BufReader::new(forwarder_side);
        while let Some(frame) = read_frame(&mut reader).await {
            let _ = framework_sender.0.send(Frame::Message(frame));
        }
    });
    let writer = tokio::spawn(async move {
        let mut output = output;
        while let Some(frame) = receiver.recv().await {
            match frame {
                Frame::Message(bytes) => {
                    if output.write_all(&bytes).await.is_err() {
                        return;
                    }
                    if receiver.is_empty() && output.flush().await.is_err() {
                        return;
                    }
                }
                Frame::Parts { head, body, tail } => {
                    for part in [&head[..], &body[..], &tail[..]] {
                        if output.write_all(part).await.is_err() {
                            return;
                        }
                    }
                    if receiver.is_empty() && output.flush().await.is_err() {
                        return;
                    }
                }
                Frame::End => break,
            }
        }
        let _ = output.flush().await;
    });
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
