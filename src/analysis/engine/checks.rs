//! Likely mistakes of §9.2 that the modal state decides: inch/metric switched inside a contour (G41/G42
//! active), G70/G71 mixed with G700/G710 in a program that programs F, a plain `AP=` under G91, and a
//! polar move right after a pole or plane change that relies on a stored AP or RP.

use crate::analysis::engine::block_words::{statements_span, PolarWords};
use crate::analysis::engine::engine_state::Engine;
use crate::diagnostics::{Code, Diagnostic};
use crate::syntax::ast::{AddressKind, Statement};
use crate::syntax::gcodes::{known, GCode};

/// Whether a unit function programs inch (G70, G700) rather than metric (G71, G710).
fn is_inch(code: GCode) -> bool {
    matches!(code, known::G70 | known::G700)
}

impl Engine<'_> {
    /// At the first move after a rotating, scaling or mirroring frame change: A224 for the geometry
    /// axes the change affects that the move leaves out (reference §3.9 [?]).
    pub(super) fn check_axes_after_rotation(
        &mut self,
        statements: &[Statement],
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        let rotated = std::mem::take(&mut self.memory.rotated_slots);
        if rotated == [false; 3] {
            return;
        }
        let left_out: Vec<&str> = (0..self.config.axes.len())
            .filter(|&index| {
                // Only where the change gave the axis a workpiece value other than the one last
                // programmed does leaving it out move it unexpectedly.
                let shifted = match (self.state.positions[index], self.state.programmed[index]) {
                    (Some(current), Some(programmed)) => (current - programmed).abs() > 1e-9,
                    (None, None) => false,
                    _ => true,
                };
                self.slots.slot(index).is_some_and(|slot| rotated[slot])
                    && self.written[index] == 0
                    && self.state.touched[index]
                    && shifted
            })
            .map(|index| self.config.axes[index].name.as_str())
            .collect();
        if !left_out.is_empty() {
            let (verb, pronoun) = if left_out.len() == 1 {
                ("is", "it")
            } else {
                ("are", "them")
            };
            diagnostics.push(Diagnostic::new(
                Code::AxisLeftOutAfterRotation,
                statements_span(statements).unwrap_or_default(),
                format!("{} {verb} left out of the first move after a frame change that rotates, scales or mirrors: the last programmed value is not kept, the position in the new coordinates is, so this move may move {pronoun} too; program all geometry axes here", left_out.join(", ")),
            ));
        }
    }

    /// After the block's G functions: A221 when the unit system switches while G41/G42 is active, and
    /// A220 once a program has used G70/G71 and G700/G710 and programmed F.
    pub(super) fn check_units(
        &mut self,
        units_before: Option<GCode>,
        unit_word: Option<(GCode, crate::diagnostics::Span)>,
        feed_written: bool,
        statements: &[Statement],
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        if let Some((code, span)) = unit_word {
            let compensating = self.state.groups[7]
                .is_some_and(|active| matches!(active, known::G41 | known::G42));
            let switched = units_before.is_some_and(|before| is_inch(before) != is_inch(code));
            if compensating && switched {
                diagnostics.push(Diagnostic::new(
                    Code::UnitsChangeInContour,
                    span,
                    format!("{} switches between inch and metric while tool radius compensation ({}) is active, inside a contour: switch units before G41/G42 or after G40", code.name(), self.state.active_name(7)),
                ));
            }
            let kind = if code.name().len() == 4 { 2 } else { 1 };
            self.memory.unit_kinds_used |= kind;
        }
        self.memory.feed_programmed |= feed_written;
        if self.memory.unit_kinds_used == 3
            && self.memory.feed_programmed
            && !self.memory.unit_mix_reported
        {
            self.memory.unit_mix_reported = true;
            let feed_word = statements.iter().find_map(|statement| match statement {
                Statement::Address(word) if word.kind == AddressKind::Feed => Some(word.span),
                _ => None,
            });
            let span = unit_word
                .map(|(_, span)| span)
                .or(feed_word)
                .unwrap_or_default();
            diagnostics.push(Diagnostic::new(
                Code::InchFeedMixed,
                span,
                "this program uses both G70/G71 and G700/G710 and programs F: only G700/G710 read F in the programmed unit, so a feed may be off by a factor of 25.4",
            ));
        }
    }

    /// Before a polar move: A217 for a plain `AP=` under G91 (absolute, reference §3.4) and A218 for
    /// the first polar move after a pole or plane change without AP or RP (reference §5.2).
    pub(super) fn check_polar_words(
        &mut self,
        polar: &PolarWords,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        if let Some(span) = polar.plain_angle_span {
            if self.state.is_incremental() == Some(true) {
                diagnostics.push(Diagnostic::new(
                    Code::PolarAngleUnderG91,
                    span,
                    "AP is an absolute angle also under G91; write `AP=IC(..)` for an angle relative to the last one",
                ));
            }
        }
        let pole_changed = std::mem::take(&mut self.memory.pole_changed);
        if pole_changed && matches!(polar.angle, Some((_, true))) && polar.radius.is_some() {
            // `AP=IC(..)` adds to the stored angle, and after a pole or plane change no angle is
            // stored that belongs to the new pole (reference §5.2).
            diagnostics.push(Diagnostic::new(
                Code::PolarValueAfterPoleChange,
                polar.span.unwrap_or_default(),
                "`AP=IC(..)` adds to the stored polar angle, but after a pole or plane change no angle for the new pole is stored: write the first AP after the change absolute",
            ));
        } else if pole_changed && (polar.angle.is_none() || polar.radius.is_none()) {
            let missing = if polar.angle.is_none() { "AP" } else { "RP" };
            diagnostics.push(Diagnostic::new(
                Code::PolarValueAfterPoleChange,
                polar.span.unwrap_or_default(),
                format!("after a pole or plane change AP and RP must be written again; {missing} is missing, and what the control takes for it then is not documented, so the end point is unknown"),
            ));
        }
    }

    /// G1/G2/G3 need a feed (alarm 10860); reported once, at the first feed move without one.
    pub(super) fn check_feed(
        &mut self,
        motion: &str,
        statements: &[Statement],
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        let needs_feed = matches!(motion, "G1" | "G2" | "G3" | "CIP" | "CT");
        if !needs_feed || self.state.feed.is_some() || self.missing_feed_reported {
            return;
        }
        let span = statements
            .iter()
            .find(|statement| matches!(statement, Statement::Address(word) if word.kind == AddressKind::Axis))
            .map(Statement::span)
            .unwrap_or_default();
        self.missing_feed_reported = true;
        diagnostics.push(Diagnostic::new(
            Code::FeedMissing,
            span,
            format!("{motion} moves at the programmed feed, but no F has been programmed yet (alarm 10860)"),
        ));
    }
}
