//! The machine configuration as plain data: what the control's machine data would tell about axes, units,
//! reset state and tolerances, with the defaults of a mill and a lathe.

pub use super::axes::{Axis, AxisKind};
use super::contours::ContourOptions;
use super::cycles::CycleOptions;
use super::execution::ExecutionOptions;
use super::timing::TimingOptions;
use crate::diagnostics::{Code, Severity};
use std::collections::BTreeMap;

/// The two machine kinds whose reset state and axes differ by default.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MachineKind {
    #[default]
    Mill,
    Turn,
}

/// Everything the syntax and analysis layers need to know about the machine.
#[derive(Debug, Clone, PartialEq)]
pub struct MachineConfig {
    pub kind: MachineKind,
    /// Channel axes in the order geometry axes first (X, Y, Z for a mill).
    pub axes: Vec<Axis>,
    /// The basic unit system (MD10240 `SCALING_SYSTEM_IS_METRIC`).
    pub metric: bool,
    /// G functions active after reset, beyond the Siemens defaults (MD20150 `GCODE_RESET_VALUES`),
    /// upper case, e.g. `["G18", "DIAMON"]` on a lathe.
    pub reset_gcodes: Vec<String>,
    /// MD21000 `CIRCLE_ERROR_CONST` in mm.
    pub circle_error_const: f64,
    /// MD21010 `CIRCLE_ERROR_FACTOR`.
    pub circle_error_factor: f64,
    /// Highest skip level the HMI offers; `/0` up to `/N` are valid.
    pub max_skip_level: u8,
    /// Longest block in characters, comment included, before a warning.
    pub max_block_length: usize,
    /// Number of R parameters (MD28050 `MM_NUM_R_PARAM`).
    pub r_parameter_count: u32,
    /// Whether `r_parameters` was configured: the default count is a guess (many machines have more
    /// than 100), so R parameters beyond it are reported only when the count was given.
    pub r_parameters_configured: bool,
    /// MD30455 `MISC_FUNCTION_MASK` bit 0 = 0 on the modulo axes: an absolute position outside 0..360
    /// is an error (A234). Off by default: real programs (CAM output in particular) write `C370` for
    /// machines that convert such positions, and the default axes are a guess.
    pub modulo_range_error: bool,
    /// Severities chosen by the user for individual diagnostic codes.
    pub severity_overrides: BTreeMap<Code, Severity>,
    /// File extensions (without dot, compared case-insensitively) that `check` reads from folders.
    pub extensions: Vec<String>,
    /// The settable work offsets (`$P_UIFR`) the machine holds, by frame index (0 = G500, 1 = G54 ...
    /// 4 = G57, 5 = G505 ... 99 = G599): the translation of each listed axis in the basic unit system
    /// (degrees on rotary axes, a radius on a transverse axis); axes not listed are 0. An offset that is
    /// not configured is unknown, except G500, which is zero unless configured (reference §11.1).
    pub settable_offsets: BTreeMap<u8, Vec<(String, f64)>>,
    /// SD42440 `FRAME_OFFSET_INCR_PROG`: whether a G91 move after a frame or offset change also
    /// traverses the change (1, the default), or only the programmed path (0) (reference §3.6).
    pub frame_offset_incr_prog: bool,
    /// MD18600 `MM_FRAME_FINE_TRANS`: whether the programmable translation has a fine part, which
    /// ATRANS and G59 write while TRANS and G58 write the coarse part (reference §7.2).
    pub frame_fine_trans: bool,
    /// How the interpreter runs programs (`[execution]`).
    pub execution: ExecutionOptions,
    /// How the built-in models of the standard cycles behave (`[cycles]`).
    pub cycles: CycleOptions,
    /// How chamfers and roundings are inserted (`[contours]`).
    pub contours: ContourOptions,
    /// How machining time is estimated (`[timing]`).
    pub timing: TimingOptions,
}

impl Default for MachineConfig {
    fn default() -> MachineConfig {
        MachineConfig::mill()
    }
}

impl MachineConfig {
    /// A metric milling machine with X Y Z linear and A B C modulo rotary axes.
    pub fn mill() -> MachineConfig {
        MachineConfig {
            kind: MachineKind::Mill,
            axes: vec![
                Axis::new("X", AxisKind::Linear),
                Axis::new("Y", AxisKind::Linear),
                Axis::new("Z", AxisKind::Linear),
                Axis::new("A", AxisKind::Modulo),
                Axis::new("B", AxisKind::Modulo),
                Axis::new("C", AxisKind::Modulo),
            ],
            metric: true,
            reset_gcodes: Vec::new(),
            circle_error_const: 0.01,
            circle_error_factor: 0.001,
            max_skip_level: 9,
            max_block_length: 512,
            r_parameter_count: 100,
            r_parameters_configured: false,
            modulo_range_error: false,
            severity_overrides: BTreeMap::new(),
            extensions: vec!["mpf".to_string(), "spf".to_string()],
            settable_offsets: BTreeMap::new(),
            frame_offset_incr_prog: true,
            frame_fine_trans: false,
            execution: Default::default(),
            cycles: Default::default(),
            contours: Default::default(),
            timing: Default::default(),
        }
    }

    /// A metric lathe: X transverse (diameter), Z linear, C modulo; G18 and DIAMON after reset.
    pub fn turn() -> MachineConfig {
        MachineConfig {
            kind: MachineKind::Turn,
            axes: vec![
                Axis::new("X", AxisKind::Transverse),
                Axis::new("Z", AxisKind::Linear),
                Axis::new("C", AxisKind::Modulo),
            ],
            reset_gcodes: vec!["G18".to_string(), "DIAMON".to_string()],
            ..MachineConfig::mill()
        }
    }

    /// The machine defaults for a kind.
    pub fn for_kind(kind: MachineKind) -> MachineConfig {
        match kind {
            MachineKind::Mill => MachineConfig::mill(),
            MachineKind::Turn => MachineConfig::turn(),
        }
    }

    /// Looks an axis up by its name, case-insensitively.
    pub fn axis(&self, name: &str) -> Option<&Axis> {
        self.axes
            .iter()
            .find(|axis| axis.name.eq_ignore_ascii_case(name))
    }

    /// The severity a diagnostic code has on this machine, after the user's overrides.
    pub fn severity_of(&self, code: Code) -> Severity {
        self.severity_overrides
            .get(&code)
            .copied()
            .unwrap_or_else(|| code.default_severity())
    }

    /// The configured values of settable frame `index` ($P_UIFR), G500 (index 0) being zero unless
    /// configured; `None` when the machine data are not configured.
    pub fn settable_offset(&self, index: u8) -> Option<&[(String, f64)]> {
        match self.settable_offsets.get(&index) {
            Some(values) => Some(values),
            None if index == 0 => Some(&[]),
            None => None,
        }
    }

    /// Whether `check` should read a file with this extension when it walks a folder.
    pub fn accepts_extension(&self, extension: &str) -> bool {
        self.extensions
            .iter()
            .any(|known| known.eq_ignore_ascii_case(extension))
    }
}
