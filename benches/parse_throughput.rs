//! Lexing + parsing throughput on large generated programs, printed as MB/s per style.
//!
//! Run with `cargo bench --bench parse_throughput`. The programs come from
//! `../shared/bench/gen_program.py` (1,000,000 lines each unless `BENCH_LINES` says otherwise); when the
//! generator is absent the benchmark says so and exits without figures. `BENCH_STYLES=cam3d,inc` picks
//! the styles.

use sinumerik_lsp::config::MachineConfig;
use sinumerik_lsp::syntax::{lines, Block, LineParser, SyntaxContext};
use std::time::Instant;

#[path = "../tests/support/generated.rs"]
mod generated;
use generated::generate;

/// Parses every line once; returns the number of diagnostics so the work cannot be optimised away.
fn parse_all(text: &str, context: &SyntaxContext) -> usize {
    let mut parser = LineParser::new();
    let mut block = Block::default();
    let mut diagnostics = Vec::new();
    let mut total = 0;
    for (start, end) in lines::line_ranges(text) {
        parser.parse(&text[start..end], context, &mut block, &mut diagnostics);
        total += diagnostics.len() + block.statements.len();
    }
    total
}

fn main() {
    let line_count: usize = std::env::var("BENCH_LINES")
        .ok()
        .and_then(|value| value.parse().ok())
        .unwrap_or(1_000_000);
    let mill = SyntaxContext::new(&MachineConfig::mill());
    let turn = SyntaxContext::new(&MachineConfig::turn());
    println!("lex + parse throughput, one core, {line_count} lines per program");
    let styles =
        std::env::var("BENCH_STYLES").unwrap_or_else(|_| "cam3d,inc,turning,mixed".to_string());
    for style in styles.split(',') {
        let Some(text) = generate(style, line_count) else {
            println!("{style}: skipped (../shared/bench/gen_program.py or python3 not available)");
            continue;
        };
        let context = if style == "turning" { &turn } else { &mill };
        // One warm-up pass, then the best of five timed passes.
        let mut checksum = parse_all(&text, context);
        let mut best = f64::INFINITY;
        for _ in 0..5 {
            let started = Instant::now();
            checksum = checksum.wrapping_add(parse_all(&text, context));
            best = best.min(started.elapsed().as_secs_f64());
        }
        let megabytes = text.len() as f64 / 1e6;
        println!(
            "{style:>8}: {megabytes:7.1} MB in {:7.1} ms = {:6.0} MB/s (checksum {checksum})",
            best * 1e3,
            megabytes / best
        );
    }
}
