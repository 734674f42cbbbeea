//! Signature help inside the parentheses of a call: the protocol's form of `ide::signature_help`
//! (standard cycles from the reference §8.7, `PROC` headers of the workspace, `EXTERN` declarations).

use crate::ide::signature_help::signature_help;
use crate::lsp::convert::byte_to_character;
use crate::lsp::documents::Analysed;
use crate::lsp::handlers::navigation::line_at;
use crate::lsp::state::DocumentRequest;
use tower_lsp_server::ls_types::{
    Documentation, ParameterInformation, ParameterLabel, Position, SignatureHelp,
    SignatureInformation,
};

/// The characters that open or advance a call's parameter list.
pub const TRIGGER_CHARACTERS: [&str; 2] = ["(", ","];

/// `textDocument/signatureHelp`, `None` outside a known call.
pub fn signature(
    request: &DocumentRequest,
    analysed: &Analysed,
    position: Position,
) -> Option<SignatureHelp> {
    let (shared, encoding) = (&request.shared, request.encoding);
    let id = shared.workspace.ensure_present(&request.uri, analysed);
    let (_, text, byte) = line_at(analysed, position, encoding)?;
    let state = shared.workspace.read();
    let help = signature_help(&state.index, &id, &text, byte)?;
    let offset = |byte: usize| byte_to_character(&help.label, byte, encoding);
    let parameters = help
        .parameters
        .iter()
        .zip(help.parameter_documentation.iter())
        .map(|(&(start, end), documentation)| ParameterInformation {
            label: ParameterLabel::LabelOffsets([offset(start), offset(end)]),
            documentation: documentation.clone().map(Documentation::String),
        })
        .collect();
    let active = u32::try_from(help.active_parameter).unwrap_or(u32::MAX);
    Some(SignatureHelp {
        signatures: vec![SignatureInformation {
            label: help.label.clone(),
            documentation: help.documentation.clone().map(Documentation::String),
            parameters: Some(parameters),
            active_parameter: Some(active),
        }],
        active_signature: Some(0),
        active_parameter: Some(active),
    })
}
