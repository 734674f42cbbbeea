//! The server's own protocol additions: the `sinumerik.endpointPreview` command's arguments.
//! Its result is the JSON document of `sinumerik-lsp preview` (see the README).

use serde::Deserialize;
use tower_lsp_server::ls_types::Uri;

/// The command that returns the resolved moves of a document, open or on disk.
pub const ENDPOINT_PREVIEW_COMMAND: &str = "sinumerik.endpointPreview";

/// One argument of `sinumerik.endpointPreview`: a document and, optionally, its lines
/// `startLine ..= endLine` (0-based, both included).
#[derive(Debug, Clone, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct EndpointPreviewParams {
    pub uri: Uri,
    pub start_line: Option<u32>,
    pub end_line: Option<u32>,
}

/// `sinumerik/documentText`: the server's copy of an open document, to check that it is in step with
/// the editor (rust-analyzer has the same kind of request for the same reason).
pub const DOCUMENT_TEXT_REQUEST: &str = "sinumerik/documentText";

#[derive(Debug, Clone, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct DocumentTextParams {
    pub uri: Uri,
}

#[derive(Debug, Clone, serde::Serialize)]
#[serde(rename_all = "camelCase")]
pub struct DocumentTextResult {
    pub version: i32,
    pub text: String,
}
