//! The part of every hover that describes the block as a whole: the modal state in effect before it
//! and its end point (with the machine position when a frame moves it).

use crate::analysis::document::BlockReport;
use crate::config::{AxisKind, MachineConfig};
use crate::ide::numbers::{same, short};
use std::fmt::Write;
use std::sync::Arc;

fn or_unknown(value: &Option<String>) -> &str {
    value.as_deref().unwrap_or("unknown")
}

/// `X20 Z90 Y?`: the known values in the order given, then each unknown axis.
fn axes_text(values: &[(Arc<str>, f64)], unknown: &[Arc<str>]) -> String {
    let mut parts: Vec<String> = values
        .iter()
        .map(|(name, value)| format!("{name}{}", short(*value)))
        .collect();
    parts.extend(
        unknown
            .iter()
            .filter(|name| !values.iter().any(|(known, _)| known == *name))
            .map(|name| format!("{name}?")),
    );
    parts.join(" ")
}

/// The modal state in effect before the block and the block's end point.
pub fn block_hover(report: &BlockReport, config: &MachineConfig) -> String {
    let before = &report.before;
    let mut text = String::from("**Modal state before this block**\n\n");
    let pole = match &before.pole {
        Some(None) => "none (the workpiece zero)".to_string(),
        Some(Some((first, second))) => format!("{} {}", short(*first), short(*second)),
        None => "unknown".to_string(),
    };
    let frame = match before.frame_is_identity {
        Some(true) => "none",
        Some(false) => "active",
        None => "unknown",
    };
    let feed = before
        .feed
        .map_or_else(|| "not programmed or unknown".to_string(), short);
    let _ = write!(
        text,
        "- motion {} · plane {} · units {} · {}\n- diameter mode {} · work offset {}\n- pole {pole} · programmable frame {frame} · feed {feed}",
        or_unknown(&before.motion),
        or_unknown(&before.plane),
        or_unknown(&before.units),
        or_unknown(&before.distance),
        or_unknown(&before.diameter),
        or_unknown(&before.settable_offset),
    );
    match &report.movement {
        Some(movement) => {
            let _ = write!(
                text,
                "\n\n**End point** ({}): {}",
                movement.motion,
                axes_text(&movement.end, &movement.uncertain)
            );
            if let Some(machine) = &movement.machine {
                if machine_differs(
                    machine,
                    &movement.end,
                    movement.transverse_as_diameter,
                    config,
                ) {
                    let _ = write!(text, "\n\nMachine coordinates (after the programmable frame, radius on transverse axes): {}", axes_text(machine, &[]));
                }
            }
        }
        None => text.push_str("\n\nThis block does not move an axis."),
    }
    if before.flow_uncertain {
        text.push_str("\n\n⚠ A label, jump or loop comes before this block: the values may not be the control's.");
    }
    text
}

/// Whether the machine coordinates differ from the program's end point (a frame moves the point).
pub fn machine_differs(
    machine: &[(Arc<str>, f64)],
    end: &[(Arc<str>, f64)],
    transverse_as_diameter: bool,
    config: &MachineConfig,
) -> bool {
    machine.iter().any(|(name, machine_value)| {
        let transverse = config
            .axis(name)
            .is_some_and(|axis| axis.kind == AxisKind::Transverse);
        let shown = if transverse && transverse_as_diameter {
            machine_value * 2.0
        } else {
            *machine_value
        };
        end.iter()
            .find(|(end_name, _)| end_name == name)
            .is_some_and(|(_, end_value)| !same(shown, *end_value))
    })
}
