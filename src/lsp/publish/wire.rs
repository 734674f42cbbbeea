//! One diagnostic and the `publishDiagnostics` message as JSON: the only place diagnostics are
//! encoded. Each diagnostic is written by serde from a borrowed value in the shape of the LSP type
//! (`convert::diagnostic_to_lsp`), without the type's allocations; the message around the array is
//! written here because the array's items are kept encoded from one publication to the next
//! (`publish/mod.rs`).

use crate::diagnostics::{LineDiagnostic, Severity};
use serde::Serialize;
use tower_lsp_server::ls_types::{Range, Uri};

/// A diagnostic as the client receives it.
#[derive(Serialize)]
pub struct WireDiagnostic<'a> {
    pub range: Range,
    pub severity: u8,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub code: Option<&'a str>,
    pub source: &'static str,
    pub message: &'a str,
}

impl<'a> WireDiagnostic<'a> {
    /// A finding of the core at `range`.
    pub fn of(item: &'a LineDiagnostic, range: Range) -> WireDiagnostic<'a> {
        let severity = match item.diagnostic.severity {
            Severity::Error => 1,
            Severity::Warning => 2,
            Severity::Information => 3,
            Severity::Hint => 4,
        };
        WireDiagnostic {
            range,
            severity,
            code: Some(item.diagnostic.code.as_str()),
            source: "sinumerik",
            message: &item.diagnostic.message,
        }
    }

    /// Appends the diagnostic's JSON object to `out`.
    pub fn write(&self, out: &mut Vec<u8>) {
        // Writing into a vector fails only on allocation failure, which aborts anyway.
        let _ = serde_json::to_writer(out, self);
    }
}

/// What comes before the diagnostics array's items in a `publishDiagnostics` body.
pub fn head(uri: &Uri, version: Option<i32>) -> Vec<u8> {
    let mut head = Vec::with_capacity(uri.as_str().len() + 128);
    head.extend_from_slice(
        br#"{"jsonrpc":"2.0","method":"textDocument/publishDiagnostics","params":{"uri":"#,
    );
    let _ = serde_json::to_writer(&mut head, uri.as_str());
    if let Some(version) = version {
        head.extend_from_slice(format!(r#","version":{version}"#).as_bytes());
    }
    head.extend_from_slice(br#","diagnostics":["#);
    head
}

/// What comes after the array's first items (`items_before` says whether there are any): the
/// objects `more`, each a whole object, and the end of the message.
pub fn tail(items_before: bool, more: &[Vec<u8>]) -> Vec<u8> {
    let mut tail = Vec::with_capacity(more.iter().map(|item| item.len() + 1).sum::<usize>() + 3);
    for (index, item) in more.iter().enumerate() {
        if items_before || index > 0 {
            tail.push(b',');
        }
        tail.extend_from_slice(item);
    }
    tail.extend_from_slice(b"]}}");
    tail
}

/// The whole body of a `publishDiagnostics` message whose array holds the objects `items` (joined
/// by commas) and then `more`.
pub fn publication(uri: &Uri, version: Option<i32>, items: &[u8], more: &[Vec<u8>]) -> Vec<u8> {
    let mut body = head(uri, version);
    body.extend_from_slice(items);
    body.extend_from_slice(&tail(!items.is_empty(), more));
    body
}
