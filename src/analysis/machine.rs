//! Between workpiece and machine coordinates: `machine = offset + F(workpiece)` on X, Y and Z, where F is
//! the programmable frame and the offset the active settable one, and `machine = offset + workpiece` on
//! the other axes (reference §7.3; basic and system frames are identity, tool offsets are not included).
//! The way back re-expresses the machine set-point in new frames after a frame or offset change, which
//! moves nothing by itself (reference §3.8, §3.9).

use crate::analysis::state::ModalState;
use crate::config::MachineConfig;

/// The geometry slot (0 = X, 1 = Y, 2 = Z) of each configured axis, `None` for the other axes.
#[derive(Debug, Clone)]
pub struct AxisSlots {
    slots: Vec<Option<usize>>,
}

impl AxisSlots {
    pub fn new(config: &MachineConfig) -> AxisSlots {
        AxisSlots {
            slots: config
                .axes
                .iter()
                .map(|axis| {
                    ["X", "Y", "Z"]
                        .iter()
                        .position(|name| axis.name.eq_ignore_ascii_case(name))
                })
                .collect(),
        }
    }

    pub fn slot(&self, index: usize) -> Option<usize> {
        self.slots.get(index).copied().flatten()
    }

    /// The X, Y, Z values among `values` (one per configured axis); `None` where unknown or absent.
    fn geometry_point(&self, values: &[Option<f64>]) -> [Option<f64>; 3] {
        let mut point = [None; 3];
        for (index, slot) in self.slots.iter().enumerate() {
            if let Some(slot) = slot {
                point[*slot] = values[index];
            }
        }
        point
    }
}

/// The machine value of axis `index` for the workpiece set-points of `state`, when it is known.
pub fn machine_value(state: &ModalState, slots: &AxisSlots, index: usize) -> Option<f64> {
    let offset = state.offset[index]?;
    match slots.slot(index) {
        Some(slot) => {
            let point = slots.geometry_point(&state.positions);
            Some(offset + state.frame?.apply_axis(slot, point)?)
        }
        None => Some(offset + state.positions[index]?),
    }
}

/// After a frame or offset change: the workpiece set-point of every axis (only X, Y, Z when
/// `geometry_only`) becomes its unchanged machine set-point expressed in the new frames. The last
/// programmed values stay, for G91 under SD42440 = 1.
pub fn reexpress(state: &mut ModalState, slots: &AxisSlots, geometry_only: bool) {
    let inverse = state.frame.and_then(|frame| frame.inverse());
    let mut relative = [None; 3];
    for index in 0..state.machine.len() {
        if let Some(slot) = slots.slot(index) {
            relative[slot] = state.machine[index]
                .zip(state.offset[index])
                .map(|(machine, offset)| machine - offset);
        }
    }
    for index in 0..state.machine.len() {
        let value = match slots.slot(index) {
            Some(slot) => inverse.and_then(|inverse| inverse.apply_axis(slot, relative)),
            None if geometry_only => continue,
            None => state.machine[index]
                .zip(state.offset[index])
                .map(|(machine, offset)| machine - offset),
        };
        if value.is_some() || state.positions[index].is_some() {
            state.touched[index] = true;
        }
        state.positions[index] = value;
    }
}

/// After a block: the machine set-point of the axes it moved. `written` tells per axis whether the
/// block programmed it in workpiece coordinates (1) or as a machine position (2, G53/G153/SUPA, whose
/// machine value is already set). A geometry axis the block did not program moves too when the frame
/// mixes it with one that was (a rotation), or when the frame is unknown.
pub fn update_after_block(state: &mut ModalState, slots: &AxisSlots, written: &[u8]) {
    let mut written_slots = [false; 3];
    for (index, kind) in written.iter().enumerate() {
        if let (1, Some(slot)) = (*kind, slots.slot(index)) {
            written_slots[slot] = true;
        }
    }
    for (index, kind) in written.iter().enumerate() {
        let affected = match (*kind, slots.slot(index)) {
            (1, _) => true,
            (0, Some(slot)) => (0..3).any(|other| {
                written_slots[other]
                    && state
                        .frame
                        .is_none_or(|frame| frame.matrix[slot][other] != 0.0)
            }),
            _ => false,
        };
        if affected {
            state.machine[index] = machine_value(state, slots, index);
        }
    }
}

/// The machine positions programmed in a G53/G153/SUPA block (`written` 2), stored in workpiece
/// coordinates of the active frames (reference §3.8): their set-points and last programmed values.
pub fn store_machine_targets(state: &mut ModalState, slots: &AxisSlots, written: &[u8]) {
    if !written.contains(&2) {
        return;
    }
    let saved = state.positions.clone();
    reexpress(state, slots, false);
    let expressed = std::mem::replace(&mut state.positions, saved);
    for (index, kind) in written.iter().enumerate() {
        if *kind == 2 {
            state.program(index, expressed[index]);
        }
    }
}
