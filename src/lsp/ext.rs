//! The server's own protocol additions: the `sinumerik.endpointPreview` command's arguments.
//! Its result is the JSON document of `sinumerik-lsp preview` (see docs/cli.md; the requests are
//! described in docs/server.md, "Custom requests and commands").

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

/// `sinumerik/modalState`: the modal state in effect after the block on a line (its own G functions
/// included), for a status bar. Every field is `null` where the state is unknown there (inherited from
/// a caller, or lost after a call).
pub const MODAL_STATE_REQUEST: &str = "sinumerik/modalState";

#[derive(Debug, Clone, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct ModalStateParams {
    pub uri: Uri,
    /// 0-based; a line past the end gives the state at the end of the program.
    pub line: u32,
}

#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(rename_all = "camelCase")]
pub struct ModalStateResult {
    pub motion: Option<String>,
    pub plane: Option<String>,
    pub units: Option<String>,
    pub distance: Option<String>,
    pub diameter: Option<String>,
    /// Whether the machine has a transverse axis (a lathe): only there does diameter programming
    /// mean anything, so a status bar shows `diameter` only when this is true.
    pub diameter_axis: bool,
    pub settable_offset: Option<String>,
    /// The modal feed in the basic unit system.
    pub feed: Option<f64>,
    /// Whether a label, jump or loop before this line may make the control's path differ from
    /// program order.
    pub flow_uncertain: bool,
    /// When the state is that of the block's first execution in the program's run: how often the
    /// block runs (0: never); absent when it is the state in program order.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub passes: Option<u32>,
    /// The machining time of the whole program (reference §15), as the preview's top-level `time`.
    pub time: ProgramTime,
}

/// The machining time of a program: the seconds of the moves whose time is known, by kind, and how
/// many moves' times are unknown (then the total is a lower bound).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ProgramTime {
    pub total_s: f64,
    pub feed_s: f64,
    pub rapid_s: f64,
    pub dwell_s: f64,
    pub unknown_moves: u64,
}
