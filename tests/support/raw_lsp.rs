//! A raw client for the server binary over stdio, for abuse, storm and soak runs: it writes any
//! bytes (malformed headers, bodies that are not JSON, messages cut into pieces), a reader thread
//! collects every framed message the server writes, and every wait has a deadline, so a server that
//! hangs fails the run instead of blocking it. Plain threads, no async runtime: the writer and the
//! reader never wait for each other, so a server that writes a lot cannot stall the client.
//! Included with `#[path]` by each target that needs it.

#![allow(dead_code)]

use serde_json::{json, Value};
use std::collections::VecDeque;
use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::atomic::{AtomicI64, Ordering};
use std::sync::{mpsc, Arc, Mutex};
use std::time::{Duration, Instant};

/// How long any one wait may take before the run fails (the machine may be loaded).
pub const TIMEOUT: Duration = Duration::from_secs(180);

/// A message from the server and the moment its last byte arrived.
pub struct Arrival {
    pub at: Instant,
    pub message: Value,
}

pub fn frame(body: &[u8]) -> Vec<u8> {
    let mut message = format!("Content-Length: {}\r\n\r\n", body.len()).into_bytes();
    message.extend_from_slice(body);
    message
}

/// The writing side; clones share the server's input and the request numbering, so several
/// threads can send at once (each message is written whole, under a lock).
#[derive(Clone)]
pub struct Writer {
    stdin: Arc<Mutex<Option<ChildStdin>>>,
    next_id: Arc<AtomicI64>,
}

impl Writer {
    /// Writes bytes as they are and flushes; `false` when the server's input is closed.
    pub fn write_raw(&self, bytes: &[u8]) -> bool {
        let mut stdin = self.stdin.lock().unwrap();
        match stdin.as_mut() {
            Some(stdin) => stdin.write_all(bytes).is_ok() && stdin.flush().is_ok(),
            None => false,
        }
    }

    /// Writes bytes in pieces of `piece` bytes, flushing and pausing after each, so the server
    /// reads them in as many reads.
    pub fn write_in_pieces(&self, bytes: &[u8], piece: usize, pause: Duration) {
        for chunk in bytes.chunks(piece.max(1)) {
            assert!(self.write_raw(chunk), "the server's input is open");
            std::thread::sleep(pause);
        }
    }

    pub fn send(&self, message: &Value) {
        assert!(
            self.write_raw(&frame(message.to_string().as_bytes())),
            "the server's input is open"
        );
    }

    pub fn notify(&self, method: &str, params: Value) {
        self.send(&json!({"jsonrpc": "2.0", "method": method, "params": params}));
    }

    /// Sends a request and returns its id without waiting for the answer.
    pub fn request(&self, method: &str, params: Value) -> i64 {
        let id = self.next_id.fetch_add(1, Ordering::SeqCst);
        self.send(&json!({"jsonrpc": "2.0", "id": id, "method": method, "params": params}));
        id
    }

    pub fn change(&self, uri: &str, version: i64, changes: Value) {
        self.notify(
            "textDocument/didChange",
            json!({"textDocument": {"uri": uri, "version": version}, "contentChanges": changes}),
        );
    }

    pub fn request_hover(&self, uri: &str, line: u64, character: u64) -> i64 {
        self.request(
            "textDocument/hover",
            json!({"textDocument": {"uri": uri}, "position": {"line": line, "character": character}}),
        )
    }

    pub fn request_preview(&self, uri: &str, start_line: u64, end_line: u64) -> i64 {
        self.request(
            "workspace/executeCommand",
            json!({"command": "sinumerik.endpointPreview", "arguments": [{"uri": uri, "startLine": start_line, "endLine": end_line}]}),
        )
    }
}

pub struct RawServer {
    child: Child,
    pub writer: Writer,
    incoming: mpsc::Receiver<Arrival>,
    /// Messages received while waiting for something else.
    stash: VecDeque<Arrival>,
    stderr: Arc<Mutex<String>>,
    publications: Publications,
}

/// The (uri, version) of every `publishDiagnostics`, in the order they arrived.
pub type Publications = Arc<Mutex<Vec<(String, Option<i64>)>>>;

/// Reads the server's output: one framed message after the other, until it ends. Output that is not
/// a well-framed JSON message is passed on as `{"invalidOutput": ...}`, which the waits report.
fn read_output(stdout: impl Read, sender: mpsc::Sender<Arrival>, publications: Publications) {
    let mut reader = BufReader::with_capacity(1 << 20, stdout);
    loop {
        let mut length = None;
        loop {
            let mut header = String::new();
            match reader.read_line(&mut header) {
                Ok(0) | Err(_) => return,
                Ok(_) => {}
            }
            let header = header.trim_end();
            if header.is_empty() {
                break;
            }
            if let Some(value) = header.strip_prefix("Content-Length:") {
                length = value.trim().parse::<usize>().ok();
            }
        }
        let message = match length {
            Some(length) => {
                let mut body = vec![0; length];
                if reader.read_exact(&mut body).is_err() {
                    return;
                }
                serde_json::from_slice(&body).unwrap_or_else(
                    |_| json!({"invalidOutput": String::from_utf8_lossy(&body).into_owned()}),
                )
            }
            None => json!({"invalidOutput": "a header without Content-Length"}),
        };
        if message["method"] == "textDocument/publishDiagnostics" {
            publications.lock().unwrap().push((
                message["params"]["uri"]
                    .as_str()
                    .unwrap_or_default()
                    .to_string(),
                message["params"]["version"].as_i64(),
            ));
        }
        let arrival = Arrival {
            at: Instant::now(),
            message,
        };
        if sender.send(arrival).is_err() {
            return;
        }
    }
}

impl RawServer {
    /// Starts the built binary as a language server; its log (stderr) is collected.
    pub fn spawn() -> RawServer {
        let mut child = Command::new(env!("CARGO_BIN_EXE_sinumerik-lsp"))
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("the server binary starts");
        let stdin = child.stdin.take().unwrap();
        let stdout = child.stdout.take().unwrap();
        let stderr = child.stderr.take().unwrap();
        let (sender, incoming) = mpsc::channel();
        let publications = Publications::default();
        let recorded = Arc::clone(&publications);
        std::thread::spawn(move || read_output(stdout, sender, recorded));
        let log = Arc::new(Mutex::new(String::new()));
        let log_writer = Arc::clone(&log);
        std::thread::spawn(move || {
            let mut reader = BufReader::new(stderr);
            let mut line = String::new();
            while reader.read_line(&mut line).unwrap_or(0) > 0 {
                log_writer.lock().unwrap().push_str(&line);
                line.clear();
            }
        });
        RawServer {
            child,
            writer: Writer {
                stdin: Arc::new(Mutex::new(Some(stdin))),
                next_id: Arc::new(AtomicI64::new(1)),
            },
            incoming,
            stash: VecDeque::new(),
            stderr: log,
            publications,
        }
    }

    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    /// The server's resident memory (VmRSS) in KiB, from /proc.
    pub fn resident_kib(&self) -> Option<u64> {
        let status = std::fs::read_to_string(format!("/proc/{}/status", self.pid())).ok()?;
        status
            .lines()
            .find_map(|line| line.strip_prefix("VmRSS:"))
            .and_then(|value| value.trim().trim_end_matches("kB").trim().parse().ok())
    }

    /// The (uri, version) of every `publishDiagnostics` so far, in the order they arrived.
    pub fn publications(&self) -> Vec<(String, Option<i64>)> {
        self.publications.lock().unwrap().clone()
    }

    /// What the server logged on stderr so far.
    pub fn log(&self) -> String {
        self.stderr.lock().unwrap().clone()
    }

    /// Waits until the log holds `words` (the log is written by another thread).
    pub fn wait_for_log(&self, words: &str) {
        let deadline = Instant::now() + TIMEOUT;
        while !self.log().contains(words) {
            assert!(
                Instant::now() < deadline,
                "the server did not log {words:?} within {TIMEOUT:?}; its log:\n{}",
                self.log()
            );
            std::thread::sleep(Duration::from_millis(10));
        }
    }

    /// Closes the server's input (end of file).
    pub fn close_input(&self) {
        self.writer.stdin.lock().unwrap().take();
    }

    fn next_arrival(&mut self, deadline: Instant) -> Arrival {
        let left = deadline.saturating_duration_since(Instant::now());
        match self.incoming.recv_timeout(left) {
            Ok(arrival) => {
                assert!(
                    arrival.message.get("invalidOutput").is_none(),
                    "the server wrote something that is not a message: {}",
                    arrival.message
                );
                arrival
            }
            Err(mpsc::RecvTimeoutError::Timeout) => {
                panic!(
                    "no message from the server within {TIMEOUT:?}; its log:\n{}",
                    self.log()
                )
            }
            Err(mpsc::RecvTimeoutError::Disconnected) => {
                panic!("the server closed its output; its log:\n{}", self.log())
            }
        }
    }

    /// The first message (also one received earlier) that `wanted` accepts.
    pub fn wait_for(&mut self, wanted: impl Fn(&Value) -> bool) -> Arrival {
        if let Some(index) = self
            .stash
            .iter()
            .position(|arrival| wanted(&arrival.message))
        {
            return self.stash.remove(index).unwrap();
        }
        let deadline = Instant::now() + TIMEOUT;
        loop {
            let arrival = self.next_arrival(deadline);
            if wanted(&arrival.message) {
                return arrival;
            }
            self.stash.push_back(arrival);
        }
    }

    /// Every message received so far that nobody waited for, oldest first; the stash is emptied.
    pub fn take_received(&mut self) -> Vec<Value> {
        while let Ok(arrival) = self.incoming.try_recv() {
            self.stash.push_back(arrival);
        }
        self.stash
            .drain(..)
            .map(|arrival| arrival.message)
            .collect()
    }

    /// The answer to request `id`: `Ok(result)` or `Err(error)`.
    pub fn response(&mut self, id: i64) -> Result<Value, Value> {
        let arrival = self.wait_for(|message| is_response_to(message, id));
        into_result(arrival.message)
    }

    pub fn request(&mut self, method: &str, params: Value) -> Result<Value, Value> {
        let id = self.writer.request(method, params);
        self.response(id)
    }

    pub fn notify(&mut self, method: &str, params: Value) {
        self.writer.notify(method, params);
    }

    pub fn write_raw(&mut self, bytes: &[u8]) {
        assert!(self.writer.write_raw(bytes), "the server's input is open");
    }

    /// `initialize` (UTF-16 positions, no capabilities) and `initialized`.
    pub fn initialize(&mut self) -> Value {
        let result = self
            .request(
                "initialize",
                json!({"processId": null, "rootUri": null, "capabilities": {}}),
            )
            .expect("initialize succeeds");
        self.notify("initialized", json!({}));
        result
    }

    pub fn open(&mut self, uri: &str, version: i64, text: &str) {
        self.notify(
            "textDocument/didOpen",
            json!({"textDocument": {"uri": uri, "languageId": "sinumerik", "version": version, "text": text}}),
        );
    }

    pub fn close(&mut self, uri: &str) {
        self.notify(
            "textDocument/didClose",
            json!({"textDocument": {"uri": uri}}),
        );
    }

    pub fn change(&mut self, uri: &str, version: i64, changes: Value) {
        self.writer.change(uri, version, changes);
    }

    /// The diagnostics published for `uri` at `version`.
    pub fn diagnostics(&mut self, uri: &str, version: i64) -> Vec<Value> {
        let arrival = self.wait_for(|message| {
            message["method"] == "textDocument/publishDiagnostics"
                && message["params"]["uri"] == uri
                && message["params"]["version"] == version
        });
        arrival.message["params"]["diagnostics"]
            .as_array()
            .cloned()
            .unwrap_or_default()
    }

    pub fn hover(&mut self, uri: &str, line: u64, character: u64) -> Result<Value, Value> {
        let id = self.writer.request_hover(uri, line, character);
        self.response(id)
    }

    /// The text of a hover (empty when there is none).
    pub fn hover_text(&mut self, uri: &str, line: u64, character: u64) -> String {
        let result = self.hover(uri, line, character).expect("hover succeeds");
        result["contents"]["value"]
            .as_str()
            .unwrap_or_default()
            .to_string()
    }

    /// The server's copy of a document (`sinumerik/documentText`): its version and text.
    pub fn document_text(&mut self, uri: &str) -> Result<(i64, String), Value> {
        let result = self.request("sinumerik/documentText", json!({"uri": uri}))?;
        Ok((
            result["version"].as_i64().unwrap(),
            result["text"].as_str().unwrap().to_string(),
        ))
    }

    /// Waits for the process to end and returns its exit code.
    pub fn wait_for_exit(&mut self) -> Option<i32> {
        let deadline = Instant::now() + TIMEOUT;
        loop {
            if let Some(status) = self.child.try_wait().expect("the server can be waited for") {
                return status.code();
            }
            assert!(
                Instant::now() < deadline,
                "the server did not exit within {TIMEOUT:?}"
            );
            std::thread::sleep(Duration::from_millis(10));
        }
    }

    /// `shutdown` and `exit`; returns the exit code.
    pub fn shutdown(mut self) -> Option<i32> {
        self.request("shutdown", Value::Null)
            .expect("shutdown succeeds");
        self.notify("exit", Value::Null);
        self.wait_for_exit()
    }
}

impl Drop for RawServer {
    fn drop(&mut self) {
        // A test that failed half way must not leave its server running.
        if let Ok(None) = self.child.try_wait() {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
    }
}

pub fn is_response_to(message: &Value, id: i64) -> bool {
    message.get("method").is_none() && message["id"] == id
}

pub fn into_result(message: Value) -> Result<Value, Value> {
    match message.get("error") {
        Some(error) => Err(error.clone()),
        None => Ok(message["result"].clone()),
    }
}
