//! `preview`: the resolved moves of one program as JSON or CSV, for tools and for the toolpath view.

use super::args::{PreviewFormat, PreviewOptions};
use super::exit_codes::{EXIT_ERRORS_FOUND, EXIT_OK, EXIT_TROUBLE};
use super::library::ProgramFiles;
use super::report::ProgramLines;
use crate::analysis::execution::{execute, ExecutedMove, ExecutionOptions};
use crate::analysis::library::ProgramLibrary;
use crate::analysis::simulation::time::{TimeModel, TimeTotals};
use crate::analysis::{diagnose_program, ProgramKind};
use crate::config::{discover_config_file, load_config_file, MachineConfig};
use crate::diagnostics::{LineDiagnostic, Severity};
use crate::ide::numbers::{microseconds, without_noise};
use crate::io::preview_json;
use crate::io::source_file::read_source_file;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

pub(crate) fn run_preview(
    options: &PreviewOptions,
    stdout: &mut dyn Write,
    stderr: &mut dyn Write,
) -> io::Result<u8> {
    let config_path = config_path_for(options);
    let config = match config_for(config_path.as_deref()) {
        Ok(config) => config,
        Err(message) => {
            writeln!(stderr, "sinumerik-lsp: {message}")?;
            return Ok(EXIT_TROUBLE);
        }
    };
    let program_files = match ProgramFiles::new(&options.cycles) {
        Ok(program_files) => program_files,
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
    let kind = ProgramKind::from_file_name(&options.path.to_string_lossy());
    // The programs this one calls are found through its library, which lists folders and reads files
    // only when asked.
    let library =
        program_files.library_for(&options.path, config_path.as_deref().and_then(Path::parent));
    // The JSON and CSV count the dwells in the time; no format lists them among the moves.
    let execution_options = ExecutionOptions {
        dwell_moves: options.format != PreviewFormat::Svg,
        ..config.execution.clone()
    };
    let run = |visit: &mut dyn FnMut(ExecutedMove)| {
        run_program(
            &source.text,
            &config,
            kind,
            library.as_ref(),
            &execution_options,
            visit,
        )
    };
    let model = TimeModel::new(&config);
    let mut totals = TimeTotals::default();
    let diagnostics = match options.format {
        PreviewFormat::Json => {
            let mut out = io::BufWriter::with_capacity(1 << 16, stdout);
            let file = options.path.display().to_string();
            let assumed = crate::analysis::execution::entry_assumptions(
                &source.text,
                &config,
                kind,
                &execution_options,
            );
            preview_json::write_header_with(&mut out, &file, config.metric, &assumed)?;
            let mut first = true;
            let mut written = Ok(());
            let diagnostics = run(&mut |movement| {
                let time = model.time_of(&movement.movement);
                totals.add(time);
                if written.is_ok() && movement.movement.timing.dwell.is_none() {
                    written = preview_json::write_executed_move(
                        &mut out,
                        &movement,
                        first,
                        &file,
                        time.seconds,
                    );
                    first = false;
                }
            });
            written?;
            let lines = ProgramLines::new(&source.text);
            preview_json::write_footer(&mut out, &totals, &diagnostics, &|item| {
                lines.columns(item.line, item.diagnostic.span)
            })?;
            out.flush()?;
            diagnostics
        }
        PreviewFormat::Csv => {
            let mut out = io::BufWriter::with_capacity(1 << 16, stdout);
            write_csv_header(&mut out, &config)?;
            let mut written = Ok(());
            let diagnostics = run(&mut |movement| {
                if written.is_ok() && movement.movement.timing.dwell.is_none() {
                    let time = model.time_of(&movement.movement);
                    written = write_csv_row(&mut out, &config, &movement, time.seconds);
                }
            });
            written?;
            out.flush()?;
            diagnostics
        }
        PreviewFormat::Svg => {
            let mut moves = Vec::new();
            let diagnostics = run(&mut |movement| moves.push(movement.movement));
            super::preview_svg::write_svg(stdout, &config, &moves, options.max_segments)?;
            diagnostics
        }
    };
    let has_errors = diagnostics
        .iter()
        .any(|item| item.diagnostic.severity == Severity::Error);
    Ok(if has_errors {
        EXIT_ERRORS_FOUND
    } else {
        EXIT_OK
    })
}

/// Runs a program the way the control runs it, handing each executed move to `visit`, and returns
/// every finding: those of reading the program block by block and those of running it.
pub(crate) fn run_program(
    text: &str,
    config: &MachineConfig,
    kind: ProgramKind,
    library: &dyn ProgramLibrary,
    options: &ExecutionOptions,
    visit: &mut dyn FnMut(ExecutedMove),
) -> Vec<LineDiagnostic> {
    let mut diagnostics = diagnose_program(text, config, kind);
    let execution = execute(text, config, kind, library, options, visit);
    if !execution.findings.is_empty() {
        diagnostics.extend(execution.findings);
        diagnostics.sort_by_key(|item| (item.line, item.diagnostic.span.start()));
    }
    diagnostics
}

/// The configuration file the program uses: the one given with `--config`, else the nearest
/// `sinumerik.toml`, else none (the defaults).
fn config_path_for(options: &PreviewOptions) -> Option<PathBuf> {
    match &options.config_path {
        Some(path) => Some(path.clone()),
        None => discover_config_file(options.path.parent().unwrap_or(Path::new("."))),
    }
}

fn config_for(path: Option<&Path>) -> Result<MachineConfig, String> {
    match path {
        Some(path) => load_config_file(path).map_err(|error| error.to_string()),
        None => Ok(MachineConfig::default()),
    }
}

fn write_csv_header(out: &mut dyn Write, config: &MachineConfig) -> io::Result<()> {
    write!(out, "line,block,motion")?;
    for axis in &config.axes {
        write!(out, ",{}", axis.name)?;
    }
    writeln!(out, ",feed,uncertain,pass,file,cycle,inserted,time_s")
}

fn write_csv_row(
    out: &mut dyn Write,
    config: &MachineConfig,
    executed: &ExecutedMove,
    time_s: Option<f64>,
) -> io::Result<()> {
    let movement = &executed.movement;
    write!(
        out,
        "{},{},{}",
        movement.line + 1,
        movement.block_number.as_deref().unwrap_or(""),
        movement.motion
    )?;
    for axis in &config.axes {
        match movement
            .end
            .iter()
            .find(|(name, _)| name.as_ref() == axis.name.as_str())
        {
            Some((_, value)) => write!(out, ",{}", without_noise(*value))?,
            None => write!(out, ",")?,
        }
    }
    let feed = movement
        .feed
        .map(|feed| without_noise(feed).to_string())
        .unwrap_or_default();
    write!(out, ",{feed},{}", movement.uncertain.join(" "))?;
    let pass = if executed.pass > 0 {
        executed.pass.to_string()
    } else {
        String::new()
    };
    let file = executed.path.as_deref().unwrap_or("");
    // A path with a comma or quote is quoted as CSV quotes fields.
    if file.contains([',', '"', '\n']) {
        write!(out, ",{pass},\"{}\"", file.replace('"', "\"\""))?;
    } else {
        write!(out, ",{pass},{file}")?;
    }
    // The cycle's name and the inserted element are plain words: they need no quoting.
    write!(
        out,
        ",{},{}",
        movement.cycle.as_deref().unwrap_or(""),
        movement.inserted.unwrap_or("")
    )?;
    match time_s {
        // Microseconds, as the JSON writes them.
        Some(seconds) => writeln!(out, ",{}", microseconds(seconds)),
        None => writeln!(out, ","),
    }
}
