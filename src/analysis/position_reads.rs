//! Which axis positions a block reads absolutely, so that an edit that moves every later position by
//! the same amount (a changed increment in a G91 program) can carry that difference across blocks
//! without reading them again.
//!
//! A block is *shift-safe* for a set of axes when moving the position of those axes by a difference
//! before the block moves them by the same difference after it, and leaves its findings unchanged:
//! it reads those axes only incrementally. The classification is conservative: anything beyond plain
//! G0/G1/G2/G3 moves with incremental words, feeds, spindles, tools, comments and variables counts
//! as reading every axis absolutely.

use crate::analysis::axis_lookup::AxisLookup;
use crate::analysis::engine::snapshot::PositionShift;
use crate::analysis::state::ModalState;
use crate::config::{AxisKind, MachineConfig};
use crate::syntax::ast::{AddressKind, Block, Modifier, NamedAddress, Statement};
use crate::syntax::gcodes::known;

/// The flag of a block that is not shift-safe for any axis.
pub const READS_ALL: u8 = 0x80;
/// Axes beyond this index are never shifted (their block counts as reading everything).
pub const SHIFTABLE_AXES: usize = 7;

/// The axes (bit per configuration index below [`SHIFTABLE_AXES`]) that `block` reads or sets
/// absolutely, or [`READS_ALL`]. `after` is the state after the block (its own G90/G91 included);
/// `axes` finds the configured axis of each word.
pub fn position_reads(
    config: &MachineConfig,
    axes: &AxisLookup,
    line: &str,
    block: &Block,
    after: &ModalState,
) -> u8 {
    let motion_is_plain = after.groups[1]
        .is_some_and(|code| matches!(code, known::G0 | known::G1 | known::G2 | known::G3));
    let mut mask = 0u8;
    for statement in block.interpreted_statements() {
        match statement {
            Statement::GCode { code, .. } => {
                // Non-modal functions (frames, poles, G53, dwell, reference points) and the modal
                // groups that place the coordinate system (settable offsets, PAROT/TOROT) are not
                // followed here.
                if !code.is_modal() || matches!(code.group(), 8 | 52 | 53) {
                    return READS_ALL;
                }
            }
            Statement::Address(word) => match word.kind {
                AddressKind::Axis => {
                    let Some(index) = axes.index(config, line, word) else {
                        continue;
                    };
                    let linear = matches!(
                        config.axes[index].kind,
                        AxisKind::Linear | AxisKind::Transverse
                    );
                    if index >= SHIFTABLE_AXES || !linear || !motion_is_plain {
                        return READS_ALL;
                    }
                    let incremental = match word.value.modifier {
                        Some((Modifier::Ic | Modifier::Dic | Modifier::Ric, _)) => true,
                        Some(_) => false,
                        None => after.is_incremental() == Some(true),
                    };
                    if !incremental {
                        mask |= 1 << index;
                    }
                }
                AddressKind::Interpolation => {
                    // I/J/K are incremental from the start point unless written `=AC(..)`; I1, J1,
                    // K1 (CIP) are end-point-like.
                    if word.value.modifier.is_some() || word.extension.is_some() {
                        return READS_ALL;
                    }
                }
                AddressKind::Named(
                    NamedAddress::CircleRadius | NamedAddress::OpeningAngle | NamedAddress::Turns,
                )
                | AddressKind::Feed
                | AddressKind::Spindle
                | AddressKind::Tool
                | AddressKind::ToolEdge
                | AddressKind::MFunction
                | AddressKind::HFunction => {}
                _ => return READS_ALL,
            },
            Statement::Assignment { .. }
            | Statement::Definition { .. }
            | Statement::Structure { .. }
            | Statement::CaseBranch { .. }
            | Statement::Jump { .. } => {}
            _ => return READS_ALL,
        }
    }
    mask
}

/// The axes (bit per index) whose workpiece or programmed position a shift moves; `None` when it
/// moves an axis that is never shifted. Machine positions follow from those through the frames.
pub fn shifted_axes(config: &MachineConfig, shift: &PositionShift) -> Option<u8> {
    let mut mask = 0u8;
    let moved = shift.positions.iter().zip(&shift.programmed);
    for (index, delta) in moved
        .map(|(position, programmed)| {
            if *position != 0.0 {
                position
            } else {
                programmed
            }
        })
        .enumerate()
    {
        if *delta == 0.0 {
            continue;
        }
        let linear = matches!(
            config.axes[index].kind,
            AxisKind::Linear | AxisKind::Transverse
        );
        if index >= SHIFTABLE_AXES || !linear || !delta.is_finite() {
            return None;
        }
        mask |= 1 << index;
    }
    Some(mask)
}
