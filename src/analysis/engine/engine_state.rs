//! The engine's own state: the `Engine` struct, what it remembers about the program beyond the modal
//! state (`ProgramMemory`), its construction and the controls the interpreter and the document use
//! between blocks (following calls, forgetting what a call may change, restoring SAVE).

use crate::analysis::axis_lookup::AxisLookup;
use crate::analysis::engine::corner_requests::ContourRequest;
use crate::analysis::engine::timing::Dwell;
use crate::analysis::state::ModalState;
use crate::config::MachineConfig;
use crate::syntax::gcodes::GCode;
use std::sync::Arc;

/// Interprets blocks one after the other.
pub struct Engine<'a> {
    pub(super) config: &'a MachineConfig,
    pub state: ModalState,
    /// Set once a jump or control structure has been passed: evaluation in program order may no longer
    /// match the control's path through the program.
    pub(super) flow_uncertain: bool,
    /// Whether a feed move without F has already been reported (alarm 10860 is reported once).
    pub(super) missing_feed_reported: bool,
    /// The configured axis names, shared by every move instead of copied into each.
    pub(super) axis_names: Vec<Arc<str>>,
    /// The positions before the current block, kept in one buffer for all blocks.
    pub(super) start_positions: Vec<Option<f64>>,
    /// The circle of the block last applied, for its move.
    pub(super) last_arc: Option<crate::analysis::circle::Circle>,
    /// What the block last applied asks of its corner (reference §14), for its move.
    pub(super) last_contour: Option<Box<ContourRequest>>,
    /// The geometry slot (X, Y, Z) of each configured axis, for frames.
    pub(super) slots: crate::analysis::machine::AxisSlots,
    /// Per axis, how the current block wrote it: 0 not, 1 in workpiece coordinates, 2 as a machine
    /// position (G53/G153/SUPA). One buffer for all blocks.
    pub(super) written: Vec<u8>,
    /// The settable frame whose stored data the program wrote while it was active, until it is
    /// selected again (the data are not active yet, reference §7.4).
    pub(super) stale_offset_data: Option<u8>,
    /// The direction of the path at the end of the last move, in the plane (by index) it moved in,
    /// for CT; `None` when unknown.
    pub(super) tangent: Option<(usize, (f64, f64))>,
    /// How many macro expansions the current block is inside of.
    pub(super) expansion_depth: u8,
    /// What the engine remembers about the program beyond the modal state.
    pub(super) memory: ProgramMemory,
    /// The configuration indexes of the first and second axis of G17, G18 and G19.
    pub(super) plane_axis_cache: [(Option<usize>, Option<usize>); 3],
    /// The axis of each axis word, by its letter for the common words.
    pub(super) axes: AxisLookup,
    /// Set by the interpreter, which follows labels, jumps and control structures itself: they do not
    /// make values uncertain then.
    pub(super) executing: bool,
    /// Set by the interpreter for one block whose call it runs itself (the callee was found): the call
    /// then forgets nothing, since the callee's own blocks say what changes.
    pub(super) call_followed: bool,
    /// The dwell of the block last applied, if it was a `G4` block.
    pub(super) last_dwell: Option<Dwell>,
}
/// What the engine remembers about the program beyond the modal state: its macros and what the
/// findings of §9.2 need to know about earlier blocks.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct ProgramMemory {
    /// Macros defined so far with `DEFINE name AS body`: upper-case name and body text.
    pub(super) macros: Vec<(String, String)>,
    /// A pole or plane change since the last polar move: AP and RP must be written again.
    pub(super) pole_changed: bool,
    /// Which unit functions the program has programmed: 1 for G70/G71, 2 for G700/G710.
    pub(super) unit_kinds_used: u8,
    pub(super) feed_programmed: bool,
    pub(super) unit_mix_reported: bool,
    /// The geometry slots (X, Y, Z) whose mapping a rotating, scaling or mirroring frame change has
    /// altered since the last move.
    pub(super) rotated_slots: [bool; 3],
    /// Whether diameter programming or G96 without a transverse axis has been reported (once).
    pub(super) transverse_reported: bool,
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
    #[inline]
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
    pub(super) fn forget_what_a_call_may_change(&mut self, frame_data_changed: bool, locals: bool) {
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
    #[inline]
    pub fn axis_lookup(&self) -> &AxisLookup {
        &self.axes
    }

    /// Whether a label, jump or control structure has been passed, so that values may not follow the
    /// control's path through the program.
    #[inline]
    pub fn flow_uncertain(&self) -> bool {
        self.flow_uncertain
    }

    /// The state comes from a caller the engine cannot see: a feed may be active, so a feed move without
    /// F is not reported.
    pub fn assume_inherited_state(&mut self) {
        self.missing_feed_reported = true;
        self.state.forget_inherited_groups();
    }
}
