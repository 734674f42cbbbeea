//! How machining time is estimated (`[timing]` in `sinumerik.toml`, reference §15): the model, the
//! axes' maximum velocity (MD32000 `MAX_AX_VELO`) and acceleration (MD32300 `MAX_AX_ACCEL`), and the
//! spindle's speed limit where the program sets none with `LIMS`.

use super::axes::Axis;
use serde::Deserialize;
use std::collections::BTreeMap;

/// Which model turns a block into a time.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TimeModelKind {
    /// Path length over path velocity, no dynamics (reference §15.2).
    Base,
    /// A trapezoidal velocity profile per block within the axes' velocity and acceleration limits
    /// (reference §15.3).
    Trapezoid,
}

/// The rapid traverse velocity of an axis that is not configured (reference §15.5).
pub const DEFAULT_MAX_VELOCITY: f64 = 10_000.0;

#[derive(Debug, Clone, PartialEq)]
pub struct TimingOptions {
    pub model: TimeModelKind,
    /// The configured maximum velocities by axis name: mm/min on linear axes, degrees/min on rotary
    /// axes; an axis not listed has [`DEFAULT_MAX_VELOCITY`].
    pub max_velocity: Vec<(String, f64)>,
    /// The configured maximum accelerations by axis name: m/s² on linear axes, degrees/s² on rotary
    /// axes; an axis not listed has none, and the trapezoid model cannot time a move of it.
    pub max_acceleration: Vec<(String, f64)>,
    /// The master spindle's highest speed in rpm where the program programs no `LIMS` (SD43230 or the
    /// machine's limit); `None` when not configured.
    pub max_spindle_speed: Option<f64>,
}

impl Default for TimingOptions {
    /// The base model, 10000 per axis, no acceleration, no spindle limit.
    fn default() -> TimingOptions {
        TimingOptions {
            model: TimeModelKind::Base,
            max_velocity: Vec::new(),
            max_acceleration: Vec::new(),
            max_spindle_speed: None,
        }
    }
}

impl TimingOptions {
    /// The maximum velocity of the axis `name`.
    pub fn velocity_of(&self, name: &str) -> f64 {
        self.max_velocity
            .iter()
            .find(|(axis, _)| axis.eq_ignore_ascii_case(name))
            .map_or(DEFAULT_MAX_VELOCITY, |(_, value)| *value)
    }

    /// The maximum acceleration of the axis `name`, if configured.
    pub fn acceleration_of(&self, name: &str) -> Option<f64> {
        self.max_acceleration
            .iter()
            .find(|(axis, _)| axis.eq_ignore_ascii_case(name))
            .map(|(_, value)| *value)
    }
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawTiming {
    model: Option<String>,
    max_velocity: Option<BTreeMap<String, f64>>,
    max_acceleration: Option<BTreeMap<String, f64>>,
    max_spindle_speed: Option<f64>,
}

/// A key path inside `[timing]` and what is wrong with its value.
pub(super) type TimingError = (Vec<String>, String);

impl RawTiming {
    /// The options for the configured `axes`; an error names the keys below `[timing]`.
    pub(super) fn convert(&self, axes: &[Axis]) -> Result<TimingOptions, TimingError> {
        let mut options = TimingOptions::default();
        if let Some(model) = &self.model {
            options.model = match model.as_str() {
                "base" => TimeModelKind::Base,
                "trapezoid" => TimeModelKind::Trapezoid,
                _ => {
                    return Err((
                        vec!["model".to_string()],
                        format!("must be \"base\" or \"trapezoid\", found {model:?}"),
                    ))
                }
            };
        }
        if let Some(values) = &self.max_velocity {
            options.max_velocity = per_axis(values, axes, "max_velocity")?;
        }
        if let Some(values) = &self.max_acceleration {
            options.max_acceleration = per_axis(values, axes, "max_acceleration")?;
        }
        if let Some(value) = self.max_spindle_speed {
            options.max_spindle_speed = Some(positive(value).ok_or((
                vec!["max_spindle_speed".to_string()],
                format!("must be a number greater than 0, found {value}"),
            ))?);
        }
        Ok(options)
    }
}

fn positive(value: f64) -> Option<f64> {
    (value.is_finite() && value > 0.0).then_some(value)
}

/// The values of a per-axis table with the configured axes' names; every name must be a configured
/// axis and every value positive.
fn per_axis(
    values: &BTreeMap<String, f64>,
    axes: &[Axis],
    table: &str,
) -> Result<Vec<(String, f64)>, TimingError> {
    values
        .iter()
        .map(|(name, value)| {
            let path = || vec![table.to_string(), name.clone()];
            let axis = axes
                .iter()
                .find(|axis| axis.name.eq_ignore_ascii_case(name))
                .ok_or_else(|| (path(), format!("{name:?} is not a configured axis")))?;
            let value = positive(*value).ok_or_else(|| {
                (
                    path(),
                    format!("must be a number greater than 0, found {value}"),
                )
            })?;
            Ok((axis.name.clone(), value))
        })
        .collect()
}
