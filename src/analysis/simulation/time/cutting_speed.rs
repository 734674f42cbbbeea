//! The time of a feed move under constant cutting speed G96 (reference §15.2, T119): the spindle
//! speed follows the diameter of the transverse axis, n(D) = 1000·S/(π·D), capped at the limit
//! (`LIMS`); the time is the integral of ds / (F·n) along the path. A line has a closed form (its
//! radius changes linearly along it), an arc is integrated numerically.

use crate::analysis::engine::moves::Move;
use crate::analysis::engine::timing::speed_at_radius;

/// Intervals of the numerical integration over an arc (Simpson's rule; even).
const ARC_INTERVALS: usize = 512;

/// The minutes of `movement` (path `length` in mm, feed `feed` in mm/rev) under G96, with the
/// transverse axis `transverse`; `None` when the cutting speed, the limit, the transverse axis's
/// position or the arc is unknown.
pub(super) fn minutes(
    movement: &Move,
    length: f64,
    feed: f64,
    transverse: Option<&str>,
) -> Option<f64> {
    let timing = &movement.timing;
    let cutting = timing.cutting_speed.filter(|speed| *speed > 0.0)?;
    let limit = timing.speed_limit.filter(|limit| *limit > 0.0)?;
    let transverse = transverse?;
    let radius_of = |value: f64| {
        if movement.transverse_as_diameter {
            value / 2.0
        } else {
            value
        }
    };
    let find = |values: &[(std::sync::Arc<str>, f64)]| {
        values
            .iter()
            .find(|(name, _)| name.as_ref() == transverse)
            .map(|(_, value)| radius_of(*value))
    };
    let start = find(&movement.start)?;
    let end = find(&movement.end)?;
    if let Some(arc) = &movement.arc {
        let (first, second) = movement.plane?;
        let centre = |name: &str| {
            arc.centre
                .iter()
                .find(|(axis, _)| axis.as_ref() == name)
                .map(|(axis, value)| {
                    if axis.as_ref() == transverse {
                        radius_of(*value)
                    } else {
                        *value
                    }
                })
        };
        let point = |values: &[(std::sync::Arc<str>, f64)], name: &str| {
            values
                .iter()
                .find(|(axis, _)| axis.as_ref() == name)
                .map(|(axis, value)| {
                    if axis.as_ref() == transverse {
                        radius_of(*value)
                    } else {
                        *value
                    }
                })
        };
        let transverse_is_first = first == transverse;
        if !transverse_is_first && second != transverse {
            // The diameter does not change along an arc in another plane.
            return line_minutes(start, end, length, feed, cutting, limit);
        }
        let (centre_first, centre_second) = (centre(first)?, centre(second)?);
        let (start_first, start_second) = (
            point(&movement.start, first)?,
            point(&movement.start, second)?,
        );
        let start_angle = (start_second - centre_second).atan2(start_first - centre_first);
        let direction = if arc.clockwise { -1.0 } else { 1.0 };
        let sweep = arc.sweep.abs().to_radians();
        if sweep == 0.0 {
            return Some(0.0);
        }
        let radius_at = |fraction: f64| {
            let angle = start_angle + direction * sweep * fraction;
            if transverse_is_first {
                centre_first + arc.radius * angle.cos()
            } else {
                centre_second + arc.radius * angle.sin()
            }
        };
        let inverse_speed = |fraction: f64| {
            speed_at_radius(cutting, radius_at(fraction), Some(limit)).map(|speed| 1.0 / speed)
        };
        // Simpson's rule over the fraction of the arc, ds = length · d(fraction).
        let step = 1.0 / ARC_INTERVALS as f64;
        let mut sum = inverse_speed(0.0)? + inverse_speed(1.0)?;
        for index in 1..ARC_INTERVALS {
            let weight = if index % 2 == 1 { 4.0 } else { 2.0 };
            sum += weight * inverse_speed(index as f64 * step)?;
        }
        let integral = sum * step / 3.0;
        return Some(length * integral / feed);
    }
    line_minutes(start, end, length, feed, cutting, limit)
}

/// A line from radius `start` to `end` of the transverse axis (the radius changes linearly along
/// the path of `length`): the exact integral of §15.2, split where the limit starts to apply.
fn line_minutes(
    start: f64,
    end: f64,
    length: f64,
    feed: f64,
    cutting: f64,
    limit: f64,
) -> Option<f64> {
    let change = (end - start).abs();
    if change < 1e-12 {
        let speed = speed_at_radius(cutting, start, Some(limit))?;
        return Some(length / (feed * speed));
    }
    let integral =
        (antiderivative(end, cutting, limit) - antiderivative(start, cutting, limit)).abs();
    Some(length / change * integral / feed)
}

/// An antiderivative over the radius x of 1/n(x) (minutes per revolution): 1/limit inside the radius
/// where the limit applies, 2π·|x|/(1000·S) outside; odd in x, so that a path across the axis adds
/// both sides.
pub(super) fn antiderivative(x: f64, cutting: f64, limit: f64) -> f64 {
    let slope = 2.0 * std::f64::consts::PI / (1000.0 * cutting);
    // The radius at which the free speed reaches the limit.
    let capped = 1000.0 * cutting / (2.0 * std::f64::consts::PI * limit);
    let u = x.abs();
    let value = if u <= capped {
        u / limit
    } else {
        capped / limit + slope * (u * u - capped * capped) / 2.0
    };
    value.copysign(x)
}
