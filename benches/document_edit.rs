//! The cost of keeping a document's analysis up to date, in the core (no protocol): the first analysis
//! of a 1,000,000-line program, then one-character edits on random lines, as the language server
//! applies them. Two kinds of edit: a space at the start of a line of `cam3d` (the meaning does not
//! change, so the pass stops at the next checkpoint), and a changed digit of a coordinate in the
//! incremental `inc` program (every later position moves, so the pass runs to the end).
//!
//! Run with `cargo bench --bench document_edit` (`BENCH_LINES`, `BENCH_EDITS` change the sizes;
//! `BENCH_STYLES=cam3d,inc,noisy` picks the programs, `noisy` edited as `cam3d`).

use sinumerik_lsp::analysis::document::{DocumentAnalysis, LineSource};
use sinumerik_lsp::analysis::ProgramKind;
use sinumerik_lsp::config::MachineConfig;
use std::borrow::Cow;
use std::sync::Arc;
use std::time::Instant;

#[path = "../tests/support/generated.rs"]
mod generated;

/// The document as lines, as a rope would hand them out.
struct Lines(Vec<String>);

impl LineSource for Lines {
    fn line_count(&self) -> usize {
        self.0.len()
    }

    fn line(&self, index: usize) -> Cow<'_, str> {
        Cow::Borrowed(self.0.get(index).map(String::as_str).unwrap_or(""))
    }
}

fn percentile(sorted: &[f64], fraction: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * fraction).round() as usize]
}

fn main() {
    let line_count: usize = std::env::var("BENCH_LINES")
        .ok()
        .and_then(|value| value.parse().ok())
        .unwrap_or(1_000_000);
    let edit_count: usize = std::env::var("BENCH_EDITS")
        .ok()
        .and_then(|value| value.parse().ok())
        .unwrap_or(200);
    println!("document analysis, one core, {line_count} lines, {edit_count} edits per kind");
    let styles = std::env::var("BENCH_STYLES").unwrap_or_else(|_| "cam3d,inc".to_string());
    for style in styles.split(',') {
        let Some(text) = generated::generate(style, line_count) else {
            println!("{style}: skipped (../shared/bench/gen_program.py or python3 not available)");
            continue;
        };
        let mut lines = Lines(text.lines().map(str::to_string).collect());
        let config = Arc::new(MachineConfig::mill());
        let started = Instant::now();
        let mut analysis = DocumentAnalysis::new(&lines, config, ProgramKind::Main);
        let open = started.elapsed().as_secs_f64() * 1e3;
        let mut random = 0x9E37_79B9_7F4A_7C15u64;
        let mut times = Vec::new();
        let mut lines_read = 0usize;
        while times.len() < edit_count {
            random ^= random << 13;
            random ^= random >> 7;
            random ^= random << 17;
            let index = 10 + (random as usize) % (lines.0.len() - 20);
            let line = &mut lines.0[index];
            if style != "inc" {
                line.insert(0, ' ');
            } else {
                // A digit of the first coordinate of a plain incremental block.
                let Some(position) = line.find('X').map(|x| x + 1) else {
                    continue;
                };
                let Some(digit) = line[position..].find(|c: char| c.is_ascii_digit()) else {
                    continue;
                };
                let position = position + digit;
                let old = line.as_bytes()[position];
                let new = if old == b'9' { '0' } else { (old + 1) as char };
                line.replace_range(position..position + 1, &new.to_string());
            }
            let started = Instant::now();
            analysis.update(&lines, index, 1, 1);
            times.push(started.elapsed().as_secs_f64() * 1e3);
            lines_read += analysis.lines_read_by_last_update();
        }
        times.sort_by(f64::total_cmp);
        // A hover's core: the report of a block on a random line (the state before it, resolved
        // from the checkpoint before it, and its end point).
        let mut reports = Vec::new();
        while reports.len() < edit_count {
            random ^= random << 13;
            random ^= random >> 7;
            random ^= random << 17;
            let index = (random as usize) % lines.0.len();
            let started = Instant::now();
            let report = analysis.block_report(&lines, index);
            reports.push(started.elapsed().as_secs_f64() * 1e3);
            assert_eq!(report.line, index);
        }
        reports.sort_by(f64::total_cmp);
        println!(
            "{style:>6}: open {open:7.1} ms ({} findings); edit median {:6.2} ms, p99 {:6.2} ms, max {:6.2} ms; {:.0} lines re-read per edit",
            analysis.diagnostics().len(),
            percentile(&times, 0.5),
            percentile(&times, 0.99),
            times[times.len() - 1],
            lines_read as f64 / times.len() as f64,
        );
        println!(
            "{style:>6}: block report (a hover's core) median {:6.3} ms, p99 {:6.3} ms",
            percentile(&reports, 0.5),
            percentile(&reports, 0.99),
        );
    }
}
