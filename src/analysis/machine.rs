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

/// What a frame or offset change replaced, for [`reexpress`].
pub enum Replaced {
    /// The programmable frame before the change (the settable offset stayed).
    Frame(Option<crate::analysis::frame::Frame>),
    /// The settable offset before the change (the programmable frame stayed).
    Offset(Vec<Option<f64>>),
}

/// After a frame or offset change: the workpiece set-point of every axis the change concerns (X, Y, Z
/// for the programmable frame, all axes for the offset) becomes its unchanged machine set-point
/// expressed in the new frames. The machine set-point itself may be unknown: a change of the
/// programmable frame alone is followed from the workpiece values, since the offset outside it stays.
/// The last programmed values stay, for G91 under SD42440 = 1.
pub fn reexpress(state: &mut ModalState, slots: &AxisSlots, replaced: Replaced) {
    let (old_frame, old_offset, offset_changed) = match &replaced {
        Replaced::Frame(frame) => (*frame, &state.offset, false),
        Replaced::Offset(offset) => (state.frame, offset, true),
    };
    let difference = |a: Option<f64>, b: Option<f64>| a.zip(b).map(|(a, b)| a - b);
    let workpiece = slots.geometry_point(&state.positions);
    // Each axis in the coordinates between the settable offset and the programmable frame, before and
    // after the change.
    let mut parent = vec![None; state.machine.len()];
    for (index, value) in parent.iter_mut().enumerate() {
        let slot = slots.slot(index);
        if slot.is_none() && !offset_changed {
            continue;
        }
        let before = difference(state.machine[index], old_offset[index]).or_else(|| match slot {
            Some(slot) => old_frame.and_then(|frame| frame.apply_axis(slot, workpiece)),
            None => state.positions[index],
        });
        *value = if offset_changed {
            let machine = state.machine[index].or_else(|| {
                before
                    .zip(old_offset[index])
                    .map(|(before, offset)| before + offset)
            });
            difference(machine, state.offset[index])
        } else {
            before
        };
    }
    let inverse = state.frame.and_then(|frame| frame.inverse());
    let parent_point = slots.geometry_point(&parent);
    for (index, value) in parent.iter().enumerate() {
        let new = match slots.slot(index) {
            Some(slot) => inverse.and_then(|inverse| inverse.apply_axis(slot, parent_point)),
            None if offset_changed => *value,
            None => continue,
        };
        if new.is_some() || state.positions[index].is_some() {
            state.touched[index] = true;
        }
        state.positions[index] = new;
    }
}

/// After a block: the machine set-point of the axes it moved. `written` tells per axis whether the
/// block programmed it in workpiece coordinates (1) or as a machine position (2, G53/G153/SUPA, whose
/// machine value is already set). A geometry axis the block did not program moves too when the frame
/// mixes it with one that was (a rotation), or when the frame is unknown.
pub fn update_after_block(state: &mut ModalState, slots: &AxisSlots, written: &[u8]) {
    // `written` and the slots have one entry per configured axis; walking them side by side, rather
    // than by index, spares the bounds checks of this function that runs after every block.
    debug_assert_eq!(written.len(), slots.slots.len());
    let mut written_slots = [false; 3];
    let mut any_written = false;
    for (kind, slot) in written.iter().zip(&slots.slots) {
        if *kind == 1 {
            any_written = true;
            if let Some(slot) = slot {
                written_slots[*slot] = true;
            }
        }
    }
    if !any_written {
        return;
    }
    // Which geometry slots the block moves: those written, and under a frame that mixes axes (or an
    // unknown one) those mixed with a written one.
    let mut moved_slots = written_slots;
    match state.frame {
        Some(frame) => {
            for (slot, moved) in moved_slots.iter_mut().enumerate() {
                *moved |=
                    (0..3).any(|other| written_slots[other] && frame.matrix[slot][other] != 0.0);
            }
        }
        None => {
            if written_slots.contains(&true) {
                moved_slots = [true; 3];
            }
        }
    }
    // Without a known frame a moved geometry axis gets an unknown machine position: the point is
    // needed only with a frame.
    let point = match state.frame {
        Some(_) if moved_slots.contains(&true) => slots.geometry_point(&state.positions),
        _ => [None; 3],
    };
    let frame = state.frame;
    let axes = written
        .iter()
        .zip(&slots.slots)
        .zip(&state.positions)
        .zip(&state.offset);
    for ((((kind, slot), position), offset), machine) in axes.zip(&mut state.machine) {
        let relative = match (*kind, *slot) {
            (2, _) => continue,
            (_, Some(slot)) if moved_slots[slot] => {
                frame.and_then(|frame| frame.apply_axis(slot, point))
            }
            (1, None) => *position,
            _ => continue,
        };
        *machine = relative
            .zip(*offset)
            .map(|(relative, offset)| relative + offset);
    }
}

/// The machine positions programmed in a G53/G153/SUPA block (`written` 2), stored in workpiece
/// coordinates of the active frames (reference §3.8): their set-points and last programmed values.
pub fn store_machine_targets(state: &mut ModalState, slots: &AxisSlots, written: &[u8]) {
    if !written.contains(&2) {
        return;
    }
    let saved = state.positions.clone();
    let offset = state.offset.clone();
    reexpress(state, slots, Replaced::Offset(offset));
    let expressed = std::mem::replace(&mut state.positions, saved);
    for (index, kind) in written.iter().enumerate() {
        if *kind == 2 {
            state.program(index, expressed[index]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::frame::Frame;

    fn state_at(config: &MachineConfig, machine: [f64; 3]) -> ModalState {
        let mut state = ModalState::reset(config);
        for (index, value) in machine.iter().enumerate() {
            state.program(index, Some(*value));
            state.machine[index] = Some(*value);
        }
        state
    }

    #[test]
    fn a_frame_change_keeps_the_machine_position() {
        let config = MachineConfig::mill();
        let slots = AxisSlots::new(&config);
        let mut state = state_at(&config, [10.0, 0.0, 5.0]);
        let before = state.frame;
        state.frame = Some(Frame::rotation_in_plane(0, 1, 90.0));
        reexpress(&mut state, &slots, Replaced::Frame(before));
        // Machine (10, 0) seen in a frame turned by 90°: (0, -10); Z and the last programmed values stay.
        assert_eq!(state.positions[..3], [Some(0.0), Some(-10.0), Some(5.0)]);
        assert_eq!(state.programmed[0], Some(10.0));
        // Programming X alone moves Y in the machine too: the frame mixes them, Z is not touched.
        state.program(0, Some(10.0));
        update_after_block(&mut state, &slots, &[1, 0, 0, 0, 0, 0]);
        assert_eq!(state.machine[..3], [Some(10.0), Some(10.0), Some(5.0)]);
    }

    #[test]
    fn an_unknown_offset_leaves_unmoved_axes_alone() {
        let config = MachineConfig::mill();
        let slots = AxisSlots::new(&config);
        let mut state = state_at(&config, [1.0, 2.0, 3.0]);
        let before = std::mem::replace(&mut state.offset, vec![None; config.axes.len()]);
        reexpress(&mut state, &slots, Replaced::Offset(before));
        assert_eq!(state.positions[..3], [None, None, None]);
        state.program(0, Some(4.0));
        update_after_block(&mut state, &slots, &[1, 0, 0, 0, 0, 0]);
        assert_eq!(state.machine[..3], [None, Some(2.0), Some(3.0)]);
        // A G53 target is stored in workpiece coordinates of the active frames, here unknown.
        state.machine[1] = Some(0.0);
        store_machine_targets(&mut state, &slots, &[0, 2, 0, 0, 0, 0]);
        assert_eq!(state.positions[1], None);
        assert_eq!(state.machine[1], Some(0.0));
    }
}
