//! Workspace edits as the client can take them: `documentChanges` with the version of each document
//! when the client supports it (so it refuses an edit computed for an older text), else `changes`;
//! and the conversion of the core's line edits to text edits in the negotiated encoding.

use crate::analysis::document::LineSource;
use crate::ide::LineEdit;
use crate::lsp::convert::{span_to_range, PositionEncoding};
use std::collections::HashMap;
use tower_lsp_server::ls_types::{
    DocumentChangeOperation, DocumentChanges, OneOf, OptionalVersionedTextDocumentIdentifier,
    RenameFile, RenameFileOptions, ResourceOp, TextDocumentEdit, TextEdit, Uri, WorkspaceEdit,
};

/// The edits of one document: its URI, the version they were computed for (`None` for a file that
/// is not open) and the text edits.
pub struct DocumentEdits {
    pub uri: Uri,
    pub version: Option<i32>,
    pub edits: Vec<TextEdit>,
}

/// The edits of one document with its version.
fn text_document_edit(document: DocumentEdits) -> TextDocumentEdit {
    TextDocumentEdit {
        text_document: OptionalVersionedTextDocumentIdentifier {
            uri: document.uri,
            version: document.version,
        },
        edits: document.edits.into_iter().map(OneOf::Left).collect(),
    }
}

/// One workspace edit holding the versioned edits of every document, then the renames of files as
/// (old, new) URIs: the client applies the operations in order, so each file is edited under its old
/// name first. A file is never overwritten.
pub fn workspace_edit_with_renames(
    documents: Vec<DocumentEdits>,
    renames: Vec<(Uri, Uri)>,
) -> WorkspaceEdit {
    let edits = documents
        .into_iter()
        .map(|document| DocumentChangeOperation::Edit(text_document_edit(document)));
    let renames = renames.into_iter().map(|(old_uri, new_uri)| {
        DocumentChangeOperation::Op(ResourceOp::Rename(RenameFile {
            old_uri,
            new_uri,
            options: Some(RenameFileOptions {
                overwrite: Some(false),
                ignore_if_exists: Some(false),
            }),
            annotation_id: None,
        }))
    });
    WorkspaceEdit {
        document_changes: Some(DocumentChanges::Operations(edits.chain(renames).collect())),
        ..WorkspaceEdit::default()
    }
}

/// One workspace edit holding the edits of every document.
pub fn workspace_edit(documents: Vec<DocumentEdits>, versioned: bool) -> WorkspaceEdit {
    if versioned {
        let edits = documents.into_iter().map(text_document_edit).collect();
        WorkspaceEdit {
            document_changes: Some(DocumentChanges::Edits(edits)),
            ..WorkspaceEdit::default()
        }
    } else {
        let changes: HashMap<Uri, Vec<TextEdit>> = documents
            .into_iter()
            .map(|document| (document.uri, document.edits))
            .collect();
        WorkspaceEdit {
            changes: Some(changes),
            ..WorkspaceEdit::default()
        }
    }
}

/// The core's edits (byte spans of one line each) as text edits, reading each edited line once.
pub fn text_edits(
    edits: &[LineEdit],
    lines: &dyn LineSource,
    encoding: PositionEncoding,
) -> Vec<TextEdit> {
    let mut current: Option<(usize, String)> = None;
    edits
        .iter()
        .map(|edit| {
            if current.as_ref().map(|(line, _)| *line) != Some(edit.line) {
                current = Some((edit.line, lines.line(edit.line).into_owned()));
            }
            let line = current.as_ref().map_or("", |(_, text)| text.as_str());
            TextEdit {
                range: span_to_range(edit.line, line, edit.span, encoding),
                new_text: edit.new_text.clone(),
            }
        })
        .collect()
}
