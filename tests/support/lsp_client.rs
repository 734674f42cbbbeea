//! A test client for the language server: speaks the protocol over any byte stream (an in-process
//! duplex or the stdio of the built binary), answers the server's requests, and waits for responses
//! and notifications with generous timeouts (the test machine may be loaded), never with sleeps.
//! Included with `#[path]` by each test target that needs it.

#![allow(dead_code)]

use serde_json::{json, Value};
use std::collections::VecDeque;
use std::sync::{Arc, Mutex};
use std::time::Duration;
use tokio::io::{AsyncBufReadExt, AsyncRead, AsyncReadExt, AsyncWrite, AsyncWriteExt, BufReader};
use tokio::sync::mpsc;

/// How long any one wait may take before the test fails.
pub const TIMEOUT: Duration = Duration::from_secs(180);

type Writer = Arc<tokio::sync::Mutex<Box<dyn AsyncWrite + Unpin + Send>>>;

pub struct TestClient {
    writer: Writer,
    incoming: mpsc::UnboundedReceiver<Value>,
    /// Messages received while waiting for something else.
    stash: VecDeque<Value>,
    next_id: i64,
    /// The answer to `workspace/configuration` (one value per item asked for).
    pub configuration: Arc<Mutex<Value>>,
    /// The answers to other requests of the server by method (`null` for methods not listed);
    /// `workspace/applyEdit` is answered `{"applied": true}` unless a test changes it.
    pub replies: Arc<Mutex<std::collections::HashMap<String, Value>>>,
    child: Option<tokio::process::Child>,
    server: Option<tokio::task::JoinHandle<()>>,
}

pub fn frame(body: &[u8]) -> Vec<u8> {
    let mut message = format!("Content-Length: {}\r\n\r\n", body.len()).into_bytes();
    message.extend_from_slice(body);
    message
}

/// Reads one framed message; `None` at the end of the stream.
pub async fn read_message<R: AsyncRead + Unpin>(reader: &mut BufReader<R>) -> Option<Value> {
    let mut length = None;
    loop {
        let mut header = String::new();
        if reader.read_line(&mut header).await.ok()? == 0 {
            return None;
        }
        let header = header.trim_end();
        if header.is_empty() {
            break;
        }
        if let Some(value) = header.strip_prefix("Content-Length:") {
            length = value.trim().parse::<usize>().ok();
        }
    }
    let mut body = vec![0; length?];
    reader.read_exact(&mut body).await.ok()?;
    serde_json::from_slice(&body).ok()
}

async fn write_value(writer: &Writer, value: &Value) {
    let message = frame(value.to_string().as_bytes());
    let mut writer = writer.lock().await;
    writer
        .write_all(&message)
        .await
        .expect("the server's input is open");
    writer.flush().await.expect("the server's input is open");
}

impl TestClient {
    fn start<R, W>(reader: R, writer: W) -> TestClient
    where
        R: AsyncRead + Unpin + Send + 'static,
        W: AsyncWrite + Unpin + Send + 'static,
    {
        let writer: Writer = Arc::new(tokio::sync::Mutex::new(Box::new(writer)));
        let configuration = Arc::new(Mutex::new(json!([null])));
        let replies = Arc::new(Mutex::new(std::collections::HashMap::from([(
            "workspace/applyEdit".to_string(),
            json!({"applied": true}),
        )])));
        let (sender, incoming) = mpsc::unbounded_channel();
        let reply_writer = Arc::clone(&writer);
        let reply_configuration = Arc::clone(&configuration);
        let reply_table = Arc::clone(&replies);
        tokio::spawn(async move {
            let mut reader = BufReader::new(reader);
            while let Some(message) = read_message(&mut reader).await {
                let is_request = message.get("method").is_some() && message.get("id").is_some();
                if is_request {
                    let result = if message["method"] == "workspace/configuration" {
                        reply_configuration.lock().unwrap().clone()
                    } else {
                        let method = message["method"].as_str().unwrap_or_default();
                        reply_table
                            .lock()
                            .unwrap()
                            .get(method)
                            .cloned()
                            .unwrap_or(Value::Null)
                    };
                    let reply = json!({"jsonrpc": "2.0", "id": message["id"], "result": result});
                    write_value(&reply_writer, &reply).await;
                }
                if sender.send(message).is_err() {
                    break;
                }
            }
        });
        TestClient {
            writer,
            incoming,
            stash: VecDeque::new(),
            next_id: 1,
            configuration,
            replies,
            child: None,
            server: None,
        }
    }

    /// A server in this process, over an in-memory pipe.
    pub fn in_process() -> TestClient {
        let (client_side, server_side) = tokio::io::duplex(1 << 20);
        let (server_read, server_write) = tokio::io::split(server_side);
        let server = tokio::spawn(sinumerik_lsp::lsp::serve(server_read, server_write));
        let (client_read, client_write) = tokio::io::split(client_side);
        let mut client = TestClient::start(client_read, client_write);
        client.server = Some(server);
        client
    }

    /// The built binary with `args`, over its stdin and stdout.
    pub fn spawn_binary(args: &[&str]) -> TestClient {
        let mut child = tokio::process::Command::new(env!("CARGO_BIN_EXE_sinumerik-lsp"))
            .args(args)
            .stdin(std::process::Stdio::piped())
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::null())
            .kill_on_drop(true)
            .spawn()
            .expect("the server binary starts");
        let stdin = child.stdin.take().unwrap();
        let stdout = child.stdout.take().unwrap();
        let mut client = TestClient::start(stdout, stdin);
        client.child = Some(child);
        client
    }

    async fn next_message(&mut self) -> Value {
        match tokio::time::timeout(TIMEOUT, self.incoming.recv()).await {
            Ok(Some(message)) => message,
            Ok(None) => panic!("the server closed its output"),
            Err(_) => panic!("no message from the server within {TIMEOUT:?}"),
        }
    }

    pub async fn notify(&mut self, method: &str, params: Value) {
        write_value(
            &self.writer,
            &json!({"jsonrpc": "2.0", "method": method, "params": params}),
        )
        .await;
    }

    /// Sends raw bytes (for malformed input).
    pub async fn send_raw(&mut self, bytes: &[u8]) {
        let mut writer = self.writer.lock().await;
        writer.write_all(bytes).await.unwrap();
        writer.flush().await.unwrap();
    }

    /// Sends a request and returns its id without waiting.
    pub async fn send_request(&mut self, method: &str, params: Value) -> i64 {
        let id = self.next_id;
        self.next_id += 1;
        write_value(
            &self.writer,
            &json!({"jsonrpc": "2.0", "id": id, "method": method, "params": params}),
        )
        .await;
        id
    }

    /// The response to request `id`: `Ok(result)` or `Err(error)`.
    pub async fn response(&mut self, id: i64) -> Result<Value, Value> {
        if let Some(index) = self
            .stash
            .iter()
            .position(|message| is_response(message, id))
        {
            return into_result(self.stash.remove(index).unwrap());
        }
        loop {
            let message = self.next_message().await;
            if is_response(&message, id) {
                return into_result(message);
            }
            self.stash.push_back(message);
        }
    }

    pub async fn request(&mut self, method: &str, params: Value) -> Result<Value, Value> {
        let id = self.send_request(method, params).await;
        self.response(id).await
    }

    /// The first notification `method` whose params satisfy `wanted`, also one received earlier.
    pub async fn notification(&mut self, method: &str, wanted: impl Fn(&Value) -> bool) -> Value {
        let matches = |message: &Value| {
            message.get("id").is_none() && message["method"] == method && wanted(&message["params"])
        };
        if let Some(index) = self.stash.iter().position(matches) {
            return self.stash.remove(index).unwrap()["params"].clone();
        }
        loop {
            let message = self.next_message().await;
            if matches(&message) {
                return message["params"].clone();
            }
            self.stash.push_back(message);
        }
    }

    /// The first request from the server `method` (already answered by this client).
    pub async fn server_request(&mut self, method: &str) -> Value {
        let matches = |message: &Value| message.get("id").is_some() && message["method"] == method;
        if let Some(index) = self.stash.iter().position(matches) {
            return self.stash.remove(index).unwrap();
        }
        loop {
            let message = self.next_message().await;
            if matches(&message) {
                return message;
            }
            self.stash.push_back(message);
        }
    }

    /// The diagnostics published for `uri` at `version`.
    pub async fn diagnostics(&mut self, uri: &str, version: i64) -> Vec<Value> {
        let params = self
            .notification("textDocument/publishDiagnostics", |params| {
                params["uri"] == uri && params["version"] == version
            })
            .await;
        params["diagnostics"]
            .as_array()
            .cloned()
            .unwrap_or_default()
    }

    /// `initialize` with the given client capabilities and options, then `initialized`.
    pub async fn initialize(&mut self, capabilities: Value, options: Value) -> Value {
        let result = self
            .request(
                "initialize",
                json!({"processId": null, "rootUri": null, "capabilities": capabilities, "initializationOptions": options}),
            )
            .await
            .expect("initialize succeeds");
        self.notify("initialized", json!({})).await;
        result
    }

    pub async fn open(&mut self, uri: &str, version: i64, text: &str) {
        self.notify(
            "textDocument/didOpen",
            json!({"textDocument": {"uri": uri, "languageId": "sinumerik", "version": version, "text": text}}),
        )
        .await;
    }

    pub async fn change(&mut self, uri: &str, version: i64, changes: Value) {
        self.notify(
            "textDocument/didChange",
            json!({"textDocument": {"uri": uri, "version": version}, "contentChanges": changes}),
        )
        .await;
    }

    pub async fn document_text(&mut self, uri: &str) -> (i64, String) {
        let result = self
            .request("sinumerik/documentText", json!({"uri": uri}))
            .await
            .expect("the document is open");
        (
            result["version"].as_i64().unwrap(),
            result["text"].as_str().unwrap().to_string(),
        )
    }

    pub async fn hover(&mut self, uri: &str, line: u32, character: u32) -> String {
        let result = self
            .request("textDocument/hover", json!({"textDocument": {"uri": uri}, "position": {"line": line, "character": character}}))
            .await
            .expect("hover succeeds");
        result["contents"]["value"]
            .as_str()
            .unwrap_or_default()
            .to_string()
    }

    /// `shutdown` and `exit`; for the binary, waits for it to end and returns its exit code.
    pub async fn shutdown(mut self) -> Option<i32> {
        self.request("shutdown", Value::Null)
            .await
            .expect("shutdown succeeds");
        self.notify("exit", Value::Null).await;
        if let Some(server) = self.server.take() {
            tokio::time::timeout(TIMEOUT, server)
                .await
                .expect("the server stops after exit")
                .unwrap();
        }
        match self.child.take() {
            Some(mut child) => {
                let status = tokio::time::timeout(TIMEOUT, child.wait())
                    .await
                    .expect("the binary exits")
                    .unwrap();
                status.code()
            }
            None => None,
        }
    }
}

impl TestClient {
    /// Waits for the binary to end (after `exit`) and returns its exit code.
    pub async fn wait_for_exit(mut self) -> Option<i32> {
        let mut child = self.child.take()?;
        let status = tokio::time::timeout(TIMEOUT, child.wait())
            .await
            .expect("the binary exits")
            .unwrap();
        status.code()
    }
}

fn is_response(message: &Value, id: i64) -> bool {
    message.get("method").is_none() && message["id"] == id
}

fn into_result(message: Value) -> Result<Value, Value> {
    match message.get("error") {
        Some(error) => Err(error.clone()),
        None => Ok(message["result"].clone()),
    }
}

/// A `file:` URI for a path.
pub fn file_uri(path: &std::path::Path) -> String {
    let absolute = std::path::absolute(path).unwrap();
    let mut uri = String::from("file://");
    for byte in absolute.to_string_lossy().bytes() {
        match byte {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'/' | b'-' | b'_' | b'.' | b'~' => {
                uri.push(byte as char)
            }
            _ => uri.push_str(&format!("%{byte:02X}")),
        }
    }
    uri
}

/// The seed example of the repository.
pub fn seed_text() -> String {
    std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/fixtures/examples/turning_seed.mpf"
    ))
    .unwrap()
}

/// LSP position (line, UTF-16 column) of the first occurrence of `needle` in `text`.
pub fn position_of(text: &str, needle: &str) -> (u32, u32) {
    let byte = text
        .find(needle)
        .unwrap_or_else(|| panic!("{needle:?} is in the text"));
    let before = &text[..byte];
    let line_start = before.rfind(['\n', '\r']).map_or(0, |index| index + 1);
    let line = before.matches('\n').count() + before.matches('\r').count()
        - before.matches("\r\n").count();
    (
        line as u32,
        before[line_start..].encode_utf16().count() as u32,
    )
}

/// The byte offset of an LSP position (UTF-16 columns) in `text`, clamped as the protocol's
/// servers clamp: past the end of a line is its end, past the last line is the end of the text,
/// inside a surrogate pair is the start of the character. Lines end at LF, CRLF or CR.
pub fn byte_offset(text: &str, line: u32, character: u32) -> usize {
    let bytes = text.as_bytes();
    let mut line_start = 0;
    for _ in 0..line {
        match bytes[line_start..]
            .iter()
            .position(|&byte| byte == b'\n' || byte == b'\r')
        {
            Some(offset) => {
                let terminator = line_start + offset;
                line_start = terminator
                    + if bytes[terminator] == b'\r' && bytes.get(terminator + 1) == Some(&b'\n') {
                        2
                    } else {
                        1
                    };
            }
            None => return text.len(),
        }
    }
    let line_end = bytes[line_start..]
        .iter()
        .position(|&byte| byte == b'\n' || byte == b'\r')
        .map_or(text.len(), |offset| line_start + offset);
    let mut units = 0;
    for (offset, ch) in text[line_start..line_end].char_indices() {
        let next = units + ch.len_utf16() as u32;
        if next > character {
            return line_start + offset;
        }
        units = next;
    }
    line_end
}

/// Applies one LSP edit to `text` the way the protocol defines it.
pub fn apply_edit(text: &mut String, start: (u32, u32), end: (u32, u32), new_text: &str) {
    let start = byte_offset(text, start.0, start.1);
    let end = byte_offset(text, end.0, end.1).max(start);
    text.replace_range(start..end, new_text);
}

/// A small deterministic pseudo-random generator (xorshift64*), so failures repeat.
pub struct Random(u64);

impl Random {
    pub fn new(seed: u64) -> Random {
        Random(seed.max(1))
    }

    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// A number in `0..bound` (0 when `bound` is 0).
    pub fn below(&mut self, bound: usize) -> usize {
        if bound == 0 {
            0
        } else {
            (self.next() % bound as u64) as usize
        }
    }

    pub fn pick<'a>(&mut self, items: &[&'a str]) -> &'a str {
        items[self.below(items.len())]
    }
}

/// The number of LSP lines of a text (at least one).
pub fn lsp_line_count(text: &str) -> usize {
    1 + text.matches('\n').count() + text.matches('\r').count() - text.matches("\r\n").count()
}

/// The UTF-16 length of LSP line `line` of `text`.
pub fn lsp_line_length(text: &str, line: u32) -> u32 {
    let start = byte_offset(text, line, 0);
    let end = byte_offset(text, line, u32::MAX);
    text[start..end].encode_utf16().count() as u32
}

impl TestClient {
    /// `sinumerik.endpointPreview` with one argument object (`{"uri", "startLine"?, "endLine"?}`).
    pub async fn preview(&mut self, argument: Value) -> Result<Value, Value> {
        self.request(
            "workspace/executeCommand",
            json!({"command": "sinumerik.endpointPreview", "arguments": [argument]}),
        )
        .await
    }

    /// The inlay hints of lines `first ..= last` as (line, label).
    pub async fn inlay_hint_labels(
        &mut self,
        uri: &str,
        first: u32,
        last: u32,
    ) -> Vec<(u64, String)> {
        let hints = self
            .request(
                "textDocument/inlayHint",
                json!({"textDocument": {"uri": uri}, "range": {"start": {"line": first, "character": 0}, "end": {"line": last, "character": 0}}}),
            )
            .await
            .expect("inlay hints succeed");
        hints
            .as_array()
            .expect("a list of hints")
            .iter()
            .map(|hint| {
                (
                    hint["position"]["line"].as_u64().unwrap(),
                    hint["label"].as_str().unwrap().to_string(),
                )
            })
            .collect()
    }
}

/// An empty folder of its own for one test.
pub fn temp_folder(name: &str) -> std::path::PathBuf {
    let folder =
        std::env::temp_dir().join(format!("sinumerik-lsp-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&folder);
    std::fs::create_dir_all(&folder).unwrap();
    folder
}

/// Applies LSP text edits (`[{"range", "newText"}]`, positions in UTF-16) to `text`, as a client
/// does: all ranges refer to the text before the edits.
pub fn apply_text_edits(text: &str, edits: &[Value]) -> String {
    let mut located: Vec<(usize, usize, &str)> = edits
        .iter()
        .map(|edit| {
            let at = |point: &Value| {
                byte_offset(
                    text,
                    point["line"].as_u64().unwrap() as u32,
                    point["character"].as_u64().unwrap() as u32,
                )
            };
            (
                at(&edit["range"]["start"]),
                at(&edit["range"]["end"]),
                edit["newText"].as_str().unwrap(),
            )
        })
        .collect();
    located.sort_by_key(|(start, end, _)| std::cmp::Reverse((*start, *end)));
    let mut out = text.to_string();
    for (start, end, new_text) in located {
        out.replace_range(start..end.max(start), new_text);
    }
    out
}
