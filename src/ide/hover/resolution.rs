//! How the hover explains one resolved axis word: the arithmetic of the value (absolute, incremental,
//! inch, diameter, a radius increment under DIAM90), the machine position of G53/G153/SUPA, and why a
//! value is unknown.

use crate::analysis::document::{ResolutionMode, StateSummary, WordResolution};
use crate::config::{AxisKind, MachineConfig};
use crate::ide::numbers::{fixed, same, term};
use crate::syntax::ast::Modifier;
use std::fmt::Write;

fn units_label(config: &MachineConfig, kind: Option<AxisKind>) -> &'static str {
    match kind {
        Some(kind) if kind.is_rotary() => "°",
        _ if config.metric => "mm",
        _ => "in",
    }
}

pub fn is_incremental(mode: ResolutionMode) -> bool {
    matches!(
        mode,
        ResolutionMode::Incremental
            | ResolutionMode::Override(
                Modifier::Ic | Modifier::Dic | Modifier::Ric | Modifier::Cic
            )
    )
}

/// `in_effect` is the modal state that applies to the block's words (after its own G functions).
fn mode_note(mode: ResolutionMode, in_effect: &StateSummary) -> String {
    let modal = in_effect.distance.as_deref().unwrap_or("the modal G90/G91");
    match mode {
        ResolutionMode::Absolute => "G90: absolute".to_string(),
        ResolutionMode::Incremental => "G91: incremental".to_string(),
        ResolutionMode::Machine => {
            "G53/G153/SUPA: a machine position for this block only".to_string()
        }
        ResolutionMode::Unknown => {
            "G90 or G91 is inherited from the caller and not known here".to_string()
        }
        ResolutionMode::Override(modifier) => {
            let what = match modifier {
                Modifier::Ac => "absolute for this block only",
                Modifier::Ic => "incremental for this block only",
                Modifier::Dc => "absolute, the rotary axis takes the shortest way",
                Modifier::Acp => "absolute, the rotary axis turns in the positive direction",
                Modifier::Acn => "absolute, the rotary axis turns in the negative direction",
                Modifier::Dac => "absolute diameter for this block only",
                Modifier::Dic => "incremental diameter for this block only",
                Modifier::Rac => "absolute radius for this block only",
                Modifier::Ric => "incremental radius for this block only",
                Modifier::Cac => "coded position, absolute",
                Modifier::Cic => "coded position, incremental",
                Modifier::Cdc => "coded position, shortest way",
                Modifier::Cacp => "coded position, positive direction",
                Modifier::Cacn => "coded position, negative direction",
            };
            format!(
                "{}: {what}; {modal} stays active",
                modifier.as_str().to_ascii_uppercase()
            )
        }
    }
}

/// The explanation of one resolved word, e.g. `Z = 90.000 + (-32.000) = **58.000** mm (IC: ...)`;
/// `in_effect` is the modal state that applies to the block's words.
pub fn explain_resolution(
    resolution: &WordResolution,
    in_effect: &StateSummary,
    config: &MachineConfig,
) -> String {
    let axis = &resolution.axis;
    let axis_kind = config.axis(axis).map(|axis| axis.kind);
    let unit = units_label(config, axis_kind);
    let note = mode_note(resolution.mode, in_effect);
    if resolution.mode == ResolutionMode::Machine {
        return explain_machine_position(resolution, axis_kind, unit, &note);
    }
    let mut text = String::new();
    let Some(end) = resolution.end else {
        let reason = resolution
            .unknown_reason
            .clone()
            .unwrap_or_else(|| "the analysis cannot follow this value here".to_string());
        let _ = write!(text, "{axis} = **unknown**: {reason} ({note})");
        return text;
    };
    let factor = resolution.unit_factor.unwrap_or(1.0);
    let converted = resolution.programmed.map(|programmed| programmed * factor);
    let inch = resolution
        .unit_factor
        .is_some_and(|factor| !same(factor, 1.0));
    // The programmed value as a term: `1.000 in (25.400 mm)` under G70, else the value itself.
    let programmed_term = |programmed: f64| -> String {
        if inch {
            let program_unit = if config.metric { "in" } else { "mm" };
            format!(
                "{} {program_unit} ({} {unit})",
                term(programmed),
                fixed(programmed * factor)
            )
        } else {
            term(programmed)
        }
    };
    // A sum is shown only where the analysis says plain arithmetic gives its end point, and where
    // it does here too.
    // An increment that is a radius while positions show diameters (G91 under DIAM90, RIC under
    // DIAMON) moves the diameter by twice its value: the sum says so.
    let radius_increment = is_incremental(resolution.mode)
        && resolution.shown_as_diameter
        && !resolution.read_as_diameter;
    let formula = match (resolution.programmed, converted, resolution.start) {
        (Some(programmed), Some(converted), Some(start))
            if radius_increment && same(start + 2.0 * converted, end) =>
        {
            Some(format!(
                "{axis} = {} + 2 × {} = **{}** {unit}",
                term(start),
                programmed_term(programmed),
                fixed(end)
            ))
        }
        _ if !resolution.explained => None,
        (Some(programmed), Some(converted), Some(start))
            if is_incremental(resolution.mode) && same(start + converted, end) =>
        {
            Some(format!(
                "{axis} = {} + {} = **{}** {unit}",
                term(start),
                programmed_term(programmed),
                fixed(end)
            ))
        }
        (Some(programmed), Some(converted), _)
            if !is_incremental(resolution.mode) && same(converted, end) && inch =>
        {
            Some(format!(
                "{axis} = {} = **{}** {unit}",
                programmed_term(programmed),
                fixed(end)
            ))
        }
        _ => None,
    };
    match formula {
        Some(formula) => {
            let _ = write!(text, "{formula} ({note})");
        }
        None => match resolution.start {
            Some(start) if is_incremental(resolution.mode) && !same(start, end) => {
                let _ = write!(
                    text,
                    "{axis}: {} → **{}** {unit} ({note})",
                    fixed(start),
                    fixed(end)
                );
            }
            _ => {
                let _ = write!(text, "{axis} = **{}** {unit} ({note})", fixed(end));
            }
        },
    }
    if radius_increment {
        let _ = write!(
            text,
            "\n\nThe increment is a radius (under DIAM90, G91 values are radii; RIC always is one): it changes the diameter by twice its value. Diameter {} {unit}, radius {} {unit}",
            fixed(end),
            fixed(end / 2.0)
        );
    } else if resolution.shown_as_diameter {
        let _ = write!(
            text,
            "\n\nDiameter {} {unit}, radius {} {unit}",
            fixed(end),
            fixed(end / 2.0)
        );
    } else if resolution.read_as_diameter {
        text.push_str("\n\nThe value is read as a diameter; the position is shown as a radius.");
    }
    if let Some(machine) = resolution.machine {
        let shown_machine = if resolution.shown_as_diameter {
            machine * 2.0
        } else {
            machine
        };
        if !same(shown_machine, end) {
            let radius_note = if axis_kind == Some(AxisKind::Transverse) {
                " (radius)"
            } else {
                ""
            };
            let _ = write!(
                text,
                "\n\nAfter the programmable frame (machine coordinates): {axis} = **{}** {unit}{radius_note}",
                fixed(machine)
            );
        }
    }
    text
}

/// The hover of an axis word of a G53/G153/SUPA block: the machine position first (what the block
/// programs), then where that lies in workpiece coordinates (what later blocks build on).
fn explain_machine_position(
    resolution: &WordResolution,
    axis_kind: Option<AxisKind>,
    unit: &str,
    note: &str,
) -> String {
    let axis = &resolution.axis;
    let transverse = axis_kind == Some(AxisKind::Transverse);
    let mut text = match (resolution.machine, resolution.programmed) {
        (Some(machine), _) => format!(
            "{axis} = **{}** {unit}{} in machine coordinates ({note})",
            fixed(machine),
            if transverse { " (radius)" } else { "" }
        ),
        (None, Some(programmed)) => format!(
            "{axis} = **{}** {unit} as programmed, in machine coordinates ({note})",
            fixed(programmed * resolution.unit_factor.unwrap_or(1.0))
        ),
        (None, None) => format!("{axis} = **unknown** in machine coordinates: the value depends on a variable, parameter or function whose value is not known here ({note})"),
    };
    match resolution.end {
        Some(end) => {
            let _ = write!(
                text,
                "\n\nIn workpiece coordinates: {axis} = **{}** {unit}",
                fixed(end)
            );
            if resolution.shown_as_diameter {
                let _ = write!(text, " (diameter; radius {} {unit})", fixed(end / 2.0));
            }
        }
        None => {
            let reason = resolution
                .unknown_reason
                .clone()
                .unwrap_or_else(|| "the analysis cannot follow this value here".to_string());
            let _ = write!(
                text,
                "\n\nIn workpiece coordinates: {axis} = **unknown**: {reason}"
            );
        }
    }
    text
}
