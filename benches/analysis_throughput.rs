//! Full analysis throughput (parse + modal state + resolution) on large generated programs, in MB/s.
//!
//! Run with `cargo bench --bench analysis_throughput`. Programs come from
//! `../shared/bench/gen_program.py` (1,000,000 lines each unless `BENCH_LINES` says otherwise;
//! `BENCH_STYLES=cam3d,inc` picks the styles); without the generator the benchmark says so.

use sinumerik_lsp::analysis::{analyze_program, ProgramKind};
use sinumerik_lsp::config::MachineConfig;
use std::time::Instant;

#[path = "../tests/support/generated.rs"]
mod generated;
use generated::generate;

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
        let mut best = f64::INFINITY;
        let mut move_count = 0;
        for _ in 0..3 {
            let started = Instant::now();
            let analysis = analyze_program(&text, &config, ProgramKind::Main);
            best = best.min(started.elapsed().as_secs_f64());
            move_count = analysis.moves.len();
        }
        let megabytes = text.len() as f64 / 1e6;
        println!(
            "{style:>8}: {megabytes:7.1} MB in {:7.1} ms = {:6.0} MB/s ({move_count} moves)",
            best * 1e3,
            megabytes / best
        );
    }
}
