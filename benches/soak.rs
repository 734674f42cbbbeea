//! Soak run of the language server: the release binary, driven over stdio for a bounded time with
//! random edits, hovers, previews and now and then a close and reopen, on several documents (LF,
//! CRLF and CR line ends, 2,000 to 50,000 lines). Each step waits for its answer (the edit for the
//! diagnostics of its version), so the latencies are those of an editor that types and looks.
//!
//! Prints, per interval (a minute by default): the server's resident memory (VmRSS from /proc), the
//! steps done, the diagnostics the documents have, and latency percentiles of each kind of step; at the end a verdict line: memory growth
//! after the first interval (the warm-up) and latency drift from the second interval to the last.
//! Before that it checks that every document's text and last diagnostics equal the local copy and a
//! from-scratch analysis. Exits with 1 when memory grew or latency drifted beyond the bounds below.
//!
//! `cargo bench --bench soak`; `SOAK_SECONDS` (default 600), `SOAK_INTERVAL_SECONDS` (default 60)
//! and `SOAK_SEED` change the run. CI does not run it.

#[path = "../tests/support/compare.rs"]
mod compare;
#[path = "../tests/support/edit_session.rs"]
mod edit_session;
#[path = "../tests/support/env_setting.rs"]
mod env_setting;
#[path = "../tests/support/raw_lsp.rs"]
mod raw_lsp;

use edit_session::{program, LineDocument, Random};
use env_setting::setting;
use raw_lsp::RawServer;
use serde_json::{json, Value};
use std::time::{Duration, Instant};

/// Growth of resident memory after the warm-up that counts as a leak: this much and this share.
const MEMORY_GROWTH_MB: f64 = 32.0;
const MEMORY_GROWTH_SHARE: f64 = 0.25;
/// A median latency that grew this many times (and by at least a millisecond) is drift.
const LATENCY_DRIFT: f64 = 2.0;

struct Document {
    uri: String,
    local: LineDocument,
    version: i64,
    /// The diagnostics published for `version`.
    diagnostics: Vec<Value>,
    /// The `didChange`s sent.
    edits: i64,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Step {
    Edit,
    Hover,
    Preview,
    Reopen,
}

const STEPS: [(Step, &str); 4] = [
    (Step::Edit, "edit → diagnostics"),
    (Step::Hover, "hover"),
    (Step::Preview, "preview"),
    (Step::Reopen, "reopen → diagnostics"),
];

/// The latencies of one interval, per kind of step.
#[derive(Default)]
struct Interval {
    samples: [Vec<Duration>; 4],
}

impl Interval {
    fn record(&mut self, step: Step, latency: Duration) {
        let index = STEPS.iter().position(|(kind, _)| *kind == step).unwrap();
        self.samples[index].push(latency);
    }

    fn percentile(&mut self, index: usize, fraction: f64) -> Option<f64> {
        let samples = &mut self.samples[index];
        if samples.is_empty() {
            return None;
        }
        samples.sort();
        let at = ((samples.len() - 1) as f64 * fraction).round() as usize;
        Some(samples[at].as_secs_f64() * 1e3)
    }

    fn steps(&self) -> usize {
        self.samples.iter().map(Vec::len).sum()
    }
}

fn open_all(server: &mut RawServer, documents: &mut [Document]) {
    for document in documents {
        server.open(&document.uri, document.version, &document.local.text());
        document.diagnostics = server.diagnostics(&document.uri, document.version);
    }
}

/// One random step on a random document; returns its kind and latency.
fn step(
    server: &mut RawServer,
    documents: &mut [Document],
    random: &mut Random,
) -> (Step, Duration) {
    let document = &mut documents[random.below(documents.len())];
    let uri = document.uri.clone();
    let lines = document.local.lines.len();
    match random.below(100) {
        0..=59 => {
            let version_before = document.version;
            let mut started = Instant::now();
            for _ in 0..1 + random.below(4) {
                for edit in document.local.tidy_edits(random) {
                    document.version += 1;
                    document.edits += 1;
                    started = Instant::now();
                    server.change(&uri, document.version, json!([edit.to_json()]));
                }
            }
            // A step whose edits all came to nothing (a line without a digit) waits for nothing.
            if document.version > version_before {
                document.diagnostics = server.diagnostics(&uri, document.version);
            }
            (Step::Edit, started.elapsed())
        }
        60..=87 => {
            let started = Instant::now();
            let line = random.below(lines) as u64;
            let answer = server.hover(&uri, line, random.below(40) as u64);
            assert!(answer.is_ok(), "hover on {uri} line {line}: {answer:?}");
            (Step::Hover, started.elapsed())
        }
        88..=98 => {
            let started = Instant::now();
            let line = random.below(lines) as u64;
            let id = server.writer.request_preview(&uri, line, line + 40);
            let answer = server.response(id);
            assert!(
                answer
                    .as_ref()
                    .is_ok_and(|result| result["moves"].is_array()),
                "preview of {uri} from line {line}: {answer:?}"
            );
            (Step::Preview, started.elapsed())
        }
        _ => {
            server.close(&uri);
            document.version += 1;
            let started = Instant::now();
            server.open(&uri, document.version, &document.local.text());
            document.diagnostics = server.diagnostics(&uri, document.version);
            (Step::Reopen, started.elapsed())
        }
    }
}

fn milliseconds(value: Option<f64>) -> String {
    value.map_or("—".to_string(), |value| format!("{value:.2}"))
}

/// Every document's text and last diagnostics, compared with the local copy and a fresh analysis.
fn check_documents(server: &mut RawServer, documents: &[Document]) {
    for document in documents {
        let text = document.local.text();
        assert_eq!(
            server.document_text(&document.uri),
            Ok((document.version, text.clone())),
            "{}: the server's text differs from the local copy",
            document.uri
        );
        assert_eq!(
            compare::published(&document.diagnostics),
            compare::fresh(&text),
            "{}: the last diagnostics differ from a fresh analysis",
            document.uri
        );
    }
    // No publication of a document came after one of a newer version.
    for document in documents {
        let versions: Vec<i64> = server
            .publications()
            .into_iter()
            .filter(|(uri, _)| *uri == document.uri)
            .filter_map(|(_, version)| version)
            .collect();
        assert!(
            versions.windows(2).all(|pair| pair[0] <= pair[1]),
            "{}: publications out of version order",
            document.uri
        );
    }
}

fn main() {
    // `cargo bench` passes `--bench`; this run takes no arguments of its own.
    let seconds = setting("SOAK_SECONDS", 600);
    let interval = Duration::from_secs(setting("SOAK_INTERVAL_SECONDS", 60).max(1));
    let mut random = Random::new(setting("SOAK_SEED", 1));
    let shapes: [(&str, usize, &'static str); 4] = [
        ("large", 50_000, "\n"),
        ("crlf", 20_000, "\r\n"),
        ("cr", 5_000, "\r"),
        ("small", 2_000, "\n"),
    ];
    let mut documents: Vec<Document> = shapes
        .iter()
        .map(|(name, lines, terminator)| Document {
            uri: format!("file:///soak/{name}.mpf"),
            local: LineDocument::new(&program(&mut random, *lines, terminator), terminator),
            version: 1,
            diagnostics: Vec::new(),
            edits: 0,
        })
        .collect();
    println!(
        "soak: {seconds} s of random edits, hovers, previews and reopens on {} documents ({} lines), release binary",
        documents.len(),
        shapes.iter().map(|(_, lines, _)| lines).sum::<usize>()
    );
    let mut server = RawServer::spawn();
    server.initialize();
    open_all(&mut server, &mut documents);

    println!(
        "{:>8} | {:>8} | {:>6} | {:>11} | {:>27} | {:>20} | {:>20} | {:>20}",
        "interval",
        "RSS MB",
        "steps",
        "diagnostics",
        "edit → diagnostics p50/p95/p99",
        "hover p50/p99",
        "preview p50/p99",
        "reopen p50/p99"
    );
    let started = Instant::now();
    let deadline = started + Duration::from_secs(seconds);
    let mut rows: Vec<Row> = Vec::new();
    let mut index = 0;
    while Instant::now() < deadline {
        index += 1;
        let interval_end = (started + interval * index).min(deadline);
        let mut current = Interval::default();
        while Instant::now() < interval_end {
            let (kind, latency) = step(&mut server, &mut documents, &mut random);
            current.record(kind, latency);
            // Messages nobody waited for (other documents' diagnostics, log lines) are dropped.
            server.take_received();
        }
        let resident_mb = server.resident_kib().unwrap_or(0) as f64 / 1024.0;
        let edit = (
            current.percentile(0, 0.5),
            current.percentile(0, 0.95),
            current.percentile(0, 0.99),
        );
        let hover = (current.percentile(1, 0.5), current.percentile(1, 0.99));
        let preview = (current.percentile(2, 0.5), current.percentile(2, 0.99));
        let reopen = (current.percentile(3, 0.5), current.percentile(3, 0.99));
        let diagnostics: usize = documents
            .iter()
            .map(|document| document.diagnostics.len())
            .sum();
        println!(
            "{:>8} | {:>8.1} | {:>6} | {:>11} | {:>27} | {:>20} | {:>20} | {:>20}",
            index,
            resident_mb,
            current.steps(),
            diagnostics,
            format!(
                "{} / {} / {}",
                milliseconds(edit.0),
                milliseconds(edit.1),
                milliseconds(edit.2)
            ),
            format!("{} / {}", milliseconds(hover.0), milliseconds(hover.1)),
            format!("{} / {}", milliseconds(preview.0), milliseconds(preview.1)),
            format!("{} / {}", milliseconds(reopen.0), milliseconds(reopen.1)),
        );
        rows.push(Row {
            resident_mb,
            edit: edit.0,
            hover: hover.0,
            preview: preview.0,
        });
    }
    check_documents(&mut server, &documents);
    let lines: usize = documents
        .iter()
        .map(|document| document.local.lines.len())
        .sum();
    let edits: i64 = documents.iter().map(|document| document.edits).sum();
    println!(
        "checked: every document's text and last diagnostics equal the local copy and a fresh analysis ({lines} lines now, {edits} edits sent)"
    );
    let code = server.shutdown();
    assert_eq!(code, Some(0), "exit code after shutdown");

    let verdict = verdict(&rows);
    println!("verdict: {}", verdict.0);
    if !verdict.1 {
        std::process::exit(1);
    }
}

/// What an interval's verdict is drawn from: resident memory and median latencies in ms.
struct Row {
    resident_mb: f64,
    edit: Option<f64>,
    hover: Option<f64>,
    preview: Option<f64>,
}

/// The verdict line and whether the run passed: memory after the warm-up (the first interval) and
/// the median latencies of the second interval and the last.
fn verdict(rows: &[Row]) -> (String, bool) {
    if rows.len() < 3 {
        return (
            "too short for a verdict (at least three intervals: a warm-up, a first and a last)"
                .to_string(),
            true,
        );
    }
    let warm = rows[0].resident_mb;
    let last = rows[rows.len() - 1].resident_mb;
    let middle = rows[rows.len() / 2].resident_mb;
    let peak = rows[1..]
        .iter()
        .map(|row| row.resident_mb)
        .fold(0.0, f64::max);
    let growth = last - warm;
    let leaked = growth > MEMORY_GROWTH_MB && growth > warm * MEMORY_GROWTH_SHARE;
    let drift = |name: &str, first: Option<f64>, last: Option<f64>| match (first, last) {
        (Some(first), Some(last)) => {
            let drifted = last > first * LATENCY_DRIFT && last - first > 1.0;
            (format!("{name} p50 {first:.2} → {last:.2} ms"), drifted)
        }
        _ => (format!("{name}: no samples"), false),
    };
    let second = &rows[1];
    let final_row = &rows[rows.len() - 1];
    let latencies = [
        drift("edit", second.edit, final_row.edit),
        drift("hover", second.hover, final_row.hover),
        drift("preview", second.preview, final_row.preview),
    ];
    let drifted = latencies.iter().any(|(_, drifted)| *drifted);
    let line = format!(
        "memory {} ({warm:.1} MB after the warm-up, {last:.1} MB at the end, {:+.1} MB, peak {peak:.1} MB; second half {middle:.1} → {last:.1} MB); latency {} ({})",
        if leaked { "GREW" } else { "flat" },
        growth,
        if drifted { "DRIFTED" } else { "steady" },
        latencies
            .iter()
            .map(|(text, _)| text.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    );
    (line, !leaked && !drifted)
}
