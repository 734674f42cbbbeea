//! The cli target: a program written to a file and run through the command line's own entry point
//! (`cli::run_with_output`) with `check` (human and JSON) and `preview` (JSON, CSV and SVG). The
//! output writers must give an exit code of 0 or 1, valid JSON, no NaN or infinity in any format, and
//! no raw escape characters in the human format.

use sinumerik_lsp::cli::run_with_output;
use std::ffi::OsString;
use std::path::PathBuf;

/// The files one thread uses: the program and a configuration for each machine, in a folder of the
/// thread's own. `check` searches the program's folder for the programs it calls, so the program must
/// not lie among whatever else the temporary folder holds: each case would read all of it.
fn scratch_path(name: &str) -> PathBuf {
    let thread = format!("{:?}", std::thread::current().id());
    let thread: String = thread.chars().filter(char::is_ascii_digit).collect();
    let folder =
        std::env::temp_dir().join(format!("sinumerik-fuzz-{}-{thread}", std::process::id()));
    let _ = std::fs::create_dir_all(&folder);
    folder.join(name)
}

/// Runs the command line on `text` in every output format and checks what it prints. The scratch
/// files are removed afterwards.
pub fn check_cli(text: &str) -> Result<(), String> {
    let result = run_every_format(text);
    for name in ["program.mpf", "mill.toml", "turn.toml"] {
        let _ = std::fs::remove_file(scratch_path(name));
    }
    if let Some(folder) = scratch_path("program.mpf").parent() {
        let _ = std::fs::remove_dir(folder);
    }
    result
}

fn run_every_format(text: &str) -> Result<(), String> {
    let program = scratch_path("program.mpf");
    std::fs::write(&program, text).map_err(|error| format!("cannot write the program: {error}"))?;
    for kind in ["mill", "turn"] {
        let config = scratch_path(&format!("{kind}.toml"));
        std::fs::write(&config, format!("[machine]\nkind = \"{kind}\"\n"))
            .map_err(|error| format!("cannot write the configuration: {error}"))?;
        let config = config.display().to_string();
        let program = program.display().to_string();
        for args in [
            vec!["check", "--config", &config, &program],
            vec!["check", "--format", "json", "--config", &config, &program],
            vec!["preview", "--config", &config, &program],
            vec!["preview", "--format", "csv", "--config", &config, &program],
            vec!["preview", "--format", "svg", "--config", &config, &program],
        ] {
            check_run(&args)?;
        }
    }
    Ok(())
}

fn check_run(args: &[&str]) -> Result<(), String> {
    let mut stdout = Vec::new();
    let mut stderr = Vec::new();
    let argv = std::iter::once("sinumerik-lsp")
        .chain(args.iter().copied())
        .map(OsString::from);
    let exit_code = run_with_output(argv, &mut stdout, &mut stderr);
    let command = args
        .iter()
        .filter(|arg| !arg.contains('/'))
        .copied()
        .collect::<Vec<_>>()
        .join(" ");
    if exit_code > 1 {
        return Err(format!(
            "`{command}` exits with {exit_code}: {}",
            String::from_utf8_lossy(&stderr)
        ));
    }
    let output =
        String::from_utf8(stdout).map_err(|_| format!("`{command}` prints invalid UTF-8"))?;
    let format = args
        .iter()
        .position(|arg| *arg == "--format")
        .map_or(if args[0] == "check" { "human" } else { "json" }, |index| {
            args[index + 1]
        });
    match (args[0], format) {
        ("check", "human") if output.contains('\u{1b}') => Err(format!(
            "`{command}` passes an escape character to the terminal"
        )),
        ("check", "json") => serde_json::from_str::<serde_json::Value>(&output)
            .map(|_| ())
            .map_err(|error| format!("`{command}` prints invalid JSON: {error}")),
        ("preview", "json") => {
            let document: serde_json::Value = serde_json::from_str(&output)
                .map_err(|error| format!("`{command}` prints invalid JSON: {error}"))?;
            check_preview_numbers(&document).map_err(|problem| format!("`{command}`: {problem}"))
        }
        // Neither the table nor the picture holds text of the program, only numbers and names.
        ("preview", _) if output.contains("inf") || output.contains("NaN") => {
            Err(format!("`{command}` prints infinity or NaN"))
        }
        _ => Ok(()),
    }
}

/// Every axis value in `start`, `end` and `mcs` of the preview is a number: an unknown one is left
/// out, never `null` (which is how serde writes infinity and NaN).
fn check_preview_numbers(document: &serde_json::Value) -> Result<(), String> {
    let moves = document["moves"]
        .as_array()
        .ok_or("the preview has no moves array")?;
    for movement in moves {
        for field in ["start", "end", "mcs"] {
            let Some(values) = movement[field].as_object() else {
                continue;
            };
            if let Some((axis, value)) = values.iter().find(|(_, value)| !value.is_number()) {
                return Err(format!(
                    "line {}: {field} {axis} is {value}",
                    movement["line"]
                ));
            }
        }
    }
    Ok(())
}
