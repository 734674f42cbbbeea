//! Go to definition, references, document highlights, prepare rename and rename, and workspace
//! symbols: the protocol's form of `ide::navigation` over the server's workspace index. Locations in
//! other documents are converted with those documents' own lines: an open document's current text,
//! or the file on disk read as `check` reads it (not read at all when it is ASCII).

use crate::diagnostics::Span;
use crate::ide::navigation::{self, RenameError, Role, WorkspaceSymbolKind};
use crate::ide::workspace::file_name_for_program;
use crate::ide::{DocumentId, Location as IdeLocation};
use crate::lsp::convert::{character_to_byte, span_to_range, PositionEncoding};
use crate::lsp::documents::Analysed;
use crate::lsp::handlers::workspace_edit::{
    workspace_edit, workspace_edit_with_renames, DocumentEdits,
};
use crate::lsp::state::{DocumentRequest, Shared};
use crate::lsp::uris::file_path;
use crate::lsp::workspace::index::IndexState;
use crate::lsp::workspace::updates::update_all_open;
use std::collections::HashMap;
use tower_lsp_server::jsonrpc::{Error, ErrorCode};
use tower_lsp_server::ls_types::{
    DocumentHighlight, DocumentHighlightKind, Location, Position, PrepareRenameResponse, Range,
    SymbolInformation, SymbolKind, TextEdit, Uri, WorkspaceEdit,
};

/// The cursor of a request in the analysed document: its index id, line and byte offset.
pub struct Cursor {
    pub id: DocumentId,
    pub line: usize,
    pub byte: usize,
}

impl Cursor {
    pub fn new(
        id: DocumentId,
        analysed: &Analysed,
        position: Position,
        encoding: PositionEncoding,
    ) -> Cursor {
        let (line, _, byte) = line_at(analysed, position, encoding).unwrap_or((
            position.line as usize,
            String::new(),
            0,
        ));
        Cursor { id, line, byte }
    }
}

/// The line of a position, its text and the position's byte offset in it; `None` past the end.
pub fn line_at(
    analysed: &Analysed,
    position: Position,
    encoding: PositionEncoding,
) -> Option<(usize, String, usize)> {
    use crate::analysis::document::LineSource;
    let line = position.line as usize;
    let lines = analysed.lines();
    if line >= lines.line_count() {
        return None;
    }
    let text = lines.line(line).into_owned();
    let byte = character_to_byte(&text, position.character, encoding);
    Some((line, text, byte))
}

/// The text of line `line` of the analysed document (empty past the end).
fn line_text(analysed: &Analysed, line: usize) -> String {
    use crate::analysis::document::LineSource;
    analysed.lines().line(line).into_owned()
}

/// The lines of the documents that locations point into, read once per document.
pub struct LineTexts<'a> {
    shared: &'a Shared,
    state: &'a IndexState,
    encoding: PositionEncoding,
    /// The document of the request, as the request saw it.
    current: Option<(&'a DocumentId, &'a Analysed)>,
    /// Other documents: their lines and version (`None` for files on disk).
    others: HashMap<DocumentId, (Vec<String>, Option<i32>)>,
}

impl<'a> LineTexts<'a> {
    pub fn new(
        shared: &'a Shared,
        state: &'a IndexState,
        encoding: PositionEncoding,
        current: Option<(&'a DocumentId, &'a Analysed)>,
    ) -> LineTexts<'a> {
        LineTexts {
            shared,
            state,
            encoding,
            current,
            others: HashMap::new(),
        }
    }

    fn load(&mut self, id: &DocumentId) -> &(Vec<String>, Option<i32>) {
        let shared = self.shared;
        let uri = self.state.uri(id).cloned();
        self.others.entry(id.clone()).or_insert_with(|| {
            let split = |text: &str| -> Vec<String> {
                crate::syntax::lines::line_ranges(text)
                    .map(|(start, end)| text[start..end].to_string())
                    .collect()
            };
            if let Some(document) = uri.as_ref().and_then(|uri| shared.documents.get(uri)) {
                let (version, text) = document.text_now();
                return (split(&text), Some(version));
            }
            let text = uri
                .as_ref()
                .and_then(file_path)
                .and_then(|path| crate::io::source_file::read_source_file(&path).ok())
                .map(|source| source.text)
                .unwrap_or_default();
            (split(&text), None)
        })
    }

    /// The range of a span of a line of a document.
    pub fn range(&mut self, id: &DocumentId, line: usize, span: Span) -> Range {
        if let Some((_, analysed)) = self.current.filter(|(current, _)| *current == id) {
            let text = line_text(analysed, line);
            return span_to_range(line, &text, span, self.encoding);
        }
        if self.state.is_ascii(id) {
            let line_number = u32::try_from(line).unwrap_or(u32::MAX);
            let column = |byte: usize| u32::try_from(byte).unwrap_or(u32::MAX);
            return Range::new(
                Position::new(line_number, column(span.start())),
                Position::new(line_number, column(span.end().max(span.start()))),
            );
        }
        let encoding = self.encoding;
        let (lines, _) = self.load(id);
        let text = lines.get(line).map(String::as_str).unwrap_or("");
        span_to_range(line, text, span, encoding)
    }

    /// The version of an open document (the one of the request for its own document).
    pub fn version(&mut self, id: &DocumentId) -> Option<i32> {
        if let Some((_, analysed)) = self.current.filter(|(current, _)| *current == id) {
            return Some(analysed.version);
        }
        let uri = self.state.uri(id)?;
        self.shared
            .documents
            .get(uri)
            .map(|document| document.version())
    }

    pub fn location(&mut self, location: &IdeLocation) -> Option<Location> {
        let uri = self.state.uri(&location.document)?.clone();
        let range = self.range(&location.document, location.line, location.span);
        Some(Location { uri, range })
    }
}

fn locations(texts: &mut LineTexts<'_>, found: &[IdeLocation]) -> Vec<Location> {
    found
        .iter()
        .filter_map(|location| texts.location(location))
        .collect()
}

/// `textDocument/definition`.
pub fn definition(
    request: &DocumentRequest,
    analysed: &Analysed,
    position: Position,
) -> Vec<Location> {
    let (shared, uri, encoding) = (&*request.shared, &request.uri, request.encoding);
    let id = shared.workspace.ensure_current(uri, analysed);
    let cursor = Cursor::new(id.clone(), analysed, position, encoding);
    let state = shared.workspace.read();
    let found = navigation::definition(&state.index, &cursor.id, cursor.line, cursor.byte);
    let mut texts = LineTexts::new(shared, &state, encoding, Some((&id, analysed)));
    locations(&mut texts, &found)
}

/// `textDocument/references`: every open document is brought up to date first.
pub fn references(
    request: &DocumentRequest,
    analysed: &Analysed,
    position: Position,
    include_declaration: bool,
) -> Vec<Location> {
    let (shared, uri, encoding) = (&*request.shared, &request.uri, request.encoding);
    update_all_open(shared);
    let id = shared.workspace.ensure_current(uri, analysed);
    let cursor = Cursor::new(id.clone(), analysed, position, encoding);
    let state = shared.workspace.read();
    let found = navigation::references(
        &state.index,
        &cursor.id,
        cursor.line,
        cursor.byte,
        include_declaration,
    );
    let mut texts = LineTexts::new(shared, &state, encoding, Some((&id, analysed)));
    locations(&mut texts, &found)
}

/// `textDocument/documentHighlight`: a label and its jumps, a variable and its reads and writes
/// (nothing while a large document's entry is older than its text, see `current_if_cheap`).
pub fn highlights(
    request: &DocumentRequest,
    analysed: &Analysed,
    position: Position,
) -> Vec<DocumentHighlight> {
    let (shared, uri, encoding) = (&*request.shared, &request.uri, request.encoding);
    let Some(id) = shared.workspace.current_if_cheap(uri, analysed) else {
        return Vec::new();
    };
    let cursor = Cursor::new(id.clone(), analysed, position, encoding);
    let state = shared.workspace.read();
    let found = navigation::highlights(&state.index, &cursor.id, cursor.line, cursor.byte);
    let mut texts = LineTexts::new(shared, &state, encoding, Some((&id, analysed)));
    found
        .into_iter()
        .map(|(line, span, role)| DocumentHighlight {
            range: texts.range(&id, line, span),
            kind: Some(match role {
                Role::Definition => DocumentHighlightKind::TEXT,
                Role::Read => DocumentHighlightKind::READ,
                Role::Write => DocumentHighlightKind::WRITE,
            }),
        })
        .collect()
}

/// `textDocument/prepareRename`: the renamable name at the cursor, `None` where there is none.
pub fn prepare_rename(
    request: &DocumentRequest,
    analysed: &Analysed,
    position: Position,
) -> Option<PrepareRenameResponse> {
    let (shared, uri, encoding) = (&*request.shared, &request.uri, request.encoding);
    let id = shared.workspace.ensure_current(uri, analysed);
    let cursor = Cursor::new(id.clone(), analysed, position, encoding);
    let state = shared.workspace.read();
    let (span, _) = navigation::prepare_rename(&state.index, &cursor.id, cursor.line, cursor.byte)?;
    let text = line_text(analysed, cursor.line);
    let placeholder = text.get(span.start()..span.end()).unwrap_or("").to_string();
    Some(PrepareRenameResponse::RangeWithPlaceholder {
        range: span_to_range(cursor.line, &text, span, encoding),
        placeholder,
    })
}

/// The error of a refused rename: the reason, for the editor to show.
fn rename_error(error: RenameError) -> Error {
    let message = match error {
        RenameError::NothingToRename => "there is nothing to rename here".to_string(),
        RenameError::Refused(reason) => reason,
    };
    Error {
        // RequestFailed: the request was valid, the rename cannot be done.
        code: ErrorCode::ServerError(-32803),
        message: message.into(),
        data: None,
    }
}

/// `textDocument/rename` across the workspace; every open document is brought up to date first
/// and edited at its current version.
pub fn rename(
    request: &DocumentRequest,
    analysed: &Analysed,
    position: Position,
    new_name: &str,
) -> Result<WorkspaceEdit, Error> {
    let (shared, uri, encoding) = (&*request.shared, &request.uri, request.encoding);
    update_all_open(shared);
    let id = shared.workspace.ensure_current(uri, analysed);
    let cursor = Cursor::new(id.clone(), analysed, position, encoding);
    let state = shared.workspace.read();
    let config = analysed.analysis.config();
    let edit = navigation::rename(
        &state.index,
        config,
        &cursor.id,
        cursor.line,
        cursor.byte,
        new_name,
    )
    .map_err(rename_error)?;
    // The control finds a program by its file name: the files named after the renamed program are
    // renamed in the same edit, or the rename is refused.
    let file_renames = file_renames(&state, &edit.renamed_programs, shared.renames_files())?;
    let mut texts = LineTexts::new(shared, &state, encoding, Some((&id, analysed)));
    let mut documents = Vec::new();
    for (document, edits) in &edit.changes {
        let Some(target) = state.uri(document).cloned() else {
            continue;
        };
        let text_edits: Vec<TextEdit> = edits
            .iter()
            .map(|line_edit| TextEdit {
                range: texts.range(document, line_edit.line, line_edit.span),
                new_text: line_edit.new_text.clone(),
            })
            .collect();
        documents.push(DocumentEdits {
            uri: target,
            version: texts.version(document),
            edits: text_edits,
        });
    }
    if file_renames.is_empty() {
        Ok(workspace_edit(documents, shared.versioned_edits()))
    } else {
        Ok(workspace_edit_with_renames(documents, file_renames))
    }
}

/// The file renames that go with a program rename, as (old, new) URIs: each file named after the
/// program gets the new name in the same style ([`file_name_for_program`]). Refused when
/// the client cannot rename files or a file of the new name exists already.
fn file_renames(
    state: &IndexState,
    renamed_programs: &[(DocumentId, String)],
    client_renames_files: bool,
) -> Result<Vec<(Uri, Uri)>, Error> {
    let mut renames = Vec::new();
    for (document, new_program) in renamed_programs {
        let Some(old_uri) = state.uri(document) else {
            continue;
        };
        let refused = |reason: String| rename_error(RenameError::Refused(reason));
        let Some(old_path) = file_path(old_uri) else {
            return Err(refused(format!(
                "`{new_program}` would need {} renamed, which is not a file",
                old_uri.as_str()
            )));
        };
        let old_name = old_path
            .file_name()
            .map(|name| name.to_string_lossy().into_owned())
            .unwrap_or_default();
        if !client_renames_files {
            return Err(refused(format!(
                "the control finds the program by its file name, so {old_name} must be renamed too, and this editor does not let the language server rename files: rename the file first, then the program"
            )));
        }
        let new_name = file_name_for_program(&old_name, new_program);
        let new_path = old_path.with_file_name(&new_name);
        if new_path.exists() {
            return Err(refused(format!(
                "{old_name} would be renamed to {new_name}, which exists already"
            )));
        }
        let Some(new_uri) = Uri::from_file_path(&new_path) else {
            continue;
        };
        renames.push((old_uri.clone(), new_uri));
    }
    Ok(renames)
}

/// `workspace/symbol`: programs, labels, global variables and macros whose name contains the query.
pub fn workspace_symbols(
    shared: &Shared,
    query: &str,
    encoding: PositionEncoding,
) -> Vec<SymbolInformation> {
    let state = shared.workspace.read();
    let found = navigation::workspace_symbols(&state.index, query);
    let mut texts = LineTexts::new(shared, &state, encoding, None);
    found
        .into_iter()
        .filter_map(|(name, kind, location)| {
            #[allow(deprecated)]
            Some(SymbolInformation {
                name,
                kind: match kind {
                    WorkspaceSymbolKind::Program => SymbolKind::FUNCTION,
                    WorkspaceSymbolKind::Label => SymbolKind::KEY,
                    WorkspaceSymbolKind::GlobalVariable => SymbolKind::VARIABLE,
                    WorkspaceSymbolKind::Macro => SymbolKind::CONSTANT,
                },
                tags: None,
                deprecated: None,
                location: texts.location(&location)?,
                container_name: None,
            })
        })
        .collect()
}

/// The hover documentation of the word at `byte` of line `line` (whose text is `line_text`) of the
/// analysed document. While the entry of a large document is older than its text, only the
/// language's own words are documented (the document's symbols could be on other lines now).
pub fn documentation(
    request: &DocumentRequest,
    analysed: &Analysed,
    line_text: &str,
    line: usize,
    byte: usize,
) -> Option<crate::ide::documentation::Documentation> {
    let workspace = &request.shared.workspace;
    let id = workspace
        .current_if_cheap(&request.uri, analysed)
        .unwrap_or_else(|| DocumentId::from(""));
    let state = workspace.read();
    crate::ide::documentation::documentation_at(&state.index, &id, line_text, line, byte)
}
