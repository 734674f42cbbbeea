//! The modal state the control carries from block to block: active G functions by group, the last
//! programmed position of every axis (or unknown), feed, variables, and what is known about frames.

use crate::analysis::eval::Variables;
use crate::config::MachineConfig;
use crate::syntax::gcodes::{known, GCode};

/// Number of G groups tracked (the highest group number in the table is below this).
pub const GROUP_COUNT: usize = 64;

/// The first and second axis of the planes G17, G18 and G19, in that order (reference §6.1). Circles
/// turn, and polar angles count, from the first axis toward the second.
pub const PLANE_AXES: [(&str, &str); 3] = [("X", "Y"), ("Z", "X"), ("Y", "Z")];

/// The modal state in effect between two blocks.
#[derive(Debug, Clone, PartialEq)]
pub struct ModalState {
    /// The active G function of each group, by group number; `None` for groups without a modal value.
    pub groups: [Option<GCode>; GROUP_COUNT],
    /// The workpiece set-point of each configured axis (same order as the configuration): the machine
    /// set-point expressed in the active frames (`$P_EP`), in the basic unit system and as a radius on
    /// transverse axes. It equals the last programmed value until a frame or offset changes (reference
    /// §3.9). `None` is unknown.
    pub positions: Vec<Option<f64>>,
    /// The last programmed workpiece value of each axis, which a G91 move adds to while SD42440 = 1,
    /// so that the increment also traverses a frame change (reference §3.6).
    pub programmed: Vec<Option<f64>>,
    /// The machine set-point of each axis (basic coordinate system, without tool offsets), `None` when
    /// unknown.
    pub machine: Vec<Option<f64>>,
    /// The active settable offset (group 8) per axis, `None` where unknown.
    pub offset: Vec<Option<f64>>,
    /// The stored data of the settable frames (`$P_UIFR`).
    pub settable_data: crate::analysis::offsets::SettableData,
    /// Whether an axis has been programmed or otherwise affected, so that previews leave out axes a
    /// program never uses.
    pub touched: Vec<bool>,
    /// The modal feed in the basic unit system (`None` until programmed).
    pub feed: Option<f64>,
    /// Known values of R parameters and user variables.
    pub variables: Variables,
    /// The programmable frame; `None` when it cannot be followed (a frame instruction with unknown
    /// values, a spatial rotation, a transformation, a call).
    pub frame: Option<crate::analysis::frame::Frame>,
    /// With MD18600 = 1, the fine part of the programmable translation (in the frame's parent
    /// coordinates), which `frame` includes; `None` when unknown. Meaningful only while `frame` is known.
    pub fine_translation: Option<[f64; 3]>,
    /// The polar pole of each plane (G17, G18, G19).
    pub poles: [Pole; 3],
    /// The stored polar angle AP in degrees (`None` after a pole or plane change, or when unknown).
    pub polar_angle: Option<f64>,
    /// The stored polar radius RP in the basic unit system.
    pub polar_radius: Option<f64>,
    /// The modal rounding radius `RNDM` in the basic unit system (0 = off, `None` unknown).
    pub rounding_modal: Option<f64>,
    /// The modal feed of chamfers and roundings `FRCM` in the basic unit system (0 = off).
    pub chamfer_feed_modal: Option<f64>,
    /// The first line of a two-block contour definition by angles, waiting for its second line.
    pub open_angle: Option<crate::analysis::engine::corner_requests::OpenAngle>,
    /// The master spindle and the feed type's state for the machining time.
    pub spindle: crate::analysis::engine::timing::SpindleState,
}

/// The pole of a plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Pole {
    /// No pole programmed: the WCS zero is the pole (reference §5.1).
    Undefined,
    /// In plane coordinates (first, second axis), basic unit system.
    At(f64, f64),
    /// Set somewhere the analysis cannot see (a caller, a subprogram), or from unknown values.
    Unknown,
}

/// Siemens defaults of the G groups (reference §2.2), before the machine's MD20150 values.
const SIEMENS_RESET: &[&str] = &[
    "G1",
    "G17",
    "G40",
    "G500",
    "G60",
    "G601",
    "G71",
    "G90",
    "G94",
    "DIAMOF",
    "RTLION",
    "STARTFIFO",
    "CFC",
    "NORM",
    "G450",
    "BNAT",
    "ENAT",
    "BRISK",
    "CUT2D",
    "CDOF",
    "FFWOF",
    "ORIWKS",
    "RMI",
    "ORIC",
    "WALIMON",
    "COMPOF",
    "G290",
    "PAROTOF",
    "TOROTOF",
];

/// Looks up a G function by its written name: `G18`, `G01` or `DIAMON`.
pub fn gcode_by_written_name(name: &str) -> Option<GCode> {
    let upper = name.trim().to_ascii_uppercase();
    if let Some(digits) = upper.strip_prefix('G') {
        if !digits.is_empty() && digits.bytes().all(|byte| byte.is_ascii_digit()) {
            return digits.parse().ok().and_then(GCode::from_number);
        }
    }
    GCode::from_name(&upper)
}

impl ModalState {
    /// The state after reset on this machine (MD20150), with every position unknown.
    pub fn reset(config: &MachineConfig) -> ModalState {
        let mut state = ModalState {
            groups: [None; GROUP_COUNT],
            positions: vec![None; config.axes.len()],
            programmed: vec![None; config.axes.len()],
            machine: vec![None; config.axes.len()],
            offset: vec![None; config.axes.len()],
            settable_data: Default::default(),
            touched: vec![false; config.axes.len()],
            feed: None,
            variables: Variables::default(),
            frame: Some(crate::analysis::frame::Frame::IDENTITY),
            fine_translation: Some([0.0; 3]),
            poles: [Pole::Undefined; 3],
            polar_angle: None,
            polar_radius: None,
            rounding_modal: Some(0.0),
            chamfer_feed_modal: Some(0.0),
            open_angle: None,
            spindle: Default::default(),
        };
        for name in SIEMENS_RESET {
            if let Some(code) = gcode_by_written_name(name) {
                state.set_modal(code);
            }
        }
        if !config.metric {
            if let Some(code) = gcode_by_written_name("G70") {
                state.set_modal(code);
            }
        }
        for name in &config.reset_gcodes {
            if let Some(code) = gcode_by_written_name(name) {
                if code.is_modal() {
                    state.set_modal(code);
                }
            }
        }
        state.offset = state.selected_offset(config);
        state
    }

    /// The offset the active group-8 function selects from the stored data; unknown when the group is.
    pub fn selected_offset(&self, config: &MachineConfig) -> Vec<Option<f64>> {
        match self.groups[8].and_then(crate::analysis::offsets::frame_index) {
            Some(index) => self.settable_data.values(config, index),
            None => vec![None; config.axes.len()],
        }
    }

    /// The axis is programmed to `value` (workpiece coordinates): its set-point and last programmed
    /// value.
    pub fn program(&mut self, index: usize, value: Option<f64>) {
        self.positions[index] = value;
        self.programmed[index] = value;
        self.touched[index] = true;
    }

    pub fn set_modal(&mut self, code: GCode) {
        let group = code.group() as usize;
        if group < GROUP_COUNT {
            self.groups[group] = Some(code);
        }
    }

    /// The active function of a group, by its canonical name (`"G90"`), or `""`.
    pub fn active_name(&self, group: usize) -> String {
        self.groups
            .get(group)
            .copied()
            .flatten()
            .map(|code| code.name().into_owned())
            .unwrap_or_default()
    }

    /// G91 active: `Some(true)`; G90: `Some(false)`; `None` in a subprogram that has not programmed
    /// either (the caller's mode applies, unknown here).
    pub fn is_incremental(&self) -> Option<bool> {
        self.groups[14].map(|code| code == known::G91)
    }

    // The questions below are asked several times for every axis word: each reads its group once
    // and compares the active function as a number.

    /// The factor from programmed lengths to the basic system: 25.4 for G70/G700 on a metric machine,
    /// 1/25.4 for G71/G710 on an inch machine, else 1; `None` when the unit group is unknown.
    pub fn length_factor(&self, metric_machine: bool) -> Option<f64> {
        let units = self.groups[13]?;
        let inch_programmed = matches!(units, known::G70 | known::G700);
        Some(match (metric_machine, inch_programmed) {
            (true, true) => 25.4,
            (false, false) => 1.0 / 25.4,
            _ => 1.0,
        })
    }

    /// G700/G710 also convert the feed; `None` when the unit group is unknown.
    pub fn feed_factor(&self, metric_machine: bool) -> Option<f64> {
        let units = self.groups[13]?;
        Some(
            match (metric_machine, units == known::G700, units == known::G710) {
                (true, true, _) => 25.4,
                (false, _, true) => 1.0 / 25.4,
                _ => 1.0,
            },
        )
    }

    /// How the transverse axis reads values: (absolute values are diameters, incremental values are
    /// diameters), by the modal group 29 (reference §3.7); `None` when the group is unknown.
    pub fn diameter_mode(&self) -> Option<(bool, bool)> {
        Some(match self.groups[29]? {
            known::DIAMON => (true, true),
            known::DIAM90 => (true, false),
            _ => (false, false),
        })
    }

    /// Whether the position display shows the transverse axis as a diameter; `None` when unknown.
    pub fn shows_diameter(&self) -> Option<bool> {
        let diameter = self.groups[29]?;
        Some(matches!(diameter, known::DIAMON | known::DIAM90))
    }

    /// A subprogram starts with its caller's modal state, which is not known here: the groups that
    /// decide how axis words read (motion, plane, settable offset, units, G90/G91, feed type, diameter)
    /// stay unknown until the subprogram programs them.
    pub fn forget_inherited_groups(&mut self) {
        for group in [1, 6, 8, 13, 14, 15, 29] {
            self.groups[group] = None;
        }
        self.poles = [Pole::Unknown; 3];
        // The caller's frames are not known either, nor whether it changed the stored offsets.
        self.frame = None;
        self.offset.iter_mut().for_each(|value| *value = None);
        self.settable_data.forget_all();
    }

    /// The first and second axis of the active plane (see [`PLANE_AXES`]); `None` when inherited.
    pub fn plane_axis_names(&self) -> Option<(&'static str, &'static str)> {
        self.plane_index().map(|plane| PLANE_AXES[plane])
    }

    /// The active plane as an index: 0 for G17, 1 for G18, 2 for G19; `None` when inherited.
    pub fn plane_index(&self) -> Option<usize> {
        match self.groups[6]? {
            known::G17 => Some(0),
            known::G18 => Some(1),
            known::G19 => Some(2),
            _ => None,
        }
    }

    /// Whether some machine coordinate of an axis the program uses is known.
    pub fn machine_known(&self) -> bool {
        self.machine
            .iter()
            .zip(&self.touched)
            .any(|(machine, touched)| *touched && machine.is_some())
    }

    /// Every axis position becomes unknown: a subprogram, cycle or transformation the engine cannot see
    /// may have moved anything.
    pub fn forget_positions(&mut self) {
        self.poles = [Pole::Unknown; 3];
        self.polar_angle = None;
        self.polar_radius = None;
        for (position, touched) in self.positions.iter_mut().zip(&mut self.touched) {
            if position.is_some() {
                *touched = true;
            }
            *position = None;
        }
        self.programmed.iter_mut().for_each(|value| *value = None);
        self.machine.iter_mut().for_each(|value| *value = None);
    }
}

/// How the program shows an axis value kept internally (a radius on a transverse axis): doubled
/// under diameter display (`shows_diameter`, from [`ModalState::shows_diameter`]), unknown while the
/// display mode is unknown, and unknown when doubling overflows the range of a double.
pub fn shown_value(transverse: bool, shows_diameter: Option<bool>, value: f64) -> Option<f64> {
    if !transverse {
        return Some(value);
    }
    shows_diameter
        .map(|diameter| if diameter { value * 2.0 } else { value })
        .filter(|shown| shown.is_finite())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reset_follows_the_machine_kind() {
        let mill = ModalState::reset(&MachineConfig::mill());
        assert_eq!(mill.active_name(6), "G17");
        assert_eq!(mill.active_name(14), "G90");
        assert_eq!(mill.active_name(29), "DIAMOF");
        assert!(mill.positions.iter().all(Option::is_none));
        let turn = ModalState::reset(&MachineConfig::turn());
        assert_eq!(turn.active_name(6), "G18");
        assert_eq!(turn.active_name(29), "DIAMON");
    }

    #[test]
    fn units_convert_lengths_and_feeds() {
        let mut state = ModalState::reset(&MachineConfig::mill());
        assert_eq!(state.length_factor(true), Some(1.0));
        state.set_modal(gcode_by_written_name("G70").unwrap());
        assert_eq!(state.length_factor(true), Some(25.4));
        assert_eq!(state.feed_factor(true), Some(1.0));
        state.set_modal(gcode_by_written_name("G700").unwrap());
        assert_eq!(state.feed_factor(true), Some(25.4));
        state.forget_inherited_groups();
        assert_eq!(state.length_factor(true), None);
        assert_eq!(state.is_incremental(), None);
    }
}
