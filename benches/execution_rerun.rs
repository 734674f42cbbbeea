//! What running a program again after an edit costs: the 1,000,000-line `mixed` program of
//! `../shared/bench/gen_program.py` (tens of thousands of loops of jumps and WHILE loops) run from
//! the start, then run again after one-character edits on random lines of blocks without flow (a
//! coordinate digit changed, a comment added), each resumed from the run before it. Prints the
//! fresh run, the median and p99 of the resumed runs with how many blocks each ran again, and how
//! many rejoined the earlier run.
//!
//! Run with `cargo bench --bench execution_rerun`. `BENCH_LINES` (default 1,000,000) and
//! `BENCH_EDITS` (default 100) change the run.

use sinumerik_lsp::analysis::execution::entry::RunSetup;
use sinumerik_lsp::analysis::execution::{run_recorded, ExecutionOptions, RecordedRun, RunStart};
use sinumerik_lsp::analysis::library::NoLibrary;
use sinumerik_lsp::analysis::ProgramKind;
use sinumerik_lsp::config::MachineConfig;
use std::sync::Arc;
use std::time::{Duration, Instant};

#[path = "../tests/support/generated.rs"]
mod generated;

struct Random(u64);

impl Random {
    fn below(&mut self, bound: usize) -> usize {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 % bound.max(1) as u64) as usize
    }
}

fn env_number(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|value| value.parse().ok())
        .unwrap_or(default)
}

fn run(text: &str, config: &MachineConfig, earlier: Option<&RecordedRun>) -> RecordedRun {
    run_recorded(
        Arc::from(text),
        config,
        ProgramKind::Main,
        &NoLibrary,
        &ExecutionOptions::default(),
        &RunSetup {
            entry: None,
            record_first_passes: true,
        },
        earlier,
    )
}

fn milliseconds(duration: Duration) -> String {
    format!("{:.1} ms", duration.as_secs_f64() * 1000.0)
}

fn main() {
    let line_count = env_number("BENCH_LINES", 1_000_000);
    let Some(text) = generated::generate("mixed", line_count) else {
        println!("mixed: skipped (../shared/bench/gen_program.py or python3 not available)");
        return;
    };
    let config = MachineConfig::mill();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let started = Instant::now();
    let mut earlier = run(&text, &config, None);
    let fresh = started.elapsed();
    println!(
        "mixed, {} lines: run from the start {} ({} blocks executed, {} moves)",
        lines.len(),
        milliseconds(fresh),
        earlier.execution.executed_blocks,
        earlier.moves.len()
    );
    // Lines of blocks without flow: coordinates and assignments.
    let plain: Vec<usize> = (0..lines.len())
        .filter(|&index| {
            let line = &lines[index];
            (line.starts_with("G1 ") || line.starts_with("G0 ") || line.starts_with("TRANS "))
                && !line.contains(':')
        })
        .collect();
    let mut random = Random(0x5EED ^ line_count as u64);
    let mut times = Vec::new();
    let mut again_blocks = Vec::new();
    let mut rejoined = 0;
    let mut from_start = 0;
    for edit in 0..env_number("BENCH_EDITS", 100) {
        let index = plain[random.below(plain.len())];
        let line = &mut lines[index];
        if edit % 2 == 0 {
            line.push_str(" ; checked");
        } else if let Some(position) = line.rfind(|character: char| character.is_ascii_digit()) {
            let digit = (b'0' + random.below(10) as u8) as char;
            line.replace_range(position..position + 1, &digit.to_string());
        }
        let edited = lines.join("\n") + "\n";
        let started = Instant::now();
        let again = run(&edited, &config, Some(&earlier));
        times.push(started.elapsed());
        match again.start {
            RunStart::Resumed { from, rejoined: at } => {
                let end = at.unwrap_or(again.execution.executed_blocks);
                again_blocks.push(end - from);
                rejoined += usize::from(at.is_some());
            }
            RunStart::Unchanged => again_blocks.push(0),
            RunStart::Fresh => {
                from_start += 1;
                again_blocks.push(again.execution.executed_blocks);
            }
        }
        earlier = again;
    }
    times.sort();
    again_blocks.sort();
    let percentile = |fraction: f64| times[((times.len() - 1) as f64 * fraction).round() as usize];
    println!(
        "  run again after an edit: median {}, p99 {} ({} edits; {} rejoined the earlier run, {} ran from the start)",
        milliseconds(percentile(0.5)),
        milliseconds(percentile(0.99)),
        times.len(),
        rejoined,
        from_start
    );
    println!(
        "  blocks run again: median {}, p99 {}",
        again_blocks[again_blocks.len() / 2],
        again_blocks[((again_blocks.len() - 1) as f64 * 0.99).round() as usize]
    );
}
