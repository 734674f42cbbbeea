//! Settable work offsets (G500, G54 ... G57, G505 ... G599): the stored frame data `$P_UIFR[n]` as the
//! configuration gives them and as the program overwrites them, and which data a G function of group 8
//! activates (reference §7.1, §7.4). Only translations are followed; data holding a rotation, scale or
//! mirroring, or written with values the analysis cannot evaluate, are unknown.

use crate::config::MachineConfig;
use crate::syntax::gcodes::GCode;
use std::collections::BTreeMap;

/// The number of settable frames `$P_UIFR[0]` ... `$P_UIFR[99]`.
pub const SETTABLE_FRAME_COUNT: u8 = 100;

/// The `$P_UIFR` index a G function of group 8 activates: 0 for G500, 1 to 4 for G54 to G57, 5 to 99
/// for G505 to G599.
pub fn frame_index(code: GCode) -> Option<u8> {
    (code.group() == 8)
        .then(|| code.index_in_group().checked_sub(1))
        .flatten()
}

/// The G function that activates settable frame `index`, for messages.
pub fn frame_name(index: u8) -> String {
    match index {
        0 => "G500".to_string(),
        1..=4 => format!("G{}", 53 + u16::from(index)),
        _ => format!("G{}", 500 + u16::from(index)),
    }
}

/// The stored data of the settable frames as far as the program has changed them; frames the program
/// has not written keep the configured values.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SettableData {
    /// Frames written by the program: the translation per configured axis, `None` where unknown.
    written: BTreeMap<u8, Vec<Option<f64>>>,
    /// Set when data may have changed in a way the analysis cannot follow (a write to an unknown index,
    /// a call, a write to a basic or system frame): every frame not written since is unknown.
    unknown: bool,
}

impl SettableData {
    /// The translation per configured axis that frame `index` holds, `None` where unknown.
    pub fn values(&self, config: &MachineConfig, index: u8) -> Vec<Option<f64>> {
        if let Some(values) = self.written.get(&index) {
            return values.clone();
        }
        if self.unknown {
            return vec![None; config.axes.len()];
        }
        match config.settable_offset(index) {
            Some(listed) => config
                .axes
                .iter()
                .map(|axis| {
                    Some(
                        listed
                            .iter()
                            .find(|(name, _)| name.eq_ignore_ascii_case(&axis.name))
                            .map_or(0.0, |(_, value)| *value),
                    )
                })
                .collect(),
            None => vec![None; config.axes.len()],
        }
    }

    /// Frame `index` now holds `values` (per configured axis).
    pub fn write(&mut self, index: u8, values: Vec<Option<f64>>) {
        self.written.insert(index, values);
    }

    /// Every frame's data may have changed.
    pub fn forget_all(&mut self) {
        self.written.clear();
        self.unknown = true;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn group_8_functions_select_their_frames() {
        // The names are `G` and a number; `state` reads written names, and is not imported here because
        // it imports this file.
        let index =
            |name: &str| frame_index(GCode::from_number(name[1..].parse().unwrap()).unwrap());
        assert_eq!(index("G500"), Some(0));
        assert_eq!(index("G54"), Some(1));
        assert_eq!(index("G57"), Some(4));
        assert_eq!(index("G505"), Some(5));
        assert_eq!(index("G599"), Some(99));
        assert_eq!(index("G90"), None);
        assert_eq!(frame_name(0), "G500");
        assert_eq!(frame_name(1), "G54");
        assert_eq!(frame_name(99), "G599");
    }

    #[test]
    fn configured_data_until_the_program_writes() {
        let mut config = MachineConfig::mill();
        config
            .settable_offsets
            .insert(1, vec![("X".to_string(), 100.0)]);
        let mut data = SettableData::default();
        assert_eq!(
            data.values(&config, 1)[..3],
            [Some(100.0), Some(0.0), Some(0.0)]
        );
        assert_eq!(data.values(&config, 0)[0], Some(0.0));
        assert_eq!(data.values(&config, 2)[0], None);
        data.write(2, vec![Some(5.0); 6]);
        assert_eq!(data.values(&config, 2)[0], Some(5.0));
        data.forget_all();
        assert_eq!(data.values(&config, 1)[0], None);
        assert_eq!(data.values(&config, 0)[0], None);
    }
}
