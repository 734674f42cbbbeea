//! Full analysis throughput (parse + modal state + resolution of every end point) on large generated
//! programs, in MB/s: once for diagnostics alone (what `check` and the language server run) and once
//! with every move built and handed to a visitor (what `preview` runs).
//!
//! Run with `cargo bench --bench analysis_throughput`. Programs come from
//! `../shared/bench/gen_program.py` (1,000,000 lines each unless `BENCH_LINES` says otherwise;
//! `BENCH_STYLES=cam3d,inc` picks the styles); without the generator the benchmark says so.

use sinumerik_lsp::analysis::{diagnose_program, visit_moves, ProgramKind};
use sinumerik_lsp::config::MachineConfig;
use std::time::Instant;

#[path = "../tests/support/generated.rs"]
mod generated;
use generated::generate;

/// The best of three runs of `work`, in seconds, with what the last run returned.
fn best_of_three<T>(mut work: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut result = work();
    for _ in 0..3 {
        let started = Instant::now();
        result = work();
        best = best.min(started.elapsed().as_secs_f64());
    }
    (best, result)
}

fn main() {
    let line_count: usize = std::env::var("BENCH_LINES")
        .ok()
        .and_then(|value| value.parse().ok())
        .unwrap_or(1_000_000);
    let styles = std::env::var("BENCH_STYLES").unwrap_or_else(|_| "cam3d,inc,turning".to_string());
    println!("full analysis throughput, one core, {line_count} lines per program");
    for style in styles.split(',') {
        let Some(text) = generate(style, line_count) else {
            println!("{style}: skipped (../shared/bench/gen_program.py or python3 not available)");
            continue;
        };
        let config = if style == "turning" {
            MachineConfig::turn()
        } else {
            MachineConfig::mill()
        };
        let megabytes = text.len() as f64 / 1e6;
        let (diagnose_time, diagnostic_count) =
            best_of_three(|| diagnose_program(&text, &config, ProgramKind::Main).len());
        let (moves_time, move_count) = best_of_three(|| {
            let mut count = 0usize;
            visit_moves(&text, &config, ProgramKind::Main, |_| count += 1);
            count
        });
        println!(
            "{style:>8}: {megabytes:5.1} MB; diagnostics {:6.1} ms = {:4.0} MB/s ({diagnostic_count} findings); \
             with moves {:6.1} ms = {:4.0} MB/s ({move_count} moves)",
            diagnose_time * 1e3,
            megabytes / diagnose_time,
            moves_time * 1e3,
            megabytes / moves_time,
        );
    }
}
