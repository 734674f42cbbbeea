//! The machine configuration: what the control's machine data would tell about axes, units, reset state
//! and tolerances. Plain data with defaults
//! (`machine.rs`, with one file per table of its own); reading `sinumerik.toml` lives in `file.rs`.

mod axes;
pub mod contours;
pub mod cycles;
pub mod execution;
mod file;
mod machine;
#[cfg(test)]
mod section_tests;
pub mod timing;

pub use axes::{Axis, AxisKind};
pub use machine::{MachineConfig, MachineKind};

pub use file::{
    discover_config_file, load_config_file, parse_config_text, ConfigError, CONFIG_FILE_NAME,
};
