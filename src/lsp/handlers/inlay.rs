//! Inlay hints: the resolved end point (`⟶ X115 Z60`) at the end of each moving block whose end
//! point is not plain to read from its words (incremental, AC/IC, polar, inch, a frame, unknown).

use crate::analysis::document::LineSource;
use crate::analysis::Move;
use crate::config::MachineConfig;
use crate::ide::execution::DocumentExecution;
use crate::lsp::convert::{end_of_line, PositionEncoding};
use crate::lsp::documents::Analysed;
use crate::lsp::handlers::hover::{axis_of, machine_differs};
use crate::lsp::handlers::numbers::{same, short};
use crate::lsp::handlers::words::{words, Word, WordValue};
use crate::lsp::settings::InlayHintMode;
use tower_lsp_server::ls_types::{InlayHint, InlayHintLabel, InlayHintTooltip, Range};

/// The hints for the lines of `range` (both ends included).
pub fn inlay_hints(
    analysed: &Analysed,
    library: &dyn crate::analysis::library::ProgramLibrary,
    range: Range,
    mode: InlayHintMode,
    encoding: PositionEncoding,
) -> Vec<InlayHint> {
    if mode == InlayHintMode::Off {
        return Vec::new();
    }
    let lines = analysed.lines();
    let first = range.start.line as usize;
    let last = (range.end.line as usize)
        .saturating_add(1)
        .min(lines.line_count());
    if first >= last {
        return Vec::new();
    }
    let config = analysed.analysis.config();
    let moves = analysed.analysis.moves(&lines, first..last);
    // A program whose flow differs from program order (or a subprogram, which starts from an
    // assumed state) shows what the run gives: the first pass of each block and how often it runs.
    let needs_run = analysed.analysis.kind() == crate::analysis::ProgramKind::Subprogram
        || moves.iter().any(|movement| {
            movement
                .uncertain
                .iter()
                .any(|name| movement.end.iter().any(|(known, _)| known == name))
        });
    if needs_run {
        let execution = analysed.execution(library);
        if let Some(hints) = run_hints(&execution, &lines, first..last, encoding) {
            return hints;
        }
    }
    moves
        .iter()
        .filter_map(|movement| {
            let line = lines.line(movement.line);
            let line_words = words(&line);
            if mode == InlayHintMode::NotPlain && is_plain(movement, &line_words, config) {
                return None;
            }
            Some(InlayHint {
                position: end_of_line(movement.line, &line, encoding),
                label: InlayHintLabel::String(label(movement, config)),
                kind: None,
                text_edits: None,
                tooltip: Some(InlayHintTooltip::String(
                    "Resolved end point of this block in program coordinates (? = unknown)"
                        .to_string(),
                )),
                padding_left: Some(true),
                padding_right: None,
                data: None,
            })
        })
        .collect()
}

/// The hints of a program that was run: per line, the end of the first pass with the count of
/// passes, and after a call line where the call ends. `None` when the program runs in order.
fn run_hints(
    execution: &DocumentExecution,
    lines: &dyn LineSource,
    range: std::ops::Range<usize>,
    encoding: PositionEncoding,
) -> Option<Vec<InlayHint>> {
    if matches!(execution, DocumentExecution::InOrder) {
        return None;
    }
    let mut hints = Vec::new();
    for line_index in range {
        let moves = execution.moves_of_line(line_index);
        let own: Vec<_> = moves
            .iter()
            .filter(|executed| executed.stack.is_empty())
            .collect();
        let called = moves
            .iter()
            .rev()
            .find(|executed| !executed.stack.is_empty());
        let text = match (own.first(), called) {
            (Some(first), _) => {
                let passes = execution.passes_of_line(line_index);
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
        let line = lines.line(line_index);
        hints.push(InlayHint {
            position: end_of_line(line_index, &line, encoding),
            label: InlayHintLabel::String(text),
            kind: None,
            text_edits: None,
            tooltip: Some(InlayHintTooltip::String(
                "End point of this block as the program runs (? = unknown)".to_string(),
            )),
            padding_left: Some(true),
            padding_right: None,
            data: None,
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
pub fn is_plain(movement: &Move, line_words: &[Word<'_>], config: &MachineConfig) -> bool {
    if !movement.uncertain.is_empty() {
        return false;
    }
    let polar = line_words.iter().any(|word| {
        let name = word.upper_name();
        (name == "AP" || name == "RP") && !matches!(word.value, WordValue::None)
    });
    if polar {
        return false;
    }
    let axes_plain = line_words.iter().all(|word| match axis_of(word, config) {
        None => true,
        Some(axis) => match (
            &word.value,
            movement.end.iter().find(|(name, _)| **name == *axis),
        ) {
            (WordValue::Number(Some(written)), Some((_, end))) => same(*written, *end),
            _ => false,
        },
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
