//! What the machining time of a move depends on besides its geometry, as plain values: the feed type,
//! the master spindle's state, a dwell and the timing a move carries (`engine/spindle.rs` follows
//! them block by block).

use crate::syntax::gcodes::GCode;

/// How the feed F reads (group 15), as far as the time depends on it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FeedType {
    /// G93: F is the inverse of the block's time in minutes.
    InverseTime,
    /// G94, G961, G971, G942: F in mm/min (degrees/min when only rotary axes move).
    PerMinute,
    /// G95, G97, G952, G973: F in mm per revolution of the master spindle at `S` rpm.
    PerRevolution,
    /// G96: F in mm per revolution, the speed following the diameter (`S` in m/min, up to `LIMS`).
    ConstantCuttingSpeed,
}

impl FeedType {
    /// The feed type of a group-15 function; `None` for those whose feed the time model does not
    /// read (G931, G962, G972).
    pub fn of(code: GCode) -> Option<FeedType> {
        if code.group() != 15 {
            return None;
        }
        match code.index_in_group() {
            1 => Some(FeedType::InverseTime),
            2 | 7 | 8 | 9 => Some(FeedType::PerMinute),
            3 | 5 | 10 | 13 => Some(FeedType::PerRevolution),
            4 => Some(FeedType::ConstantCuttingSpeed),
            _ => None,
        }
    }

    /// The kind of feed value (inverse time, per minute, per revolution): after a change of kind the
    /// feed must be programmed again (ONE19 p.108).
    pub(super) fn kind(self) -> u8 {
        match self {
            FeedType::InverseTime => 0,
            FeedType::PerMinute => 1,
            FeedType::PerRevolution | FeedType::ConstantCuttingSpeed => 2,
        }
    }
}

/// Whether `S` is a cutting speed in m/min (G96, G961, G962) rather than a speed in rpm.
pub(super) fn is_cutting_speed(code: Option<GCode>) -> bool {
    code.is_some_and(|code| code.group() == 15 && matches!(code.index_in_group(), 4 | 7 | 11))
}

/// The master spindle as the time model needs it, part of the modal state.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SpindleState {
    /// The speed in rpm while `S` is a speed; `None` when unknown.
    pub speed: Option<f64>,
    /// The cutting speed in m/min while `S` is one (G96); `None` when unknown.
    pub cutting_speed: Option<f64>,
    /// The speed limit `LIMS` in rpm, `None` when not programmed or unknown.
    pub limit: Option<f64>,
    /// The feed type changed its kind and no F has been programmed since: the feed is unknown.
    pub feed_pending: bool,
    /// The missing feed after the last change of feed type has been reported.
    pub feed_pending_reported: bool,
}

impl SpindleState {
    /// What a called program the analysis cannot see may change.
    pub fn forget(&mut self) {
        self.speed = None;
        self.cutting_speed = None;
        self.limit = None;
        self.feed_pending = false;
    }

    /// Forgets what differs from `other`, where two ways through the program meet.
    pub fn join(&mut self, other: &SpindleState) {
        let keep = |value: &mut Option<f64>, other: Option<f64>| {
            if *value != other {
                *value = None;
            }
        };
        keep(&mut self.speed, other.speed);
        keep(&mut self.cutting_speed, other.cutting_speed);
        keep(&mut self.limit, other.limit);
        self.feed_pending |= other.feed_pending;
        self.feed_pending_reported |= other.feed_pending_reported;
    }
}

/// A dwell block `G4 F..` (seconds) or `G4 S..` (revolutions of the master spindle).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dwell {
    /// The dwell in seconds; `None` when the value or the spindle speed is unknown.
    pub seconds: Option<f64>,
}

/// What a move carries for its time, taken after its block.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Timing {
    /// The feed type; `None` when unknown or not modelled.
    pub feed_type: Option<FeedType>,
    /// The feed in the basic unit system (mm/min, mm/rev); `None` when unknown or when it must be
    /// programmed again after a change of feed type.
    pub feed: Option<f64>,
    /// The feed as written (1/min under G93, degrees/min for rotary axes alone); `None` as `feed`.
    pub programmed_feed: Option<f64>,
    /// The master spindle's speed in rpm (G95, G97); `None` when unknown.
    pub spindle_speed: Option<f64>,
    /// The cutting speed in m/min under G96; `None` when unknown.
    pub cutting_speed: Option<f64>,
    /// The highest spindle speed in rpm: `LIMS`, else the configured `max_spindle_speed`.
    pub speed_limit: Option<f64>,
    /// Set on the move of a dwell block: it moves no axis (see [`Engine::describe_last_dwell`]).
    pub dwell: Option<Dwell>,
}

/// The spindle speed in rpm that a cutting speed `cutting_speed` (m/min) gives at `radius` (mm),
/// limited to `limit`; `None` when the limit is unknown.
pub fn speed_at_radius(cutting_speed: f64, radius: f64, limit: Option<f64>) -> Option<f64> {
    let limit = limit?;
    let diameter = 2.0 * radius.abs();
    let free = 1000.0 * cutting_speed / (std::f64::consts::PI * diameter);
    Some(if free.is_finite() {
        free.min(limit)
    } else {
        limit
    })
}
