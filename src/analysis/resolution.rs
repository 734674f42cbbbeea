//! How each axis word of a block resolves, step by step, for a person reading a hover: the value as
//! written, the mode that applies, the unit and diameter conversion, the start and the end point.
//!
//! The end point always comes from the engine (the state after the block); the steps are derived
//! from the same state and checked against it, so an explanation never shows arithmetic that leads to
//! another number than the engine's. Where they would disagree, `explained` is false and only the
//! engine's value is to be shown.

use crate::analysis::engine::evaluation::axis_name;
use crate::analysis::eval::evaluate;
use crate::analysis::state::ModalState;
use crate::config::{AxisKind, MachineConfig};
use crate::diagnostics::Span;
use crate::syntax::ast::{AddressKind, Block, Modifier, Statement, ValueExpr};
use std::sync::Arc;

/// How the value of an axis word is read (reference §3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ResolutionMode {
    /// Modal G90: the value is the end point.
    Absolute,
    /// Modal G91: the value is added to the last position.
    Incremental,
    /// A non-modal override written on the word: `AC`, `IC`, `DC`, `ACP`, `ACN`, `DAC`, `DIC`, `RAC`,
    /// `RIC`, `CAC`, `CIC`, `CACP`, `CACN`, `CDC`.
    Override(Modifier),
    /// G53, G153 or SUPA in the block: the value is a machine position.
    Machine,
    /// The mode is inherited from an unseen caller (a subprogram that has not programmed G90/G91).
    Unknown,
}

/// The resolution of one axis word, with the steps a person needs to follow it.
#[derive(Debug, Clone, PartialEq)]
pub struct WordResolution {
    /// The word's byte span within the line.
    pub span: Span,
    /// The axis name in upper case (`X`, `Z1`).
    pub axis: String,
    /// The value as written (after evaluating an expression), in the program's units; `None` when it
    /// depends on something unknown.
    pub programmed: Option<f64>,
    pub mode: ResolutionMode,
    /// The factor from program units to the basic system (25.4 under G70 on a metric machine); 1 for
    /// rotary axes.
    pub unit_factor: Option<f64>,
    /// Whether the value was read as a diameter (DIAMON, DIAM90 absolute, DAC, DIC).
    pub read_as_diameter: bool,
    /// Whether start and end are shown as diameters (the position display under DIAMON or DIAM90).
    pub shown_as_diameter: bool,
    /// The axis position before the block, as the program shows it (a diameter under DIAMON).
    pub start: Option<f64>,
    /// The resolved end point, as the program shows it.
    pub end: Option<f64>,
    /// The end point after the programmable frame (machine coordinates, a radius on transverse axes).
    pub machine: Option<f64>,
    /// Whether `start`, `programmed`, the mode and the factors give `end` by plain arithmetic (absolute:
    /// end = programmed x factor; incremental: end = start + programmed x factor). False for the
    /// rules a hover should not spell out as a sum (modulo rotary axes, DIAM90 increments shown as
    /// diameters, machine positions) and whenever the engine's value differs.
    pub explained: bool,
    /// Why the end point is unknown, when it is.
    pub unknown_reason: Option<String>,
}

/// The resolutions of the axis words of `block` (the text `line`), given the state before and after
/// it and the machine coordinates of its move, if known. Frame and pole instructions have no axis
/// words that move (their words are frame values): they give an empty list.
pub fn resolve_words(
    config: &MachineConfig,
    before: &ModalState,
    after: &ModalState,
    line: &str,
    block: &Block,
    machine: Option<&[(Arc<str>, f64)]>,
) -> Vec<WordResolution> {
    let statements = block.interpreted_statements();
    let mut machine_coordinates = false;
    for statement in statements {
        if let Statement::GCode { code, .. } = statement {
            if code.is_modal() {
                continue;
            }
            match code.group() {
                // Frame and pole instructions, and dwell or reference-point blocks, do not move to
                // their axis values.
                3 | 2 => return Vec::new(),
                9 => machine_coordinates = true,
                _ => {}
            }
        }
    }
    let shows_diameter = after.shows_diameter();
    let mut out = Vec::new();
    for statement in statements {
        let Statement::Address(word) = statement else {
            continue;
        };
        if word.kind != AddressKind::Axis {
            continue;
        }
        let axis = axis_name(line, word);
        let Some(index) = config
            .axes
            .iter()
            .position(|configured| configured.name.eq_ignore_ascii_case(&axis))
        else {
            continue;
        };
        let kind = config.axes[index].kind;
        let modifier = word.value.modifier.map(|(modifier, _)| modifier);
        let programmed = match word.value.expr {
            ValueExpr::Missing => None,
            ValueExpr::Constant { value, .. } => Some(value),
            ValueExpr::Expr(id) => evaluate(block, line, id, &before.variables).ok().flatten(),
        };
        let mode = if machine_coordinates {
            ResolutionMode::Machine
        } else if let Some(modifier) = modifier {
            ResolutionMode::Override(modifier)
        } else {
            match after.is_incremental() {
                Some(true) => ResolutionMode::Incremental,
                Some(false) => ResolutionMode::Absolute,
                None => ResolutionMode::Unknown,
            }
        };
        let incremental = match mode {
            ResolutionMode::Incremental => Some(true),
            ResolutionMode::Absolute | ResolutionMode::Machine => Some(false),
            ResolutionMode::Override(modifier) => Some(matches!(
                modifier,
                Modifier::Ic | Modifier::Dic | Modifier::Ric | Modifier::Cic
            )),
            ResolutionMode::Unknown => None,
        };
        let unit_factor = match kind {
            AxisKind::Linear | AxisKind::Transverse => after.length_factor(config.metric),
            AxisKind::Rotary | AxisKind::Modulo => Some(1.0),
        };
        let transverse = kind == AxisKind::Transverse;
        let read_as_diameter = transverse
            && match modifier {
                Some(Modifier::Dac | Modifier::Dic) => true,
                Some(Modifier::Rac | Modifier::Ric) => false,
                _ => after.diameter_mode().is_some_and(|(absolute, increment)| {
                    if incremental == Some(true) {
                        increment
                    } else {
                        absolute
                    }
                }),
            };
        let shown_as_diameter = transverse && shows_diameter == Some(true);
        let display =
            |value: f64| crate::analysis::state::shown_value(transverse, shows_diameter, value);
        let start = before.positions[index].and_then(display);
        let end = after.positions[index].and_then(display);
        let machine_value = machine.and_then(|values| {
            values
                .iter()
                .find(|(name, _)| name.eq_ignore_ascii_case(&axis))
                .map(|(_, value)| *value)
        });
        // The arithmetic a hover spells out, in the units the program shows.
        let expected = match (programmed, unit_factor, incremental) {
            (Some(value), Some(factor), Some(is_incremental))
                if read_as_diameter == shown_as_diameter
                    && kind != AxisKind::Modulo
                    && mode != ResolutionMode::Machine =>
            {
                let value = value * factor;
                if is_incremental {
                    start.map(|start| start + value)
                } else {
                    Some(value)
                }
            }
            _ => None,
        };
        let explained = matches!((expected, end), (Some(expected), Some(end)) if (expected - end).abs() <= 1e-9 * end.abs().max(1.0));
        let unknown_reason = end.is_none().then(|| {
            unknown_reason(
                programmed,
                mode,
                unit_factor,
                incremental,
                start,
                transverse && shows_diameter.is_none(),
            )
        });
        out.push(WordResolution {
            span: word.span,
            axis,
            programmed,
            mode,
            unit_factor,
            read_as_diameter,
            shown_as_diameter,
            start,
            end,
            machine: machine_value,
            explained,
            unknown_reason,
        });
    }
    out
}

/// Why an axis word's end point is unknown, in the order a person would check it.
fn unknown_reason(
    programmed: Option<f64>,
    mode: ResolutionMode,
    unit_factor: Option<f64>,
    incremental: Option<bool>,
    start: Option<f64>,
    diameter_mode_unknown: bool,
) -> String {
    if programmed.is_none() {
        return "the value depends on a variable, parameter or function whose value is not known here"
            .to_string();
    }
    if mode == ResolutionMode::Unknown {
        return "G90/G91 is inherited from the calling program and not known here".to_string();
    }
    if unit_factor.is_none() {
        return "inch or metric (G70/G71/G700/G710) is inherited from the calling program"
            .to_string();
    }
    if diameter_mode_unknown {
        return "diameter or radius programming is inherited from the calling program".to_string();
    }
    if mode == ResolutionMode::Machine {
        return "a machine position (G53/G153/SUPA) under a work offset or frame whose value is not known"
            .to_string();
    }
    if incremental == Some(true) && start.is_none() {
        return "an incremental move from a position that is not known (never programmed, or lost after a call, a tool change or a transformation)".to_string();
    }
    "the analysis does not follow how the control resolves this word (see the block's diagnostics)"
        .to_string()
}
