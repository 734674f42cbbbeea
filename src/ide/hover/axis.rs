//! The hover of an axis word: how its value resolves, from the analysis's per-word report, or worked
//! out from the block's move when the analysis gave none (checked against its end point).

use crate::analysis::document::{BlockReport, ResolutionMode, WordResolution};
use crate::config::{AxisKind, MachineConfig};
use crate::ide::block_words::{AxisWord, BlockWords};
use crate::ide::hover::resolution::{explain_resolution, is_incremental};
use std::sync::Arc;

/// The explanation of the axis word `word` of the block `words`.
pub fn axis_hover(
    word: &AxisWord,
    words: &BlockWords<'_>,
    report: &BlockReport,
    config: &MachineConfig,
) -> String {
    let from_core = report.words.iter().find(|resolution| {
        resolution.span.start() <= word.span.start()
            && word.span.start() < resolution.span.end().max(resolution.span.start() + 1)
    });
    let resolution = match from_core {
        Some(resolution) => resolution.clone(),
        None => resolution_from_movement(word, words, report, config),
    };
    let axis = &word.axis;
    let mut text = match words.modifier_without_brackets(word) {
        Some(modifier) if resolution.end.is_none() => format!(
            "{axis} = **unknown**: `{modifier}` needs its value in parentheses, `{axis}={modifier}(...)` (S101); as written, the control reads `{modifier}` as the name of a variable"
        ),
        _ => explain_resolution(&resolution, &report.after, config),
    };
    if report.before.flow_uncertain {
        text.push_str("\n\n⚠ A label, jump or loop comes before this block: the control may run another path than program order, so these values may not be the control's.");
    }
    text
}

/// How a word resolves, worked out from the block's move when the analysis gave no per-word
/// report: the arithmetic shown is checked against the analysis's end point, never assumed.
fn resolution_from_movement(
    word: &AxisWord,
    words: &BlockWords<'_>,
    report: &BlockReport,
    config: &MachineConfig,
) -> WordResolution {
    let axis = word.axis.as_str();
    let lookup = |values: &[(Arc<str>, f64)]| {
        values
            .iter()
            .find(|(name, _)| &**name == axis)
            .map(|(_, value)| *value)
    };
    let movement = report.movement.as_ref();
    let mode = if words.is_machine_block() {
        ResolutionMode::Machine
    } else if let Some(modifier) = word.modifier {
        ResolutionMode::Override(modifier)
    } else {
        // The block's own G functions apply to its words: the state in effect is the one after it.
        match report.after.distance.as_deref() {
            Some("G90") => ResolutionMode::Absolute,
            Some("G91") => ResolutionMode::Incremental,
            _ => ResolutionMode::Unknown,
        }
    };
    let axis_kind = config.axis(axis).map(|axis| axis.kind);
    let unit_factor = if axis_kind.is_some_and(AxisKind::is_rotary) {
        Some(1.0)
    } else {
        match report.after.units.as_deref() {
            Some("G70" | "G700") => Some(if config.metric { 25.4 } else { 1.0 }),
            Some("G71" | "G710") => Some(if config.metric { 1.0 } else { 1.0 / 25.4 }),
            _ => None,
        }
    };
    let end = movement.and_then(|movement| lookup(&movement.end));
    let start = movement.and_then(|movement| lookup(&movement.start));
    let unknown_reason = end.is_none().then(|| {
        if is_incremental(mode) && start.is_none() {
            return "the move is incremental and the axis position before the block is not known"
                .to_string();
        }
        "the analysis cannot follow this value here (see the block's findings)".to_string()
    });
    let transverse_as_diameter = axis_kind == Some(AxisKind::Transverse)
        && movement.is_some_and(|movement| movement.transverse_as_diameter);
    WordResolution {
        span: word.span,
        axis: axis.to_string(),
        programmed: word.literal,
        mode,
        unit_factor,
        read_as_diameter: transverse_as_diameter,
        shown_as_diameter: transverse_as_diameter,
        // Built from the move alone; `explain_resolution` spells out a sum only when it checks
        // against the analysis's end point.
        explained: true,
        start,
        end,
        machine: movement
            .and_then(|movement| movement.machine.as_deref())
            .and_then(lookup),
        unknown_reason,
    }
}
