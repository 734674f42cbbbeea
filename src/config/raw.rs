//! The configuration file as written (serde structs with every key optional) and its validation into a
//! `MachineConfig`: range checks, axis names and kinds, settable offsets, and the tables of the
//! execution, cycle, contour and timing options.

use super::contours::RawContours;
use super::cycles::RawCycles;
use super::execution::RawExecution;
use super::file_keys::{invalid, invalid_key, key, InvalidValue, KeySegment};
use super::machine::{Axis, AxisKind, MachineConfig, MachineKind};
use super::timing::RawTiming;
use crate::diagnostics::{Code, Severity};
use serde::Deserialize;
use std::collections::BTreeMap;

/// The file as written, before validation. Every field is optional so that a missing key keeps the
/// default of the machine kind, and `deny_unknown_fields` turns a misspelt key into an error.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawConfig {
    #[serde(default)]
    machine: RawMachine,
    axes: Option<BTreeMap<String, String>>,
    #[serde(default)]
    diagnostics: BTreeMap<String, String>,
    #[serde(default)]
    check: RawCheck,
    #[serde(default)]
    offsets: BTreeMap<String, BTreeMap<String, f64>>,
    #[serde(default)]
    execution: RawExecution,
    #[serde(default)]
    cycles: RawCycles,
    #[serde(default)]
    contours: RawContours,
    #[serde(default)]
    timing: RawTiming,
}

/// The `[machine]` table. Numbers are read as `i64` and range-checked here, which gives a clearer
/// message than an integer overflow reported by serde.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawMachine {
    kind: Option<String>,
    units: Option<String>,
    reset_gcodes: Option<Vec<String>>,
    circle_error_const: Option<f64>,
    circle_error_factor: Option<f64>,
    max_skip_level: Option<i64>,
    max_block_length: Option<i64>,
    r_parameters: Option<i64>,
    frame_offset_incr_prog: Option<i64>,
    mm_frame_fine_trans: Option<i64>,
    modulo_range_error: Option<i64>,
}

/// The `[check]` table.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawCheck {
    extensions: Option<Vec<String>>,
}

impl RawConfig {
    pub(super) fn into_machine_config(self) -> Result<MachineConfig, InvalidValue> {
        let machine = self.machine;
        let kind = match &machine.kind {
            None => MachineKind::Mill,
            Some(text) => match text.to_ascii_lowercase().as_str() {
                "mill" => MachineKind::Mill,
                "turn" => MachineKind::Turn,
                _ => {
                    return Err(invalid(
                        &[key("machine"), key("kind")],
                        format!("unknown machine kind {text:?} (expected mill or turn)"),
                    ))
                }
            },
        };
        let mut config = MachineConfig::for_kind(kind);

        if let Some(text) = &machine.units {
            config.metric = match text.to_ascii_lowercase().as_str() {
                "mm" => true,
                "inch" => false,
                _ => {
                    return Err(invalid(
                        &[key("machine"), key("units")],
                        format!("unknown unit system {text:?} (expected mm or inch)"),
                    ))
                }
            };
        }

        if let Some(reset_gcodes) = &machine.reset_gcodes {
            let mut names = Vec::with_capacity(reset_gcodes.len());
            for (index, name) in reset_gcodes.iter().enumerate() {
                let key_path = [
                    key("machine"),
                    key("reset_gcodes"),
                    KeySegment::Index(index),
                ];
                if name.is_empty()
                    || !name
                        .chars()
                        .all(|character| character.is_ascii_alphanumeric())
                {
                    return Err(invalid(
                        &key_path,
                        format!("{name:?} is not a G function name (expected letters and digits, like \"G18\" or \"DIAMON\")"),
                    ));
                }
                names.push(name.to_ascii_uppercase());
            }
            config.reset_gcodes = names;
        }

        if let Some(value) = machine.circle_error_const {
            if !(value.is_finite() && value > 0.0) {
                return Err(invalid(
                    &[key("machine"), key("circle_error_const")],
                    format!("must be a number greater than 0 (in mm), found {value}"),
                ));
            }
            config.circle_error_const = value;
        }

        if let Some(value) = machine.circle_error_factor {
            if !(value.is_finite() && value >= 0.0) {
                return Err(invalid(
                    &[key("machine"), key("circle_error_factor")],
                    format!("must be a number of 0 or greater, found {value}"),
                ));
            }
            config.circle_error_factor = value;
        }

        if let Some(value) = machine.max_skip_level {
            config.max_skip_level = u8::try_from(value)
                .ok()
                .filter(|level| *level <= 9)
                .ok_or_else(|| {
                    invalid(
                        &[key("machine"), key("max_skip_level")],
                        format!("must be a whole number from 0 to 9, found {value}"),
                    )
                })?;
        }

        if let Some(value) = machine.max_block_length {
            config.max_block_length = usize::try_from(value)
                .ok()
                .filter(|length| *length > 0)
                .ok_or_else(|| {
                    invalid(
                        &[key("machine"), key("max_block_length")],
                        format!("must be a whole number greater than 0, found {value}"),
                    )
                })?;
        }

        if let Some(value) = machine.r_parameters {
            config.r_parameters_configured = true;
            config.r_parameter_count = u32::try_from(value).map_err(|_| {
                invalid(
                    &[key("machine"), key("r_parameters")],
                    format!(
                        "must be a whole number from 0 to {}, found {value}",
                        u32::MAX
                    ),
                )
            })?;
        }

        if let Some(value) = machine.frame_offset_incr_prog {
            config.frame_offset_incr_prog = match value {
                0 => false,
                1 => true,
                _ => {
                    return Err(invalid(
                        &[key("machine"), key("frame_offset_incr_prog")],
                        format!("must be 0 or 1 (SD42440), found {value}"),
                    ))
                }
            };
        }

        if let Some(value) = machine.mm_frame_fine_trans {
            config.frame_fine_trans = match value {
                0 => false,
                1 => true,
                _ => {
                    return Err(invalid(
                        &[key("machine"), key("mm_frame_fine_trans")],
                        format!("must be 0 or 1 (MD18600), found {value}"),
                    ))
                }
            };
        }

        if let Some(value) = machine.modulo_range_error {
            config.modulo_range_error = match value {
                0 => false,
                1 => true,
                _ => {
                    return Err(invalid(
                        &[key("machine"), key("modulo_range_error")],
                        format!("must be 0 or 1 (MD30455 bit 0), found {value}"),
                    ))
                }
            };
        }

        if let Some(axes) = &self.axes {
            config.axes = convert_axes(axes)?;
        }

        for (name, values) in &self.offsets {
            let key_path = [key("offsets"), key(name)];
            let index = settable_frame_index(name).ok_or_else(|| {
                invalid_key(
                    &key_path,
                    format!("{name:?} is not a settable work offset (expected G500, G54 to G57 or G505 to G599)"),
                )
            })?;
            let mut axes = Vec::with_capacity(values.len());
            for (axis_name, value) in values {
                let axis_path = [key("offsets"), key(name), key(axis_name)];
                let Some(axis) = config.axis(axis_name) else {
                    return Err(invalid_key(
                        &axis_path,
                        format!("{axis_name:?} is not an axis of this machine"),
                    ));
                };
                if !value.is_finite() {
                    return Err(invalid(
                        &axis_path,
                        format!("must be a finite number, found {value}"),
                    ));
                }
                if axes.iter().any(|(name, _)| *name == axis.name) {
                    return Err(invalid_key(
                        &axis_path,
                        format!(
                            "axis {} is listed twice (axis names are not case-sensitive)",
                            axis.name
                        ),
                    ));
                }
                axes.push((axis.name.clone(), *value));
            }
            // In the order of the configured axes, as everywhere else.
            axes.sort_by_key(|(name, _)| config.axes.iter().position(|axis| axis.name == *name));
            if config.settable_offsets.insert(index, axes).is_some() {
                return Err(invalid_key(
                    &key_path,
                    format!("offset {name} is listed twice (names are not case-sensitive)"),
                ));
            }
        }

        for (code_text, severity_text) in &self.diagnostics {
            let key_path = [key("diagnostics"), key(code_text)];
            let code = Code::parse(code_text).ok_or_else(|| {
                invalid_key(
                    &key_path,
                    format!("unknown diagnostic code {code_text:?} (codes look like \"S101\")"),
                )
            })?;
            let severity = Severity::parse(severity_text).ok_or_else(|| {
                invalid(
                    &key_path,
                    format!("unknown severity {severity_text:?} (expected error, warning, info or hint)"),
                )
            })?;
            if config.severity_overrides.insert(code, severity).is_some() {
                return Err(invalid_key(
                    &key_path,
                    format!("code {code} is listed twice (codes are not case-sensitive)"),
                ));
            }
        }

        if let Some(extensions) = &self.check.extensions {
            if extensions.is_empty() {
                return Err(invalid(
                    &[key("check"), key("extensions")],
                    "list at least one extension, like [\"mpf\", \"spf\"]".to_string(),
                ));
            }
            let mut normalized = Vec::with_capacity(extensions.len());
            for (index, extension) in extensions.iter().enumerate() {
                let is_plain = !extension.is_empty()
                    && !extension.contains(['.', '/', '\\'])
                    && !extension.chars().any(char::is_whitespace);
                if !is_plain {
                    return Err(invalid(
                        &[key("check"), key("extensions"), KeySegment::Index(index)],
                        format!("{extension:?} is not a file extension (write it without the dot, like \"mpf\")"),
                    ));
                }
                normalized.push(extension.to_ascii_lowercase());
            }
            config.extensions = normalized;
        }

        config.execution = self
            .execution
            .convert()
            .map_err(|(name, message)| invalid(&[key("execution"), key(name)], message))?;
        config.cycles = self
            .cycles
            .convert()
            .map_err(|(name, message)| invalid(&[key("cycles"), key(name)], message))?;
        config.contours = self
            .contours
            .convert()
            .map_err(|(name, message)| invalid(&[key("contours"), key(name)], message))?;
        config.timing = self
            .timing
            .convert(&config.axes)
            .map_err(|(path, message)| {
                let keys: Vec<KeySegment> = std::iter::once(key("timing"))
                    .chain(path.iter().map(|name| key(name)))
                    .collect();
                invalid(&keys, message)
            })?;
        Ok(config)
    }
}

/// The `$P_UIFR` index of a settable work offset by its G function: G500 is 0, G54 to G57 are 1 to 4,
/// G505 to G599 are 5 to 99.
fn settable_frame_index(name: &str) -> Option<u8> {
    let digits = name.strip_prefix(['G', 'g'])?;
    if digits.is_empty() || !digits.bytes().all(|byte| byte.is_ascii_digit()) || digits.len() > 3 {
        return None;
    }
    match digits.parse::<u16>().ok()? {
        500 => Some(0),
        number @ 54..=57 => Some((number - 53) as u8),
        number @ 505..=599 => Some((number - 500) as u8),
        _ => None,
    }
}

/// Validates the `[axes]` table and orders it geometry axes first.
fn convert_axes(raw_axes: &BTreeMap<String, String>) -> Result<Vec<Axis>, InvalidValue> {
    if raw_axes.is_empty() {
        return Err(invalid(
            &[key("axes")],
            "no axes listed; list at least one axis or remove the [axes] table to keep the defaults".to_string(),
        ));
    }
    let mut axes: Vec<Axis> = Vec::with_capacity(raw_axes.len());
    for (name, kind_text) in raw_axes {
        let key_path = [key("axes"), key(name)];
        let mut characters = name.chars();
        let is_valid_name = name.len() <= 8
            && characters
                .next()
                .is_some_and(|first| first.is_ascii_alphabetic())
            && characters.all(|character| character.is_ascii_alphanumeric() || character == '_');
        if !is_valid_name {
            return Err(invalid_key(
                &key_path,
                format!("{name:?} is not an axis name (1 to 8 letters, digits or underscores, starting with a letter)"),
            ));
        }
        let kind = match kind_text.to_ascii_lowercase().as_str() {
            "linear" => AxisKind::Linear,
            "transverse" => AxisKind::Transverse,
            "rotary" => AxisKind::Rotary,
            "modulo" => AxisKind::Modulo,
            _ => {
                return Err(invalid(
                    &key_path,
                    format!("unknown axis kind {kind_text:?} (expected linear, transverse, rotary or modulo)"),
                ))
            }
        };
        let name = name.to_ascii_uppercase();
        if axes.iter().any(|axis| axis.name == name) {
            return Err(invalid_key(
                &key_path,
                format!("axis {name} is listed twice (axis names are not case-sensitive)"),
            ));
        }
        axes.push(Axis { name, kind });
    }
    // The geometry axes come first because the rest of the product reads the first axes as the
    // geometry axes; TOML tables carry no order, so the other axes are sorted for determinism.
    axes.sort_by_key(|axis| {
        let geometry_rank = ["X", "Y", "Z"]
            .iter()
            .position(|geometry| *geometry == axis.name)
            .unwrap_or(3);
        (geometry_rank, axis.name.clone())
    });
    Ok(axes)
}
