//! The one writer: every message the server sends (responses, its requests to the client, its own
//! notifications) is encoded by [`encode`] where it is made and queued here as a body; one task
//! writes the bodies in queue order, each behind its header. Diagnostics are encoded by
//! `publish/` straight from the analysis's values; the framework's `Client` would first build a JSON
//! value tree of them.

use crate::lsp::log;
use crate::lsp::transport::framing;
use serde::Serialize;
use std::time::Duration;
use tokio::io::{AsyncWrite, AsyncWriteExt};
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

enum Queued {
    Body(Vec<u8>),
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

    /// Queues a body that is already encoded (a publication of diagnostics).
    pub fn send_body(&self, body: Vec<u8>) {
        let _ = self.0.send(Queued::Body(body));
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

/// The task that writes; [`Writer::finish`] waits until everything queued is out.
pub struct Writer {
    sender: OutgoingSender,
    task: JoinHandle<()>,
}

impl Writer {
    pub async fn finish(self) {
        let _ = self.sender.0.send(Queued::End);
        let _ = tokio::time::timeout(Duration::from_secs(5), self.task).await;
    }
}

/// Starts writing to `output`.
pub fn start<O>(mut output: O) -> (OutgoingSender, Writer)
where
    O: AsyncWrite + Unpin + Send + 'static,
{
    let (sender, mut receiver) = mpsc::unbounded_channel();
    let task = tokio::spawn(async move {
        while let Some(queued) = receiver.recv().await {
            let Queued::Body(body) = queued else {
                let _ = output.flush().await;
                return;
            };
            let started = std::time::Instant::now();
            let written = async {
                output.write_all(&framing::header(body.len())).await?;
                output.write_all(&body).await?;
                // Flushed when nothing else is waiting: a burst of messages goes out together.
                if receiver.is_empty() {
                    output.flush().await?;
                }
                std::io::Result::Ok(())
            }
            .await;
            log::slow_with(
                || format!("writing a message of {} bytes", body.len()),
                started.elapsed(),
            );
            // The client has gone: nothing more can be written.
            if written.is_err() {
                return;
            }
        }
    });
    let sender = OutgoingSender(sender);
    (sender.clone(), Writer { sender, task })
}
