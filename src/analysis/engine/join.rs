//! Where two ways through a program meet (the two branches of an `IF` whose condition is not known, a
//! jump that may or may not be taken), the interpreter continues with one state: what is equal on
//! every way stays known, what differs becomes unknown. Joining only ever forgets, so repeated joins
//! reach a fixed point.

use crate::analysis::engine::engine_state::ProgramMemory;
use crate::analysis::engine::snapshot::EngineSnapshot;
use crate::analysis::state::{ModalState, Pole};

/// `value` stays only when `other` holds the same.
fn keep_if_equal<T: PartialEq>(value: &mut Option<T>, other: &Option<T>) {
    if value != other {
        *value = None;
    }
}

fn join_values(values: &mut [Option<f64>], others: &[Option<f64>]) {
    for (value, other) in values.iter_mut().zip(others) {
        keep_if_equal(value, other);
    }
}

impl ModalState {
    /// Forgets what differs from `other`.
    pub fn join(&mut self, other: &ModalState) {
        for (group, other_group) in self.groups.iter_mut().zip(&other.groups) {
            keep_if_equal(group, other_group);
        }
        join_values(&mut self.positions, &other.positions);
        join_values(&mut self.programmed, &other.programmed);
        join_values(&mut self.machine, &other.machine);
        join_values(&mut self.offset, &other.offset);
        if self.settable_data != other.settable_data {
            self.settable_data.forget_all();
        }
        for (touched, other_touched) in self.touched.iter_mut().zip(&other.touched) {
            *touched |= *other_touched;
        }
        keep_if_equal(&mut self.feed, &other.feed);
        self.variables.join(&other.variables);
        keep_if_equal(&mut self.frame, &other.frame);
        keep_if_equal(&mut self.fine_translation, &other.fine_translation);
        for (pole, other_pole) in self.poles.iter_mut().zip(&other.poles) {
            if pole != other_pole {
                *pole = Pole::Unknown;
            }
        }
        keep_if_equal(&mut self.polar_angle, &other.polar_angle);
        keep_if_equal(&mut self.polar_radius, &other.polar_radius);
        keep_if_equal(&mut self.rounding_modal, &other.rounding_modal);
        keep_if_equal(&mut self.chamfer_feed_modal, &other.chamfer_feed_modal);
        keep_if_equal(&mut self.open_angle, &other.open_angle);
        self.spindle.join(&other.spindle);
    }
}

impl ProgramMemory {
    /// Joins what the findings remember so that a way that met a condition keeps it: a finding made
    /// on one way is not made again on the other.
    fn join(&mut self, other: &ProgramMemory) {
        if self.macros != other.macros {
            // Macros are defined in program order; ways that defined different ones keep the common
            // start only.
            let common = self
                .macros
                .iter()
                .zip(&other.macros)
                .take_while(|(mine, theirs)| mine == theirs)
                .count();
            self.macros.truncate(common);
        }
        self.pole_changed |= other.pole_changed;
        self.unit_kinds_used |= other.unit_kinds_used;
        self.feed_programmed &= other.feed_programmed;
        self.unit_mix_reported |= other.unit_mix_reported;
        for (rotated, other_rotated) in self.rotated_slots.iter_mut().zip(&other.rotated_slots) {
            *rotated |= *other_rotated;
        }
    }
}

impl EngineSnapshot {
    /// Forgets what differs from `other`: the state where two ways of the program meet.
    pub fn join(&mut self, other: &EngineSnapshot) {
        self.state.join(&other.state);
        self.flow_uncertain |= other.flow_uncertain;
        self.missing_feed_reported |= other.missing_feed_reported;
        keep_if_equal(&mut self.stale_offset_data, &other.stale_offset_data);
        keep_if_equal(&mut self.tangent, &other.tangent);
        self.memory.join(&other.memory);
    }
}

#[cfg(test)]
mod tests {
    use crate::analysis::engine::engine_state::Engine;
    use crate::config::MachineConfig;
    use crate::syntax::{parse_line, SyntaxContext};

    fn run(engine: &mut Engine, line: &str) {
        let (block, _) = parse_line(line, &SyntaxContext::new(&MachineConfig::default()));
        engine.step(line, &block, &mut Vec::new());
    }

    #[test]
    fn what_differs_becomes_unknown_and_the_rest_stays() {
        let config = MachineConfig::default();
        let mut first = Engine::new(&config);
        run(&mut first, "G90 G0 X10 Y20 Z5 R1=3 R2=4");
        let mut second = Engine::from_snapshot(&config, first.snapshot());
        run(&mut first, "G1 X11 F100 R2=5");
        run(&mut second, "G1 X12 F100");
        let mut joined = first.snapshot();
        joined.join(&second.snapshot());
        let engine = Engine::from_snapshot(&config, joined);
        let x = config
            .axes
            .iter()
            .position(|axis| axis.name == "X")
            .unwrap();
        let y = config
            .axes
            .iter()
            .position(|axis| axis.name == "Y")
            .unwrap();
        assert_eq!(engine.state.positions[x], None);
        assert_eq!(engine.state.positions[y], Some(20.0));
        assert_eq!(engine.state.feed, Some(100.0));
        assert_eq!(engine.state.variables.r_parameter(1), Some(3.0));
        assert_eq!(engine.state.variables.r_parameter(2), None);
        assert_eq!(
            engine.state.groups[1].map(|code| code.name().to_string()),
            Some("G1".to_string())
        );
    }
}
