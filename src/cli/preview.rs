//! `preview`: the resolved moves of one program as JSON or CSV, for tools and for the toolpath view.

use super::args::{PreviewFormat, PreviewOptions};
use super::report::ProgramLines;
use super::source_file::read_source_file;
use super::{EXIT_ERRORS_FOUND, EXIT_OK, EXIT_TROUBLE};
use crate::analysis::{analyze_program, Move, ProgramKind};
use crate::config::{discover_config_file, load_config_file, MachineConfig};
use crate::diagnostics::{LineDiagnostic, Severity, Span};
use serde_json::{json, Map, Value};
use std::io::{self, Write};
use std::path::Path;

pub(crate) fn run_preview(
    options: &PreviewOptions,
    stdout: &mut dyn Write,
    stderr: &mut dyn Write,
) -> io::Result<u8> {
    let config = match config_for(options) {
        Ok(config) => config,
        Err(message) => {
            writeln!(stderr, "sinumerik-lsp: {message}")?;
            return Ok(EXIT_TROUBLE);
        }
    };
    let source = match read_source_file(&options.path) {
        Ok(source) => source,
        Err(io_error) => {
            writeln!(
                stderr,
                "sinumerik-lsp: {}: {io_error}",
                options.path.display()
            )?;
            return Ok(EXIT_TROUBLE);
        }
    };
    let kind = ProgramKind::from_extension(
        options
            .path
            .extension()
            .and_then(|extension| extension.to_str()),
    );
    let analysis = analyze_program(&source.text, &config, kind);
    match options.format {
        PreviewFormat::Json => write_json(stdout, options, &config, &source.text, &analysis)?,
        PreviewFormat::Csv => write_csv(stdout, &config, &analysis.moves)?,
        PreviewFormat::Svg => {
            super::preview_svg::write_svg(stdout, &config, &analysis.moves, options.max_segments)?
        }
    }
    let has_errors = analysis
        .diagnostics
        .iter()
        .any(|item| item.diagnostic.severity == Severity::Error);
    Ok(if has_errors {
        EXIT_ERRORS_FOUND
    } else {
        EXIT_OK
    })
}

/// Writes the document move by move: a program of a million blocks must not build a tree of a million
/// JSON values in memory first.
fn write_json(
    stdout: &mut dyn Write,
    options: &PreviewOptions,
    config: &MachineConfig,
    text: &str,
    analysis: &crate::analysis::Analysis,
) -> io::Result<()> {
    let mut out = io::BufWriter::new(stdout);
    let lines = ProgramLines::new(text);
    write_preview_json(
        &mut out,
        &options.path.display().to_string(),
        config.metric,
        &analysis.moves,
        &analysis.diagnostics,
        &mut |line_idx, span| lines.columns(line_idx, span),
    )?;
    out.flush()
}

/// The JSON document of `preview` (and of the language server's `sinumerik.endpointPreview`) for
/// `moves` and `diagnostics` of the program `file`; `columns` gives the 1-based character columns
/// of a span in a 0-based line.
pub(crate) fn write_preview_json(
    out: &mut dyn Write,
    file: &str,
    metric: bool,
    moves: &[Move],
    diagnostics: &[LineDiagnostic],
    columns: &mut dyn FnMut(usize, Span) -> (usize, usize),
) -> io::Result<()> {
    let header = json!({
        "file": file,
        "units": if metric { "mm" } else { "inch" },
    });
    let header = serde_json::to_string(&header)?;
    // The header object without its closing brace, then the two arrays.
    write!(out, "{},\n\"moves\": [", &header[..header.len() - 1])?;
    for (index, movement) in moves.iter().enumerate() {
        let separator = if index == 0 { "\n" } else { ",\n" };
        write!(out, "{separator}  ")?;
        serde_json::to_writer(&mut *out, &move_json(movement))?;
    }
    write!(out, "\n],\n\"diagnostics\": [")?;
    for (index, item) in diagnostics.iter().enumerate() {
        let (column, end_column) = columns(item.line, item.diagnostic.span);
        let separator = if index == 0 { "\n" } else { ",\n" };
        write!(out, "{separator}  ")?;
        serde_json::to_writer(
            &mut *out,
            &json!({
                "line": item.line + 1,
                "column": column,
                "end_column": end_column,
                "severity": item.diagnostic.severity.as_str(),
                "code": item.diagnostic.code.as_str(),
                "message": item.diagnostic.message,
            }),
        )?;
    }
    writeln!(out, "\n]}}")
}

/// The 1-based character columns of a span in one line of text.
pub(crate) fn line_columns(line: &str, span: Span) -> (usize, usize) {
    ProgramLines::new(line).columns(0, span)
}

fn config_for(options: &PreviewOptions) -> Result<MachineConfig, String> {
    let path = match &options.config_path {
        Some(path) => Some(path.clone()),
        None => discover_config_file(options.path.parent().unwrap_or(Path::new("."))),
    };
    match path {
        Some(path) => load_config_file(&path).map_err(|error| error.to_string()),
        None => Ok(MachineConfig::default()),
    }
}

fn axes_json(values: &[(std::sync::Arc<str>, f64)]) -> Value {
    let mut map = Map::new();
    for (name, value) in values {
        map.insert(name.to_string(), json!(round(*value)));
    }
    Value::Object(map)
}

/// Rounds away floating-point noise (1e-9 mm) so that `58.0` does not print as `57.99999999999999`.
fn round(value: f64) -> f64 {
    let rounded = (value * 1e9).round() / 1e9;
    if rounded == 0.0 {
        0.0
    } else {
        rounded
    }
}

fn move_json(movement: &Move) -> Value {
    json!({
        "line": movement.line + 1,
        "block": movement.block_number,
        "motion": movement.motion,
        "start": axes_json(&movement.start),
        "end": axes_json(&movement.end),
        "mcs": movement.machine.as_ref().map(|values| axes_json(values)),
        "arc": movement.arc.as_ref().map(|arc| json!({
            "centre": axes_json(&arc.centre),
            "radius": round(arc.radius),
            "direction": if arc.clockwise { "cw" } else { "ccw" },
            "sweep": round(arc.sweep),
        })),
        "feed": movement.feed.map(round),
        "uncertain": movement.uncertain.iter().map(|name| name.as_ref()).collect::<Vec<&str>>(),
    })
}

fn write_csv(stdout: &mut dyn Write, config: &MachineConfig, moves: &[Move]) -> io::Result<()> {
    let names: Vec<&str> = config.axes.iter().map(|axis| axis.name.as_str()).collect();
    write!(stdout, "line,block,motion")?;
    for name in &names {
        write!(stdout, ",{name}")?;
    }
    writeln!(stdout, ",feed,uncertain")?;
    for movement in moves {
        write!(
            stdout,
            "{},{},{}",
            movement.line + 1,
            movement.block_number.as_deref().unwrap_or(""),
            movement.motion
        )?;
        for name in &names {
            match movement.end.iter().find(|(axis, _)| axis.as_ref() == *name) {
                Some((_, value)) => write!(stdout, ",{}", round(*value))?,
                None => write!(stdout, ",")?,
            }
        }
        let feed = movement
            .feed
            .map(|feed| round(feed).to_string())
            .unwrap_or_default();
        writeln!(stdout, ",{feed},{}", movement.uncertain.join(" "))?;
    }
    Ok(())
}
