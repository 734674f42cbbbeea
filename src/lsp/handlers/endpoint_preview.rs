//! `sinumerik.endpointPreview`: the JSON document of `sinumerik-lsp preview` for an open document
//! (its current text) or for a file on disk, optionally for some of its lines only.

use crate::analysis::document::{DocumentAnalysis, LineSource, TextLines};
use crate::analysis::library::ProgramLibrary;
use crate::analysis::ProgramKind;
use crate::config::MachineConfig;
use crate::ide::execution::{execute_document, DocumentExecution};
use crate::ide::timing::DocumentTimes;
use crate::ide::timing::{TimeModel, TimeTotals};
use crate::io::preview_json::{line_columns, write_executed_preview_json, write_preview_json};
use crate::io::source_file::read_source_file;
use crate::lsp::documents::Analysed;
use crate::lsp::ext::{EndpointPreviewParams, ENDPOINT_PREVIEW_COMMAND};
use crate::lsp::state::Shared;
use crate::lsp::uris::{file_path, program_kind};
use serde_json::Value;
use std::path::Path;
use std::sync::Arc;
use tower_lsp_server::jsonrpc::Error;

/// Lines `start ..= end` (0-based); a missing end is the end of the document.
#[derive(Debug, Clone, Copy)]
pub struct LineSelection {
    pub start: Option<u32>,
    pub end: Option<u32>,
}

impl LineSelection {
    fn range(self, line_count: usize) -> std::ops::Range<usize> {
        let start = self.start.map_or(0, |start| start as usize).min(line_count);
        let end = self
            .end
            .map_or(line_count, |end| (end as usize).saturating_add(1))
            .min(line_count);
        start..end.max(start)
    }
}

fn preview(
    analysis: &DocumentAnalysis,
    execution: &DocumentExecution,
    times: Option<&DocumentTimes>,
    source: &dyn LineSource,
    label: &str,
    lines: LineSelection,
) -> Result<Value, String> {
    let range = lines.range(source.line_count());
    // Each move's time, and the totals of the lines asked for: from the document's times (with the
    // dwells) when they are made, else from the moves listed.
    let model = TimeModel::new(analysis.config());
    let diagnostics = analysis.diagnostics();
    let first = diagnostics.partition_point(|item| item.line < range.start);
    let last = diagnostics.partition_point(|item| item.line < range.end);
    let mut diagnostics = diagnostics[first..last.max(first)].to_vec();
    diagnostics.extend(
        execution
            .findings()
            .iter()
            .filter(|item| range.contains(&item.line))
            .cloned(),
    );
    diagnostics.sort_by_key(|item| (item.line, item.diagnostic.span.start()));
    let mut json = Vec::new();
    let mut columns = |line_idx: usize, span| line_columns(&source.line(line_idx), span);
    let executed = execution.moves_in(range.clone());
    let in_order = match executed {
        Some(_) => Vec::new(),
        None => analysis.moves(source, range.clone()),
    };
    let totals = match times {
        Some(times) => times.totals_in(range.clone()),
        None => {
            let mut totals = TimeTotals::default();
            let listed = executed.iter().flatten().map(|executed| &executed.movement);
            for movement in listed.chain(in_order.iter()) {
                totals.add(model.time_of(movement));
            }
            totals
        }
    };
    match executed {
        Some(moves) => write_executed_preview_json(
            &mut json,
            label,
            analysis.config().metric,
            execution.assumed(),
            &moves,
            (&model, &totals),
            &diagnostics,
            &mut columns,
        ),
        None => write_preview_json(
            &mut json,
            label,
            analysis.config().metric,
            &in_order,
            (&model, &totals),
            &diagnostics,
            &mut columns,
        ),
    }
    .map_err(|error| format!("cannot write the preview: {error}"))?;
    let mut value: Value = serde_json::from_slice(&json)
        .map_err(|error| format!("cannot read the preview back: {error}"))?;
    // `time` sums the lines asked for; `program_time` is the whole document's, the same for every
    // range, so that a client fetching ranges whose ends overlap needs not add them up.
    let (Some(times), Some(object)) = (times, value.as_object_mut()) else {
        return Ok(value);
    };
    let whole = times.totals();
    {
        object.insert(
            "program_time".to_string(),
            serde_json::json!({
                "total_s": whole.total_s,
                "feed_s": whole.feed_s,
                "rapid_s": whole.rapid_s,
                "dwell_s": whole.dwell_s,
                "unknown_moves": whole.unknown_moves,
            }),
        );
    }
    Ok(value)
}

/// The preview of an open document, from its up-to-date analysis.
pub fn preview_open(
    analysed: &Analysed,
    label: &str,
    lines: LineSelection,
    library: &dyn ProgramLibrary,
) -> Result<Value, String> {
    let execution = analysed.execution(library);
    // The document's times are made by a request from its first line (where a client's load of the
    // toolpath starts) or found made; a request for a few lines in the middle of a large document
    // after each edit does not read the whole program again.
    let times = if lines.start.unwrap_or(0) == 0 {
        Some(analysed.times(library))
    } else {
        analysed.cached_times(library)
    };
    preview(
        &analysed.analysis,
        &execution,
        times.as_deref(),
        &analysed.lines(),
        label,
        lines,
    )
}

/// The preview of a file on disk, read as `check` reads it (UTF-8, else Windows-1252).
pub fn preview_file(
    path: &Path,
    label: &str,
    config: Arc<MachineConfig>,
    kind: ProgramKind,
    lines: LineSelection,
    library: &dyn ProgramLibrary,
) -> Result<Value, String> {
    let source = read_source_file(path).map_err(|error| format!("{}: {error}", path.display()))?;
    let text_lines = TextLines::new(&source.text);
    let analysis = DocumentAnalysis::new(&text_lines, Arc::clone(&config), kind);
    let execution = execute_document(&text_lines, &config, kind, library, &config.execution, None);
    let times = DocumentTimes::new(&text_lines, &execution, &config, kind);
    preview(
        &analysis,
        &execution,
        Some(&times),
        &text_lines,
        label,
        lines,
    )
}

/// `workspace/executeCommand` of `sinumerik.endpointPreview`: the preview of an open document (on
/// its analysis) or of a file on disk.
pub async fn execute(
    shared: &Arc<Shared>,
    command: &str,
    arguments: &[Value],
) -> tower_lsp_server::jsonrpc::Result<Option<Value>> {
    if command != ENDPOINT_PREVIEW_COMMAND {
        return Err(Error::invalid_params(format!(
            "unknown command {}",
            command
        )));
    }
    let [argument] = arguments else {
        return Err(Error::invalid_params(format!(
            "{ENDPOINT_PREVIEW_COMMAND} takes one argument {{\"uri\", \"startLine\"?, \"endLine\"?}}"
        )));
    };
    let preview: EndpointPreviewParams = serde_json::from_value(argument.clone())
        .map_err(|error| Error::invalid_params(format!("{ENDPOINT_PREVIEW_COMMAND}: {error}")))?;
    let lines = LineSelection {
        start: preview.start_line,
        end: preview.end_line,
    };
    let label = file_path(&preview.uri)
        .map(|path| path.display().to_string())
        .unwrap_or_else(|| preview.uri.as_str().to_string());
    let library = crate::lsp::workspace::library::workspace_library(
        shared,
        file_path(&preview.uri).as_deref(),
    );
    if shared.documents.get(&preview.uri).is_some() {
        let result = shared
            .on_analysis(&preview.uri, move |analysed| {
                preview_open(analysed, &label, lines, library.as_ref())
            })
            .await?;
        return result.map(Some).map_err(Error::invalid_params);
    }
    let path = file_path(&preview.uri).ok_or_else(|| {
        Error::invalid_params(format!(
            "{} is neither open nor a file: URI",
            preview.uri.as_str()
        ))
    })?;
    let config = shared.machine_config(Some(&path));
    let kind = program_kind(&preview.uri, Some(&path));
    let result = tokio::task::spawn_blocking(move || {
        preview_file(&path, &label, config, kind, lines, library.as_ref())
    })
    .await
    .map_err(|_| Error::internal_error())?;
    result.map(Some).map_err(Error::invalid_params)
}
