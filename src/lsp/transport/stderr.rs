//! Lines on stderr (editors show a server's stderr in its output panel), for the transport itself,
//! which cannot send log messages through the output it is writing; `lsp/log.rs` adds the client.

use std::time::Duration;
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

/// Logs on stderr only, for the output itself.
pub fn slow_with(what: impl FnOnce() -> String, elapsed: Duration) {
    if elapsed > SLOW {
        to_stderr(
            MessageType::INFO,
            &format!("{} took {} ms", what(), elapsed.as_millis()),
        );
    }
}
