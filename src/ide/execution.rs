//! The execution of an open document, for the features that show what the control does: the
//! toolpath of a program with loops, jumps or calls, the passes of a block in its hover, the first
//! pass and the count in an inlay hint. A program that runs in program order (no flow, a main
//! program) needs none of this: its moves are those of the document's analysis.

use crate::analysis::document::LineSource;
use crate::analysis::execution::entry::RunSetup;
use crate::analysis::execution::first_pass::PassState;
use crate::analysis::execution::library_macros::LibraryMacros;
use crate::analysis::execution::{entry_assumptions, ExecutionOptions, RESET_SOURCE};
use crate::analysis::execution::{program::lines_have_flow, ExecutedMove};
use crate::analysis::execution::{resume_run, run_recorded, RecordedRun};
use crate::analysis::library::ProgramLibrary;
use crate::analysis::ProgramKind;
use crate::config::MachineConfig;
use std::ops::Range;
use std::sync::Arc;

/// What running a document gave: its moves in execution order, or that it runs in program order.
#[derive(Debug, Clone, PartialEq)]
pub enum DocumentExecution {
    /// A main program without labels, jumps, structures or calls: every block runs once, in program
    /// order, from the reset state; the document's analysis has its moves.
    InOrder,
    /// The run with its moves, findings and assumptions, and the record to run it again after an
    /// edit.
    Executed {
        run: Arc<RecordedRun>,
        assumed: Vec<(&'static str, String)>,
        /// Per line of the document, the indexes of its moves in `order` (a call line: the moves
        /// the call causes).
        by_line: Vec<Range<u32>>,
        /// The indexes of the moves sorted by their outer line, in execution order within a line.
        order: Vec<u32>,
        /// The same for the run's `path_moves`, when the corner stage inserted elements.
        path_order: Option<Vec<u32>>,
    },
}

/// Runs the document held by `source`; `earlier`, the run of an earlier revision with the same
/// configuration, is resumed when the edit allows it.
pub fn execute_document(
    source: &dyn LineSource,
    config: &MachineConfig,
    kind: ProgramKind,
    library: &dyn ProgramLibrary,
    options: &ExecutionOptions,
    earlier: Option<&DocumentExecution>,
) -> DocumentExecution {
    if runs_in_order(source, config, kind, library) {
        return DocumentExecution::InOrder;
    }
    // The text is made once at its final size: a string that grows by doubling would hold up to
    // twice the text while it is copied into the shared one.
    let mut size = 0;
    source.for_each_line(0, &mut |_, line| {
        size += line.len() + 1;
        true
    });
    let mut text = String::with_capacity(size);
    source.for_each_line(0, &mut |_, line| {
        text.push_str(line);
        text.push('\n');
        true
    });
    let text: Arc<str> = Arc::from(text);
    let subprogram = kind == ProgramKind::Subprogram || crate::analysis::has_proc_header(&text);
    // The run hands out the dwells too, for the machining time (`ide/timing.rs`); the features that
    // show the path leave them out (`moves_in`, `moves_of_line`).
    let options = &ExecutionOptions {
        dwell_moves: true,
        ..options.clone()
    };
    let setup = RunSetup {
        entry: subprogram.then(|| library.caller_entry()).flatten(),
        record_first_passes: true,
    };
    let resumed = match earlier {
        Some(DocumentExecution::Executed { run, .. }) => resume_run(
            Arc::clone(&text),
            config,
            kind,
            library,
            options,
            &setup,
            run,
        ),
        _ => None,
    };
    let run = resumed.unwrap_or_else(|| {
        run_recorded(
            Arc::clone(&text),
            config,
            kind,
            library,
            options,
            &setup,
            None,
        )
    });
    // From the call sites, the run says what it started from; else the reset state is assumed.
    let assumed = match setup.entry {
        Some(_) => run.execution.assumed.clone(),
        None => entry_assumptions(&text, config, kind, options),
    };
    let (by_line, order) = index_by_line(&run.moves, source.line_count());
    // The toolpath shows the path with roundings and chamfers; the hover and the inlay hints the
    // programmed positions (reference §14.2).
    let path_order = (!Arc::ptr_eq(&run.moves, &run.path_moves))
        .then(|| index_by_line(&run.path_moves, source.line_count()).1);
    DocumentExecution::Executed {
        run: Arc::new(run),
        assumed,
        by_line,
        order,
        path_order,
    }
}

/// Whether the document runs in program order, so that its moves are those of its analysis: a main
/// program (by its kind, and without a `PROC` line) without flow (`lines_have_flow`, with the macros
/// of the library's definition files, which read like calls) and without the rounding and chamfer
/// words that only the run's corner stage makes into a path. Read from the lines themselves: the
/// copy of the text that a run needs is tens of MB for a large CAM program, and most never run.
fn runs_in_order(
    source: &dyn LineSource,
    config: &MachineConfig,
    kind: ProgramKind,
    library: &dyn ProgramLibrary,
) -> bool {
    if kind == ProgramKind::Subprogram {
        return false;
    }
    let mut needs_run = false;
    source.for_each_line(0, &mut |_, line| {
        needs_run = crate::analysis::program_kind::is_proc_header(line)
            || crate::analysis::simulation::mentions_contour_words(line, config);
        !needs_run
    });
    if needs_run {
        return false;
    }
    let macros = LibraryMacros::read(library, config);
    !lines_have_flow(
        source.line_count(),
        &|visit| source.for_each_line(0, visit),
        config,
        macros.names(),
    )
}

/// The moves grouped by their outer line (a counting sort: execution order stays within a line).
fn index_by_line(moves: &[ExecutedMove], line_count: usize) -> (Vec<Range<u32>>, Vec<u32>) {
    let mut counts = vec![0u32; line_count + 1];
    for executed in moves {
        counts[executed.outer_line().min(line_count)] += 1;
    }
    let mut by_line = Vec::with_capacity(line_count);
    let mut starts = Vec::with_capacity(line_count + 1);
    let mut start = 0u32;
    for (line, &count) in counts.iter().enumerate() {
        starts.push(start);
        if line < line_count {
            by_line.push(start..start + count);
        }
        start += count;
    }
    let mut order = vec![0u32; moves.len()];
    for (index, executed) in moves.iter().enumerate() {
        let slot = &mut starts[executed.outer_line().min(line_count)];
        order[*slot as usize] = index as u32;
        *slot += 1;
    }
    (by_line, order)
}

impl DocumentExecution {
    /// The moves whose outer line is in `lines`, in execution order, on the path the tool takes
    /// (with inserted roundings and chamfers); `None` when the document runs in program order.
    pub fn moves_in(&self, lines: Range<usize>) -> Option<Vec<&ExecutedMove>> {
        let DocumentExecution::Executed {
            run,
            order,
            path_order,
            ..
        } = self
        else {
            return None;
        };
        let (moves, order) = match path_order {
            Some(path_order) => (&run.path_moves, path_order),
            None => (&run.moves, order),
        };
        let first =
            order.partition_point(|&index| moves[index as usize].outer_line() < lines.start);
        let last = order.partition_point(|&index| moves[index as usize].outer_line() < lines.end);
        let mut indexes: Vec<u32> = order[first..last.max(first)].to_vec();
        indexes.sort_unstable();
        Some(
            indexes
                .iter()
                .map(|&index| &moves[index as usize])
                .filter(|executed| executed.movement.timing.dwell.is_none())
                .collect(),
        )
    }

    /// The moves line `line` of the document causes (its own, or those of the program it calls), in
    /// execution order, as the blocks program them (a rounded corner ends at the corner).
    pub fn moves_of_line(&self, line: usize) -> Vec<&ExecutedMove> {
        match self {
            DocumentExecution::InOrder => Vec::new(),
            DocumentExecution::Executed {
                run,
                by_line,
                order,
                ..
            } => {
                let moves = &run.moves;
                let Some(range) = by_line.get(line) else {
                    return Vec::new();
                };
                let mut indexes: Vec<u32> =
                    order[range.start as usize..range.end as usize].to_vec();
                indexes.sort_unstable();
                indexes
                    .iter()
                    .map(|&index| &moves[index as usize])
                    .filter(|executed| executed.movement.timing.dwell.is_none())
                    .collect()
            }
        }
    }

    /// How often line `line` ran (1 for every line of a document that runs in program order).
    pub fn passes_of_line(&self, line: usize) -> u32 {
        match self {
            DocumentExecution::InOrder => 1,
            DocumentExecution::Executed { run, .. } => run.execution.passes_of_line(line),
        }
    }

    /// The findings of the run, at lines of the document.
    pub fn findings(&self) -> &[crate::diagnostics::LineDiagnostic] {
        match self {
            DocumentExecution::InOrder => &[],
            DocumentExecution::Executed { run, .. } => &run.execution.findings,
        }
    }

    /// The modal state after the first execution of `line` and how often the line runs; `None` for
    /// a document that runs in program order, or a line that never runs.
    pub fn first_pass(&self, line: usize) -> Option<(&PassState, u32)> {
        let DocumentExecution::Executed { run, .. } = self else {
            return None;
        };
        let state = run.execution.first_passes.as_ref()?.state(line)?;
        Some((state, run.execution.passes_of_line(line)))
    }

    /// What was assumed about the entry state.
    pub fn assumed(&self) -> &[(&'static str, String)] {
        match self {
            DocumentExecution::InOrder => &[],
            DocumentExecution::Executed { assumed, .. } => assumed,
        }
    }
}

/// Values as the run's summary writes them: at most four decimals, no trailing zeros.
fn short(value: f64) -> String {
    crate::ide::numbers::short_to(value, 4)
}

fn end_text(executed: &ExecutedMove) -> String {
    let movement = &executed.movement;
    let mut parts: Vec<String> = movement
        .end
        .iter()
        .map(|(name, value)| format!("{name}{}", short(*value)))
        .collect();
    parts.extend(movement.uncertain.iter().map(|name| format!("{name}?")));
    parts.join(" ")
}

/// What a call on `line` ran, as Markdown: the called file and, for its first pass, where the axes
/// are when it returned; `called` are the moves the call made (every pass).
fn call_summary(
    execution: &DocumentExecution,
    line: usize,
    called: &[&&ExecutedMove],
) -> Option<String> {
    let DocumentExecution::Executed { run, .. } = execution else {
        return None;
    };
    let run = &run.execution;
    let recorded = run
        .first_passes
        .as_ref()
        .and_then(|passes| passes.call(line));
    // The directly called file: the recorded one, else the first called move's second stack entry
    // (a move of a deeper call) or its own file.
    let file = match recorded {
        Some((path, _)) => path.map(str::to_string),
        None => {
            let first = called.first()?;
            first
                .stack
                .get(1)
                .map_or(first.path.clone(), |site| site.path.clone())
                .map(|path| path.to_string())
        }
    };
    let file = file.unwrap_or_else(|| "this program".to_string());
    let mut text = format!("**Calls** `{file}`: {} moves.", called.len());
    match recorded.and_then(|(_, after)| after) {
        Some(after) if !after.positions.is_empty() => {
            let positions: Vec<String> = after
                .positions
                .iter()
                .map(|(name, value)| match value {
                    Some(value) => format!("{name}{}", short(*value)),
                    None => format!("{name}?"),
                })
                .collect();
            text.push_str(&format!(
                " After the call (first pass): {}.",
                positions.join(" ")
            ));
        }
        Some(_) => {}
        None if recorded.is_some() => {
            text.push_str(" The first call does not return to this program.")
        }
        None => {
            if let Some(last) = called.last() {
                text.push_str(&format!(" The last ends at {}.", end_text(last)));
            }
        }
    }
    Some(text)
}

/// What the run says about line `line`, as Markdown for a hover: how often it runs and where each
/// pass ends, what a call on it runs and where the call ends, what is assumed. `None` for a document
/// that runs in program order.
pub fn execution_summary(execution: &DocumentExecution, line: usize) -> Option<String> {
    let DocumentExecution::Executed { assumed, .. } = execution else {
        return None;
    };
    let mut text = String::new();
    let passes = execution.passes_of_line(line);
    let moves = execution.moves_of_line(line);
    let own: Vec<&&ExecutedMove> = moves
        .iter()
        .filter(|executed| executed.stack.is_empty())
        .collect();
    if passes == 0 {
        text.push_str("**Not run**: no way the control takes through the program reaches this block (or it lies past an endless loop).");
    } else if passes > 1 {
        text.push_str(&format!("**Runs {passes} times.**"));
        for (index, executed) in own.iter().take(5).enumerate() {
            text.push_str(&format!("\n- pass {}: {}", index + 1, end_text(executed)));
        }
        if own.len() > 5 {
            text.push_str(&format!("\n- … {} more", own.len() - 5));
        }
    }
    let called: Vec<&&ExecutedMove> = moves
        .iter()
        .filter(|executed| !executed.stack.is_empty())
        .collect();
    if let Some(call) = call_summary(execution, line, &called) {
        if !text.is_empty() {
            text.push_str("\n\n");
        }
        text.push_str(&call);
    }
    if own
        .iter()
        .chain(called.iter())
        .any(|executed| executed.conditional)
    {
        if !text.is_empty() {
            text.push_str("\n\n");
        }
        text.push_str("Some of these moves lie on a way whose condition the program does not decide (main-run values, machine data).");
    }
    if !assumed.is_empty() {
        let axes: Vec<&str> = own
            .iter()
            .flat_map(|executed| executed.assumed.iter().map(|name| name.as_ref()))
            .collect();
        if !axes.is_empty() {
            let state: Vec<&str> = assumed
                .iter()
                .filter(|(name, _)| *name != "source")
                .map(|(_, value)| value.as_str())
                .collect();
            let source = assumed
                .iter()
                .find(|(name, _)| *name == "source")
                .map_or(RESET_SOURCE, |(_, value)| value.as_str());
            let why = if source == RESET_SOURCE {
                "assumed: reset state — this subprogram is analysed on its own, and no call sites that agree on units, distance mode and plane are known"
            } else {
                source
            };
            if !text.is_empty() {
                text.push_str("\n\n");
            }
            let mut axes = axes;
            axes.sort_unstable();
            axes.dedup();
            text.push_str(&format!(
                "**Assumed**: {} rest on the entry state {} ({why}).",
                axes.join(" "),
                state.join(" ")
            ));
        }
    }
    (!text.is_empty()).then_some(text)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::document::TextLines;
    use crate::analysis::library::NoLibrary;

    fn run(text: &str, kind: ProgramKind) -> DocumentExecution {
        execute_document(
            &TextLines::new(text),
            &MachineConfig::mill(),
            kind,
            &NoLibrary,
            &ExecutionOptions::default(),
            None,
        )
    }

    #[test]
    fn a_program_in_order_is_not_run_again() {
        let execution = run("G90 G0 X1\nX2\nM30\n", ProgramKind::Main);
        assert_eq!(execution, DocumentExecution::InOrder);
        assert_eq!(execution.passes_of_line(1), 1);
    }

    #[test]
    fn a_program_with_roundings_runs_through_the_corner_stage() {
        // T106 and a rounding at a reversal: the editor gets the path with the inserted element and
        // the stage's finding, as `check` does.
        let text = "G17 G90 G1 X0 Y0 F100\nX50 Y0 RND=5\nY50 RND=2\nY0\nM30\n";
        let execution = run(text, ProgramKind::Main);
        let path = execution.moves_in(1..2).expect("executed");
        let of_corner: Vec<Option<&str>> = path
            .iter()
            .map(|executed| executed.movement.inserted)
            .collect();
        assert_eq!(of_corner, vec![None, Some("RND")]);
        assert_eq!(path[0].movement.end[0].1, 45.0);
        // The hover and the inlay hints show the programmed corner (T115).
        let programmed = execution.moves_of_line(1);
        assert_eq!(programmed.len(), 1);
        assert_eq!(programmed[0].movement.end[0].1, 50.0);
        let codes: Vec<(usize, &str)> = execution
            .findings()
            .iter()
            .map(|finding| (finding.line, finding.diagnostic.code.as_str()))
            .collect();
        assert_eq!(codes, vec![(2, "E431")]);
        let checked = crate::analysis::execution::execution_findings(
            text,
            &MachineConfig::mill(),
            ProgramKind::Main,
            &NoLibrary,
            &ExecutionOptions::default(),
        );
        assert_eq!(checked.as_slice(), execution.findings());
    }

    #[test]
    fn moves_are_found_by_line_and_range() {
        let text = "G90 G0 X0\nFOR R1=1 TO 3\nG0 X=R1\nENDFOR\nY5\nM30\n";
        let execution = run(text, ProgramKind::Main);
        let of_loop: Vec<f64> = execution
            .moves_of_line(2)
            .iter()
            .map(|executed| executed.movement.end[0].1)
            .collect();
        assert_eq!(of_loop, vec![1.0, 2.0, 3.0]);
        assert_eq!(execution.passes_of_line(2), 3);
        let range = execution.moves_in(2..5).expect("executed");
        assert_eq!(range.len(), 4);
        assert_eq!(range[3].movement.line, 4);
        let summary = execution_summary(&execution, 2).expect("a summary");
        assert!(summary.contains("Runs 3 times"), "{summary}");
        assert!(summary.contains("pass 2: X2"), "{summary}");
    }

    #[test]
    fn a_subprogram_says_what_it_assumes() {
        let execution = run("G0 X10\nM17\n", ProgramKind::Subprogram);
        let summary = execution_summary(&execution, 0).expect("a summary");
        assert!(summary.contains("**Assumed**: X"), "{summary}");
        assert!(summary.contains("G71"), "{summary}");
    }
}
