//! Renumbering and formatting from the editor: the commands `sinumerik.renumber` and
//! `sinumerik.format` (`workspace/executeCommand`), which compute the edits on the open document as
//! the request saw it and send them to the client with `workspace/applyEdit`, and the requests
//! `textDocument/formatting` and `textDocument/rangeFormatting`, which return them.

use crate::ide::format::{format, FormatOptions};
use crate::ide::renumber::{renumber, NumberingMode, RenumberOptions};
use crate::ide::LineEdit;
use crate::lsp::convert::PositionEncoding;
use crate::lsp::documents::Analysed;
use crate::lsp::handlers::workspace_edit::{text_edits, workspace_edit, DocumentEdits};
use crate::lsp::state::Shared;
use serde::Deserialize;
use serde_json::{json, Value};
use tower_lsp_server::jsonrpc::{Error, Result};
use tower_lsp_server::ls_types::request::ApplyWorkspaceEdit;
use tower_lsp_server::ls_types::{ApplyWorkspaceEditParams, Range, TextEdit, Uri};

/// Renumbers the blocks of an open document: `[{"uri", "start"?, "step"?, "mode"?}]`.
pub const RENUMBER_COMMAND: &str = "sinumerik.renumber";
/// Formats an open document: `[{"uri"}]`.
pub const FORMAT_COMMAND: &str = "sinumerik.format";

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
enum ModeArgument {
    Keep,
    All,
    Drop,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RenumberArguments {
    uri: Uri,
    start: Option<u64>,
    step: Option<u64>,
    mode: Option<ModeArgument>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct FormatArguments {
    uri: Uri,
}

/// One of the two rewrites, with its options.
#[derive(Debug, Clone, Copy)]
pub enum Rewrite {
    Renumber(RenumberOptions),
    Format,
}

impl Rewrite {
    /// The document and the rewrite a command asks for; a message for arguments that do not fit.
    fn from_command(
        command: &str,
        arguments: &[Value],
    ) -> std::result::Result<(Uri, Rewrite), String> {
        let [argument] = arguments else {
            return Err(match command {
                RENUMBER_COMMAND => format!(
                    "{RENUMBER_COMMAND} takes one argument {{\"uri\", \"start\"?, \"step\"?, \"mode\"?: \"keep\"|\"all\"|\"drop\"}}"
                ),
                _ => format!("{command} takes one argument {{\"uri\"}}"),
            });
        };
        let problem = |error: serde_json::Error| format!("{command}: {error}");
        if command == RENUMBER_COMMAND {
            let arguments: RenumberArguments =
                serde_json::from_value(argument.clone()).map_err(problem)?;
            let defaults = RenumberOptions::default();
            let options = RenumberOptions {
                start: arguments.start.unwrap_or(defaults.start),
                step: arguments.step.unwrap_or(defaults.step),
                mode: match arguments.mode {
                    None | Some(ModeArgument::Keep) => NumberingMode::Keep,
                    Some(ModeArgument::All) => NumberingMode::All,
                    Some(ModeArgument::Drop) => NumberingMode::Drop,
                },
            };
            Ok((arguments.uri, Rewrite::Renumber(options)))
        } else {
            let arguments: FormatArguments =
                serde_json::from_value(argument.clone()).map_err(problem)?;
            Ok((arguments.uri, Rewrite::Format))
        }
    }

    /// The label the editor shows for the edit (in its undo history, for instance).
    fn label(self) -> &'static str {
        match self {
            Rewrite::Renumber(_) => "Renumber blocks",
            Rewrite::Format => "Format program",
        }
    }

    /// The core's edits for the analysed text, or why the program cannot be rewritten.
    fn line_edits(self, analysed: &Analysed) -> std::result::Result<Vec<LineEdit>, String> {
        let lines = analysed.lines();
        let config = analysed.analysis.config();
        match self {
            Rewrite::Renumber(options) => {
                renumber(&lines, config, options).map_err(|error| error.to_string())
            }
            Rewrite::Format => Ok(format(&lines, config, FormatOptions::default())),
        }
    }
}

/// Whether `command` is one of the rewrite commands.
pub fn is_rewrite_command(command: &str) -> bool {
    command == RENUMBER_COMMAND || command == FORMAT_COMMAND
}

/// Runs a rewrite command: computes the edits, has the client apply them, and answers
/// `{"applied": bool, "edits": number}`. Nothing to change is answered as applied, without asking the
/// client.
pub async fn execute(shared: &Shared, command: &str, arguments: &[Value]) -> Result<Option<Value>> {
    let (uri, rewrite) =
        Rewrite::from_command(command, arguments).map_err(Error::invalid_params)?;
    let encoding = shared.encoding();
    let (version, edits) = shared
        .on_analysis(&uri, move |analysed| {
            rewrite.line_edits(analysed).map(|edits| {
                (
                    analysed.version,
                    text_edits(&edits, &analysed.lines(), encoding),
                )
            })
        })
        .await?
        .map_err(Error::invalid_params)?;
    let count = edits.len();
    if count == 0 {
        return Ok(Some(json!({"applied": true, "edits": 0})));
    }
    let edit = workspace_edit(
        vec![DocumentEdits {
            uri,
            version: Some(version),
            edits,
        }],
        shared.versioned_edits(),
    );
    let params = ApplyWorkspaceEditParams {
        label: Some(rewrite.label().to_string()),
        edit,
    };
    let applied = match shared
        .client
        .send_request::<ApplyWorkspaceEdit>(params)
        .await
    {
        Ok(response) => {
            if !response.applied {
                shared.warn(format!(
                    "{command}: the client did not apply the edit{}",
                    response
                        .failure_reason
                        .map(|reason| format!(": {reason}"))
                        .unwrap_or_default()
                ));
            }
            response.applied
        }
        Err(error) => {
            shared.warn(format!("{command}: workspace/applyEdit failed: {error}"));
            false
        }
    };
    Ok(Some(json!({"applied": applied, "edits": count})))
}

/// `textDocument/formatting` and `textDocument/rangeFormatting`: the formatting edits of the lines
/// that `range` touches (all lines when `None`).
pub fn formatting_edits(
    analysed: &Analysed,
    range: Option<Range>,
    encoding: PositionEncoding,
) -> Vec<TextEdit> {
    let mut edits = Rewrite::Format.line_edits(analysed).unwrap_or_default();
    if let Some(range) = range {
        let (first, last) = touched_lines(range);
        edits.retain(|edit| first <= edit.line && edit.line <= last);
    }
    text_edits(&edits, &analysed.lines(), encoding)
}

/// The lines a range touches. A range that ends at the start of a later line (a selection of whole
/// lines) does not touch that line.
fn touched_lines(range: Range) -> (usize, usize) {
    let first = range.start.line.min(range.end.line) as usize;
    let mut last = range.start.line.max(range.end.line) as usize;
    if range.end.character == 0 && last > first && range.end.line as usize == last {
        last -= 1;
    }
    (first, last)
}

#[cfg(test)]
mod tests {
    use super::*;
    use tower_lsp_server::ls_types::Position;

    #[test]
    fn a_selection_of_whole_lines_does_not_take_the_next_line() {
        let range = |a: (u32, u32), b: (u32, u32)| {
            Range::new(Position::new(a.0, a.1), Position::new(b.0, b.1))
        };
        assert_eq!(touched_lines(range((2, 0), (4, 0))), (2, 3));
        assert_eq!(touched_lines(range((2, 3), (4, 1))), (2, 4));
        assert_eq!(touched_lines(range((2, 0), (2, 0))), (2, 2));
    }

    #[test]
    fn arguments_are_read_with_defaults_and_refused_when_wrong() {
        let (_, rewrite) = Rewrite::from_command(
            RENUMBER_COMMAND,
            &[json!({"uri": "file:///a.mpf", "step": 5, "mode": "drop"})],
        )
        .unwrap();
        match rewrite {
            Rewrite::Renumber(options) => {
                assert_eq!(options.start, 10);
                assert_eq!(options.step, 5);
                assert_eq!(options.mode, NumberingMode::Drop);
            }
            Rewrite::Format => panic!("a renumbering was asked for"),
        }
        let error = Rewrite::from_command(
            RENUMBER_COMMAND,
            &[json!({"uri": "file:///a.mpf", "mode": "sometimes"})],
        )
        .unwrap_err();
        assert!(error.contains("sometimes"), "{error}");
        assert!(Rewrite::from_command(FORMAT_COMMAND, &[]).is_err());
    }
}
