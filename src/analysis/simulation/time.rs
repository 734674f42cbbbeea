//! Machining time of a move (reference §15): the base model of §15.2 (path length over path
//! velocity, G0 by the slowest axis at its maximum velocity, dwell) and, as an option, the trapezoid of
//! §15.3. A move's time is computed from the move alone (its start, end, arc, feed and `timing`), so
//! moves that other stages make (inserted roundings, cycle moves) are timed alike. What depends on a
//! value the program does not determine (feed, spindle speed, length) is unknown, never guessed.

mod axis_delta;
mod cutting_speed;
mod trapezoid;

use crate::analysis::engine::moves::Move;
use crate::analysis::engine::timing::FeedType;
use crate::config::timing::TimeModelKind;
use crate::config::{AxisKind, MachineConfig};
use axis_delta::AxisDelta;

/// What a move's time counts as in the totals.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TimeKind {
    Feed,
    Rapid,
    Dwell,
}

/// The time of one move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MoveTime {
    pub kind: TimeKind,
    /// Seconds; `None` when unknown.
    pub seconds: Option<f64>,
}

/// The sums over a program's moves.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TimeTotals {
    /// Seconds of every move whose time is known.
    pub total_s: f64,
    pub feed_s: f64,
    pub rapid_s: f64,
    pub dwell_s: f64,
    /// Moves whose time is unknown (not in the sums).
    pub unknown_moves: u64,
}

impl TimeTotals {
    pub fn add(&mut self, time: MoveTime) {
        let Some(seconds) = time.seconds else {
            self.unknown_moves += 1;
            return;
        };
        self.total_s += seconds;
        match time.kind {
            TimeKind::Feed => self.feed_s += seconds,
            TimeKind::Rapid => self.rapid_s += seconds,
            TimeKind::Dwell => self.dwell_s += seconds,
        }
    }
}

/// What the model knows of a configured axis.
#[derive(Debug, Clone)]
struct AxisTiming {
    name: String,
    kind: AxisKind,
    /// X, Y or Z: a geometry axis, whose path the feed applies to (FGROUP default).
    geometry: bool,
    /// mm/min or degrees/min.
    max_velocity: f64,
    /// mm/s² or degrees/s².
    max_acceleration: Option<f64>,
}

/// Times moves on one machine configuration.
#[derive(Debug, Clone)]
pub struct TimeModel {
    axes: Vec<AxisTiming>,
    model: TimeModelKind,
    /// The transverse axis, whose diameter G96 reads (the first configured).
    transverse: Option<String>,
}

impl TimeModel {
    pub fn new(config: &MachineConfig) -> TimeModel {
        let timing = &config.timing;
        let axes = config
            .axes
            .iter()
            .map(|axis| {
                let rotary = matches!(axis.kind, AxisKind::Rotary | AxisKind::Modulo);
                AxisTiming {
                    name: axis.name.clone(),
                    kind: axis.kind,
                    geometry: !rotary
                        && ["X", "Y", "Z"]
                            .iter()
                            .any(|name| axis.name.eq_ignore_ascii_case(name)),
                    max_velocity: timing.velocity_of(&axis.name),
                    // m/s² on linear axes is 1000 mm/s².
                    max_acceleration: timing.acceleration_of(&axis.name).map(|value| {
                        if rotary {
                            value
                        } else {
                            value * 1000.0
                        }
                    }),
                }
            })
            .collect();
        TimeModel {
            axes,
            model: timing.model,
            transverse: config
                .axes
                .iter()
                .find(|axis| axis.kind == AxisKind::Transverse)
                .map(|axis| axis.name.clone()),
        }
    }

    /// The time of `movement`.
    pub fn time_of(&self, movement: &Move) -> MoveTime {
        if let Some(dwell) = movement.timing.dwell {
            return MoveTime {
                kind: TimeKind::Dwell,
                seconds: dwell.seconds,
            };
        }
        let rapid = movement.motion == "G0";
        let kind = if rapid {
            TimeKind::Rapid
        } else {
            TimeKind::Feed
        };
        let seconds = self.motion_seconds(movement, rapid);
        MoveTime {
            kind,
            seconds: seconds.filter(|seconds| seconds.is_finite() && *seconds >= 0.0),
        }
    }

    fn motion_seconds(&self, movement: &Move, rapid: bool) -> Option<f64> {
        let mut deltas = [AxisDelta::default(); 16];
        let count = self.deltas(movement, &mut deltas)?;
        let deltas = &deltas[..count];
        if rapid {
            return match self.model {
                TimeModelKind::Base => Some(rapid_minutes(deltas) * 60.0),
                TimeModelKind::Trapezoid => trapezoid::seconds(deltas, None, false),
            };
        }
        let path = self.path(movement, deltas)?;
        let minutes = feed_minutes(movement, &path, self.transverse.as_deref())?;
        match self.model {
            TimeModelKind::Base => Some(minutes * 60.0),
            TimeModelKind::Trapezoid if path.length == 0.0 => Some(minutes * 60.0),
            TimeModelKind::Trapezoid => {
                // The programmed feed, as the base model reads it, is the velocity to reach.
                let feed = path.length / minutes;
                trapezoid::seconds(deltas, Some((path.length, feed)), movement.arc.is_some())
            }
        }
    }

    /// The distance each moved axis travels; `None` when an axis's start or end is unknown. At most
    /// 16 axes are followed; a move of more is unknown.
    fn deltas(&self, movement: &Move, out: &mut [AxisDelta; 16]) -> Option<usize> {
        if movement.start.len() != movement.end.len() {
            return None;
        }
        // An axis whose end is unknown moves by an unknown distance.
        if movement
            .uncertain
            .iter()
            .any(|name| !movement.end.iter().any(|(end, _)| end == name))
        {
            return None;
        }
        let mut count = 0;
        for ((name, start), (end_name, end)) in movement.start.iter().zip(&movement.end) {
            if name != end_name {
                return None;
            }
            let index = self
                .axes
                .iter()
                .position(|axis| axis.name == name.as_ref())?;
            let axis = &self.axes[index];
            let mut delta = (end - start).abs();
            if axis.kind == AxisKind::Transverse && movement.transverse_as_diameter {
                delta /= 2.0;
            }
            if delta == 0.0 {
                continue;
            }
            *out.get_mut(count)? = AxisDelta {
                index,
                geometry: axis.geometry,
                rotary: matches!(axis.kind, AxisKind::Rotary | AxisKind::Modulo),
                max_velocity: axis.max_velocity,
                max_acceleration: axis.max_acceleration,
                delta,
            };
            count += 1;
        }
        Some(count)
    }

    /// The path the feed applies to: the geometry axes' path (an arc's length with its helix), else
    /// the other axes' (rotary axes in degrees).
    fn path(&self, movement: &Move, deltas: &[AxisDelta]) -> Option<Path> {
        let geometry_squares: f64 = deltas
            .iter()
            .filter(|delta| delta.geometry)
            .map(|delta| delta.delta * delta.delta)
            .sum();
        if let Some(arc) = &movement.arc {
            let (first, second) = movement.plane?;
            // The part of the path outside the plane: the helix's lead.
            let lead_squares: f64 = deltas
                .iter()
                .filter(|delta| {
                    let name = &self.axes[delta.index].name;
                    delta.geometry
                        && !name.eq_ignore_ascii_case(first)
                        && !name.eq_ignore_ascii_case(second)
                })
                .map(|delta| delta.delta * delta.delta)
                .sum();
            let in_plane = arc.radius * arc.sweep.abs().to_radians();
            return Some(Path {
                length: (in_plane * in_plane + lead_squares).sqrt(),
                degrees: false,
            });
        }
        if matches!(movement.motion.as_ref(), "G2" | "G3" | "CIP" | "CT") {
            // A circle whose geometry is not known.
            return None;
        }
        if geometry_squares > 0.0 {
            return Some(Path {
                length: geometry_squares.sqrt(),
                degrees: false,
            });
        }
        let other_squares: f64 = deltas.iter().map(|delta| delta.delta * delta.delta).sum();
        let degrees = deltas.iter().any(|delta| delta.rotary);
        Some(Path {
            length: other_squares.sqrt(),
            degrees,
        })
    }
}

/// The length of a feed move's path, and whether it is in degrees (only rotary axes move).
#[derive(Debug, Clone, Copy)]
struct Path {
    length: f64,
    degrees: bool,
}

/// G0 in the base model: the axis that needs longest at its maximum velocity decides (§15.2).
fn rapid_minutes(deltas: &[AxisDelta]) -> f64 {
    deltas
        .iter()
        .map(|delta| delta.delta / delta.max_velocity)
        .fold(0.0, f64::max)
}

/// A feed move's time in minutes by its feed type (§15.2).
fn feed_minutes(movement: &Move, path: &Path, transverse: Option<&str>) -> Option<f64> {
    let timing = &movement.timing;
    let feed_type = timing.feed_type?;
    if feed_type == FeedType::InverseTime {
        // G93: F is 1/min for the whole block, whatever its length.
        let feed = timing.programmed_feed.filter(|feed| *feed > 0.0)?;
        return Some(if path.length == 0.0 { 0.0 } else { 1.0 / feed });
    }
    if path.length == 0.0 {
        return Some(0.0);
    }
    // Degrees are read as F in degrees/min (with the default FGREF); lengths in the basic unit system.
    let feed = if path.degrees {
        timing.programmed_feed
    } else {
        timing.feed
    }
    .filter(|feed| *feed > 0.0)?;
    match feed_type {
        FeedType::InverseTime => None,
        FeedType::PerMinute => Some(path.length / feed),
        FeedType::PerRevolution => {
            let speed = timing.spindle_speed.filter(|speed| *speed > 0.0)?;
            Some(path.length / (feed * speed))
        }
        FeedType::ConstantCuttingSpeed => {
            cutting_speed::minutes(movement, path.length, feed, transverse)
        }
    }
}

#[cfg(test)]
mod tests;
