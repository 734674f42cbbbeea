//! The trapezoid model of reference §15.3: every block starts and ends at standstill (exact stop,
//! BRISK), accelerates at the path acceleration the axes allow, cruises at the lower of the
//! programmed feed and the axes' velocity limits, and decelerates. A lower bound of the real time:
//! jerk, blending and look-ahead are not modelled.

use super::axis_delta::AxisDelta;

/// Seconds of a block whose axes move by `deltas`; `feed` is the path length and the velocity to
/// reach (per minute) of a feed move, `None` for G0 (the path over all axes at their limits). On an
/// arc (`arc`) an axis's share of the path changes along it, so each axis limits the path velocity
/// and acceleration with its own limits. `None` when an axis's acceleration is not configured.
pub(super) fn seconds(deltas: &[AxisDelta], feed: Option<(f64, f64)>, arc: bool) -> Option<f64> {
    let length = match feed {
        Some((length, _)) => length,
        None => deltas
            .iter()
            .map(|delta| delta.delta * delta.delta)
            .sum::<f64>()
            .sqrt(),
    };
    if length == 0.0 {
        return Some(0.0);
    }
    // Per second.
    let mut velocity = feed.map_or(f64::INFINITY, |(_, feed)| feed / 60.0);
    let mut acceleration = f64::INFINITY;
    for delta in deltas {
        let share = if arc { 1.0 } else { length / delta.delta };
        velocity = velocity.min(delta.max_velocity / 60.0 * share);
        acceleration = acceleration.min(delta.max_acceleration? * share);
    }
    if !(velocity.is_finite() && acceleration.is_finite() && velocity > 0.0) {
        return None;
    }
    Some(if length >= velocity * velocity / acceleration {
        length / velocity + velocity / acceleration
    } else {
        2.0 * (length / acceleration).sqrt()
    })
}
