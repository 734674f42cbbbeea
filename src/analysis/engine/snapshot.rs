//! Checkpoints of the engine: `EngineSnapshot` (what the engine carries from one block to the next,
//! detached from the configuration), taking one, comparing with one, continuing from one, and the
//! `PositionShift` by which an edit moved every position.

use crate::analysis::engine::engine_state::{Engine, ProgramMemory};
use crate::analysis::state::ModalState;
use crate::config::MachineConfig;

/// What an [`Engine`] carries from one block to the next, detached from the configuration: a
/// checkpoint from which the analysis of a document is replayed after an edit or for a hover. Two
/// equal snapshots make every later block resolve the same way.
#[derive(Debug, Clone, PartialEq)]
pub struct EngineSnapshot {
    pub(super) state: ModalState,
    pub(super) flow_uncertain: bool,
    pub(super) missing_feed_reported: bool,
    pub(super) stale_offset_data: Option<u8>,
    pub(super) tangent: Option<(usize, (f64, f64))>,
    pub(super) memory: ProgramMemory,
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
    /// Whether a label, jump or control structure had been passed when the snapshot was taken.
    pub fn flow_uncertain(&self) -> bool {
        self.flow_uncertain
    }

    /// Moves every known position by `shift`.
    pub fn shift_positions(&mut self, shift: &PositionShift) {
        add_to_known(&mut self.state.positions, &shift.positions);
        add_to_known(&mut self.state.programmed, &shift.programmed);
        add_to_known(&mut self.state.machine, &shift.machine);
    }
}

pub(super) fn add_to_known(values: &mut [Option<f64>], deltas: &[f64]) {
    for (value, delta) in values.iter_mut().zip(deltas) {
        if let Some(value) = value {
            *value += delta;
        }
    }
}

/// `now - then` per axis where both are known, 0 where both are unknown; `None` when an axis is known
/// in one and not the other.
pub(super) fn difference(now: &[Option<f64>], then: &[Option<f64>]) -> Option<Vec<f64>> {
    now.iter()
        .zip(then)
        .map(|pair| match pair {
            (Some(now), Some(then)) => Some(now - then),
            (None, None) => Some(0.0),
            _ => None,
        })
        .collect()
}

impl<'a> Engine<'a> {
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
}
