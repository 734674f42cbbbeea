//! Logging of the server to the client (window/logMessage) and stderr, and the handlers or jobs that
//! took longer than [`SLOW`]. Lines on stderr alone, which the transport writes, are in
//! `transport/stderr.rs`.

use crate::lsp::transport::outbox::OutgoingSender;
use crate::lsp::transport::stderr::SLOW;
use std::time::{Duration, Instant};
use tower_lsp_server::ls_types::MessageType;

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
