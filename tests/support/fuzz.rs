//! The fuzzer's modules (examples/fuzz/), for the tests that replay its reproducers and run its
//! document comparison at scale. Included with `#[path]`, so that there is one copy of each module.

#[path = "../../examples/fuzz/approx.rs"]
pub mod approx;
#[path = "../../examples/fuzz/cases.rs"]
pub mod cases;
#[path = "../../examples/fuzz/cli.rs"]
pub mod cli;
#[path = "../../examples/fuzz/config.rs"]
pub mod config;
#[path = "../../examples/fuzz/document.rs"]
pub mod document;
#[path = "../../examples/fuzz/generate.rs"]
pub mod generate;
#[path = "../../examples/fuzz/random.rs"]
pub mod random;
#[path = "../../examples/fuzz/seeds.rs"]
pub mod seeds;
#[path = "../../examples/fuzz/spans.rs"]
pub mod spans;
#[path = "../../examples/fuzz/targets.rs"]
pub mod targets;
#[path = "../../examples/fuzz/transport.rs"]
pub mod transport;
