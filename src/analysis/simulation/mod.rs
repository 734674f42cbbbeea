//! Simulating what the machine does with the moves the engine resolves: machining time (`time`).

pub mod time;
