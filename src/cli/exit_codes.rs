//! The exit codes of the command line, shared by every command.

/// No diagnostic of severity error.
pub const EXIT_OK: u8 = 0;
/// At least one diagnostic of severity error.
pub const EXIT_ERRORS_FOUND: u8 = 1;
/// The run could not do what was asked: usage, IO or configuration problems.
pub const EXIT_TROUBLE: u8 = 2;
