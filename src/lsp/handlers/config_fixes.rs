//! Quick fixes that change the machine configuration instead of the program: `kind = "turn"` for
//! diameter programming or G96 on a machine without a transverse axis (A235, A236), and an axis the
//! machine does not have (S180) added to `[axes]`. The file edited is the `sinumerik.toml` the document
//! is checked with (the `configFile` setting, or the nearest one from the document's folder upward);
//! without one, it is created in the document's folder. The edit is a workspace edit with
//! `documentChanges`: CreateFile (never overwriting) and the text edits, computed on the file as it is
//! on disk by `config::edit`, which keeps every other key and comment.

use crate::analysis::document::LineSource;
use crate::config::edit::{axis_edits, lathe_edits, new_axis_kind, ConfigTextEdit};
use crate::config::{discover_config_file, MachineConfig, CONFIG_FILE_NAME};
use crate::diagnostics::{Code, LineDiagnostic};
use crate::lsp::convert::{diagnostic_to_lsp, PositionEncoding};
use crate::lsp::documents::Analysed;
use crate::lsp::settings::Settings;
use crate::syntax::unconfigured_axes;
use std::path::{Path, PathBuf};
use tower_lsp_server::ls_types::{
    CodeAction, CodeActionKind, CodeActionOrCommand, CreateFile, CreateFileOptions,
    DocumentChangeOperation, DocumentChanges, OneOf, OptionalVersionedTextDocumentIdentifier,
    Position, Range, ResourceOp, TextDocumentEdit, TextEdit, Uri, WorkspaceEdit,
};

/// The configuration file a document's fixes edit: its path, and its text when it exists.
pub struct ConfigTarget {
    pub path: PathBuf,
    pub text: Option<String>,
}

impl ConfigTarget {
    /// The file for the document at `document` (a file path), as the server chooses its
    /// configuration (see `settings::machine_config_for`); reads it when it exists. `None` when the
    /// document is not a file, or the file exists and cannot be read as UTF-8.
    pub fn for_document(
        document: &Path,
        settings: &Settings,
        workspace_root: Option<&Path>,
    ) -> Option<ConfigTarget> {
        let folder = document.parent()?;
        let path = match &settings.config_file {
            Some(file) if file.is_relative() => workspace_root
                .map(|root| root.join(file))
                .unwrap_or_else(|| file.clone()),
            Some(file) => file.clone(),
            None => discover_config_file(folder).unwrap_or_else(|| folder.join(CONFIG_FILE_NAME)),
        };
        let text = match std::fs::read(&path) {
            Ok(bytes) => Some(String::from_utf8(bytes).ok()?),
            Err(error) if error.kind() == std::io::ErrorKind::NotFound => None,
            Err(_) => return None,
        };
        Some(ConfigTarget { path, text })
    }
}

/// The configuration fixes of the findings of `analysed` in `range`, for the document at
/// `document_path`; the configuration file is read only when a finding there has such a fix.
pub fn actions_for(
    analysed: &Analysed,
    range: Range,
    document_path: Option<&Path>,
    settings: &Settings,
    workspace_root: Option<&Path>,
    encoding: PositionEncoding,
) -> Vec<CodeActionOrCommand> {
    let diagnostics = analysed.analysis.diagnostics();
    let start = diagnostics.partition_point(|item| item.line < range.start.line as usize);
    let wanted = diagnostics[start..]
        .iter()
        .take_while(|item| item.line <= range.end.line as usize)
        .any(|item| has_config_fix(item.diagnostic.code));
    let Some(target) = document_path
        .filter(|_| wanted)
        .and_then(|path| ConfigTarget::for_document(path, settings, workspace_root))
    else {
        return Vec::new();
    };
    let lines = analysed.lines();
    config_actions(
        diagnostics,
        &|line| lines.line(line).into_owned(),
        range,
        analysed.analysis.config(),
        &target,
        encoding,
    )
}

/// Whether findings of `code` get a fix in the configuration file.
fn has_config_fix(code: Code) -> bool {
    matches!(
        code,
        Code::DiameterWithoutTransverseAxis
            | Code::CuttingSpeedWithoutTransverseAxis
            | Code::AxisNotConfigured
    )
}

/// The configuration fixes of the findings in `diagnostics` whose range meets `range`; `line_text`
/// gives a line of the document.
pub fn config_actions(
    diagnostics: &[LineDiagnostic],
    line_text: &dyn Fn(usize) -> String,
    range: Range,
    config: &MachineConfig,
    target: &ConfigTarget,
    encoding: PositionEncoding,
) -> Vec<CodeActionOrCommand> {
    let Some(uri) = Uri::from_file_path(&target.path) else {
        return Vec::new();
    };
    let file_name = target
        .path
        .file_name()
        .map(|name| name.to_string_lossy().into_owned())
        .unwrap_or_else(|| CONFIG_FILE_NAME.to_string());
    let start = diagnostics.partition_point(|item| item.line < range.start.line as usize);
    let mut actions = Vec::new();
    for item in diagnostics[start..]
        .iter()
        .take_while(|item| item.line <= range.end.line as usize)
    {
        let (title, edits) = match item.diagnostic.code {
            Code::DiameterWithoutTransverseAxis | Code::CuttingSpeedWithoutTransverseAxis => {
                let Some(edits) = lathe_edits(target.text.as_deref()) else {
                    continue;
                };
                (
                    format!("Configure a lathe: kind = \"turn\" in {file_name}"),
                    edits,
                )
            }
            Code::AxisNotConfigured => {
                let Some(name) = unconfigured_axes::axis_of(&item.diagnostic.message) else {
                    continue;
                };
                let kind = new_axis_kind(name);
                let Some(edits) = axis_edits(target.text.as_deref(), config, name, kind) else {
                    continue;
                };
                (
                    format!(
                        "Add the {} axis {name} to [axes] in {file_name}",
                        kind.as_str()
                    ),
                    edits,
                )
            }
            _ => continue,
        };
        let diagnostic = diagnostic_to_lsp(item, &line_text(item.line), encoding);
        if !overlaps(diagnostic.range, range) {
            continue;
        }
        let text = target.text.as_deref().unwrap_or("");
        actions.push(CodeActionOrCommand::CodeAction(CodeAction {
            title,
            kind: Some(CodeActionKind::QUICKFIX),
            diagnostics: Some(vec![diagnostic]),
            edit: Some(file_edit(
                &uri,
                target.text.is_none(),
                text,
                &edits,
                encoding,
            )),
            ..CodeAction::default()
        }));
    }
    actions
}

fn overlaps(left: Range, right: Range) -> bool {
    let before = |a: Position, b: Position| (a.line, a.character) <= (b.line, b.character);
    before(left.start, right.end) && before(right.start, left.end)
}

/// The workspace edit: the file created first when it does not exist (never overwritten), then the
/// text edits.
fn file_edit(
    uri: &Uri,
    create: bool,
    text: &str,
    edits: &[ConfigTextEdit],
    encoding: PositionEncoding,
) -> WorkspaceEdit {
    let mut operations = Vec::new();
    if create {
        operations.push(DocumentChangeOperation::Op(ResourceOp::Create(
            CreateFile {
                uri: uri.clone(),
                options: Some(CreateFileOptions {
                    overwrite: Some(false),
                    ignore_if_exists: Some(true),
                }),
                annotation_id: None,
            },
        )));
    }
    let edits = edits
        .iter()
        .map(|edit| {
            OneOf::Left(TextEdit {
                range: Range::new(
                    position_of(text, edit.start, encoding),
                    position_of(text, edit.end, encoding),
                ),
                new_text: edit.text.clone(),
            })
        })
        .collect();
    operations.push(DocumentChangeOperation::Edit(TextDocumentEdit {
        text_document: OptionalVersionedTextDocumentIdentifier {
            uri: uri.clone(),
            version: None,
        },
        edits,
    }));
    WorkspaceEdit {
        document_changes: Some(DocumentChanges::Operations(operations)),
        ..WorkspaceEdit::default()
    }
}

/// The position of the byte `offset` of `text` (at a character boundary) in the negotiated encoding.
fn position_of(text: &str, offset: usize, encoding: PositionEncoding) -> Position {
    let before = &text[..offset.min(text.len())];
    let line_start = before.rfind('\n').map_or(0, |index| index + 1);
    let line = before.matches('\n').count() as u32;
    let column = &before[line_start..];
    let character = match encoding {
        PositionEncoding::Utf8 => column.len(),
        PositionEncoding::Utf16 => column.encode_utf16().count(),
    };
    Position::new(line, character as u32)
}
