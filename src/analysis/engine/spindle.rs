//! What the machining time of a block needs beyond its geometry (reference §15.2, §2.4): the feed type
//! (group 15), the master spindle's speed `S` and its limit `LIMS`, whether the feed must be programmed
//! again after a change of feed type, and the dwell of a `G4` block. The engine follows these per
//! block; [`Timing`] is what a move carries of them.

use super::Engine;
use crate::analysis::eval::{evaluate_value, EvalOptions};
use crate::config::AxisKind;
use crate::diagnostics::{Code, Diagnostic};
use crate::syntax::ast::ValueExpr;
use crate::syntax::ast::{AddressKind, AddressWord, Block, Extension, NamedAddress, Statement};
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
    fn kind(self) -> u8 {
        match self {
            FeedType::InverseTime => 0,
            FeedType::PerMinute => 1,
            FeedType::PerRevolution | FeedType::ConstantCuttingSpeed => 2,
        }
    }
}

/// Whether `S` is a cutting speed in m/min (G96, G961, G962) rather than a speed in rpm.
fn is_cutting_speed(code: Option<GCode>) -> bool {
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

impl Engine<'_> {
    /// Follows the spindle, the feed type and the dwell of the block just applied. `feed_type_before`
    /// is group 15 before the block; `feed_move` says whether the block moves at the programmed feed.
    pub(super) fn observe_timing(
        &mut self,
        line: &str,
        block: &Block,
        feed_type_before: Option<GCode>,
        feed_move: bool,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        let statements = block.interpreted_statements();
        let dwell = statements.iter().any(|statement| {
            matches!(statement, Statement::GCode { code, .. } if !code.is_modal() && code.is_dwell())
        });
        let mut feed_word = None;
        let mut speed_word = None;
        let mut limit_word = None;
        for statement in statements {
            let Statement::Address(word) = statement else {
                continue;
            };
            match word.kind {
                AddressKind::Feed if word.extension.is_none() => feed_word = Some(word),
                AddressKind::Spindle if is_master_spindle(word) => speed_word = Some(word),
                AddressKind::Named(NamedAddress::Other)
                    if line[word.name.start()..word.name.end()].eq_ignore_ascii_case("LIMS") =>
                {
                    limit_word = Some(word)
                }
                _ => {}
            }
        }
        let value = |word: &AddressWord| self.silent_value(line, block, word);
        if dwell {
            let seconds = match (feed_word, speed_word) {
                (Some(word), _) => value(word),
                (None, Some(word)) => value(word)
                    .zip(self.spindle_speed_at(
                        is_cutting_speed(self.state.groups[15]),
                        &self.state.positions,
                    ))
                    .filter(|(_, speed)| *speed > 0.0)
                    .map(|(revolutions, speed)| revolutions / speed * 60.0),
                (None, None) => None,
            };
            self.last_dwell = Some(Dwell {
                seconds: seconds.filter(|seconds| seconds.is_finite() && *seconds >= 0.0),
            });
            return;
        }
        let limit = limit_word.map(|word| value(word).filter(|limit| *limit > 0.0));
        let speed = speed_word.map(|word| value(word).filter(|speed| *speed >= 0.0));
        let feed_type = self.state.groups[15];
        let before = feed_type_before.and_then(FeedType::of);
        let after = feed_type.and_then(FeedType::of);
        // G97 without S keeps the speed G96 reached last (ONE19 p.99), at the block's start.
        let frozen = if is_cutting_speed(feed_type_before) && !is_cutting_speed(feed_type) {
            self.spindle_speed_at(true, &self.start_positions)
        } else {
            None
        };
        // A cutting speed under inch units is not followed.
        let metric = self.state.length_factor(self.config.metric) == Some(1.0);
        let spindle = &mut self.state.spindle;
        if let Some(limit) = limit {
            spindle.limit = limit;
        }
        match speed {
            Some(speed) if is_cutting_speed(feed_type) => {
                spindle.cutting_speed = speed.filter(|_| metric);
            }
            Some(speed) => spindle.speed = speed,
            None if is_cutting_speed(feed_type_before) && !is_cutting_speed(feed_type) => {
                spindle.speed = frozen;
            }
            None => {}
        }
        if feed_word.is_some() {
            spindle.feed_pending = false;
        } else if before.map(FeedType::kind) != after.map(FeedType::kind)
            && feed_type_before.is_some()
            && feed_type != feed_type_before
        {
            spindle.feed_pending = true;
            spindle.feed_pending_reported = false;
        }
        if feed_move && spindle.feed_pending && !spindle.feed_pending_reported {
            spindle.feed_pending_reported = true;
            let span = statements
                .iter()
                .map(Statement::span)
                .reduce(|whole, span| whole.to(span))
                .unwrap_or_default();
            diagnostics.push(Diagnostic::new(
                Code::FeedNotReprogrammed,
                span,
                "the feed type changed (G93/G94/G95) and no F has been programmed since: the control does not reuse the old F, so this move has no feed (alarm 10860)",
            ));
        }
    }

    /// The master spindle's speed in rpm at `positions`: `S` while it is a speed, else (`cutting`)
    /// the speed the cutting speed gives at the transverse axis's diameter.
    fn spindle_speed_at(&self, cutting: bool, positions: &[Option<f64>]) -> Option<f64> {
        let spindle = &self.state.spindle;
        if !cutting {
            return spindle.speed;
        }
        let index = self
            .config
            .axes
            .iter()
            .position(|axis| axis.kind == AxisKind::Transverse)?;
        let radius = (*positions.get(index)?)?;
        let limit = match (spindle.limit, self.config.timing.max_spindle_speed) {
            (Some(limit), Some(machine)) => Some(limit.min(machine)),
            (limit, machine) => limit.or(machine),
        };
        speed_at_radius(spindle.cutting_speed?, radius, limit)
    }

    /// The value of a word without reporting errors (the engine reports them where it reads the
    /// word for its own purposes).
    fn silent_value(&self, line: &str, block: &Block, word: &AddressWord) -> Option<f64> {
        match word.value.expr {
            ValueExpr::Missing => None,
            ValueExpr::Constant { value, .. } => Some(value),
            ValueExpr::Expr(id) => evaluate_value(
                block,
                line,
                id,
                &self.state.variables,
                &EvalOptions::default(),
            )
            .ok()
            .flatten()
            .and_then(|value| value.number()),
        }
        .filter(|value| value.is_finite())
    }

    /// What the move of the block just applied carries for its time.
    pub(super) fn timing(&self) -> Timing {
        let spindle = &self.state.spindle;
        let feed = self.state.feed.filter(|_| !spindle.feed_pending);
        let programmed_feed = feed.zip(self.state.feed_factor(self.config.metric));
        let speed_limit = match (spindle.limit, self.config.timing.max_spindle_speed) {
            (Some(limit), Some(machine)) => Some(limit.min(machine)),
            (limit, machine) => limit.or(machine),
        };
        Timing {
            feed_type: self.state.groups[15].and_then(FeedType::of),
            feed,
            programmed_feed: programmed_feed.map(|(feed, factor)| feed / factor),
            spindle_speed: spindle.speed,
            cutting_speed: spindle.cutting_speed,
            speed_limit,
            dwell: None,
        }
    }
}

/// `S` or `S1`: the master spindle (MD20090 default 1).
fn is_master_spindle(word: &AddressWord) -> bool {
    matches!(
        word.extension,
        None | Some(Extension::Number { value: 1, .. })
    )
}
