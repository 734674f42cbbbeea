//! Applies one parsed block to the modal state, the way the control's interpreter does, and describes
//! the resulting move. What this engine does not model (spatial rotations, basic frames, calls of
//! subprograms, jumps) turns the affected values into "unknown" or "uncertain": it never shows a
//! number it cannot stand behind.

use crate::analysis::axis_lookup::AxisLookup;
use crate::analysis::eval::{evaluate_value, EvalOptions, Value, Variables};
use crate::analysis::four_decimals::FourDecimals;
use crate::analysis::state::ModalState;
use crate::config::{AxisKind, MachineConfig};
use crate::diagnostics::{Code, Diagnostic};
use crate::syntax::ast::*;
use crate::syntax::gcodes::GCode;
use std::borrow::Cow;
use std::sync::Arc;

mod assignments;
mod checks;
mod circle_checks;
mod circles;
mod contours;
mod frame_variables;
mod indirect_axes;
mod join;
mod machine_checks;
mod macros;
pub use contours::{ContourRequest, CornerElement, OpenAngle};
pub mod spindle;
pub(crate) use macros::macro_definition;

/// A block that moves axes.
#[derive(Debug, Clone, PartialEq)]
pub struct Move {
    /// 0-based line of the block.
    pub line: usize,
    /// The block number as written (`N20`), if any.
    pub block_number: Option<String>,
    /// The motion G function in effect (`G0`, `G1`, `G2`, ...).
    pub motion: Cow<'static, str>,
    /// Axis values before the block, as the program shows them (a diameter under DIAMON); unknown
    /// axes are left out.
    pub start: Vec<(Arc<str>, f64)>,
    /// Axis values after the block, as the program shows them; unknown axes are left out.
    pub end: Vec<(Arc<str>, f64)>,
    /// Machine coordinates (radius on transverse axes) when they are known, i.e. when no offset or
    /// frame whose value is unknown is active.
    pub machine: Option<Vec<(Arc<str>, f64)>>,
    /// The modal feed in the basic unit system, if known.
    pub feed: Option<f64>,
    /// Axes whose value is unknown or depends on the program's flow (jumps, loops).
    pub uncertain: Vec<Arc<str>>,
    /// The circle of a G2/G3 block, when start, end and centre are known.
    pub arc: Option<ArcMove>,
    /// The working plane of the block: the names of its first and second axis (G17: X, Y; G18: Z, X;
    /// G19: Y, Z), `None` when it is unknown.
    pub plane: Option<(&'static str, &'static str)>,
    /// Whether the values of transverse axes in `start`, `end` and `arc` are diameters.
    pub transverse_as_diameter: bool,
    /// The standard cycle whose built-in model made the move (`"CYCLE81"`, `"HOLES1"`), `None` for
    /// a move the program's own block makes.
    pub cycle: Option<Arc<str>>,
    /// What the block asks of the corner at its end (RND, CHF, CHR, RNDM, FRC, FRCM; reference §14),
    /// for the corner stage of the simulation; `None` for most moves.
    pub contour: Option<Box<ContourRequest>>,
    /// For a chamfer or rounding the corner stage inserted: `"RND"`, `"CHF"` or `"CHR"`.
    pub inserted: Option<&'static str>,
    /// What the machining time of the move depends on besides its geometry (`engine/spindle.rs`).
    pub timing: spindle::Timing,
}

/// The circle a G2/G3 block follows.
#[derive(Debug, Clone, PartialEq)]
pub struct ArcMove {
    /// The centre in the two plane axes, as the program shows them (like `Move::end`).
    pub centre: Vec<(Arc<str>, f64)>,
    /// The radius in the basic unit system.
    pub radius: f64,
    pub clockwise: bool,
    /// The direction the machine turns, after the programmable frame: a mirror in the plane turns a
    /// clockwise arc counter-clockwise (reference §7.2, T49). `None` when the frame is unknown.
    pub machine_clockwise: Option<bool>,
    /// The swept angle in degrees.
    pub sweep: f64,
}

/// The polar words of one block: AP (value, written as `=IC(..)`) and RP (basic unit system).
#[derive(Default)]
struct PolarWords {
    angle: Option<(Option<f64>, bool)>,
    radius: Option<Option<f64>>,
    span: Option<crate::diagnostics::Span>,
    /// The span of an AP written without `=IC`/`=AC`.
    plain_angle_span: Option<crate::diagnostics::Span>,
}

/// The circle words of one block: I, J, K (value, absolute) in the basic unit system, and CR.
#[derive(Default)]
struct CircleWords {
    centre: [Option<(f64, bool)>; 3],
    /// A centre word whose value is unknown: the circle cannot be checked.
    centre_unknown: bool,
    /// Whether CR was written, and its value when known.
    radius_written: bool,
    radius: Option<f64>,
    opening_angle: bool,
    /// The value of AR, when known.
    opening_angle_value: Option<f64>,
    /// I1, J1, K1 of CIP: written, with (value, absolute) when known.
    intermediate: [Option<Option<(f64, bool)>>; 3],
    /// TURN: its value when known, and its span.
    turns: Option<(Option<f64>, crate::diagnostics::Span)>,
    /// The span of the block's words, for findings about the circle as a whole.
    span: Option<crate::diagnostics::Span>,
}

/// The span from the first to the last of the statements, `None` when there are none.
fn statements_span(statements: &[Statement]) -> Option<crate::diagnostics::Span> {
    statements
        .iter()
        .map(Statement::span)
        .reduce(|whole, span| whole.to(span))
}

/// Interprets blocks one after the other.
pub struct Engine<'a> {
    config: &'a MachineConfig,
    pub state: ModalState,
    /// Set once a jump or control structure has been passed: evaluation in program order may no longer
    /// match the control's path through the program.
    flow_uncertain: bool,
    /// Whether a feed move without F has already been reported (alarm 10860 is reported once).
    missing_feed_reported: bool,
    /// The configured axis names, shared by every move instead of copied into each.
    axis_names: Vec<Arc<str>>,
    /// The positions before the current block, kept in one buffer for all blocks.
    start_positions: Vec<Option<f64>>,
    /// The circle of the block last applied, for its move.
    last_arc: Option<crate::analysis::circle::Circle>,
    /// What the block last applied asks of its corner (reference §14), for its move.
    last_contour: Option<Box<ContourRequest>>,
    /// The geometry slot (X, Y, Z) of each configured axis, for frames.
    slots: crate::analysis::machine::AxisSlots,
    /// Per axis, how the current block wrote it: 0 not, 1 in workpiece coordinates, 2 as a machine
    /// position (G53/G153/SUPA). One buffer for all blocks.
    written: Vec<u8>,
    /// The settable frame whose stored data the program wrote while it was active, until it is
    /// selected again (the data are not active yet, reference §7.4).
    stale_offset_data: Option<u8>,
    /// The direction of the path at the end of the last move, in the plane (by index) it moved in,
    /// for CT; `None` when unknown.
    tangent: Option<(usize, (f64, f64))>,
    /// How many macro expansions the current block is inside of.
    expansion_depth: u8,
    /// What the engine remembers about the program beyond the modal state.
    memory: ProgramMemory,
    /// The configuration indexes of the first and second axis of G17, G18 and G19.
    plane_axis_cache: [(Option<usize>, Option<usize>); 3],
    /// The axis of each axis word, by its letter for the common words.
    axes: AxisLookup,
    /// Set by the interpreter, which follows labels, jumps and control structures itself: they do not
    /// make values uncertain then.
    executing: bool,
    /// Set by the interpreter for one block whose call it runs itself (the callee was found): the call
    /// then forgets nothing, since the callee's own blocks say what changes.
    call_followed: bool,
    /// The dwell of the block last applied, if it was a `G4` block.
    last_dwell: Option<spindle::Dwell>,
}

/// What the engine remembers about the program beyond the modal state: its macros and what the
/// findings of §9.2 need to know about earlier blocks.
#[derive(Debug, Clone, Default, PartialEq)]
struct ProgramMemory {
    /// Macros defined so far with `DEFINE name AS body`: upper-case name and body text.
    macros: Vec<(String, String)>,
    /// A pole or plane change since the last polar move: AP and RP must be written again.
    pole_changed: bool,
    /// Which unit functions the program has programmed: 1 for G70/G71, 2 for G700/G710.
    unit_kinds_used: u8,
    feed_programmed: bool,
    unit_mix_reported: bool,
    /// The geometry slots (X, Y, Z) whose mapping a rotating, scaling or mirroring frame change has
    /// altered since the last move.
    rotated_slots: [bool; 3],
    /// Whether diameter programming or G96 without a transverse axis has been reported (once).
    transverse_reported: bool,
}

/// What an [`Engine`] carries from one block to the next, detached from the configuration: a
/// checkpoint from which the analysis of a document is replayed after an edit or for a hover. Two
/// equal snapshots make every later block resolve the same way.
#[derive(Debug, Clone, PartialEq)]
pub struct EngineSnapshot {
    state: ModalState,
    flow_uncertain: bool,
    missing_feed_reported: bool,
    stale_offset_data: Option<u8>,
    tangent: Option<(usize, (f64, f64))>,
    memory: ProgramMemory,
}

/// How far an edit moved the positions of every axis, per kind of position (basic unit system): the
/// workpiece set-points, the last programmed values and the machine set-points.
#[derive(Debug, Clone, PartialEq)]
pub struct PositionShift {
    pub positions: Vec<f64>,
    pub programmed: Vec<f64>,
    pub machine: Vec<f64>,
}

impl EngineSnapshot {
    /// Moves every known position by `shift`.
    pub fn shift_positions(&mut self, shift: &PositionShift) {
        add_to_known(&mut self.state.positions, &shift.positions);
        add_to_known(&mut self.state.programmed, &shift.programmed);
        add_to_known(&mut self.state.machine, &shift.machine);
    }
}

fn add_to_known(values: &mut [Option<f64>], deltas: &[f64]) {
    for (value, delta) in values.iter_mut().zip(deltas) {
        if let Some(value) = value {
            *value += delta;
        }
    }
}

/// `now - then` per axis where both are known, 0 where both are unknown; `None` when an axis is known
/// in one and not the other.
fn difference(now: &[Option<f64>], then: &[Option<f64>]) -> Option<Vec<f64>> {
    now.iter()
        .zip(then)
        .map(|pair| match pair {
            (Some(now), Some(then)) => Some(now - then),
            (None, None) => Some(0.0),
            _ => None,
        })
        .collect()
}

/// The non-modal G functions of one block that change what its axis words mean.
#[derive(Default)]
pub(super) struct BlockFunctions {
    frame_or_pole: Option<GCode>,
    dwell: bool,
    machine_coordinates: bool,
    reference_point: bool,
}

impl<'a> Engine<'a> {
    pub fn new(config: &'a MachineConfig) -> Engine<'a> {
        Engine {
            config,
            state: ModalState::reset(config),
            flow_uncertain: false,
            missing_feed_reported: false,
            axis_names: config
                .axes
                .iter()
                .map(|axis| Arc::from(axis.name.as_str()))
                .collect(),
            start_positions: Vec::with_capacity(config.axes.len()),
            last_arc: None,
            last_contour: None,
            slots: crate::analysis::machine::AxisSlots::new(config),
            written: vec![0; config.axes.len()],
            stale_offset_data: None,
            tangent: None,
            expansion_depth: 0,
            memory: ProgramMemory::default(),
            plane_axis_cache: crate::analysis::state::PLANE_AXES.map(|(first, second)| {
                let index = |name: &str| {
                    config
                        .axes
                        .iter()
                        .position(|axis| axis.name.eq_ignore_ascii_case(name))
                };
                (index(first), index(second))
            }),
            axes: AxisLookup::new(config),
            executing: false,
            call_followed: false,
            last_dwell: None,
        }
    }

    /// The state between blocks, to continue from later with [`Engine::from_snapshot`].
    pub fn snapshot(&self) -> EngineSnapshot {
        EngineSnapshot {
            state: self.state.clone(),
            flow_uncertain: self.flow_uncertain,
            missing_feed_reported: self.missing_feed_reported,
            stale_offset_data: self.stale_offset_data,
            tangent: self.tangent,
            memory: self.memory.clone(),
        }
    }

    /// Whether the engine is in the state `snapshot` holds: then every later block resolves as it did
    /// from there.
    pub fn matches(&self, snapshot: &EngineSnapshot) -> bool {
        self.flow_uncertain == snapshot.flow_uncertain
            && self.missing_feed_reported == snapshot.missing_feed_reported
            && self.stale_offset_data == snapshot.stale_offset_data
            && self.tangent == snapshot.tangent
            && self.memory == snapshot.memory
            && self.state == snapshot.state
    }

    /// When the engine's state differs from `snapshot` only by known positions (the same axes known in
    /// both), the difference of each kind of position per axis (engine minus snapshot, zero where
    /// equal); `None` otherwise.
    pub fn position_shift_from(&self, snapshot: &EngineSnapshot) -> Option<PositionShift> {
        if self.flow_uncertain != snapshot.flow_uncertain
            || self.missing_feed_reported != snapshot.missing_feed_reported
            || self.stale_offset_data != snapshot.stale_offset_data
            // The tangent is a direction: a shift of positions leaves it as it is.
            || self.tangent != snapshot.tangent
            || self.memory != snapshot.memory
        {
            return None;
        }
        let shift = PositionShift {
            positions: difference(&self.state.positions, &snapshot.state.positions)?,
            programmed: difference(&self.state.programmed, &snapshot.state.programmed)?,
            machine: difference(&self.state.machine, &snapshot.state.machine)?,
        };
        let mut probe = snapshot.state.clone();
        probe.positions.clone_from(&self.state.positions);
        probe.programmed.clone_from(&self.state.programmed);
        probe.machine.clone_from(&self.state.machine);
        (probe == self.state).then_some(shift)
    }

    /// An engine that continues where `snapshot` was taken, on the same configuration.
    pub fn from_snapshot(config: &'a MachineConfig, snapshot: EngineSnapshot) -> Engine<'a> {
        // Every field is named (no `..`), so that a field added to the engine must be decided here:
        // carried in the snapshot, or rebuilt from the configuration.
        let Engine {
            config,
            state: _,
            flow_uncertain: _,
            missing_feed_reported: _,
            axis_names,
            start_positions,
            last_arc,
            last_contour,
            slots,
            written,
            stale_offset_data: _,
            tangent: _,
            expansion_depth,
            memory: _,
            plane_axis_cache,
            axes,
            executing,
            call_followed,
            last_dwell,
        } = Engine::new(config);
        Engine {
            config,
            state: snapshot.state,
            flow_uncertain: snapshot.flow_uncertain,
            missing_feed_reported: snapshot.missing_feed_reported,
            axis_names,
            start_positions,
            last_arc,
            last_contour,
            slots,
            written,
            stale_offset_data: snapshot.stale_offset_data,
            tangent: snapshot.tangent,
            expansion_depth,
            memory: snapshot.memory,
            plane_axis_cache,
            axes,
            executing,
            call_followed,
            last_dwell,
        }
    }

    /// Makes the engine a part of the interpreter: labels, jumps and control structures no longer make
    /// values uncertain, because the interpreter runs the blocks in the order the control runs them.
    pub fn set_executing(&mut self, executing: bool) {
        self.executing = executing;
    }

    /// Tells the engine that the interpreter runs the call of the next block itself, so that the call
    /// forgets nothing; it applies to one [`Engine::step`] only.
    pub fn follow_call_of_next_block(&mut self) {
        self.call_followed = true;
    }

    /// A subprogram analysed on its own starts from the reset state as an assumption: the G functions
    /// keep their reset values, while what no reset determines (the settable offset, the frames, the
    /// poles, positions) stays unknown.
    pub fn assume_reset_entry(&mut self) {
        self.missing_feed_reported = true;
        self.state.groups[8] = None;
        self.state.poles = [crate::analysis::state::Pole::Unknown; 3];
        self.state.frame = None;
        self.state.offset.iter_mut().for_each(|value| *value = None);
        self.state.settable_data.forget_all();
    }

    /// Per configured axis, how the block last applied wrote it: 0 not, 1 in workpiece coordinates,
    /// 2 as a machine position.
    pub fn written_axes(&self) -> &[u8] {
        &self.written
    }

    /// Forgets what a call of a program the analysis cannot see may change: positions, variables,
    /// frames and the settable offsets' data.
    pub fn forget_after_unknown_call(&mut self) {
        self.forget_what_a_call_may_change(true, true);
    }

    /// Forgets what a called program may change; the settable frames' data only when
    /// `frame_data_changed` (a call, a kinematic change), not after a tool change.
    fn forget_what_a_call_may_change(&mut self, frame_data_changed: bool, locals: bool) {
        // The callee may have programmed a feed, so a later feed move without F is not reported.
        self.missing_feed_reported = true;
        self.state.spindle.forget();
        self.state.forget_positions();
        if locals {
            self.state.variables.forget_all();
        } else {
            self.state.variables.forget_global();
        }
        self.state.frame = None;
        self.tangent = None;
        // RNDM and FRCM are kept: a program the analysis cannot see is assumed not to change them
        // (a tool change cycle does not).
        self.state.open_angle = None;
        // The callee may select another settable offset; it is read again when the program
        // selects one.
        self.state.offset.iter_mut().for_each(|value| *value = None);
        if frame_data_changed {
            self.state.settable_data.forget_all();
        }
    }

    /// From here on the values may not follow the control's path through the program: what the
    /// interpreter could not run is read in program order.
    pub fn mark_flow_uncertain(&mut self) {
        self.flow_uncertain = true;
    }

    /// The return from a subprogram with `SAVE` (reference §8.3): the modal G functions and the
    /// programmable frame active at the call are active again; the axes keep their machine
    /// set-points, expressed in the restored frame.
    pub fn restore_saved(
        &mut self,
        groups: &[Option<GCode>; crate::analysis::state::GROUP_COUNT],
        frame: Option<crate::analysis::frame::Frame>,
    ) {
        self.state.groups = *groups;
        let frame_before = self.state.frame;
        if frame_before != frame {
            self.state.frame = frame;
            crate::analysis::machine::reexpress(
                &mut self.state,
                &self.slots,
                crate::analysis::machine::Replaced::Frame(frame_before),
            );
        }
    }

    /// How this engine finds the configured axis of an axis word.
    pub fn axis_lookup(&self) -> &AxisLookup {
        &self.axes
    }

    /// Whether a label, jump or control structure has been passed, so that values may not follow the
    /// control's path through the program.
    pub fn flow_uncertain(&self) -> bool {
        self.flow_uncertain
    }

    /// The state comes from a caller the engine cannot see: a feed may be active, so a feed move without
    /// F is not reported.
    pub fn assume_inherited_state(&mut self) {
        self.missing_feed_reported = true;
        self.state.forget_inherited_groups();
    }

    /// Applies `block` (the parsed form of `line`, line number `line_index`) and returns its move, if
    /// it moves axes. Semantic findings go to `diagnostics`.
    pub fn apply(
        &mut self,
        line_index: usize,
        line: &str,
        block: &Block,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> Option<Move> {
        self.step(line, block, diagnostics)
            .then(|| self.describe_last_move(line_index, line, block))
    }

    /// Applies `block` like [`Engine::apply`] but only says whether it moved axes: building the move is
    /// left to [`Engine::describe_last_move`], so that callers that need only diagnostics pay nothing
    /// for it.
    pub fn step(&mut self, line: &str, block: &Block, diagnostics: &mut Vec<Diagnostic>) -> bool {
        let moved = self.step_block(line, block, diagnostics);
        self.forget_non_finite();
        moved
    }

    /// Values that overflowed (`X1EX308` twice under G91, a frame scaled beyond the range of a double)
    /// are unknown, never infinity or NaN: a number shown must be one the control could reach.
    fn forget_non_finite(&mut self) {
        let finite = |value: &Option<f64>| value.filter(|value| value.is_finite());
        let state = &mut self.state;
        for values in [
            &mut state.positions,
            &mut state.programmed,
            &mut state.machine,
            &mut state.offset,
        ] {
            // Written only where a value is not finite: almost never, and the loop runs for every
            // axis after every block.
            for value in values.iter_mut() {
                if value.is_some_and(|value| !value.is_finite()) {
                    *value = None;
                }
            }
        }
        if state
            .fine_translation
            .is_some_and(|translation| !translation.iter().all(|value| value.is_finite()))
        {
            state.fine_translation = None;
        }
        self.state.feed = finite(&self.state.feed);
        self.state.polar_angle = finite(&self.state.polar_angle);
        self.state.polar_radius = finite(&self.state.polar_radius);
        for pole in &mut self.state.poles {
            if let crate::analysis::state::Pole::At(first, second) = *pole {
                if !(first.is_finite() && second.is_finite()) {
                    *pole = crate::analysis::state::Pole::Unknown;
                }
            }
        }
        if let Some(frame) = self.state.frame {
            let numbers = frame.matrix.iter().flatten().chain(&frame.translation);
            if !numbers.into_iter().all(|value| value.is_finite()) {
                self.state.frame = None;
            }
        }
        if let Some(circle) = self.last_arc {
            let numbers = [
                circle.centre.0,
                circle.centre.1,
                circle.radius,
                circle.sweep,
            ];
            if !numbers.iter().all(|value| value.is_finite()) {
                self.last_arc = None;
            }
        }
    }

    fn step_block(&mut self, line: &str, block: &Block, diagnostics: &mut Vec<Diagnostic>) -> bool {
        self.last_arc = None;
        self.last_contour = None;
        self.last_dwell = None;
        let call_followed = std::mem::take(&mut self.call_followed);
        if block.is_header {
            return false;
        }
        self.record_macro_definitions(line, block);
        if let Some((expanded, used_at)) = self.expand_macro(line, block) {
            return self.step_expanded(&expanded, used_at, diagnostics);
        }
        let statements = block.interpreted_statements();
        // A label may be the target of a backward jump and a structure keyword opens a loop or branch:
        // from here on the control may run blocks again or skip them, so values assigned from here on
        // (this block included) are not followed in program order.
        if !self.executing
            && (block.label.is_some()
                || statements.iter().any(|statement| {
                    matches!(
                        statement,
                        Statement::Jump { .. } | Statement::Structure { .. }
                    )
                }))
        {
            self.flow_uncertain = true;
        }
        let mut functions = BlockFunctions::default();
        let mut forget_for_frames = false;
        let mut offset_selected = false;
        let units_before = self.state.groups[13];
        let mut unit_word = None;
        let feed_type_before = self.state.groups[15];
        self.written.iter_mut().for_each(|kind| *kind = 0);
        for statement in statements {
            if let Statement::GCode { code, span } = statement {
                if code.is_modal() {
                    self.state.set_modal(*code);
                    if code.group() == 13 {
                        unit_word = Some((*code, *span));
                    }
                    // Selecting a settable offset activates its stored data, also when the same
                    // function is programmed again (reference §7.4).
                    offset_selected |= code.group() == 8;
                    // PAROT, TOROT and TOFRAME turn the coordinate system with the table or the tool:
                    // positions are unknown afterwards (reference §7.5).
                    if matches!(code.group(), 52 | 53) && !code.name().ends_with("OF") {
                        forget_for_frames = true;
                    }
                } else {
                    match code.group() {
                        3 => functions.frame_or_pole = Some(*code),
                        2 if code.is_dwell() => functions.dwell = true,
                        2 => functions.reference_point = true,
                        9 => functions.machine_coordinates = true,
                        _ => {}
                    }
                }
            }
        }
        if offset_selected {
            self.stale_offset_data = None;
            self.change_offset(self.state.selected_offset(self.config));
        }
        let mut start_positions = std::mem::take(&mut self.start_positions);
        start_positions.clear();
        start_positions.extend_from_slice(&self.state.positions);
        let mut moved = false;
        let mut feed_in_block = None;
        let mut polar = PolarWords::default();
        let plane_before = self.state.plane_index();
        let mut forget_after = forget_for_frames;
        // A tool change alone runs a cycle without arguments: with MD11120 = 0 it cannot reach the
        // variables this program level defined (reference §17.6), only R parameters and global data.
        let mut locals_may_change = forget_for_frames;
        // A call or a kinematic change may also write the settable frames' data (measuring cycles do).
        let mut frame_data_changed = forget_for_frames;
        let mut circle_words = CircleWords::default();
        let mut contour = contours::ContourWords::default();
        for statement in statements {
            match statement {
                Statement::Address(word) => match word.kind {
                    AddressKind::Axis => {
                        if functions.frame_or_pole.is_some() || functions.dwell {
                            continue;
                        }
                        // A word of an axis the machine does not have (reported as S180) moves
                        // nothing the engine can follow: the block is no move of its own, so no
                        // finding about its motion is made from it.
                        let axis = self.axes.index(self.config, line, word);
                        moved |= axis.is_some();
                        // A word of an axis that is not configured was reported by the syntax
                        // layer; there is nothing to track.
                        if let Some(index) = axis {
                            self.apply_axis_word(index, line, block, word, &functions, diagnostics);
                        }
                    }
                    AddressKind::Feed if !functions.dwell => {
                        feed_in_block = Some(self.word_value(line, block, word, diagnostics));
                    }
                    AddressKind::Named(NamedAddress::PolarAngle) => {
                        let incremental = matches!(word.value.modifier, Some((Modifier::Ic, _)));
                        let value = self.word_value(line, block, word, diagnostics);
                        polar.angle = Some((value, incremental));
                        polar.span = Some(word.span);
                        if word.value.modifier.is_none() && functions.frame_or_pole.is_none() {
                            polar.plain_angle_span = Some(word.span);
                        }
                    }
                    AddressKind::Named(NamedAddress::PolarRadius) => {
                        let value = self.word_value(line, block, word, diagnostics);
                        let factor = self.state.length_factor(self.config.metric);
                        polar.radius =
                            Some(value.zip(factor).map(|(value, factor)| value * factor));
                        if value.is_some_and(|value| value < 0.0) {
                            diagnostics.push(Diagnostic::new(
                                Code::PolarRadiusNegative,
                                word.span,
                                "RP is a distance from the pole and must not be negative",
                            ));
                        }
                        polar.span = Some(polar.span.map_or(word.span, |span| span.to(word.span)));
                    }
                    AddressKind::Interpolation if word.extension.is_none() => {
                        self.collect_centre_word(line, block, word, &mut circle_words, diagnostics);
                    }
                    AddressKind::Interpolation
                        if matches!(word.extension, Some(Extension::Number { value: 1, .. })) =>
                    {
                        self.collect_intermediate_word(
                            line,
                            block,
                            word,
                            &mut circle_words,
                            diagnostics,
                        );
                    }
                    AddressKind::Named(NamedAddress::Positioning | NamedAddress::IndirectAxis)
                        if functions.frame_or_pole.is_none() && !functions.dwell =>
                    {
                        moved |=
                            self.apply_named_axis_word(line, block, word, &functions, diagnostics);
                    }
                    AddressKind::Named(NamedAddress::Turns) => {
                        circle_words.turns =
                            Some((self.word_value(line, block, word, diagnostics), word.span));
                    }
                    AddressKind::Named(NamedAddress::CircleRadius) => {
                        circle_words.radius_written = true;
                        circle_words.radius = self
                            .word_value(line, block, word, diagnostics)
                            .zip(self.state.length_factor(self.config.metric))
                            .map(|(value, factor)| value * factor);
                    }
                    AddressKind::Named(NamedAddress::OpeningAngle) => {
                        // `G3 I10 J0 AR=90` moves without any axis word.
                        circle_words.opening_angle = true;
                        circle_words.opening_angle_value =
                            self.word_value(line, block, word, diagnostics);
                        moved |= functions.frame_or_pole.is_none() && !functions.dwell;
                    }
                    AddressKind::Named(NamedAddress::Other) => {
                        self.read_contour_address(line, block, word, &mut contour, diagnostics);
                    }
                    AddressKind::MFunction => {
                        // A tool change (M6) may run a machine-specific cycle that moves axes.
                        let value = self.word_value(line, block, word, diagnostics);
                        if word.extension.is_none() && value == Some(6.0) {
                            forget_after = true;
                        }
                    }
                    _ => {}
                },
                // `ANG=30` (and a configured name the parser does not know) reads as an assignment.
                Statement::Assignment {
                    target,
                    target_span,
                    value,
                    ..
                } if self.read_contour_assignment(
                    line,
                    block,
                    target,
                    *target_span,
                    *value,
                    &mut contour,
                    diagnostics,
                ) => {}
                Statement::Assignment {
                    target,
                    target_span,
                    value,
                    ..
                } => {
                    self.apply_assignment(line, block, target, *target_span, *value, diagnostics);
                }
                Statement::Definition {
                    declarators,
                    data_type,
                    ..
                } => {
                    self.apply_definition(line, block, *data_type, declarators, diagnostics);
                }
                Statement::Call { kind, args, .. }
                    if *kind != CallKind::Modal && !call_followed =>
                {
                    forget_after = true;
                    // Only a `VAR` parameter reaches the caller's own variables, and only a variable
                    // can be passed to one.
                    locals_may_change |= args.iter().flatten().any(|&argument| {
                        matches!(block.expr(argument).kind, ExprKind::Name { .. })
                    });
                    frame_data_changed = true;
                }
                Statement::Instruction { name, .. } => {
                    let upper = line[name.start()..name.end()].to_ascii_uppercase();
                    if changes_kinematics(&upper) {
                        forget_after = true;
                        locals_may_change = true;
                        frame_data_changed = true;
                    }
                }
                _ => {}
            }
        }
        self.check_units(
            units_before,
            unit_word,
            feed_in_block.is_some(),
            statements,
            diagnostics,
        );
        self.check_machine_words(line, block, statements, diagnostics);
        if self.state.plane_index() != plane_before {
            // The stored AP and RP belong to the old plane (reference §5.2).
            self.state.polar_angle = None;
            self.state.polar_radius = None;
            self.memory.pole_changed = true;
        }
        let mut polar_circle_centre = None;
        if let Some(code) = functions.frame_or_pole {
            if matches!(code.name().as_ref(), "G110" | "G111" | "G112") {
                self.define_pole(code, line, block, statements, &polar, diagnostics);
            } else {
                let frame_before = self.state.frame;
                self.apply_frame_instruction(code, line, block, statements, diagnostics);
                if let (Some(before), Some(after)) = (frame_before, self.state.frame) {
                    for (slot, rotated) in self.memory.rotated_slots.iter_mut().enumerate() {
                        *rotated |=
                            (0..3).any(|row| before.matrix[row][slot] != after.matrix[row][slot]);
                    }
                }
                // A frame instruction moves nothing: the axes keep their machine set-points.
                crate::analysis::machine::reexpress(
                    &mut self.state,
                    &self.slots,
                    crate::analysis::machine::Replaced::Frame(frame_before),
                );
            }
        } else if polar.angle.is_some() || polar.radius.is_some() {
            moved = true;
            self.check_polar_words(&polar, diagnostics);
            polar_circle_centre = self.apply_polar_move(line, statements, &polar, diagnostics);
        }
        if let Some(feed) = feed_in_block {
            match feed {
                Some(value) => {
                    if value <= 0.0 {
                        if let Some(word) = find_word(statements, AddressKind::Feed) {
                            diagnostics.push(Diagnostic::new(
                                Code::FeedNotPositive,
                                word.span,
                                "the feedrate must be greater than 0 (alarm 14800)",
                            ));
                        }
                    }
                    self.state.feed = self
                        .state
                        .feed_factor(self.config.metric)
                        .map(|factor| value * factor);
                }
                None => self.state.feed = None,
            }
        }
        // ANG changes the programmed position (reference §14.6); a rounding or chamfer only the path.
        let mut angle_open = false;
        if contour.any() || self.state.open_angle.is_some() {
            let (angle_moves, opened) =
                self.apply_contour_angle(&contour, &mut start_positions, diagnostics);
            moved |= angle_moves;
            angle_open = opened;
        }
        let motion = self.state.groups[1]
            .map(GCode::name)
            .unwrap_or(Cow::Borrowed(""));
        let polar_move = polar.angle.is_some() || polar.radius.is_some();
        let moves_path = moved && functions.frame_or_pole.is_none() && !functions.dwell;
        // The span of the block's words is needed only by findings about a circle (and the rare ones
        // below): it is worked out for the blocks that may have one, not for every block.
        if moves_path && matches!(motion.as_ref(), "G2" | "G3" | "CIP") {
            circle_words.span = statements_span(statements);
        }
        let circle_rejected = self.check_circle_words(
            &circle_checks::CircleBlock {
                line,
                statements,
                motion: motion.as_ref(),
                moves_path,
                frame_or_pole: functions.frame_or_pole,
                words: &circle_words,
                polar: &polar,
                start_positions: &start_positions,
            },
            diagnostics,
        );
        let arc = if moves_path && !circle_rejected {
            match motion.as_ref() {
                // A polar circle turns around the pole; the start must lie on it (reference §5.2).
                "G2" | "G3" if polar_move => polar_circle_centre.and_then(|centre| {
                    self.polar_circle(
                        motion.as_ref() == "G2",
                        &start_positions,
                        centre,
                        &polar,
                        diagnostics,
                    )
                }),
                "G2" | "G3" => self.resolve_circle(
                    motion.as_ref() == "G2",
                    &start_positions,
                    &circle_words,
                    diagnostics,
                ),
                "CIP" => self.resolve_cip(&start_positions, &circle_words, diagnostics),
                "CT" => self.resolve_ct(&start_positions),
                _ => None,
            }
        } else {
            None
        };
        let arc = self.apply_turns(arc, &circle_words, diagnostics);
        if moves_path {
            self.update_tangent(&motion, &start_positions, arc.as_ref());
        }
        if moved && functions.frame_or_pole.is_none() && !functions.dwell {
            self.check_feed(&motion, statements, diagnostics);
        }
        let moves_axes = moved && functions.frame_or_pole.is_none() && !functions.dwell;
        if let Some(index) = self.stale_offset_data.filter(|_| moves_axes) {
            self.stale_offset_data = None;
            let name = crate::analysis::offsets::frame_name(index);
            diagnostics.push(Diagnostic::new(
                Code::SettableDataNotActive,
                statements_span(statements).unwrap_or_default(),
                format!("the data of {name} ($P_UIFR[{index}]) were changed while {name} was active; this move still uses the old data: program {name} again to activate them"),
            ));
        }
        if moves_axes {
            self.check_axes_after_rotation(statements, diagnostics);
        }
        if functions.machine_coordinates && find_word(statements, AddressKind::Axis).is_none() {
            // G53/G153/SUPA are non-modal (reference §2.3, §9.2 #13).
            if let Some(span) = statements.iter().find_map(|statement| match statement {
                Statement::GCode { code, span } if code.group() == 9 => Some(*span),
                _ => None,
            }) {
                diagnostics.push(Diagnostic::new(
                    Code::SuppressionWithoutAxes,
                    span,
                    "G53, G153 and SUPA act only on the axes of their own block; alone they do nothing: write them in every block that moves in machine coordinates",
                ));
            }
        }
        if functions.machine_coordinates || functions.reference_point {
            crate::analysis::machine::store_machine_targets(
                &mut self.state,
                &self.slots,
                &self.written,
            );
        }
        crate::analysis::machine::update_after_block(&mut self.state, &self.slots, &self.written);
        let result = moves_axes;
        if moves_axes {
            self.last_contour = self.contour_request(&contour, angle_open, diagnostics);
        }
        self.last_arc = arc;
        self.start_positions = start_positions;
        let feed_move = moves_axes && matches!(motion.as_ref(), "G1" | "G2" | "G3" | "CIP" | "CT");
        self.observe_timing(line, block, feed_type_before, feed_move, diagnostics);
        if forget_after {
            self.forget_what_a_call_may_change(frame_data_changed, locals_may_change);
        }
        result
    }

    /// Applies one axis word of the configured axis `index`; returns false when the axis became
    /// unknown.
    pub(super) fn apply_axis_word(
        &mut self,
        index: usize,
        line: &str,
        block: &Block,
        word: &AddressWord,
        functions: &BlockFunctions,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> bool {
        let name = AxisName(line, word);
        self.state.touched[index] = true;
        self.written[index] = 1;
        let kind = self.config.axes[index].kind;
        let modifier = word.value.modifier.map(|(modifier, _)| modifier);
        let absolute = match modifier {
            Some(Modifier::Ic | Modifier::Dic | Modifier::Ric | Modifier::Cic) => Some(false),
            Some(_) => Some(true),
            None => self.state.is_incremental().map(|incremental| !incremental),
        };
        if let (Some((modifier, modifier_span)), Some(incremental)) =
            (word.value.modifier, self.state.is_incremental())
        {
            let redundant = match modifier {
                Modifier::Ac => !incremental,
                Modifier::Ic => incremental,
                _ => false,
            };
            if redundant {
                let active = if incremental { "G91" } else { "G90" };
                diagnostics.push(Diagnostic::new(
                    Code::RedundantModifier,
                    modifier_span,
                    format!(
                        "{} is redundant here: {active} already reads `{name}` this way",
                        modifier.as_str()
                    ),
                ));
            }
        }
        let value = self.word_value(line, block, word, diagnostics);
        // Unknown value, or a mode inherited from an unseen caller: the position is unknown.
        let (Some(mut value), Some(absolute)) = (value, absolute) else {
            self.state.program(index, None);
            return false;
        };
        if matches!(kind, AxisKind::Linear | AxisKind::Transverse) {
            match self.state.length_factor(self.config.metric) {
                Some(factor) => value *= factor,
                None => {
                    self.state.program(index, None);
                    return false;
                }
            }
        }
        if kind == AxisKind::Transverse {
            let is_diameter = match modifier {
                Some(Modifier::Dac | Modifier::Dic) => Some(true),
                Some(Modifier::Rac | Modifier::Ric) => Some(false),
                _ => self
                    .state
                    .diameter_mode()
                    .map(|(absolute_diameter, incremental_diameter)| {
                        if absolute {
                            absolute_diameter
                        } else {
                            incremental_diameter
                        }
                    }),
            };
            match is_diameter {
                Some(true) => value /= 2.0,
                Some(false) => {}
                None => {
                    self.state.program(index, None);
                    return false;
                }
            }
        }
        if functions.machine_coordinates || functions.reference_point {
            // G53/G153/SUPA values are machine positions, stored in workpiece coordinates after the
            // block (reference §3.8); G74/G75 approach machine-defined points. An increment in machine
            // coordinates is not followed.
            let known = functions.machine_coordinates && absolute;
            self.state.machine[index] = known.then_some(value);
            self.state.program(index, None);
            self.written[index] = 2;
            return known;
        }
        // Under SD42440 = 1 an increment adds to the last programmed value, so that it also traverses
        // a frame change since; under 0 it adds to the set-point in the new frames (reference §3.6).
        let reference = if self.config.frame_offset_incr_prog {
            self.state.programmed[index]
        } else {
            self.state.positions[index]
        };
        if !absolute && self.config.frame_offset_incr_prog {
            let programmed = self.state.programmed[index];
            let difference = match (programmed, self.state.positions[index]) {
                (Some(programmed), Some(current)) => ((programmed - current).abs() > 1e-9)
                    .then(|| FourDecimals(programmed - current).to_string()),
                (Some(_), None) => Some("an unknown amount".to_string()),
                _ => None,
            };
            if let Some(difference) = difference {
                diagnostics.push(Diagnostic::new(
                    Code::IncrementAfterOffsetChange,
                    word.span,
                    format!("`{name}` moves incrementally after a frame or offset change: the change ({difference} in workpiece coordinates) is traversed in addition to the increment (SD42440 = 1)"),
                ));
            }
        }
        let target = if absolute {
            Some(value)
        } else {
            match reference {
                // A modulo axis counts 0 to 360 degrees: an increment wraps (reference §3.5).
                Some(previous) if kind == AxisKind::Modulo => {
                    Some((previous + value).rem_euclid(360.0))
                }
                Some(previous) => Some(previous + value),
                None => {
                    // Turning a modulo axis on by an increment from wherever it stands is usual
                    // practice (`C=IC(720)`), not a likely mistake: information only.
                    let code = if kind == AxisKind::Modulo {
                        Code::ModuloIncrementOnUnknownPosition
                    } else {
                        Code::IncrementOnUnknownPosition
                    };
                    diagnostics.push(Diagnostic::new(
                        code,
                        word.span,
                        format!("`{name}` moves incrementally, but its position is not known here, so the end point is unknown"),
                    ));
                    None
                }
            }
        };
        self.state.program(index, target);
        target.is_some()
    }

    /// The block programs axis `index` to `value` in workpiece coordinates.
    pub(super) fn program_axis(&mut self, index: usize, value: Option<f64>) {
        self.state.program(index, value);
        self.written[index] = 1;
    }

    /// The value of a word's expression (constant or evaluated), or `None` when unknown.
    fn word_value(
        &self,
        line: &str,
        block: &Block,
        word: &AddressWord,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> Option<f64> {
        match word.value.expr {
            ValueExpr::Missing => None,
            ValueExpr::Constant { value, .. } => Some(value),
            ValueExpr::Expr(id) => {
                evaluate_or_report(block, line, id, &self.state.variables, diagnostics)
            }
        }
    }

    /// `DEF`: LUD variables of their type, starting at zero (reference §8.1) or at their initial
    /// value (`=5`, `=(1,2,3)`, `=SET(..)`, `=REP(..)`); arrays of up to three dimensions.
    fn apply_definition(
        &mut self,
        line: &str,
        block: &Block,
        data_type: Option<DataType>,
        declarators: &[Declarator],
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        use crate::analysis::eval::{evaluate_value, EvalOptions, Value, VarType};
        let var_type = VarType::of_declared(data_type);
        let options = EvalOptions::default();
        for declarator in declarators {
            let upper = line[declarator.name.start()..declarator.name.end()].to_ascii_uppercase();
            let mut dimensions = Vec::with_capacity(declarator.dimensions.len());
            for id in &declarator.dimensions {
                match evaluate_or_report(block, line, *id, &self.state.variables, diagnostics) {
                    Some(size) if size >= 1.0 && size.fract() == 0.0 && size <= 1e9 => {
                        dimensions.push(size as usize)
                    }
                    _ => {
                        dimensions.clear();
                        break;
                    }
                }
            }
            if dimensions.len() != declarator.dimensions.len() {
                // An array whose size is not known: nothing of it is followed.
                self.state.variables.set_variable(&upper, None);
                continue;
            }
            if self
                .state
                .variables
                .define(&upper, var_type, &dimensions)
                .is_err()
            {
                self.state.variables.forget_variable(&upper);
                continue;
            }
            if self.flow_uncertain {
                self.state.variables.forget_variable(&upper);
                continue;
            }
            let value_of = |id: ExprId, variables: &crate::analysis::eval::Variables| {
                evaluate_value(block, line, id, variables, &options)
                    .ok()
                    .flatten()
            };
            let elements: Vec<Option<Value>> = match &declarator.initial {
                None => continue,
                // An AXIS variable's initial value is an axis name written bare (`DEF AXIS AC1=X`).
                Some(Initializer::Value(id)) => vec![value_of(*id, &self.state.variables)
                    .or_else(|| self.axis_name_value(line, block, &upper, Some(*id)))],
                Some(Initializer::List(items) | Initializer::Set(items)) => items
                    .iter()
                    .map(|item| {
                        item.and_then(|id| {
                            value_of(id, &self.state.variables)
                                .or_else(|| self.axis_name_value(line, block, &upper, Some(id)))
                        })
                    })
                    .collect(),
                Some(Initializer::Repeat { value, count }) => {
                    let element = value_of(*value, &self.state.variables);
                    let total: usize = dimensions.iter().product::<usize>().max(1);
                    let count = match count {
                        None => Some(total),
                        Some(id) => value_of(*id, &self.state.variables)
                            .and_then(|value| value.number())
                            .filter(|count| *count >= 0.0 && count.fract() == 0.0)
                            .map(|count| (count as usize).min(total)),
                    };
                    match count {
                        Some(count) => vec![element; count],
                        None => {
                            self.state.variables.forget_variable(&upper);
                            continue;
                        }
                    }
                }
            };
            if dimensions.is_empty() {
                let _ =
                    self.state
                        .variables
                        .assign(&upper, &[], elements.into_iter().next().flatten());
                continue;
            }
            // Initial values fill the array in the order of its last index first (row by row).
            let total: usize = dimensions.iter().product();
            for (position, element) in elements.into_iter().enumerate().take(total) {
                let indexes = crate::analysis::eval::element_indexes(position, &dimensions);
                let _ = self.state.variables.assign(&upper, &indexes, element);
            }
        }
    }

    fn apply_assignment(
        &mut self,
        line: &str,
        block: &Block,
        target: &AssignTarget,
        target_span: crate::diagnostics::Span,
        value: Option<ExprId>,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        let evaluated = value.and_then(|id| {
            evaluate_value_or_report(block, line, id, &self.state.variables, diagnostics)
        });
        // After a jump or inside a control structure the assignment may run any number of times.
        let evaluated = if self.flow_uncertain { None } else { evaluated };
        let number = evaluated.as_ref().and_then(Value::number);
        match target {
            AssignTarget::RParameter(parameter) => {
                self.state.variables.set_r_parameter(*parameter, number)
            }
            AssignTarget::RParameterIndexed(index) => self.write_indexed_r_parameter(
                line,
                block,
                *index,
                target_span,
                number,
                diagnostics,
            ),
            AssignTarget::Variable { indexes } => self.write_variable(
                line,
                block,
                target_span,
                indexes,
                value,
                evaluated,
                diagnostics,
            ),
            // `$R[n]` names the same parameters as `R[n]` (reference §8.1).
            AssignTarget::SystemVariable { indexes }
                if indexes.len() == 1 && is_r_parameter_array(line, target_span) =>
            {
                self.write_indexed_r_parameter(
                    line,
                    block,
                    indexes[0],
                    target_span,
                    number,
                    diagnostics,
                )
            }
            AssignTarget::SystemVariable { indexes } => {
                self.apply_system_variable_write(
                    line,
                    block,
                    target_span,
                    indexes,
                    value,
                    diagnostics,
                );
            }
            AssignTarget::GGroup { group } => {
                self.apply_group_write(line, block, *group, value, diagnostics);
            }
        }
    }

    /// TRANS/ATRANS, ROT/AROT (RPL in the plane), SCALE/ASCALE, MIRROR/AMIRROR (reference §7.2, §7.3).
    /// What cannot be followed (a spatial rotation, unknown values, frame values of other axes, G58/G59,
    /// ROTS) makes the frame unknown.
    fn apply_frame_instruction(
        &mut self,
        code: GCode,
        line: &str,
        block: &Block,
        statements: &[Statement],
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        use crate::analysis::frame::Frame;
        let name = code.name();
        let name = name.as_ref();
        if !matches!(
            name,
            "TRANS"
                | "ATRANS"
                | "ROT"
                | "AROT"
                | "SCALE"
                | "ASCALE"
                | "MIRROR"
                | "AMIRROR"
                | "ROTS"
                | "AROTS"
                | "G58"
                | "G59"
        ) {
            // Working-area limits (G25/G26) do not move the coordinate system.
            return;
        }
        let is_length = matches!(name, "TRANS" | "ATRANS" | "G58" | "G59");
        let mut values: [Option<Option<f64>>; 3] = [None; 3];
        // G58 and G59 replace the coarse and fine translation axially; without a fine translation
        // (MD18600 = 0) they are not followed.
        let mut followable = !matches!(name, "ROTS" | "AROTS")
            && (self.config.frame_fine_trans || !matches!(name, "G58" | "G59"));
        let mut rotation_in_plane = None;
        for statement in statements {
            let Statement::Address(word) = statement else {
                continue;
            };
            match word.kind {
                AddressKind::Axis => {
                    let axis = axis_name(line, word);
                    let Some(slot) = ["X", "Y", "Z"]
                        .iter()
                        .position(|name| axis.eq_ignore_ascii_case(name))
                    else {
                        // Frame components of other axes are not followed.
                        followable = false;
                        continue;
                    };
                    let mut value = self.word_value(line, block, word, diagnostics);
                    if is_length {
                        value = value
                            .zip(self.state.length_factor(self.config.metric))
                            .map(|(value, factor)| value * factor);
                        let transverse = self
                            .config
                            .axis(&axis)
                            .is_some_and(|axis| axis.kind == AxisKind::Transverse);
                        if transverse && self.state.diameter_mode() != Some((false, false)) {
                            // Whether a frame offset on a diameter axis is a diameter is not followed.
                            value = None;
                        }
                    }
                    values[slot] = Some(value);
                }
                AddressKind::Named(NamedAddress::RotationInPlane) => {
                    rotation_in_plane = Some(self.word_value(line, block, word, diagnostics));
                }
                _ => {}
            }
        }
        let any_unknown = values.iter().any(|value| matches!(value, Some(None)));
        let written = |slot: usize, default: f64| values[slot].flatten().unwrap_or(default);
        let element = if !followable || any_unknown {
            None
        } else {
            match name {
                "TRANS" | "ATRANS" | "G58" | "G59" => Some(Frame::translation([
                    written(0, 0.0),
                    written(1, 0.0),
                    written(2, 0.0),
                ])),
                "ROT" | "AROT" => {
                    if values.iter().any(Option::is_some) {
                        // A spatial rotation (ROT X.. Y.. Z..) is not followed.
                        None
                    } else {
                        match rotation_in_plane {
                            None => Some(Frame::IDENTITY),
                            Some(None) => None,
                            Some(Some(degrees)) => {
                                self.state.plane_axis_names().map(|(first, second)| {
                                    let slot = |name: &str| {
                                        ["X", "Y", "Z"]
                                            .iter()
                                            .position(|axis| *axis == name)
                                            .unwrap_or(0)
                                    };
                                    Frame::rotation_in_plane(slot(first), slot(second), degrees)
                                })
                            }
                        }
                    }
                }
                "SCALE" | "ASCALE" => Some(Frame::scale([
                    written(0, 1.0),
                    written(1, 1.0),
                    written(2, 1.0),
                ])),
                // The value of a mirrored axis is ignored: writing the axis mirrors it.
                _ => Some(Frame::scale([0, 1, 2].map(|slot| {
                    if values[slot].is_some() {
                        -1.0
                    } else {
                        1.0
                    }
                }))),
            }
        };
        if self.config.frame_fine_trans {
            let written = values.map(|value| value.is_some());
            self.compose_with_fine_translation(name, element, written);
            return;
        }
        let absolute = matches!(name, "TRANS" | "ROT" | "SCALE" | "MIRROR");
        self.state.frame = match (absolute, element) {
            (_, None) => None,
            (true, Some(element)) => Some(element),
            (false, Some(element)) => self.state.frame.map(|frame| frame.then_inner(&element)),
        };
    }

    /// Frame composition with a fine translation (MD18600 = 1, reference §7.2): TRANS writes the
    /// coarse part and keeps the fine one, ATRANS adds to the fine part, G58 and G59 replace the
    /// coarse and the fine part of the written axes. Whether ROT, SCALE and MIRROR clear a fine part is
    /// not documented: with one, the frame becomes unknown.
    fn compose_with_fine_translation(
        &mut self,
        name: &str,
        element: Option<crate::analysis::frame::Frame>,
        written: [bool; 3],
    ) {
        use crate::analysis::frame::Frame;
        let known = self.state.frame.zip(self.state.fine_translation);
        let result = element.zip(known).and_then(|(element, (frame, fine))| {
            let add =
                |left: [f64; 3], right: [f64; 3]| [0, 1, 2].map(|axis| left[axis] + right[axis]);
            match name {
                "TRANS" => Some((Frame::translation(add(element.translation, fine)), fine)),
                "ATRANS" => {
                    let shift = [0, 1, 2].map(|row| {
                        (0..3)
                            .map(|column| frame.matrix[row][column] * element.translation[column])
                            .sum::<f64>()
                    });
                    Some((frame.then_inner(&element), add(fine, shift)))
                }
                "G58" | "G59" => {
                    let mut frame = frame;
                    let mut fine = fine;
                    for axis in (0..3).filter(|axis| written[*axis]) {
                        let value = element.translation[axis];
                        if name == "G58" {
                            frame.translation[axis] = value + fine[axis];
                        } else {
                            frame.translation[axis] += value - fine[axis];
                            fine[axis] = value;
                        }
                    }
                    Some((frame, fine))
                }
                "ROT" | "SCALE" | "MIRROR" => (fine == [0.0; 3]).then_some((element, fine)),
                _ => Some((frame.then_inner(&element), fine)),
            }
        });
        self.state.frame = result.map(|(frame, _)| frame);
        self.state.fine_translation = result.map(|(_, fine)| fine);
    }

    /// G110 (relative to the last programmed position), G111 (absolute), G112 (relative to the last
    /// pole): the pole of the active plane, from the plane axes or from AP/RP (reference §5.1).
    fn define_pole(
        &mut self,
        code: GCode,
        line: &str,
        block: &Block,
        statements: &[Statement],
        polar: &PolarWords,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        use crate::analysis::state::Pole;
        self.state.polar_angle = None;
        // What a stored RP means for the new pole is not documented (reference §5.2 [?]).
        self.state.polar_radius = None;
        self.memory.pole_changed = true;
        let Some(plane) = self.state.plane_index() else {
            return;
        };
        let (first, second) = self.plane_axes();
        let reference = match code.name().as_ref() {
            "G111" => Some((0.0, 0.0)),
            "G110" => first.zip(second).and_then(|(first, second)| {
                self.state.positions[first].zip(self.state.positions[second])
            }),
            _ => match self.state.poles[plane] {
                Pole::At(first, second) => Some((first, second)),
                Pole::Undefined => Some((0.0, 0.0)),
                Pole::Unknown => None,
            },
        };
        let offset = if polar.angle.is_some() || polar.radius.is_some() {
            match (polar.angle, polar.radius) {
                (Some((Some(angle), false)), Some(Some(radius))) => {
                    let radians = angle.to_radians();
                    Some((radius * radians.cos(), radius * radians.sin()))
                }
                _ => None,
            }
        } else {
            let mut values = [Some(0.0), Some(0.0)];
            for statement in statements {
                let Statement::Address(word) = statement else {
                    continue;
                };
                if word.kind != AddressKind::Axis {
                    continue;
                }
                let Some(index) = self.axes.index(self.config, line, word) else {
                    continue;
                };
                let slot = if Some(index) == first {
                    0
                } else if Some(index) == second {
                    1
                } else {
                    continue;
                };
                let factor = self.state.length_factor(self.config.metric);
                // Whether a pole coordinate on a transverse axis is a diameter is not documented
                // (reference §5.2 [?]): it stays unknown unless the axis reads radii.
                let diameter = self.config.axes[index].kind == AxisKind::Transverse
                    && self.state.diameter_mode() != Some((false, false));
                values[slot] = if diameter {
                    None
                } else {
                    self.word_value(line, block, word, diagnostics)
                        .zip(factor)
                        .map(|(value, factor)| value * factor)
                };
            }
            values[0].zip(values[1])
        };
        self.state.poles[plane] = match reference.zip(offset) {
            Some((reference, offset)) => Pole::At(reference.0 + offset.0, reference.1 + offset.1),
            None => Pole::Unknown,
        };
    }

    /// A move to AP/RP around the pole; returns the pole (the centre of a polar circle) when known.
    fn apply_polar_move(
        &mut self,
        line: &str,
        statements: &[Statement],
        polar: &PolarWords,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> Option<(f64, f64)> {
        use crate::analysis::state::Pole;
        let span = polar.span.unwrap_or_default();
        let (first, second) = self.plane_axes();
        // With the plane unknown, any geometry axis may be a plane axis.
        let plane_axes = self.plane_axis_indexes();
        let forget_plane = |engine: &mut Engine| {
            for index in &plane_axes {
                engine.program_axis(*index, None);
            }
        };
        let angle = match polar.angle {
            Some((Some(value), true)) => self.state.polar_angle.map(|stored| stored + value),
            Some((value, false)) => value,
            Some((None, true)) => None,
            None => self.state.polar_angle,
        };
        let radius = match polar.radius {
            Some(value) => value,
            None => self.state.polar_radius,
        };
        self.state.polar_angle = angle;
        self.state.polar_radius = radius;
        // Only the axis perpendicular to the plane may join AP/RP (reference §5.3, T97).
        let plane_axis_written = statements.iter().any(|statement| {
            matches!(statement, Statement::Address(word) if word.kind == AddressKind::Axis && {
                self.axes.index(self.config, line, word).is_some_and(|index| plane_axes.contains(&index))
            })
        });
        if plane_axis_written {
            diagnostics.push(Diagnostic::new(
                Code::PolarWithPlaneAxis,
                span,
                "a polar block may add only the axis perpendicular to the plane; a plane axis cannot join AP and RP",
            ));
            forget_plane(self);
            return None;
        }
        let (Some(first), Some(second), Some(plane)) = (first, second, self.state.plane_index())
        else {
            forget_plane(self);
            return None;
        };
        let pole = match self.state.poles[plane] {
            Pole::At(first, second) => Some((first, second)),
            Pole::Undefined => {
                diagnostics.push(Diagnostic::new(
                    Code::PolarWithoutPole,
                    span,
                    "no pole is defined (G110, G111, G112): the pole is the zero point of the workpiece coordinate system",
                ));
                Some((0.0, 0.0))
            }
            Pole::Unknown => None,
        };
        let transverse_in_plane = [first, second]
            .iter()
            .any(|index| self.config.axes[*index].kind == AxisKind::Transverse)
            && self.state.diameter_mode() != Some((false, false));
        let (Some(pole), Some(angle), Some(radius), false) =
            (pole, angle, radius, transverse_in_plane)
        else {
            forget_plane(self);
            return None;
        };
        let radians = angle.to_radians();
        self.program_axis(first, Some(pole.0 + radius * radians.cos()));
        self.program_axis(second, Some(pole.1 + radius * radians.sin()));
        Some(pole)
    }

    /// The circle of a polar G2/G3 block: around the pole, from the start to the polar end point.
    fn polar_circle(
        &self,
        clockwise: bool,
        start_positions: &[Option<f64>],
        centre: (f64, f64),
        polar: &PolarWords,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> Option<crate::analysis::circle::Circle> {
        let (Some(first), Some(second)) = self.plane_axes() else {
            return None;
        };
        let start = (start_positions[first]?, start_positions[second]?);
        let end = (self.state.positions[first]?, self.state.positions[second]?);
        match crate::analysis::circle::from_centre(
            start,
            end,
            centre,
            clockwise,
            self.config.circle_error_const,
            self.config.circle_error_factor,
        ) {
            Ok(circle) => Some(circle),
            Err(_) => {
                diagnostics.push(Diagnostic::new(
                    Code::CircleEndNotOnCircle,
                    polar.span.unwrap_or_default(),
                    "the start point does not lie on the polar circle around the pole within the tolerance (alarm 14040)",
                ));
                None
            }
        }
    }

    /// The configuration index of an axis, by name in any case.
    pub(super) fn axis_index(&self, name: &str) -> Option<usize> {
        self.config
            .axes
            .iter()
            .position(|axis| axis.name.eq_ignore_ascii_case(name))
    }

    /// Machine coordinates of the touched axes whose value is known (transverse axes as radii).
    fn machine_positions(&self) -> Vec<(Arc<str>, f64)> {
        self.axis_names
            .iter()
            .enumerate()
            .filter(|(index, _)| self.state.touched[*index])
            .filter_map(|(index, name)| Some((name.clone(), self.state.machine[index]?)))
            .collect()
    }

    /// The turning direction in the machine of an arc programmed `clockwise` in the active plane: the
    /// frame's map of the plane reverses it when its determinant is negative (an odd number of
    /// mirrors). `None` when the frame or the plane is unknown, or the frame tilts the plane.
    fn machine_clockwise(&self, clockwise: bool) -> Option<bool> {
        let frame = self.state.frame?;
        let (first, second) = match self.state.plane_index()? {
            0 => (0, 1),
            1 => (2, 0),
            _ => (1, 2),
        };
        let normal = 3 - first - second;
        let tilted = frame.matrix[normal][first] != 0.0
            || frame.matrix[normal][second] != 0.0
            || frame.matrix[first][normal] != 0.0
            || frame.matrix[second][normal] != 0.0;
        if tilted {
            return None;
        }
        let determinant = frame.matrix[first][first] * frame.matrix[second][second]
            - frame.matrix[first][second] * frame.matrix[second][first];
        Some(if determinant < 0.0 {
            !clockwise
        } else {
            clockwise
        })
    }

    /// The configuration indexes of the plane's first and second axis (G17: X, Y; G18: Z, X; G19: Y, Z).
    fn plane_axes(&self) -> (Option<usize>, Option<usize>) {
        match self.state.plane_index() {
            Some(plane) => self.plane_axis_cache[plane],
            // The plane is inherited from an unseen caller.
            None => (None, None),
        }
    }

    /// Reads I, J or K: incremental from the circle's start unless `=AC` (reference §3.2), converted by
    /// G70/G700; on a transverse axis an absolute value under diameter programming is a diameter.
    fn collect_centre_word(
        &self,
        line: &str,
        block: &Block,
        word: &AddressWord,
        circle_words: &mut CircleWords,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        let letter = line.as_bytes()[word.name.start()].to_ascii_uppercase();
        let slot = match letter {
            b'I' => 0,
            b'J' => 1,
            _ => 2,
        };
        let absolute = matches!(word.value.modifier, Some((Modifier::Ac, _)));
        let value = self.word_value(line, block, word, diagnostics);
        if value == Some(0.0) {
            // 0 is 0 in every unit and as a diameter: known where the units are inherited.
            circle_words.centre[slot] = Some((0.0, absolute));
            return;
        }
        let (Some(value), Some(factor)) = (value, self.state.length_factor(self.config.metric))
        else {
            circle_words.centre_unknown = true;
            return;
        };
        let mut value = value * factor;
        let axis_name = ["X", "Y", "Z"][slot];
        let transverse = self
            .config
            .axis(axis_name)
            .is_some_and(|axis| axis.kind == AxisKind::Transverse);
        if transverse && absolute {
            match self.state.diameter_mode() {
                Some((true, _)) => value /= 2.0,
                Some(_) => {}
                None => {
                    circle_words.centre_unknown = true;
                    return;
                }
            }
        }
        circle_words.centre[slot] = Some((value, absolute));
    }

    fn plane_axis_indexes(&self) -> Vec<usize> {
        match self.plane_axes() {
            (None, None) => {
                // The plane is unknown: any geometry axis may be in it.
                (0..self.config.axes.len())
                    .filter(|&index| {
                        matches!(
                            self.config.axes[index].name.to_ascii_uppercase().as_str(),
                            "X" | "Y" | "Z"
                        )
                    })
                    .collect()
            }
            (first, second) => first.into_iter().chain(second).collect(),
        }
    }

    /// G1/G2/G3 need a feed (alarm 10860); reported once, at the first feed move without one.
    fn check_feed(
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

    /// The move of the block last applied with [`Engine::step`], which returned true for it.
    pub fn describe_last_move(&self, line_index: usize, line: &str, block: &Block) -> Move {
        let motion = self.state.groups[1]
            .map(GCode::name)
            .unwrap_or(Cow::Borrowed(""));
        let start_positions = &self.start_positions;
        let arc = self.last_arc;
        let shows_diameter = self.state.shows_diameter();
        // How the program shows a value; unknown for a transverse axis while the diameter mode is.
        let display = |index: usize, value: f64| -> Option<f64> {
            let transverse = self.config.axes[index].kind == AxisKind::Transverse;
            crate::analysis::state::shown_value(transverse, shows_diameter, value)
        };
        let mut start = Vec::new();
        let mut end = Vec::new();
        let mut uncertain = Vec::new();
        for (index, name) in self.axis_names.iter().enumerate() {
            if !self.state.touched[index] {
                continue;
            }
            if let Some(value) = start_positions[index].and_then(|value| display(index, value)) {
                start.push((name.clone(), value));
            }
            match self.state.positions[index].and_then(|value| display(index, value)) {
                Some(value) => {
                    end.push((name.clone(), value));
                    if self.flow_uncertain {
                        uncertain.push(name.clone());
                    }
                }
                None => uncertain.push(name.clone()),
            }
        }
        let machine = self.state.machine_known().then(|| self.machine_positions());
        let block_number = block
            .number
            .map(|number| line[number.span.start()..number.span.end()].to_string());
        let arc = arc.map(|circle| {
            let (first, second) = self.plane_axes();
            let mut centre = Vec::new();
            for (index, value) in [(first, circle.centre.0), (second, circle.centre.1)] {
                if let Some(shown) = index.and_then(|index| display(index, value)) {
                    centre.push((self.axis_names[index.unwrap_or_default()].clone(), shown));
                }
            }
            ArcMove {
                centre,
                radius: circle.radius,
                clockwise: circle.clockwise,
                machine_clockwise: self.machine_clockwise(circle.clockwise),
                sweep: circle.sweep,
            }
        });
        Move {
            line: line_index,
            block_number,
            motion,
            start,
            end,
            machine,
            feed: self.state.feed,
            uncertain,
            arc,
            transverse_as_diameter: shows_diameter == Some(true),
            plane: self.state.plane_axis_names(),
            cycle: None,
            contour: self.last_contour.clone(),
            inserted: None,
            timing: self.timing(),
        }
    }

    /// The dwell of the block last applied with [`Engine::step`], if it was a `G4` block: a move of
    /// no axis (`start` and `end` empty, motion `G4`) whose `timing.dwell` holds the time. Consumers
    /// of the path never see it unless they ask for it (`ExecutionOptions::dwell_moves`).
    pub fn describe_last_dwell(
        &self,
        line_index: usize,
        line: &str,
        block: &Block,
    ) -> Option<Move> {
        let dwell = self.last_dwell?;
        let block_number = block
            .number
            .map(|number| line[number.span.start()..number.span.end()].to_string());
        Some(Move {
            line: line_index,
            block_number,
            motion: Cow::Borrowed("G4"),
            start: Vec::new(),
            end: Vec::new(),
            machine: None,
            feed: self.state.feed,
            uncertain: Vec::new(),
            arc: None,
            plane: self.state.plane_axis_names(),
            transverse_as_diameter: self.state.shows_diameter() == Some(true),
            timing: spindle::Timing {
                dwell: Some(dwell),
                ..self.timing()
            },
            cycle: None,
            contour: None,
            inserted: None,
        })
    }
}

/// The number an expression gives, or `None` when unknown or a text; errors of the program are
/// reported.
fn evaluate_or_report(
    block: &Block,
    line: &str,
    id: ExprId,
    variables: &Variables,
    diagnostics: &mut Vec<Diagnostic>,
) -> Option<f64> {
    evaluate_value_or_report(block, line, id, variables, diagnostics)?.number()
}

/// The value an expression gives, or `None` when unknown; errors of the program (alarms 14051,
/// 14020, 17020) are reported.
fn evaluate_value_or_report(
    block: &Block,
    line: &str,
    id: ExprId,
    variables: &Variables,
    diagnostics: &mut Vec<Diagnostic>,
) -> Option<Value> {
    match evaluate_value(block, line, id, variables, &EvalOptions::default()) {
        Ok(value) => value,
        Err(error) => {
            diagnostics.push(assignments::eval_error_diagnostic(line, error));
            None
        }
    }
}

/// Whether an assignment's target is `$R[...]`, the R parameters by number.
fn is_r_parameter_array(line: &str, target_span: crate::diagnostics::Span) -> bool {
    let written = &line[target_span.start()..target_span.end()];
    written
        .split('[')
        .next()
        .is_some_and(|name| name.trim().eq_ignore_ascii_case("$R"))
}

/// The axis name of a word: the letter and its numeric extension (`X`, `X1`), or the whole name.
pub(crate) fn axis_name(line: &str, word: &AddressWord) -> String {
    AxisName(line, word).to_string()
}

/// The axis name of a word, written only when a message needs it: most words never do, and building a
/// string per word cost an allocation per axis word of every block.
pub(crate) struct AxisName<'a>(pub &'a str, pub &'a AddressWord);

impl std::fmt::Display for AxisName<'_> {
    fn fmt(&self, formatter: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let AxisName(line, word) = self;
        for character in line[word.name.start()..word.name.end()].chars() {
            write!(formatter, "{}", character.to_ascii_uppercase())?;
        }
        if let Some(Extension::Number { value, .. }) = &word.extension {
            write!(formatter, "{value}")?;
        }
        Ok(())
    }
}

fn find_word(statements: &[Statement], kind: AddressKind) -> Option<&AddressWord> {
    statements.iter().find_map(|statement| match statement {
        Statement::Address(word) if word.kind == kind => Some(word),
        _ => None,
    })
}

/// Instructions after which machine positions cannot be followed (reference §7.5).
fn changes_kinematics(upper: &str) -> bool {
    matches!(
        upper,
        "TRAORI"
            | "TRANSMIT"
            | "TRACYL"
            | "TRAANG"
            | "TRACON"
            | "TCARR"
            | "PAROT"
            | "TOROT"
            | "TOFRAME"
            | "TRAFOOF"
    )
}
