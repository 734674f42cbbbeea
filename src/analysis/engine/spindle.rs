//! What the machining time of a block needs beyond its geometry (reference §15.2, §2.4): the feed type
//! (group 15), the master spindle's speed `S` and its limit `LIMS`, whether the feed must be programmed
//! again after a change of feed type, and the dwell of a `G4` block. The engine follows these per
//! block; [`Timing`] is what a move carries of them.

use crate::analysis::engine::engine_state::Engine;
use crate::analysis::eval::{evaluate_value, EvalOptions};
use crate::config::AxisKind;
use crate::diagnostics::{Code, Diagnostic};
use crate::syntax::ast::ValueExpr;
use crate::syntax::ast::{AddressKind, AddressWord, Block, Extension, NamedAddress, Statement};
use crate::syntax::gcodes::GCode;

use crate::analysis::engine::timing::is_cutting_speed;
pub use crate::analysis::engine::timing::{speed_at_radius, Dwell, FeedType, SpindleState, Timing};

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
