//! The hover of a G function: what it does, its group and whether it is modal, and the function of
//! that group in effect before the block when the analysis follows the group.

use crate::analysis::document::{BlockReport, StateSummary};
use crate::ide::language_docs::{gcode_summary, group_name};
use crate::syntax::gcodes::GCode;
use std::fmt::Write;

/// The value of a group in effect before the block, when the analysis follows that group.
fn group_value(group: u8, before: &StateSummary) -> Option<Option<&str>> {
    let value = match group {
        1 => &before.motion,
        6 => &before.plane,
        8 => &before.settable_offset,
        13 => &before.units,
        14 => &before.distance,
        29 => &before.diameter,
        _ => return None,
    };
    Some(value.as_deref())
}

/// `**G17** — Working plane X/Y`, its group and modality, and the group's function before the block.
pub fn gcode_hover(code: GCode, report: &BlockReport) -> String {
    let name = code.name();
    let group = code.group();
    let mut text = format!("**{name}**");
    if let Some(description) = gcode_summary(&name) {
        let _ = write!(text, " — {description}");
    } else if matches!(code, GCode::WorkOffset(_)) {
        text.push_str(" — Settable work offset from the machine's offset table.");
    }
    let modality = if code.is_modal() {
        "modal: stays active until another function of the group"
    } else {
        "non-modal: acts in this block only"
    };
    let _ = write!(
        text,
        "\n\nGroup {group} ({}), {modality}.",
        group_name(group)
    );
    match group_value(group, &report.before) {
        Some(Some(value)) => {
            let _ = write!(text, " Before this block: **{value}**.");
        }
        Some(None) => {
            text.push_str(" Before this block: **unknown** (inherited from the caller, or lost).")
        }
        None => {}
    }
    text
}
