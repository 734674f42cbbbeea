//! One block through the engine, in named phases: the block's non-modal G functions are read first
//! (`begin_step`), then its words (`engine/step_words.rs`), then what the block does as a whole
//! (frames, the pole, polar and circular motion: `engine/step_motion.rs`), and last what follows from
//! the move (`finish_block`). `BlockStep` carries what one phase hands to the next.

use crate::analysis::engine::block_words::{
    statements_span, BlockFunctions, CircleWords, PolarWords,
};
use crate::analysis::engine::contours::ContourWords;
use crate::analysis::engine::engine_state::Engine;
use crate::analysis::state::Pole;
use crate::diagnostics::{Code, Diagnostic, Span};
use crate::syntax::ast::{AddressKind, Block, Statement};
use crate::syntax::gcodes::GCode;
use std::borrow::Cow;

/// What the phases of one block hand to each other.
pub(super) struct BlockStep<'s> {
    pub(super) statements: &'s [Statement],
    /// The interpreter runs the call of this block itself: the call forgets nothing.
    pub(super) call_followed: bool,
    pub(super) functions: BlockFunctions,
    /// Group 13 (the unit system) before the block, and the block's own unit word.
    pub(super) units_before: Option<GCode>,
    pub(super) unit_word: Option<(GCode, Span)>,
    /// Group 15 (the feed type) before the block.
    pub(super) feed_type_before: Option<GCode>,
    /// The positions before the block (the engine's buffer, handed back at the end).
    pub(super) start_positions: Vec<Option<f64>>,
    pub(super) moved: bool,
    /// The block's F word: its value when known.
    pub(super) feed_in_block: Option<Option<f64>>,
    pub(super) polar: PolarWords,
    pub(super) plane_before: Option<usize>,
    /// A call, a tool change or a kinematic change: what a called program may change is forgotten
    /// after the block.
    pub(super) forget_after: bool,
    /// A tool change alone runs a cycle without arguments: with MD11120 = 0 it cannot reach the
    /// variables this program level defined (reference §17.6), only R parameters and global data.
    pub(super) locals_may_change: bool,
    /// A call or a kinematic change may also write the settable frames' data (measuring cycles do).
    pub(super) frame_data_changed: bool,
    pub(super) circle_words: CircleWords,
    pub(super) contour: ContourWords,
}

impl BlockStep<'_> {
    /// Whether the block moves along a path of its own (not a frame, pole or dwell block).
    #[inline]
    pub(super) fn moves_axes(&self) -> bool {
        self.moved && self.functions.frame_or_pole.is_none() && !self.functions.dwell
    }
}

impl<'a> Engine<'a> {
    /// Applies `block` like [`Engine::apply`] but only says whether it moved axes: building the move is
    /// left to [`Engine::describe_last_move`], so that callers that need only diagnostics pay nothing
    /// for it.
    pub fn step(&mut self, line: &str, block: &Block, diagnostics: &mut Vec<Diagnostic>) -> bool {
        let moved = self.step_block(line, block, diagnostics);
        self.forget_non_finite();
        moved
    }

    pub(super) fn step_block(
        &mut self,
        line: &str,
        block: &Block,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> bool {
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
        self.note_flow_structures(block, statements);
        let mut step = self.begin_step(statements, call_followed);
        self.read_words(line, block, &mut step, diagnostics);
        let polar_circle_centre = self.apply_block_functions(line, block, &mut step, diagnostics);
        // ANG changes the programmed position (reference §14.6); a rounding or chamfer only the path.
        let mut angle_open = false;
        if step.contour.any() || self.state.open_angle.is_some() {
            let (angle_moves, opened) =
                self.apply_contour_angle(&step.contour, &mut step.start_positions, diagnostics);
            step.moved |= angle_moves;
            angle_open = opened;
        }
        let motion = self.state.groups[1]
            .map(GCode::name)
            .unwrap_or(Cow::Borrowed(""));
        let arc = self.resolve_path(line, &motion, &mut step, polar_circle_centre, diagnostics);
        self.finish_block(line, block, step, &motion, arc, angle_open, diagnostics)
    }

    /// A label may be the target of a backward jump and a structure keyword opens a loop or branch:
    /// from here on the control may run blocks again or skip them, so values assigned from here on
    /// (this block included) are not followed in program order.
    #[inline]
    fn note_flow_structures(&mut self, block: &Block, statements: &[Statement]) {
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
    }

    /// Applies the block's modal G functions, collects its non-modal ones, activates a selected
    /// settable offset and keeps the positions before the block.
    #[inline]
    fn begin_step<'s>(
        &mut self,
        statements: &'s [Statement],
        call_followed: bool,
    ) -> BlockStep<'s> {
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
        BlockStep {
            statements,
            call_followed,
            functions,
            units_before,
            unit_word,
            feed_type_before,
            start_positions,
            moved: false,
            feed_in_block: None,
            polar: PolarWords::default(),
            plane_before: self.state.plane_index(),
            forget_after: forget_for_frames,
            locals_may_change: forget_for_frames,
            frame_data_changed: forget_for_frames,
            circle_words: CircleWords::default(),
            contour: ContourWords::default(),
        }
    }

    /// What follows from the block once its path is known: the findings about the move, the machine
    /// set-points, the corner request, the timing, and what a call forgets. Returns whether the block
    /// moved axes.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn finish_block(
        &mut self,
        line: &str,
        block: &Block,
        step: BlockStep,
        motion: &str,
        arc: Option<crate::analysis::circle::Circle>,
        angle_open: bool,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> bool {
        let statements = step.statements;
        let functions = &step.functions;
        let moves_axes = step.moves_axes();
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
        if functions.machine_coordinates
            && crate::analysis::engine::block_words::find_word(statements, AddressKind::Axis)
                .is_none()
        {
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
        if moves_axes {
            self.last_contour = self.contour_request(&step.contour, angle_open, diagnostics);
        }
        self.last_arc = arc;
        self.start_positions = step.start_positions;
        let feed_move = moves_axes && matches!(motion, "G1" | "G2" | "G3" | "CIP" | "CT");
        self.observe_timing(line, block, step.feed_type_before, feed_move, diagnostics);
        if step.forget_after {
            self.forget_what_a_call_may_change(step.frame_data_changed, step.locals_may_change);
        }
        moves_axes
    }

    /// Values that overflowed (`X1EX308` twice under G91, a frame scaled beyond the range of a double)
    /// are unknown, never infinity or NaN: a number shown must be one the control could reach.
    pub(super) fn forget_non_finite(&mut self) {
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
            if let Pole::At(first, second) = *pole {
                if !(first.is_finite() && second.is_finite()) {
                    *pole = Pole::Unknown;
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
}
