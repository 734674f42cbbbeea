//! Logging of the server: lines on stderr (editors show a server's stderr in its output panel), and
//! the handlers or jobs that took longer than [`SLOW`].

use crate::lsp::transport::outbox::OutgoingSender;
use std::time::{Duration, Instant};
use tower_lsp_server::ls_types::MessageType;

/// Work that takes longer than this is logged (rust-analyzer's "overly long loop turn").
pub const SLOW: Duration = Duration::from_millis(100);

pub fn to_stderr(level: MessageType, message: &str) {
    let level = match level {
        MessageType::ERROR => "error",
        MessageType::WARNING => "warning",
        MessageType::INFO => "info",
        _ => "log",
    };
    eprintln!("sinumerik-lsp {level}: {message}");
}

/// Logs `what` when it took longer than [`SLOW`], on stderr and to the client.
pub fn slow(what: &str, elapsed: Duration, outgoing: &OutgoingSender) {
    if elapsed > SLOW {
        outgoing.log(
            MessageType::INFO,
            format!("{what} took {} ms", elapsed.as_millis()),
        );
    }
}

/// Like [`slow`], with the description made only when it is needed.
pub fn slow_with_sender(
    what: impl FnOnce() -> String,
    elapsed: Duration,
    outgoing: &OutgoingSender,
) {
    if elapsed > SLOW {
        slow(&what(), elapsed, outgoing);
    }
}

/// Logs on stderr only, for the output itself.
pub fn slow_with(what: impl FnOnce() -> String, elapsed: Duration) {
    if elapsed > SLOW {
        to_stderr(
            MessageType::INFO,
            &format!("{} took {} ms", what(), elapsed.as_millis()),
        );
    }
}

/// Measures a handler from its creation to its drop, and logs it when it was slow.
pub struct HandlerTimer {
    method: &'static str,
    started: Instant,
    outgoing: OutgoingSender,
}

impl HandlerTimer {
    pub fn new(method: &'static str, outgoing: &OutgoingSender) -> HandlerTimer {
        HandlerTimer {
            method,
            started: Instant::now(),
            outgoing: outgoing.clone(),
        }
    }
}

impl Drop for HandlerTimer {
    fn drop(&mut self) {
        slow(self.method, self.started.elapsed(), &self.outgoing);
    }
}
