//! Inlay hints: the resolved end point (`⟶ X115 Z60`) at the end of each moving block, by default
//! only where it is not plain to read from the block's words (incremental, AC/IC, polar, inch, a
//! frame, unknown). A program whose flow differs from program order shows what its run gives.

use crate::analysis::document::{DocumentAnalysis, LineSource};
use crate::analysis::{Move, ProgramKind};
use crate::config::MachineConfig;
use crate::ide::block_words::BlockWords;
use crate::ide::execution::DocumentExecution;
use crate::ide::hover::block::machine_differs;
use crate::ide::numbers::{same, short};
use crate::ide::program_run::ProgramRun;
use crate::syntax::SyntaxContext;
use std::ops::Range;

/// Which moving blocks get a hint.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HintScope {
    /// Only blocks whose end point is not plain to read from their words.
    NotPlain,
    All,
}

/// One hint, shown at the end of its line.
#[derive(Debug, Clone, PartialEq)]
pub struct EndPointHint {
    pub line: usize,
    pub label: String,
    pub tooltip: &'static str,
}

const PROGRAM_ORDER_TOOLTIP: &str =
    "Resolved end point of this block in program coordinates (? = unknown)";
const RUN_TOOLTIP: &str = "End point of this block as the program runs (? = unknown)";

/// The hints of the lines `line_range` of the document `lines` analysed by `analysis`. `run` is
/// asked for the program's run only for a subprogram or when a block's end point depends on the
/// program's flow.
pub fn end_point_hints(
    lines: &dyn LineSource,
    analysis: &DocumentAnalysis,
    run: &dyn ProgramRun,
    line_range: Range<usize>,
    scope: HintScope,
) -> Vec<EndPointHint> {
    let first = line_range.start;
    let last = line_range.end.min(lines.line_count());
    if first >= last {
        return Vec::new();
    }
    let config = analysis.config();
    let moves = analysis.moves(lines, first..last);
    // A program whose flow differs from program order (or a subprogram, which starts from an
    // assumed state) shows what the run gives: the first pass of each block and how often it runs.
    let needs_run = analysis.kind() == ProgramKind::Subprogram
        || moves.iter().any(|movement| {
            movement
                .uncertain
                .iter()
                .any(|name| movement.end.iter().any(|(known, _)| known == name))
        });
    if needs_run {
        if let Some(hints) = run_hints(&run.execution(), first..last) {
            return hints;
        }
    }
    let context = SyntaxContext::new(config);
    moves
        .iter()
        .filter_map(|movement| {
            if scope == HintScope::NotPlain {
                let text = lines.line(movement.line);
                if is_plain(movement, &BlockWords::parse_in(&text, &context), config) {
                    return None;
                }
            }
            Some(EndPointHint {
                line: movement.line,
                label: label(movement, config),
                tooltip: PROGRAM_ORDER_TOOLTIP,
            })
        })
        .collect()
}

/// The hints of a program that was run: per line, the end of the first pass with the count of
/// passes, and after a call line where the call ends. `None` when the program runs in order.
fn run_hints(execution: &DocumentExecution, range: Range<usize>) -> Option<Vec<EndPointHint>> {
    if matches!(execution, DocumentExecution::InOrder) {
        return None;
    }
    let mut hints = Vec::new();
    for line in range {
        let moves = execution.moves_of_line(line);
        let own: Vec<_> = moves
            .iter()
            .filter(|executed| executed.stack.is_empty())
            .collect();
        let called = moves
            .iter()
            .rev()
            .find(|executed| !executed.stack.is_empty());
        let label = match (own.first(), called) {
            (Some(first), _) => {
                let passes = execution.passes_of_line(line);
                let mut text = end_text(&first.movement);
                if passes > 1 {
                    text.push_str(&format!(" (pass 1 of {passes})"));
                }
                if !first.assumed.is_empty() {
                    text.push_str(" (assumed entry state)");
                }
                text
            }
            (None, Some(last)) => format!("{} (after the call)", end_text(&last.movement)),
            (None, None) => continue,
        };
        hints.push(EndPointHint {
            line,
            label,
            tooltip: RUN_TOOLTIP,
        });
    }
    Some(hints)
}

/// `⟶ X115 Z60` with `X?` for an unknown axis, in configured order.
fn end_text(movement: &Move) -> String {
    let mut parts: Vec<String> = movement
        .end
        .iter()
        .map(|(name, value)| format!("{name}{}", short(*value)))
        .collect();
    parts.extend(
        movement
            .uncertain
            .iter()
            .filter(|name| !movement.end.iter().any(|(known, _)| known == *name))
            .map(|name| format!("{name}?")),
    );
    sort_by_axis(&mut parts);
    format!("⟶ {}", parts.join(" "))
}

/// Orders `Y40`, `Z-2`, `X?` as the configuration orders axes: X, Y, Z first, the others by name, so
/// that an unknown axis keeps its place instead of trailing behind the known ones.
fn sort_by_axis(parts: &mut [String]) {
    parts.sort_by_cached_key(|part| {
        let name: String = part
            .chars()
            .take_while(|character| character.is_ascii_alphabetic() || *character == '_')
            .collect();
        let rank = ["X", "Y", "Z"]
            .iter()
            .position(|geometry| *geometry == name)
            .unwrap_or(3);
        (rank, name)
    });
}

/// `⟶ X115 Z60`, with `X?` for an unknown axis and the machine position when a frame moves it.
pub fn label(movement: &Move, config: &MachineConfig) -> String {
    let mut parts: Vec<String> = movement
        .end
        .iter()
        .map(|(name, value)| format!("{name}{}", short(*value)))
        .collect();
    let mut flow_uncertain = false;
    for name in &movement.uncertain {
        if movement.end.iter().any(|(known, _)| known == name) {
            flow_uncertain = true;
        } else {
            parts.push(format!("{name}?"));
        }
    }
    sort_by_axis(&mut parts);
    let mut label = format!("⟶ {}", parts.join(" "));
    if let Some(machine) = &movement.machine {
        if machine_differs(
            machine,
            &movement.end,
            movement.transverse_as_diameter,
            config,
        ) {
            let machine_parts: Vec<String> = machine
                .iter()
                .map(|(name, value)| format!("{name}{}", short(*value)))
                .collect();
            label.push_str(&format!(" (machine {})", machine_parts.join(" ")));
        }
    }
    if flow_uncertain {
        label.push_str(" (flow uncertain)");
    }
    label
}

/// A block's end point is plain to read when every axis it writes is a constant equal to the
/// resolved end point, no polar word moves it, nothing is unknown and no frame moves it.
pub fn is_plain(movement: &Move, words: &BlockWords<'_>, config: &MachineConfig) -> bool {
    if !movement.uncertain.is_empty() || words.has_polar_words() {
        return false;
    }
    let axes_plain = words.axis_words(config).all(|word| {
        match (
            word.constant,
            movement.end.iter().find(|(name, _)| **name == *word.axis),
        ) {
            (Some(written), Some((_, end))) => same(written, *end),
            _ => false,
        }
    });
    axes_plain
        && !movement.machine.as_ref().is_some_and(|machine| {
            machine_differs(
                machine,
                &movement.end,
                movement.transverse_as_diameter,
                config,
            )
        })
}
