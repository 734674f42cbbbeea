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

/// The body of a `publishDiagnostics` message whose diagnostics array holds the objects `items`
/// (each followed by a comma, the last one's included) and then `more`, each a whole object.
pub fn publication(uri: &Uri, version: Option<i32>, items: &[u8], more: &[Vec<u8>]) -> Vec<u8> {
    let more_length: usize = more.iter().map(|item| item.len() + 1).sum();
    let mut body = Vec::with_capacity(items.len() + more_length + uri.as_str().len() + 128);
    body.extend_from_slice(
        br#"{"jsonrpc":"2.0","method":"textDocument/publishDiagnostics","params":{"uri":"#,
    );
    let _ = serde_json::to_writer(&mut body, uri.as_str());
    if let Some(version) = version {
        body.extend_from_slice(format!(r#","version":{version}"#).as_bytes());
    }
    body.extend_from_slice(br#","diagnostics":["#);
    body.extend_from_slice(items);
    for item in more {
        body.extend_from_slice(item);
        body.push(b',');
    }
    // The comma after the last object goes.
    if body.last() == Some(&b',') {
        body.pop();
    }
    body.extend_from_slice(b"]}}");
    body
}
