//! The corner stage: turns the executed moves of blocks that program a rounding or chamfer (`RND`,
//! `RNDM`, `CHF`, `CHR`; reference §14) into the path the tool takes. A move that asks for an element
//! at its corner is held until the next move in the plane arrives; then it is shortened to the first
//! tangent point, the element is handed out as a move of its own (same line, stack and pass as the
//! block that programs it, `inserted` set), and the next move starts at the second tangent point.
//! The programmed positions (the engine's state, the hover, G91) are not touched: only the path.
//! Moves of programs without these words pass straight through.

use super::corner_geometry::{self, Corner, Element, NoCorner};
use crate::analysis::engine::corner_requests::CornerElement;
use crate::analysis::engine::moves::ArcMove;
use crate::analysis::execution::outcome::ExecutedMove;
use crate::config::MachineConfig;
use crate::diagnostics::{Code, Diagnostic, LineDiagnostic, Span};
use std::borrow::Cow;
use std::collections::HashSet;
use std::sync::Arc;

/// The corner stage between the interpreter and whatever consumes its moves.
pub struct CornerStage<'c> {
    config: &'c MachineConfig,
    /// The analysed program's text, for the spans of findings (a finding covers its whole line).
    text: &'c str,
    /// The length of each line of `text`, worked out at the first finding.
    line_lengths: Option<Vec<usize>>,
    /// The move whose corner waits for the next move in the plane.
    held: Option<ExecutedMove>,
    /// Moves without motion in the plane since the held one (MD20200 bounds them).
    dummies: Vec<ExecutedMove>,
    findings: Vec<LineDiagnostic>,
    reported: HashSet<(usize, Code)>,
}

impl<'c> CornerStage<'c> {
    pub fn new(config: &'c MachineConfig, text: &'c str) -> CornerStage<'c> {
        CornerStage {
            config,
            text,
            line_lengths: None,
            held: None,
            dummies: Vec::new(),
            findings: Vec::new(),
            reported: HashSet::new(),
        }
    }

    /// Takes the next executed move and hands out what is complete.
    pub fn push(&mut self, next: ExecutedMove, out: &mut dyn FnMut(ExecutedMove)) {
        let Some(held) = self.held.take() else {
            // Only an element of the plane has a corner at its end; RNDM stays active over blocks
            // that move other axes.
            if next.movement.contour.is_some() && moves_in_plane(&next) {
                self.held = Some(next);
            } else {
                out(next);
            }
            return;
        };
        match self.relation(&held, &next) {
            Relation::InPlane => {
                let next = self.resolve(held, next, out);
                self.push(next, out);
            }
            Relation::Dummy
                if self.dummies.len() < self.config.contours.max_dummy_blocks as usize =>
            {
                self.held = Some(held);
                self.dummies.push(next);
            }
            Relation::Dummy => {
                self.not_inserted(
                    &held,
                    "more blocks without motion in the plane follow than MD20200 allows",
                );
                self.flush(held, out);
                self.push(next, out);
            }
            Relation::PlaneChanged => {
                self.not_inserted(&held, "the plane changes before the next element");
                self.flush(held, out);
                self.push(next, out);
            }
        }
    }

    /// Hands out what is still held at the end of the run and returns the stage's findings.
    pub fn finish(mut self, out: &mut dyn FnMut(ExecutedMove)) -> Vec<LineDiagnostic> {
        if let Some(held) = self.held.take() {
            self.not_inserted(&held, "the program ends before the next element");
            self.flush(held, out);
        }
        self.findings
    }

    fn flush(&mut self, held: ExecutedMove, out: &mut dyn FnMut(ExecutedMove)) {
        out(held);
        for dummy in self.dummies.drain(..) {
            out(dummy);
        }
    }

    fn relation(&self, held: &ExecutedMove, next: &ExecutedMove) -> Relation {
        if next.movement.plane != held.movement.plane {
            return Relation::PlaneChanged;
        }
        if next.movement.arc.is_some() {
            return Relation::InPlane;
        }
        let names = held.movement.plane;
        let start = names.and_then(|names| point(&next.movement.start, names));
        let end = names.and_then(|names| point(&next.movement.end, names));
        match start.zip(end) {
            Some((start, end)) if (start.0 - end.0).hypot(start.1 - end.1) < 1e-9 => {
                Relation::Dummy
            }
            _ => Relation::InPlane,
        }
    }

    /// Inserts the element between `held` and `next`; returns `next` as it now starts.
    fn resolve(
        &mut self,
        mut held: ExecutedMove,
        mut next: ExecutedMove,
        out: &mut dyn FnMut(ExecutedMove),
    ) -> ExecutedMove {
        let Some(request) = held.movement.contour.take() else {
            self.flush(held, out);
            return next;
        };
        let Some(names) = held.movement.plane else {
            self.flush(held, out);
            return next;
        };
        // The first line of a two-block definition by angles ends where the next block starts.
        if request.angle_open {
            if let Some(corner) = point(&next.movement.start, names) {
                set_point(&mut held.movement.end, names, corner);
                self.in_axis_order(&mut held.movement.end);
                held.movement
                    .uncertain
                    .retain(|name| !is_plane_axis(name, names));
                for dummy in &mut self.dummies {
                    set_point(&mut dummy.movement.start, names, corner);
                    set_point(&mut dummy.movement.end, names, corner);
                    dummy
                        .movement
                        .uncertain
                        .retain(|name| !is_plane_axis(name, names));
                }
            }
        }
        let Some(element) = request.element else {
            self.flush(held, out);
            return next;
        };
        let Some(element) = element else {
            // The value is not known: the tool does not reach the programmed corner, and where it
            // turns is unknown.
            mark_plane_uncertain(&mut held, names);
            mark_plane_uncertain(&mut next, names);
            self.flush(held, out);
            return next;
        };
        if self.diameter_plane(&held, names) {
            mark_plane_uncertain(&mut held, names);
            mark_plane_uncertain(&mut next, names);
            self.flush(held, out);
            return next;
        }
        let (Some(first), Some(second)) = (element_of(&held, names), element_of(&next, names))
        else {
            self.flush(held, out);
            return next;
        };
        if (first.end().0 - second.start().0).hypot(first.end().1 - second.start().1) > 1e-6 {
            // The path does not continue where the first element ends (a frame change between).
            self.flush(held, out);
            return next;
        }
        let result = match element {
            CornerElement::Rounding(radius) => corner_geometry::round(&first, &second, radius),
            CornerElement::ChamferLeg(leg) => corner_geometry::chamfer(&first, &second, leg, false),
            CornerElement::ChamferLength(length) => {
                corner_geometry::chamfer(&first, &second, length, true)
            }
        };
        // Extreme values can overflow the geometry: a point that is not finite never reaches a move.
        let finite = |(a, b): (f64, f64)| a.is_finite() && b.is_finite();
        let result = result.and_then(|corner| {
            let rounding_finite = corner.rounding.is_none_or(|rounding| {
                finite(rounding.centre) && rounding.radius.is_finite() && rounding.sweep.is_finite()
            });
            if finite(corner.first_end) && finite(corner.second_start) && rounding_finite {
                Ok(corner)
            } else {
                Err(NoCorner::DoesNotFit)
            }
        });
        let corner = match result {
            Ok(corner) => corner,
            Err(NoCorner::Tangential) => {
                self.flush(held, out);
                return next;
            }
            Err(NoCorner::Reversal) => {
                self.report(
                    &held,
                    Code::CornerReversal,
                    "the path reverses at this corner: no rounding or chamfer can be inserted"
                        .to_string(),
                );
                self.flush(held, out);
                return next;
            }
            Err(NoCorner::DoesNotFit) => {
                self.report(&held, Code::CornerElementReduced, "the rounding or chamfer does not fit the elements of this corner at all: it is left out".to_string());
                self.flush(held, out);
                return next;
            }
        };
        if corner.reduced {
            self.report(&held, Code::CornerElementReduced, "the rounding or chamfer is too large for the elements of this corner: it is reduced until it fits".to_string());
        }
        let is_chamfer = !matches!(element, CornerElement::Rounding(_));
        if is_chamfer && (held.movement.arc.is_some() || next.movement.arc.is_some()) {
            self.report(&held, Code::ChamferAtCircle, "a chamfer at a circle: its points are taken at the chord distance on the elements (the control's construction is not documented)".to_string());
        }
        let label = match element {
            CornerElement::Rounding(_) => "RND",
            CornerElement::ChamferLeg(_) => "CHR",
            CornerElement::ChamferLength(_) => "CHF",
        };
        let inserted = self.element_move(&held, &next, &request, &corner, names, label);
        shorten(&mut held, &first, names, None, Some(corner.first_end));
        shorten(&mut next, &second, names, Some(corner.second_start), None);
        let with_preceding = self.config.contours.element_with_preceding;
        out(held);
        let mut dummies = std::mem::take(&mut self.dummies);
        // The dummy blocks run at the end of the shortened element before the rounding (bit 0 = 0),
        // or at its start after it (bit 0 = 1) (reference §14.4, T112).
        let at = if with_preceding {
            corner.second_start
        } else {
            corner.first_end
        };
        for dummy in &mut dummies {
            set_point(&mut dummy.movement.start, names, at);
            set_point(&mut dummy.movement.end, names, at);
            dummy.movement.machine = None;
        }
        let mut inserted = inserted;
        if with_preceding {
            out(inserted);
            dummies.into_iter().for_each(&mut *out);
        } else {
            // The element starts where the last dummy block left the other axes.
            if let Some(last) = dummies.last() {
                inserted.movement.start = last.movement.end.clone();
                set_point(&mut inserted.movement.start, names, corner.first_end);
                inserted.movement.end = last.movement.end.clone();
                set_point(&mut inserted.movement.end, names, corner.second_start);
            }
            dummies.into_iter().for_each(&mut *out);
            out(inserted);
        }
        next
    }

    /// The inserted element as a move of the block that programs it.
    fn element_move(
        &self,
        held: &ExecutedMove,
        next: &ExecutedMove,
        request: &crate::analysis::engine::corner_requests::ContourRequest,
        corner: &Corner,
        names: (&'static str, &'static str),
        label: &'static str,
    ) -> ExecutedMove {
        let with_preceding = self.config.contours.element_with_preceding;
        let technology = if with_preceding { held } else { next };
        let rapid = technology.movement.motion == "G0";
        let feed = match request.feed {
            Some(feed) if !rapid => feed,
            _ => technology.movement.feed,
        };
        let mut start = held.movement.end.clone();
        set_point(&mut start, names, corner.first_end);
        let mut end = held.movement.end.clone();
        set_point(&mut end, names, corner.second_start);
        let motion: Cow<'static, str> = match (rapid, corner.rounding) {
            (true, _) => Cow::Borrowed("G0"),
            (false, Some(rounding)) if rounding.counter_clockwise => Cow::Borrowed("G3"),
            (false, Some(_)) => Cow::Borrowed("G2"),
            (false, None) => Cow::Borrowed("G1"),
        };
        let arc = corner.rounding.map(|rounding| ArcMove {
            centre: vec![
                (Arc::from(names.0), rounding.centre.0),
                (Arc::from(names.1), rounding.centre.1),
            ],
            radius: rounding.radius,
            clockwise: !rounding.counter_clockwise,
            machine_clockwise: None,
            sweep: rounding.sweep,
        });
        let mut movement = held.movement.clone();
        movement.motion = motion;
        movement.start = start;
        movement.end = end;
        movement.machine = None;
        movement.feed = feed;
        // The element's time follows the technology it takes (§14.5): that block's feed type and
        // spindle, with the element's own feed. Under inverse time (G93) a feed of the element is
        // not a time per block, so its time stays unknown.
        movement.timing = technology.movement.timing;
        movement.timing.dwell = None;
        movement.timing.feed = feed;
        movement.timing.programmed_feed = match movement.timing.feed_type {
            Some(crate::analysis::engine::timing::FeedType::InverseTime) => None,
            _ => feed,
        };
        movement.arc = arc;
        movement.contour = None;
        movement.inserted = Some(label);
        ExecutedMove {
            movement,
            path: held.path.clone(),
            stack: Arc::clone(&held.stack),
            pass: held.pass,
            conditional: held.conditional,
            assumed: held.assumed.clone(),
        }
    }

    /// Whether the plane has a transverse axis shown as a diameter: the shown values are not the
    /// plane's geometry, and the element is not computed.
    fn diameter_plane(&self, held: &ExecutedMove, names: (&str, &str)) -> bool {
        held.movement.transverse_as_diameter
            && [names.0, names.1].iter().any(|name| {
                self.config
                    .axis(name)
                    .is_some_and(|axis| axis.kind == crate::config::AxisKind::Transverse)
            })
    }

    /// Puts axis values in the order of the configuration, as the engine writes them.
    fn in_axis_order(&self, values: &mut [(Arc<str>, f64)]) {
        let axes = &self.config.axes;
        values.sort_by_key(|(name, _)| {
            axes.iter()
                .position(|axis| axis.name.as_str() == name.as_ref())
                .unwrap_or(usize::MAX)
        });
    }

    fn not_inserted(&mut self, held: &ExecutedMove, why: &str) {
        // RNDM rounds every corner it can; that some are not rounded is its normal working.
        let explicit = held
            .movement
            .contour
            .as_ref()
            .is_some_and(|request| request.element.is_some() && !request.modal);
        if explicit {
            self.report(
                held,
                Code::CornerNotInserted,
                format!("no rounding or chamfer is inserted here: {why}"),
            );
        }
    }

    fn report(&mut self, held: &ExecutedMove, code: Code, message: String) {
        let line = held.outer_line();
        if !self.reported.insert((line, code)) {
            return;
        }
        let message = match (&held.path, held.stack.is_empty()) {
            (Some(path), false) => {
                format!("in {path} (line {}): {message}", held.movement.line + 1)
            }
            _ => message,
        };
        let text = self.text;
        let lengths = self.line_lengths.get_or_insert_with(|| {
            crate::syntax::lines::line_ranges(text)
                .map(|(start, end)| end - start)
                .collect()
        });
        let length = lengths.get(line).copied().unwrap_or(0);
        let mut diagnostic = Diagnostic::new(code, Span::new(0, length), message);
        diagnostic.severity = self.config.severity_of(code);
        self.findings.push(LineDiagnostic { line, diagnostic });
    }
}

/// Whether a move leaves its point in the plane (an unknown point counts as moving).
fn moves_in_plane(executed: &ExecutedMove) -> bool {
    let movement = &executed.movement;
    if movement.arc.is_some() || movement.contour.as_ref().is_some_and(|c| c.angle_open) {
        return true;
    }
    let Some(names) = movement.plane else {
        return false;
    };
    match point(&movement.start, names).zip(point(&movement.end, names)) {
        Some((start, end)) => (start.0 - end.0).hypot(start.1 - end.1) >= 1e-9,
        None => true,
    }
}

/// The path of `moves` (a whole run of the program `text`) with the elements inserted, and the
/// stage's findings; `None` when no move asks for an element (the path is the moves).
pub fn path_of(
    moves: &[ExecutedMove],
    config: &MachineConfig,
    text: &str,
) -> Option<(Vec<ExecutedMove>, Vec<LineDiagnostic>)> {
    if !moves
        .iter()
        .any(|executed| executed.movement.contour.is_some())
    {
        return None;
    }
    let mut stage = CornerStage::new(config, text);
    let mut path = Vec::with_capacity(moves.len() + 16);
    for executed in moves {
        stage.push(executed.clone(), &mut |movement| path.push(movement));
    }
    let findings = stage.finish(&mut |movement| path.push(movement));
    Some((path, findings))
}

enum Relation {
    InPlane,
    Dummy,
    PlaneChanged,
}

fn is_plane_axis(name: &str, names: (&str, &str)) -> bool {
    name == names.0 || name == names.1
}

fn point(values: &[(Arc<str>, f64)], names: (&str, &str)) -> Option<(f64, f64)> {
    let find = |axis: &str| {
        values
            .iter()
            .find(|(name, _)| name.as_ref() == axis)
            .map(|(_, value)| *value)
    };
    find(names.0).zip(find(names.1))
}

fn set_point(
    values: &mut Vec<(Arc<str>, f64)>,
    names: (&'static str, &'static str),
    point: (f64, f64),
) {
    for (axis, value) in [(names.0, point.0), (names.1, point.1)] {
        match values.iter_mut().find(|(name, _)| name.as_ref() == axis) {
            Some(entry) => entry.1 = value,
            None => values.push((Arc::from(axis), value)),
        }
    }
}

fn mark_plane_uncertain(executed: &mut ExecutedMove, names: (&'static str, &'static str)) {
    for axis in [names.0, names.1] {
        if !executed
            .movement
            .uncertain
            .iter()
            .any(|name| name.as_ref() == axis)
        {
            executed.movement.uncertain.push(Arc::from(axis));
        }
    }
}

/// The move as an element of the plane, when its start and end (and circle) are known.
fn element_of(executed: &ExecutedMove, names: (&str, &str)) -> Option<Element> {
    let movement = &executed.movement;
    let start = point(&movement.start, names)?;
    let end = point(&movement.end, names)?;
    match &movement.arc {
        Some(arc) => Some(Element::Arc {
            start,
            end,
            centre: point(&arc.centre, names)?,
            radius: arc.radius,
            counter_clockwise: !arc.clockwise,
            sweep: arc.sweep,
        }),
        None => Some(Element::Line { start, end }),
    }
}

/// Moves the start or end of a move to a tangent point; an arc keeps its centre and radius.
fn shorten(
    executed: &mut ExecutedMove,
    element: &Element,
    names: (&'static str, &'static str),
    start: Option<(f64, f64)>,
    end: Option<(f64, f64)>,
) {
    let movement = &mut executed.movement;
    let new_start = start.unwrap_or(element.start());
    let new_end = end.unwrap_or(element.end());
    if let Some(start) = start {
        set_point(&mut movement.start, names, start);
    }
    if let Some(end) = end {
        set_point(&mut movement.end, names, end);
        movement.machine = None;
    }
    if let Some(arc) = movement.arc.as_mut() {
        if let Some(sweep) = corner_geometry::remaining_sweep(element, new_start, new_end) {
            arc.sweep = sweep;
        }
    }
}
