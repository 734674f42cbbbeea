//! The assumed entry state of a subprogram analysed on its own (docs/execution.md): which G groups
//! still have their assumed reset value on a way, and which axes' values rest on them.

use crate::analysis::engine::engine_state::Engine;
use crate::analysis::execution::interpreter::Interpreter;
use crate::analysis::execution::paths::Control;
use crate::config::MachineConfig;
use crate::syntax::ast::{AddressKind, Block, Modifier, NamedAddress, Statement};

/// The G groups a subprogram analysed on its own assumes from the reset state, with the names the
/// preview uses: motion, plane, units, distance, feed type, diameter programming.
pub(super) const ASSUMED_GROUPS: [(u8, &str); 6] = [
    (1, "motion"),
    (6, "plane"),
    (13, "units"),
    (14, "distance"),
    (15, "feed_type"),
    (29, "diameter"),
];

/// The groups whose assumed value changes how every axis value reads: units and distance.
const POSITION_GROUPS: u64 = 1 << 13 | 1 << 14;
/// Diameter programming changes how transverse axes read.
const DIAMETER_GROUP: u64 = 1 << 29;
/// The plane changes how polar values (AP, RP) read.
const PLANE_GROUP: u64 = 1 << 6;

impl<'a, 's> Interpreter<'a, 's> {
    /// Follows which groups still have their assumed value and which axes rest on them.
    pub(super) fn update_assumptions(
        &self,
        control: &mut Control,
        engine: &Engine<'a>,
        line: &str,
        block: &Block,
    ) {
        if control.assumed_groups == 0 && control.assumed_axes == 0 {
            return;
        }
        let statements = block.interpreted_statements();
        for statement in statements {
            if let Statement::GCode { code, .. } = statement {
                if code.is_modal() {
                    control.assumed_groups &= !(1u64 << code.group());
                }
            }
        }
        let polar = statements.iter().any(|statement| {
            matches!(statement, Statement::Address(word) if matches!(
                word.kind,
                AddressKind::Named(NamedAddress::PolarAngle | NamedAddress::PolarRadius)
            ))
        });
        let depends = control.assumed_groups & POSITION_GROUPS != 0
            || (polar && control.assumed_groups & PLANE_GROUP != 0);
        let diameter = control.assumed_groups & DIAMETER_GROUP != 0;
        let written = engine.written_axes();
        let incremental_mode = engine.state.is_incremental();
        let mut incremental_axes = 0u64;
        for statement in statements {
            if let Statement::Address(word) = statement {
                if word.kind != AddressKind::Axis {
                    continue;
                }
                let Some(index) = engine.axis_lookup().index(self.config, line, word) else {
                    continue;
                };
                let incremental = match word.value.modifier.map(|(modifier, _)| modifier) {
                    Some(Modifier::Ic | Modifier::Dic | Modifier::Ric | Modifier::Cic) => true,
                    Some(_) => false,
                    None => incremental_mode != Some(false),
                };
                if incremental && index < 64 {
                    incremental_axes |= 1 << index;
                }
            }
        }
        for (index, kind) in written.iter().enumerate().take(64) {
            if *kind == 0 {
                continue;
            }
            let bit = 1u64 << index;
            let keeps = control.assumed_axes & bit != 0 && incremental_axes & bit != 0;
            let transverse = self.config.axes[index].kind == crate::config::AxisKind::Transverse;
            if depends || keeps || (diameter && transverse) {
                control.assumed_axes |= bit;
            } else {
                control.assumed_axes &= !bit;
            }
        }
    }
}

/// The groups a subprogram analysed on its own assumes, with their reset values on this machine.
pub(super) fn reset_assumptions(config: &MachineConfig) -> Vec<(u8, &'static str, String)> {
    let reset = crate::analysis::state::ModalState::reset(config);
    ASSUMED_GROUPS
        .iter()
        .filter_map(|&(group, name)| {
            let code = reset.groups[group as usize]?;
            Some((group, name, code.name().to_string()))
        })
        .collect()
}
