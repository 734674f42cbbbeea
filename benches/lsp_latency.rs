//! Latency of the language server as an editor sees it: the release binary driven over stdio with
//! 1,000,000-line programs from `../shared/bench/gen_program.py` (`cam3d`, `inc` and `noisy`).
//!
//! Prints, per program: didOpen to the first publishDiagnostics (timed from when the message starts
//! to go out, after the client's own JSON encoding); a one-character edit on a random line to the
//! publishDiagnostics of that version (median and p99) — a space at the start of a line of `cam3d`
//! and `noisy` (meaning unchanged) and a changed coordinate digit in `inc` (every later position
//! moves); hover
//! median and p99; the server's resident memory; and what the diagnostics cost to serialize and send.
//! Each program is measured in three setups: with every finding published (the server's default)
//! and with `maxDiagnostics` at 1,000 (as the VS Code extension starts the server), both over pipes
//! (as Rust's, Python's and most process libraries start a child), and with every finding published
//! over Unix socket pairs (as libuv, under VS Code's Node.js and Neovim, starts one).
//!
//! Run with `cargo bench --bench lsp_latency`. `BENCH_LINES` (default 1,000,000), `BENCH_EDITS` and
//! `BENCH_HOVERS` (default 200 each) and `BENCH_BUDGET_SECS` (default 240, per measurement: a slow
//! server is measured on fewer samples, and the count is printed) change the run. `BENCH_STYLES`
//! (default `cam3d,inc,noisy`) and `BENCH_SETUPS` (default 3: all setups; 1: the first only, 2: the
//! first two) narrow it. `BENCH_PROGRAM_DIR` keeps the generated programs there and reuses them.
//! `BENCH_SHOW_SLOW` prints every edit that took over 12 ms and every hover over 1 ms, with when it was
//! sent.
//!
//! Side by side: `BENCH_VARIANTS` lists servers separated by `;`, each `name`, optionally
//! `@/path/to/binary` (default: this build's binary) and `:KEY=VALUE` environment settings (for
//! example `SINUMERIK_LSP_MEASURE_WITHOUT=diagnostics-reuse`); `BENCH_ROUNDS` (default 1) repeats
//! the whole set. Rounds, styles and variants are interleaved (each round runs every style with every
//! variant), and the end prints the median of each figure over the rounds, per style and variant,
//! with the peak resident memory (`VmHWM`) against the file's size.

use serde_json::{json, Value};
use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::thread;
use std::time::{Duration, Instant};

#[path = "../tests/support/generated.rs"]
mod generated;

const TIMEOUT: Duration = Duration::from_secs(600);

/// A message from the server with the moments its first and its last byte arrived.
struct Arrival {
    first_byte_at: Instant,
    at: Instant,
    bytes: usize,
    /// A large message is checked to be whole and valid JSON, but only its id, method, URI, version
    /// and number of diagnostics are kept here (see [`read_large`]).
    message: Value,
    diagnostic_count: usize,
    /// The text of the first large message after [`Server::keep_next_large_text`].
    text: Option<Vec<u8>>,
}

/// Messages from this size on are read by [`read_large`].
const LARGE_MESSAGE_BYTES: usize = 1 << 18;

#[derive(serde::Deserialize)]
struct LargeMessage {
    #[serde(default)]
    id: Value,
    #[serde(default)]
    method: Value,
    #[serde(default)]
    params: LargeParams,
}

#[derive(serde::Deserialize, Default)]
struct LargeParams {
    #[serde(default)]
    uri: Value,
    #[serde(default)]
    version: Value,
    #[serde(default)]
    diagnostics: Vec<serde::de::IgnoredAny>,
}

/// A large message (a publication of tens of thousands of diagnostics) read as an editor must read
/// it, every byte parsed and checked, but without building a JSON value tree of it: such a tree of a
/// 7.8 MB message takes this client well over 100 ms, and its allocations would leave the caches the
/// server runs from cold at every edit, which the figures would then measure instead of the server.
fn read_large(body: &[u8]) -> (Value, usize) {
    match serde_json::from_slice::<LargeMessage>(body) {
        Ok(message) => (
            json!({"id": message.id, "method": message.method, "params": {"uri": message.params.uri, "version": message.params.version}}),
            message.params.diagnostics.len(),
        ),
        Err(_) => (Value::Null, 0),
    }
}

struct Server {
    child: Child,
    stdin: Box<dyn Write + Send>,
    arrivals: mpsc::Receiver<Arrival>,
    keep_text: std::sync::Arc<std::sync::atomic::AtomicBool>,
    next_id: i64,
}

fn frame(value: &Value) -> Vec<u8> {
    let body = serde_json::to_vec(value).unwrap();
    let mut message = format!("Content-Length: {}\r\n\r\n", body.len()).into_bytes();
    message.extend_from_slice(&body);
    message
}

/// What the server's stdin and stdout are.
#[derive(Clone, Copy, PartialEq)]
enum Transport {
    /// Pipes, as Rust's, Python's and most other process libraries make them.
    Pipes,
    /// Unix socket pairs, as libuv makes them for a child's stdio (VS Code's Node.js, Neovim).
    SocketPairs,
}

impl Server {
    fn start(transport: Transport, variant: &Variant) -> Server {
        let mut command = Command::new(&variant.binary);
        command.envs(variant.env.iter().map(|(key, value)| (key, value)));
        // The server's log says how long its analyses and diagnostics took (when over 100 ms).
        command.stderr(Stdio::from(
            std::fs::File::create(log_path()).expect("the log file can be created"),
        ));
        let (stdin, stdout, child): (Box<dyn Write + Send>, Box<dyn Read + Send>, Child) =
            match transport {
                Transport::Pipes => {
                    let mut child = command
                        .stdin(Stdio::piped())
                        .stdout(Stdio::piped())
                        .spawn()
                        .expect("the server binary starts");
                    let stdin = child.stdin.take().unwrap();
                    let stdout = child.stdout.take().unwrap();
                    (Box::new(stdin), Box::new(stdout), child)
                }
                Transport::SocketPairs => {
                    let (to_server, server_input) = std::os::unix::net::UnixStream::pair().unwrap();
                    let (from_server, server_output) =
                        std::os::unix::net::UnixStream::pair().unwrap();
                    let child = command
                        .stdin(Stdio::from(std::os::fd::OwnedFd::from(server_input)))
                        .stdout(Stdio::from(std::os::fd::OwnedFd::from(server_output)))
                        .spawn()
                        .expect("the server binary starts");
                    (Box::new(to_server), Box::new(from_server), child)
                }
            };
        let (sender, arrivals) = mpsc::channel();
        let keep_text = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
        let keep_next_text = std::sync::Arc::clone(&keep_text);
        thread::spawn(move || {
            let mut reader = BufReader::with_capacity(1 << 20, stdout);
            // One body buffer for every message: a fresh multi-megabyte buffer per message would
            // add the client's own page faults (a few milliseconds) to every figure.
            let mut buffer = Vec::new();
            loop {
                let mut length = 0;
                let mut first_byte_at = None;
                loop {
                    let mut header = String::new();
                    if reader.fill_buf().map_or(true, |bytes| bytes.is_empty()) {
                        return;
                    }
                    first_byte_at.get_or_insert_with(Instant::now);
                    if reader.read_line(&mut header).unwrap_or(0) == 0 {
                        return;
                    }
                    let header = header.trim_end();
                    if header.is_empty() {
                        break;
                    }
                    if let Some(value) = header.strip_prefix("Content-Length:") {
                        length = value.trim().parse().unwrap_or(0);
                    }
                }
                if buffer.len() < length {
                    buffer.resize(length, 0);
                }
                let body = &mut buffer[..length];
                if reader.read_exact(body).is_err() {
                    return;
                }
                let at = Instant::now();
                let (message, diagnostic_count, text) = if length >= LARGE_MESSAGE_BYTES {
                    let (message, count) = read_large(body);
                    let text = keep_next_text
                        .swap(false, std::sync::atomic::Ordering::Relaxed)
                        .then(|| body.to_vec());
                    (message, count, text)
                } else {
                    let message: Value = serde_json::from_slice(body).unwrap_or(Value::Null);
                    let count = message["params"]["diagnostics"]
                        .as_array()
                        .map_or(0, Vec::len);
                    (message, count, None)
                };
                if sender
                    .send(Arrival {
                        first_byte_at: first_byte_at.unwrap_or(at),
                        at,
                        bytes: length,
                        message,
                        diagnostic_count,
                        text,
                    })
                    .is_err()
                {
                    return;
                }
            }
        });
        Server {
            child,
            stdin,
            arrivals,
            keep_text,
            next_id: 1,
        }
    }

    /// Keeps the text of the next large message, for measuring what reading it costs.
    fn keep_next_large_text(&self) {
        self.keep_text
            .store(true, std::sync::atomic::Ordering::Relaxed);
    }

    /// Sends an encoded message; returns the moment it started to go out.
    fn send(&mut self, encoded: &[u8]) -> Instant {
        let started = Instant::now();
        self.stdin.write_all(encoded).unwrap();
        self.stdin.flush().unwrap();
        started
    }

    fn notify(&mut self, method: &str, params: Value) -> Instant {
        let encoded = frame(&json!({"jsonrpc": "2.0", "method": method, "params": params}));
        self.send(&encoded)
    }

    fn request(&mut self, method: &str, params: Value) -> (Instant, i64) {
        let id = self.next_id;
        self.next_id += 1;
        let encoded =
            frame(&json!({"jsonrpc": "2.0", "id": id, "method": method, "params": params}));
        (self.send(&encoded), id)
    }

    fn wait_for(&mut self, wanted: impl Fn(&Value) -> bool) -> Arrival {
        loop {
            let arrival = self
                .arrivals
                .recv_timeout(TIMEOUT)
                .expect("the server answers");
            if wanted(&arrival.message) {
                return arrival;
            }
        }
    }

    fn diagnostics_of(&mut self, version: i64) -> Arrival {
        self.wait_for(|message| {
            message["method"] == "textDocument/publishDiagnostics"
                && message["params"]["version"] == version
        })
    }

    /// The server's minor page faults so far (`/proc/PID/stat`, field 10).
    fn minor_faults(&self) -> Option<u64> {
        let stat = std::fs::read_to_string(format!("/proc/{}/stat", self.child.id())).ok()?;
        let rest = stat.rsplit_once(')')?.1;
        rest.split_whitespace().nth(7)?.parse().ok()
    }

    fn resident_kib(&self) -> Option<u64> {
        self.status_kib("VmRSS:")
    }

    /// The most resident memory the server had at any moment (`VmHWM`).
    fn peak_kib(&self) -> Option<u64> {
        self.status_kib("VmHWM:")
    }

    fn status_kib(&self, field: &str) -> Option<u64> {
        let status = std::fs::read_to_string(format!("/proc/{}/status", self.child.id())).ok()?;
        status
            .lines()
            .find_map(|line| line.strip_prefix(field))
            .and_then(|value| value.trim().trim_end_matches("kB").trim().parse().ok())
    }

    fn stop(mut self) {
        let (_, id) = self.request("shutdown", Value::Null);
        self.wait_for(|message| message["id"] == id);
        self.notify("exit", Value::Null);
        let _ = self.child.wait();
    }
}

fn log_path() -> std::path::PathBuf {
    std::env::temp_dir().join(format!("sinumerik-lsp-latency-{}.log", std::process::id()))
}

/// From the server's log lines "analysis (A ms) and writing of N diagnostics took T ms": the median
/// time the server spent turning its diagnostics into the notification (T - A), over the runs logged.
fn writing_cost_from_log() {
    let log = std::fs::read_to_string(log_path()).unwrap_or_default();
    let mut samples: Vec<(u64, usize)> = log
        .lines()
        .filter_map(|line| {
            let rest = line.split_once("analysis (")?.1;
            let (analysis, rest) = rest.split_once(" ms) and writing of ")?;
            let (count, rest) = rest.split_once(" diagnostics took ")?;
            let total = rest.strip_suffix(" ms")?;
            Some((
                total
                    .parse::<u64>()
                    .ok()?
                    .saturating_sub(analysis.parse().ok()?),
                count.parse().ok()?,
            ))
        })
        .collect();
    if samples.is_empty() {
        println!("  server-side writing of the diagnostics: not logged (analysis and writing under 100 ms)");
        return;
    }
    samples.sort();
    let (median, count) = samples[samples.len() / 2];
    println!("  server-side conversion and writing of {count} diagnostics: median {median} ms ({} runs logged)", samples.len());
}

/// xorshift64*: repeatable random lines.
struct Random(u64);

impl Random {
    fn below(&mut self, bound: usize) -> usize {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) % bound as u64) as usize
    }
}

fn percentile(samples: &mut [Duration], fraction: f64) -> Duration {
    samples.sort();
    let index = ((samples.len() as f64 - 1.0) * fraction).round() as usize;
    samples[index.min(samples.len() - 1)]
}

fn milliseconds(duration: Duration) -> String {
    format!("{:.2} ms", duration.as_secs_f64() * 1e3)
}

fn summary(name: &str, samples: &mut [Duration]) {
    if samples.is_empty() {
        println!("  {name}: no samples");
        return;
    }
    let median = percentile(samples, 0.5);
    let p99 = percentile(samples, 0.99);
    let slowest: Vec<String> = samples
        .iter()
        .rev()
        .take(3)
        .map(|s| milliseconds(*s))
        .collect();
    println!(
        "  {name}: median {}, p99 {} ({} samples; slowest {})",
        milliseconds(median),
        milliseconds(p99),
        samples.len(),
        slowest.join(", ")
    );
}

fn env_number(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|value| value.parse().ok())
        .unwrap_or(default)
}

/// Where a one-character edit goes on line `line` of the program: a space at the start (cam3d), or
/// the last digit of its first coordinate replaced (inc). `None` when the line has no coordinate.
fn edit_for(style: &str, line: &str) -> Option<(usize, usize, String)> {
    if style != "inc" {
        return Some((0, 0, " ".to_string()));
    }
    let bytes = line.as_bytes();
    let axis = bytes
        .iter()
        .position(|&byte| byte == b'X' || byte == b'Y' || byte == b'Z')?;
    let mut end = axis + 1;
    while end < bytes.len()
        && (bytes[end].is_ascii_digit() || bytes[end] == b'.' || bytes[end] == b'-')
    {
        end += 1;
    }
    let digit = (axis + 1..end)
        .rev()
        .find(|&index| bytes[index].is_ascii_digit())?;
    let replacement = if bytes[digit] == b'9' {
        '8'
    } else {
        (bytes[digit] + 1) as char
    };
    Some((digit, digit + 1, replacement.to_string()))
}

/// The settings a run starts the server with, and what the figures are called.
struct Setup {
    name: &'static str,
    options: Value,
    transport: Transport,
}

/// A server measured side by side with others.
struct Variant {
    name: String,
    binary: std::path::PathBuf,
    env: Vec<(String, String)>,
}

/// The servers of `BENCH_VARIANTS` (see the file's documentation); this build's alone by default.
fn variants() -> Vec<Variant> {
    let list = std::env::var("BENCH_VARIANTS").unwrap_or_else(|_| "this build".to_string());
    list.split(';')
        .filter(|item| !item.trim().is_empty())
        .map(|item| {
            let mut parts = item.split(':');
            let head = parts.next().unwrap_or_default();
            let (name, binary) = match head.split_once('@') {
                Some((name, path)) => (name, std::path::PathBuf::from(path)),
                None => (
                    head,
                    std::path::PathBuf::from(env!("CARGO_BIN_EXE_sinumerik-lsp")),
                ),
            };
            let env = parts
                .filter_map(|setting| setting.split_once('='))
                .map(|(key, value)| (key.to_string(), value.to_string()))
                .collect();
            Variant {
                name: name.trim().to_string(),
                binary,
                env,
            }
        })
        .collect()
}

/// The program of `style`, from `BENCH_PROGRAM_DIR` when it was kept there before.
fn program(style: &str, line_count: usize) -> Option<String> {
    let Ok(directory) = std::env::var("BENCH_PROGRAM_DIR") else {
        return generated::generate(style, line_count);
    };
    let path = std::path::Path::new(&directory).join(format!("{style}_{line_count}.mpf"));
    if let Ok(text) = std::fs::read_to_string(&path) {
        return Some(text);
    }
    let text = generated::generate(style, line_count)?;
    let _ = std::fs::write(&path, &text);
    Some(text)
}

/// The goal figures of one run, in milliseconds and megabytes.
#[derive(Clone, Copy, Default)]
struct Figures {
    open: f64,
    edit_median: f64,
    edit_p99: f64,
    hover_p99: f64,
    peak_mb: f64,
    file_mb: f64,
}

fn run(style: &str, line_count: usize, setup: &Setup, variant: &Variant) -> Option<Figures> {
    let Some(text) = program(style, line_count) else {
        println!("{style}: skipped (../shared/bench/gen_program.py or python3 not available)");
        return None;
    };
    let mut figures = Figures::default();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let megabytes = text.len() as f64 / 1e6;
    figures.file_mb = megabytes;
    println!(
        "{style}, {}, server {}: {} lines, {megabytes:.1} MB",
        setup.name,
        variant.name,
        lines.len()
    );
    let budget = Duration::from_secs(env_number("BENCH_BUDGET_SECS", 240) as u64);
    let mut server = Server::start(setup.transport, variant);
    let (_, id) = server.request(
        "initialize",
        json!({"processId": null, "rootUri": null, "capabilities": {"general": {"positionEncodings": ["utf-16"]}}, "initializationOptions": setup.options}),
    );
    server.wait_for(|message| message["id"] == id);
    server.notify("initialized", json!({}));

    let uri = format!("file:///bench/{style}.mpf");
    let open = frame(
        &json!({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {"textDocument": {"uri": uri, "languageId": "sinumerik", "version": 1, "text": text}}}),
    );
    drop(text);
    json_costs(&open);
    server.keep_next_large_text();
    let faults_before = server.minor_faults();
    let started = server.send(&open);
    drop(open);
    let first = server.diagnostics_of(1);
    let faults_of_open = server
        .minor_faults()
        .zip(faults_before)
        .map(|(after, before)| after.saturating_sub(before));
    let diagnostic_count = first.diagnostic_count;
    figures.open = (first.at - started).as_secs_f64() * 1e3;
    println!(
        "  didOpen to first publishDiagnostics: {} ({diagnostic_count} diagnostics, a {:.1} MB message)",
        milliseconds(first.at - started),
        first.bytes as f64 / 1e6
    );
    // What that message costs a client to read, for scale: checked as this client reads every
    // large message, and as a tree of JSON values.
    if let Some(text) = &first.text {
        let checked_started = Instant::now();
        let (_, count) = read_large(text);
        let checked = checked_started.elapsed();
        let tree_started = Instant::now();
        let tree: Value = serde_json::from_slice(text).unwrap_or(Value::Null);
        let as_tree = tree_started.elapsed();
        drop(tree);
        println!(
            "  reading that message on the client side, for scale: {} parsed and checked ({count} diagnostics counted, as this client reads every large message), {} as a tree of JSON values",
            milliseconds(checked),
            milliseconds(as_tree)
        );
    }
    if let Some(resident) = server.resident_kib() {
        println!(
            "  resident memory after open: {:.1} MB ({:.2}x the file)",
            resident as f64 / 1024.0,
            resident as f64 * 1024.0 / (megabytes * 1e6)
        );
    }
    // Each first touch of a 4 KiB page is a fault; on a virtual machine each costs microseconds.
    if let Some(faults) = faults_of_open {
        println!("  page faults of the server during the open: {faults}");
    }

    let mut random = Random(0x5EED ^ line_count as u64);
    let mut version = 1;
    let mut edits = Vec::new();
    let mut edit_first_bytes = Vec::new();
    let edit_started = Instant::now();
    let show_slow = std::env::var_os("BENCH_SHOW_SLOW").is_some();
    while edits.len() < env_number("BENCH_EDITS", 200) && edit_started.elapsed() < budget {
        let line_idx = random.below(lines.len());
        let Some((start, end, new_text)) = edit_for(style, &lines[line_idx]) else {
            continue;
        };
        version += 1;
        let change = json!([{"range": {"start": {"line": line_idx, "character": start}, "end": {"line": line_idx, "character": end}}, "text": new_text}]);
        let encoded = frame(
            &json!({"jsonrpc": "2.0", "method": "textDocument/didChange", "params": {"textDocument": {"uri": uri, "version": version}, "contentChanges": change}}),
        );
        let sent = server.send(&encoded);
        let arrival = server.diagnostics_of(version);
        edits.push(arrival.at - sent);
        // `BENCH_SHOW_SLOW` prints each edit over 12 ms, to see whether slow ones come in runs.
        if show_slow && (arrival.at - sent) > Duration::from_millis(12) {
            println!(
                "    slow edit #{} at +{:.3} s: {} (first byte {})",
                edits.len(),
                (sent - edit_started).as_secs_f64(),
                milliseconds(arrival.at - sent),
                milliseconds(arrival.first_byte_at - sent)
            );
        }
        edit_first_bytes.push(arrival.first_byte_at - sent);
        lines[line_idx].replace_range(start..end, &new_text);
    }
    let kind = if style != "inc" {
        "space at the start of a line"
    } else {
        "changed coordinate digit"
    };
    summary(&format!("edit ({kind}) to publishDiagnostics"), &mut edits);
    if !edits.is_empty() {
        figures.edit_median = percentile(&mut edits, 0.5).as_secs_f64() * 1e3;
        figures.edit_p99 = percentile(&mut edits, 0.99).as_secs_f64() * 1e3;
    }
    summary(
        "  of which: edit to the first byte of that publishDiagnostics",
        &mut edit_first_bytes,
    );

    let mut hovers = Vec::new();
    let hover_started = Instant::now();
    while hovers.len() < env_number("BENCH_HOVERS", 200) && hover_started.elapsed() < budget {
        let line_idx = random.below(lines.len());
        let Some(column) = lines[line_idx].find(['X', 'Y', 'Z']) else {
            continue;
        };
        let (sent, id) = server.request("textDocument/hover", json!({"textDocument": {"uri": uri}, "position": {"line": line_idx, "character": column}}));
        let arrival = server.wait_for(|message| message["id"] == id);
        // `BENCH_SHOW_SLOW` also prints each hover over 1 ms, to see whether slow ones come in runs.
        if show_slow && (arrival.at - sent) > Duration::from_millis(1) {
            println!(
                "    slow hover #{} on line {line_idx} at +{:.3} s: {}",
                hovers.len(),
                (sent - hover_started).as_secs_f64(),
                milliseconds(arrival.at - sent)
            );
        }
        hovers.push(arrival.at - sent);
    }
    summary("hover on an axis word", &mut hovers);
    if !hovers.is_empty() {
        figures.hover_p99 = percentile(&mut hovers, 0.99).as_secs_f64() * 1e3;
    }
    if let Some(resident) = server.resident_kib() {
        println!(
            "  resident memory after the edits and hovers: {:.1} MB ({:.2}x the file)",
            resident as f64 / 1024.0,
            resident as f64 * 1024.0 / (megabytes * 1e6)
        );
    }
    // After a pause in editing the server also indexes the document's names for the workspace.
    thread::sleep(Duration::from_secs(3));
    if let Some(resident) = server.resident_kib() {
        println!(
            "  resident memory after a 3 s pause (the workspace index holds the document too): {:.1} MB ({:.2}x the file)",
            resident as f64 / 1024.0,
            resident as f64 * 1024.0 / (megabytes * 1e6)
        );
    }
    if let Some(peak) = server.peak_kib() {
        figures.peak_mb = peak as f64 * 1024.0 / 1e6;
        println!(
            "  peak resident memory (VmHWM): {:.1} MB ({:.2}x the file)",
            figures.peak_mb,
            figures.peak_mb / megabytes
        );
    }
    server.stop();
    writing_cost_from_log();
    Some(figures)
}

/// What reading the didOpen message costs a server, measured here with the same libraries: the
/// framing guard's check, and the framework's parse into a JSON value and then into typed params.
fn json_costs(framed: &[u8]) {
    let body_start = framed
        .windows(4)
        .position(|window| window == b"\r\n\r\n")
        .map_or(0, |index| index + 4);
    let body = &framed[body_start..];
    let started = Instant::now();
    let valid = std::str::from_utf8(body).is_ok()
        && serde_json::from_slice::<serde::de::IgnoredAny>(body).is_ok();
    let checked = started.elapsed();
    let started = Instant::now();
    let value: Value = serde_json::from_str(std::str::from_utf8(body).unwrap()).unwrap();
    let parsed = started.elapsed();
    let started = Instant::now();
    let params: tower_lsp_server::ls_types::DidOpenTextDocumentParams =
        serde_json::from_value(value["params"].clone()).unwrap();
    let typed = started.elapsed();
    println!(
        "  reading the didOpen message (measured here): check {} (valid: {valid}), to a JSON value {}, to typed params {} ({} bytes of text)",
        milliseconds(checked),
        milliseconds(parsed),
        milliseconds(typed),
        params.text_document.text.len()
    );
}

/// What serializing a publishDiagnostics of `count` diagnostics costs the server by itself.
fn serialization_cost(count: usize) {
    use tower_lsp_server::ls_types::{
        Diagnostic, DiagnosticSeverity, NumberOrString, Position, PublishDiagnosticsParams, Range,
        Uri,
    };
    let diagnostics: Vec<Diagnostic> = (0..count)
        .map(|index| Diagnostic {
            range: Range::new(
                Position::new(index as u32 * 40, 4),
                Position::new(index as u32 * 40, 30),
            ),
            severity: Some(DiagnosticSeverity::ERROR),
            code: Some(NumberOrString::String("A206".to_string())),
            source: Some("sinumerik".to_string()),
            message: "the end point is 0.412 mm off the circle (allowed 0.010 mm, alarm 14040)"
                .to_string(),
            ..Diagnostic::default()
        })
        .collect();
    let params = PublishDiagnosticsParams {
        uri: "file:///bench/cam3d.mpf".parse::<Uri>().unwrap(),
        diagnostics,
        version: Some(2),
    };
    // The framework turns the params into a JSON value first and that value into text.
    let started = Instant::now();
    let value = serde_json::to_value(&params).unwrap();
    let to_value = started.elapsed();
    let bytes = serde_json::to_vec(&value).unwrap();
    let total = started.elapsed();
    let started = Instant::now();
    drop(value);
    let dropped = started.elapsed();
    let started = Instant::now();
    let direct = serde_json::to_vec(&params).unwrap();
    let direct_time = started.elapsed();
    println!(
        "serializing {count} diagnostics as the framework does: {} ({} to a JSON value, {} to text, {} to free the value) for {:.1} MB; straight to text it would take {}",
        milliseconds(total + dropped),
        milliseconds(to_value),
        milliseconds(total - to_value),
        milliseconds(dropped),
        bytes.len() as f64 / 1e6,
        milliseconds(direct_time),
    );
    assert_eq!(direct.len(), bytes.len());
}

fn main() {
    let line_count = env_number("BENCH_LINES", 1_000_000);
    println!("language server latency over stdio, {line_count}-line programs, release binary");
    let setups = [
        Setup {
            name: "every finding published (the server's default), over pipes",
            options: json!({}),
            transport: Transport::Pipes,
        },
        Setup {
            name: "maxDiagnostics 1000 (what the VS Code extension sends), over pipes",
            options: json!({"maxDiagnostics": 1000}),
            transport: Transport::Pipes,
        },
        Setup {
            name:
                "every finding published, over socket pairs (as VS Code and Neovim start a server)",
            options: json!({}),
            transport: Transport::SocketPairs,
        },
    ];
    let styles = std::env::var("BENCH_STYLES").unwrap_or_else(|_| "cam3d,inc,noisy".to_string());
    let setup_count = env_number("BENCH_SETUPS", setups.len()).min(setups.len());
    let variants = variants();
    let rounds = env_number("BENCH_ROUNDS", 1).max(1);
    for setup in &setups[..setup_count] {
        let mut results: Vec<(String, String, Vec<Figures>)> = Vec::new();
        for round in 0..rounds {
            for style in styles.split(',') {
                for variant in &variants {
                    println!("round {}", round + 1);
                    let Some(figures) = run(style, line_count, setup, variant) else {
                        continue;
                    };
                    match results
                        .iter_mut()
                        .find(|(s, v, _)| s == style && *v == variant.name)
                    {
                        Some((_, _, list)) => list.push(figures),
                        None => {
                            results.push((style.to_string(), variant.name.clone(), vec![figures]))
                        }
                    }
                }
            }
        }
        side_by_side(setup.name, &results);
    }
    serialization_cost(24_000);
}

/// The median of each figure over the rounds, per style and server, as a table.
fn side_by_side(setup: &str, results: &[(String, String, Vec<Figures>)]) {
    println!("\nmedians over the rounds ({setup}):");
    println!("| style | server | rounds | open ms | edit median ms | edit p99 ms | hover p99 ms | peak MB (x file) |");
    println!("|---|---|---:|---:|---:|---:|---:|---:|");
    let median = |values: Vec<f64>| {
        let mut values = values;
        values.sort_by(f64::total_cmp);
        values[values.len() / 2]
    };
    for (style, variant, list) in results {
        let of = |pick: fn(&Figures) -> f64| median(list.iter().map(pick).collect());
        let all = |pick: fn(&Figures) -> f64| {
            list.iter()
                .map(|figures| format!("{:.1}", pick(figures)))
                .collect::<Vec<_>>()
                .join("/")
        };
        println!(
            "| {style} | {variant} | {} | {:.0} ({}) | {:.2} | {:.2} ({}) | {:.2} | {:.0} ({:.2}x; {}) |",
            list.len(),
            of(|f| f.open),
            all(|f| f.open),
            of(|f| f.edit_median),
            of(|f| f.edit_p99),
            all(|f| f.edit_p99),
            of(|f| f.hover_p99),
            of(|f| f.peak_mb),
            of(|f| f.peak_mb) / list[0].file_mb,
            all(|f| f.peak_mb),
        );
    }
}
