//! How the interpreter runs programs (`[execution]` in `sinumerik.toml`): its budgets, the entry
//! state of a subprogram analysed on its own, and the behaviours the reference leaves open (§17.4,
//! §17.7, §18.6).

use serde::Deserialize;

/// How a subprogram analysed on its own starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EntryState {
    /// The machine's reset state (MD20150), as an explicit assumption: every value that rests on it
    /// says so.
    Reset,
    /// The caller's state, unknown: values that depend on it stay unknown.
    Unknown,
}

/// The limits and choices of the interpreter.
#[derive(Debug, Clone, PartialEq)]
pub struct ExecutionOptions {
    /// Executed blocks after which the rest is read in program order.
    pub max_blocks: u64,
    /// Passes of one loop after which what its body changes is unknown (reference §18.6).
    pub max_loop_passes: u32,
    /// Program levels, the main program included (reference §17.3: 16).
    pub max_levels: usize,
    pub entry: EntryState,
    /// Whether M2/M30 in a subprogram end only that subprogram, like M17, or the whole program
    /// (reference §17.4, [?]).
    pub m30_ends_subprogram: bool,
    /// Whether the PLC requests the restart of `GOTOS` (reference §17.7): `Some(false)` (the
    /// default) never, `Some(true)` always, `None` unknown (both ways are followed).
    pub gotos_restarts: Option<bool>,
    /// Whether the run hands out the dwell blocks (`G4`) as moves of no axis
    /// (`Engine::describe_last_dwell`), for the machining time. Not a key of `sinumerik.toml`: the
    /// consumers that time a program ask for it, the others keep the moves of the path only.
    pub dwell_moves: bool,
}

impl Default for ExecutionOptions {
    fn default() -> ExecutionOptions {
        ExecutionOptions {
            max_blocks: 10_000_000,
            max_loop_passes: 10_000,
            max_levels: 16,
            entry: EntryState::Reset,
            m30_ends_subprogram: true,
            gotos_restarts: Some(false),
            dwell_moves: false,
        }
    }
}

/// The `[execution]` table as written.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawExecution {
    max_blocks: Option<i64>,
    max_loop_passes: Option<i64>,
    max_levels: Option<i64>,
    subprogram_entry: Option<String>,
    m30_ends_subprogram: Option<bool>,
    gotos_restart: Option<String>,
}

impl RawExecution {
    /// The options, or the key and the reason a value is not allowed.
    pub(super) fn convert(&self) -> Result<ExecutionOptions, (&'static str, String)> {
        let mut options = ExecutionOptions::default();
        if let Some(value) = self.max_blocks {
            options.max_blocks = u64::try_from(value)
                .ok()
                .filter(|value| *value >= 1)
                .ok_or(("max_blocks", format!("must be at least 1, found {value}")))?;
        }
        if let Some(value) = self.max_loop_passes {
            options.max_loop_passes = u32::try_from(value)
                .ok()
                .filter(|value| *value >= 1)
                .ok_or((
                    "max_loop_passes",
                    format!("must be between 1 and 4294967295, found {value}"),
                ))?;
        }
        if let Some(value) = self.max_levels {
            options.max_levels = usize::try_from(value)
                .ok()
                .filter(|value| (1..=64).contains(value))
                .ok_or((
                    "max_levels",
                    format!("must be between 1 and 64, found {value}"),
                ))?;
        }
        if let Some(value) = &self.subprogram_entry {
            options.entry = match value.as_str() {
                "reset" => EntryState::Reset,
                "unknown" => EntryState::Unknown,
                _ => {
                    return Err((
                        "subprogram_entry",
                        format!("must be \"reset\" or \"unknown\", found {value:?}"),
                    ))
                }
            };
        }
        if let Some(value) = self.m30_ends_subprogram {
            options.m30_ends_subprogram = value;
        }
        if let Some(value) = &self.gotos_restart {
            options.gotos_restarts = match value.as_str() {
                "never" => Some(false),
                "always" => Some(true),
                "unknown" => None,
                _ => {
                    return Err((
                        "gotos_restart",
                        format!("must be \"never\", \"always\" or \"unknown\", found {value:?}"),
                    ))
                }
            };
        }
        Ok(options)
    }
}
