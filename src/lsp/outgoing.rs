//! Messages from the server to the client that are produced off the async threads (diagnostics from
//! the analysis workers, log lines), sent in order by one task.

use crate::lsp::log;
use tokio::sync::mpsc;
use tower_lsp_server::ls_types::{Diagnostic, MessageType, Uri};
use tower_lsp_server::Client;

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

/// The sending side; sending never blocks and never fails (after shutdown the messages are dropped).
#[derive(Clone)]
pub struct OutgoingSender(mpsc::UnboundedSender<Outgoing>);

impl OutgoingSender {
    pub fn send(&self, message: Outgoing) {
        let _ = self.0.send(message);
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

pub fn channel() -> (OutgoingSender, mpsc::UnboundedReceiver<Outgoing>) {
    let (sender, receiver) = mpsc::unbounded_channel();
    (OutgoingSender(sender), receiver)
}

/// Sends every message to the client, in the order they were queued, until the channel closes.
pub async fn forward(client: Client, mut receiver: mpsc::UnboundedReceiver<Outgoing>) {
    while let Some(message) = receiver.recv().await {
        match message {
            Outgoing::Diagnostics {
                uri,
                version,
                diagnostics,
            } => {
                let started = std::time::Instant::now();
                let count = diagnostics.len();
                client.publish_diagnostics(uri, diagnostics, version).await;
                log::slow_with(
                    || format!("publishing {count} diagnostics"),
                    started.elapsed(),
                );
            }
            Outgoing::Log { level, message } => client.log_message(level, message).await,
        }
    }
}
