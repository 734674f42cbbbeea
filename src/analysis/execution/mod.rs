//! Running a program the way the control runs it: loops for as many passes as the control makes,
//! jumps to labels and block numbers, `IF`/`CASE` decisions, subprogram calls with their parameters,
//! repetitions and returns. Every executed block goes through the [`Engine`](crate::analysis::engine::engine_state::Engine),
//! so each execution of a block has the modal state the control has there.
//!
//! Where a decision depends on what the program does not contain (main-run variables, machine data),
//! every way is followed and the ways are joined where they meet: what is equal on every way stays
//! known, what differs becomes unknown. A loop whose number of passes is not known is run until its
//! state no longer changes (each pass forgets what differs), so that only what its body changes
//! becomes unknown. A budget of executed blocks bounds the work; past it the rest of the program is
//! read in program order, as values that are uncertain.

mod assumptions;
mod block_run;
mod calls;
mod control;
mod cycles;
pub mod entry;
pub mod first_pass;
mod first_pass_record;
mod interpreter;
mod jump_targets;
pub mod library_macros;
pub mod outcome;
mod paths;
pub mod program;
mod recorded;
mod repeats;
mod resume;
mod resume_points;
pub mod run_program;
mod tables;
mod ways;

pub use crate::config::execution::{EntryState, ExecutionOptions};
pub use outcome::{ends_program, CallSite, ExecutedMove, Execution, ProgramEnd};
pub use recorded::{resume_run, run_recorded, RecordedRun, RunStart};
pub use run_program::{
    entry_assumptions, execute, execute_collecting, execute_programmed, execute_with,
    execution_findings, RESET_SOURCE,
};
