//! The machine configuration: what the control's machine data would tell about axes, units, reset state
//! and tolerances. Plain data with defaults lives in `machine.rs`; reading `sinumerik.toml` in `file.rs`
//! (with `raw.rs` for the file as written and `file_keys.rs` for key positions); each option table of
//! its own in `contours.rs`, `cycles.rs`, `execution.rs` and `timing.rs`.

mod axes;
pub mod contours;
pub mod cycles;
pub mod edit;
pub mod execution;
mod file;
mod file_keys;
mod machine;
mod raw;
pub mod timing;

#[cfg(test)]
mod file_tests;
#[cfg(test)]
mod table_tests;

pub use file::{
    discover_config_file, load_config_file, parse_config_text, ConfigError, CONFIG_FILE_NAME,
};
pub use machine::{Axis, AxisKind, MachineConfig, MachineKind};
