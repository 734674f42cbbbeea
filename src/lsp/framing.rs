//! A guard in front of the framework's message reader: it passes on only well-formed messages
//! (a `Content-Length` header and a UTF-8 JSON-RPC message of that length) and drops the rest with a
//! log line and the error response JSON-RPC asks for. The framework's reader stops for good at the
//! first body it cannot read, which would end the server; with this guard a bad message costs only
//! itself: after a wrong or missing length the guard finds the next header and reads on from there.

use crate::lsp::arriving_open::{Arrived, ArrivingMessage};
use crate::lsp::log;
use crate::lsp::memory;
use crate::lsp::open_texts::{take_text_out, OpenTexts, LARGE_MESSAGE_BYTES};
use crate::lsp::outgoing::OutgoingSender;
use serde::de::IgnoredAny;
use serde::Deserialize;
use std::borrow::Cow;
use std::sync::Arc;
use tokio::io::{AsyncBufReadExt, AsyncRead, AsyncReadExt, AsyncWriteExt, BufReader, DuplexStream};
use tower_lsp_server::jsonrpc::{Error, Id, Response};
use tower_lsp_server::ls_types::{InitializeParams, MessageType};

/// Larger messages are refused: no editor sends a program this large (VS Code stops at 50 MB). The
/// bytes behind such a header are read as what follows it, so a wrong length cannot make the server
/// wait for gigabytes that never come.
const MAX_MESSAGE_LENGTH: usize = 1 << 30;

/// The size of the pipe between the guard and the framework.
const PIPE_SIZE: usize = 1 << 20;

/// A header line is short; a "line" of megabytes is garbage and is read in pieces of this size.
const MAX_HEADER_LINE: usize = 64 * 1024;

const CONTENT_LENGTH: &[u8] = b"content-length:";

/// Returns a reader that yields the well-formed messages of `input`, framed again. Error responses
/// to the messages dropped go to `outgoing`; the texts of large `didOpen` messages go to
/// `open_texts` (see `open_texts.rs`).
pub fn guard_input<R>(
    input: R,
    outgoing: OutgoingSender,
    open_texts: Arc<OpenTexts>,
) -> DuplexStream
where
    R: AsyncRead + Unpin + Send + 'static,
{
    let (mut to_server, from_guard) = tokio::io::duplex(PIPE_SIZE);
    tokio::spawn(async move {
        let mut input = Input::new(input);
        let mut initialize_passed = false;
        while let Some(body) =
            next_body(&mut input, &outgoing, &open_texts, &mut initialize_passed).await
        {
            let Some(body) = body else { continue };
            let header = format!("Content-Length: {}\r\n\r\n", body.len());
            if to_server.write_all(header.as_bytes()).await.is_err()
                || to_server.write_all(&body).await.is_err()
            {
                // The server has stopped reading (after `exit`).
                return;
            }
        }
        let _ = to_server.shutdown().await;
    });
    from_guard
}

/// The client's bytes, with bytes already read put back in front: the part of a damaged message's
/// body from the next header on.
struct Input<R> {
    reader: BufReader<R>,
    put_back: Vec<u8>,
    position: usize,
}

impl<R: AsyncRead + Unpin> Input<R> {
    fn new(reader: R) -> Input<R> {
        Input {
            reader: BufReader::new(reader),
            put_back: Vec::new(),
            position: 0,
        }
    }

    fn put_back(&mut self, bytes: &[u8]) {
        let mut put_back = bytes.to_vec();
        put_back.extend_from_slice(&self.put_back[self.position..]);
        self.put_back = put_back;
        self.position = 0;
    }

    /// Takes up to `limit` bytes of what was put back, up to and including a `\n`.
    fn take_put_back(&mut self, line: &mut Vec<u8>, limit: usize) -> usize {
        let rest = &self.put_back[self.position..];
        let length = memchr::memchr(b'\n', rest)
            .map_or(rest.len(), |index| index + 1)
            .min(limit);
        line.extend_from_slice(&rest[..length]);
        self.consume_put_back(length);
        length
    }

    /// Marks `count` bytes of what was put back as read; all of it read, the buffer goes.
    fn consume_put_back(&mut self, count: usize) {
        self.position += count;
        if self.position == self.put_back.len() {
            self.put_back = Vec::new();
            self.position = 0;
        }
    }

    /// Reads up to and including the next `\n`, at most `limit` bytes; 0 at the end of the input.
    async fn read_line(&mut self, line: &mut Vec<u8>, limit: usize) -> std::io::Result<usize> {
        let mut read = self.take_put_back(line, limit);
        if line.last() != Some(&b'\n') && read < limit {
            read += (&mut self.reader)
                .take((limit - read) as u64)
                .read_until(b'\n', line)
                .await?;
        }
        Ok(read)
    }

    /// The next `length` bytes, a message that is not large.
    async fn read_body(&mut self, length: usize) -> std::io::Result<Vec<u8>> {
        let mut body = Vec::with_capacity(length);
        let rest = &self.put_back[self.position..];
        let from_put_back = rest.len().min(length);
        body.extend_from_slice(&rest[..from_put_back]);
        self.consume_put_back(from_put_back);
        while body.len() < length {
            let wanted = (length - body.len()) as u64;
            if (&mut self.reader).take(wanted).read_buf(&mut body).await? == 0 {
                return Err(std::io::ErrorKind::UnexpectedEof.into());
            }
        }
        Ok(body)
    }

    /// The next `length` bytes, a large message: handed in pieces, as they arrive, to a blocking
    /// thread that reads the text of a `didOpen` meanwhile (`arriving_open.rs`) and, once all is
    /// there, passes the message on or checks it.
    async fn read_large_body(
        &mut self,
        length: usize,
        texts: Arc<OpenTexts>,
    ) -> std::io::Result<LargeBody> {
        let (pieces, arrived) = std::sync::mpsc::channel::<Vec<u8>>();
        let reading = tokio::task::spawn_blocking(move || {
            let mut message = ArrivingMessage::new();
            let mut received = 0;
            for piece in arrived {
                received += piece.len();
                message.push(piece);
            }
            // Fewer bytes mean the input ended or failed: the reading side says so.
            (received == length).then(|| read_arrived(message.finish(&texts), &texts))
        });
        let rest = &self.put_back[self.position..];
        let from_put_back = rest.len().min(length);
        let mut received = from_put_back;
        // A send fails only when the thread is gone (a panic), which the join below reports.
        let _ = pieces.send(rest[..from_put_back].to_vec());
        self.consume_put_back(from_put_back);
        while received < length {
            let wanted = (length - received).min(ARRIVING_PIECE_BYTES);
            // Each piece is filled before it is handed on: its pages are all mapped already.
            let mut piece = memory::populated_buffer(wanted);
            while piece.len() < wanted {
                let missing = (wanted - piece.len()) as u64;
                if (&mut self.reader)
                    .take(missing)
                    .read_buf(&mut piece)
                    .await?
                    == 0
                {
                    return Err(std::io::ErrorKind::UnexpectedEof.into());
                }
            }
            received += piece.len();
            let _ = pieces.send(piece);
        }
        drop(pieces);
        match reading.await {
            Ok(Some(body)) => Ok(body),
            _ => Err(std::io::Error::other("the large message could not be read")),
        }
    }
}

/// A large message goes to the thread that reads it in pieces of at most this size, small enough for
/// the thread to start on the text soon.
const ARRIVING_PIECE_BYTES: usize = 512 * 1024;

/// A large message, read.
enum LargeBody {
    /// A `didOpen` with its text taken out: the message to pass on.
    TextTaken(Vec<u8>),
    /// Any other message, with what checking it found.
    Other(Vec<u8>, Result<MessageKind, BodyProblem>),
}

/// What a large message that has arrived is, on a blocking thread. A `didOpen` whose text was not
/// found while it arrived (its fields in an unusual order) has it taken out from the whole body.
fn read_arrived(arrived: Arrived, texts: &OpenTexts) -> LargeBody {
    let (forwarded, body) = match arrived {
        Arrived::TextTaken { forwarded, pieces } => (forwarded, pieces),
        Arrived::Other(body) => match take_text_out(&body, texts) {
            Some(forwarded) => (forwarded, vec![body]),
            None => {
                let check = check_body(&body);
                return LargeBody::Other(body, check);
            }
        },
    };
    // Giving back the pages of tens of megabytes takes milliseconds: not while the editor waits for
    // the first diagnostics.
    tokio::task::spawn_blocking(move || drop(body));
    LargeBody::TextTaken(forwarded)
}

/// The value of a `Content-Length` header in `line`. The last one counts, wherever it starts: the
/// rest of a body whose length was given too short runs into the next message's header.
fn content_length(line: &[u8]) -> Option<Result<usize, String>> {
    let lower = line.to_ascii_lowercase();
    let start = memchr::memmem::rfind(&lower, CONTENT_LENGTH)? + CONTENT_LENGTH.len();
    let value = String::from_utf8_lossy(&line[start..]);
    let value = value.trim();
    Some(value.parse::<usize>().map_err(|_| value.to_string()))
}

/// The next message body: `None` at the end of the input, `Some(None)` for a message that was
/// dropped. `initialize_passed` says whether an `initialize` the server will accept went through.
async fn next_body<R: AsyncRead + Unpin>(
    input: &mut Input<R>,
    outgoing: &OutgoingSender,
    open_texts: &Arc<OpenTexts>,
    initialize_passed: &mut bool,
) -> Option<Option<Vec<u8>>> {
    let mut length = None;
    let mut header_lines = 0;
    loop {
        let mut line = Vec::new();
        if input.read_line(&mut line, MAX_HEADER_LINE).await.ok()? == 0 {
            return None;
        }
        let text = line.strip_suffix(b"\n").unwrap_or(&line);
        let text = text.strip_suffix(b"\r").unwrap_or(text);
        if text.is_empty() {
            if header_lines > 0 {
                break;
            }
            continue;
        }
        header_lines += 1;
        if let Some(value) = content_length(text) {
            length = Some(value);
        }
    }
    let length = match length {
        Some(Ok(length)) if length <= MAX_MESSAGE_LENGTH => length,
        Some(Ok(length)) => {
            warn(&format!(
                "a Content-Length of {length} bytes is over the limit of {MAX_MESSAGE_LENGTH}; the header is ignored"
            ));
            return Some(None);
        }
        Some(Err(value)) => {
            warn(&format!(
                "a message with the Content-Length {value:?}, which is not a length, was dropped"
            ));
            return Some(None);
        }
        None => {
            warn("a message without a valid Content-Length header was dropped");
            return Some(None);
        }
    };
    let (body, checked) = if length >= LARGE_MESSAGE_BYTES {
        // A didOpen of megabytes has its text read into the rope while it arrives; what goes on to
        // the framework is then a small message written here. Any other large message (a whole
        // text in a didChange) is checked off the async threads too.
        match input
            .read_large_body(length, Arc::clone(open_texts))
            .await
            .ok()?
        {
            LargeBody::TextTaken(forwarded) => {
                return Some(Some(forwarded));
            }
            LargeBody::Other(body, check) => (body, Some(check)),
        }
    } else {
        (input.read_body(length).await.ok()?, None)
    };
    match checked.unwrap_or_else(|| check_body(&body)) {
        Ok(MessageKind::Initialize) => {
            // The framework would run an `initialize` that arrives before the first is answered
            // as a second initialization: once one the server accepts went through, no other does.
            if *initialize_passed {
                warn("a second initialize was refused");
                outgoing.send_message(error_response(&body, BodyProblem::SecondInitialize));
                return Some(None);
            }
            *initialize_passed = initialize_is_valid(&body);
            Some(Some(body))
        }
        Ok(MessageKind::Other) => Some(Some(body)),
        Err(problem) => {
            // A length given too long swallowed the start of the next message: read on from its
            // header.
            if let Some(next) = memchr::memmem::find(&body, b"Content-Length:") {
                input.put_back(&body[next..]);
            }
            warn(&format!("a message of {length} bytes {problem}"));
            outgoing.send_message(error_response(&body, problem));
            Some(None)
        }
    }
}

fn warn(message: &str) {
    log::to_stderr(MessageType::WARNING, message);
}

/// What the framework accepts as a request or notification, read without building its parameters
/// (a `didOpen` may carry 50 MB): the same fields, with the same types.
/// The method is required: the framework would read a message without one as a request of the
/// method "", which may well be a damaged response that must not be answered with its id.
#[derive(Deserialize)]
struct RequestShape<'a> {
    #[serde(borrow)]
    jsonrpc: Cow<'a, str>,
    #[serde(borrow)]
    method: Cow<'a, str>,
    #[serde(default)]
    id: Option<Id>,
    #[serde(default)]
    #[allow(dead_code)]
    params: Option<IgnoredAny>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum MessageKind {
    Initialize,
    Other,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum BodyProblem {
    NotJson,
    NotMessage,
    SecondInitialize,
}

impl std::fmt::Display for BodyProblem {
    fn fmt(&self, formatter: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        formatter.write_str(match self {
            BodyProblem::NotJson => "that is not JSON was dropped",
            BodyProblem::NotMessage => "that is not a JSON-RPC message was dropped",
            BodyProblem::SecondInitialize => "is a second initialize",
        })
    }
}

/// Whether the framework can read `body` as a message. The framework reads the body as a `str`,
/// so invalid UTF-8 would stop it as well.
fn check_body(body: &[u8]) -> Result<MessageKind, BodyProblem> {
    if std::str::from_utf8(body).is_err() {
        return Err(BodyProblem::NotJson);
    }
    if let Ok(request) = serde_json::from_slice::<RequestShape>(body) {
        if request.jsonrpc == "2.0" {
            return Ok(if request.method == "initialize" && request.id.is_some() {
                MessageKind::Initialize
            } else {
                MessageKind::Other
            });
        }
    }
    if serde_json::from_slice::<IgnoredAny>(body).is_err() {
        return Err(BodyProblem::NotJson);
    }
    // Responses to the server's requests are small; the framework's own type decides.
    if serde_json::from_slice::<Response>(body).is_ok() {
        return Ok(MessageKind::Other);
    }
    Err(BodyProblem::NotMessage)
}

/// Whether the server accepts this `initialize` (its only failure is parameters it cannot read).
fn initialize_is_valid(body: &[u8]) -> bool {
    #[derive(Deserialize)]
    struct Initialize {
        #[allow(dead_code)]
        params: InitializeParams,
    }
    serde_json::from_slice::<Initialize>(body).is_ok()
}

/// The error response to a dropped message, framed: a parse error, or an invalid request answered
/// with the request's id when it has one (a message without a method is no request, and a response
/// is never answered with its own id).
fn error_response(body: &[u8], problem: BodyProblem) -> Vec<u8> {
    let (id, error) = match problem {
        BodyProblem::NotJson => (Id::Null, Error::parse_error()),
        BodyProblem::NotMessage | BodyProblem::SecondInitialize => {
            let value: serde_json::Value = serde_json::from_slice(body).unwrap_or_default();
            let id = match (value.get("method"), value.get("id")) {
                (Some(_), Some(id)) => serde_json::from_value(id.clone()).unwrap_or(Id::Null),
                _ => Id::Null,
            };
            (id, Error::invalid_request())
        }
    };
    let body = serde_json::to_vec(&Response::from_error(id, error)).unwrap_or_default();
    let mut message = format!("Content-Length: {}\r\n\r\n", body.len()).into_bytes();
    message.extend_from_slice(&body);
    message
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_last_content_length_of_a_line_counts() {
        assert_eq!(content_length(b"Content-Length: 12"), Some(Ok(12)));
        assert_eq!(content_length(b"content-length:7 "), Some(Ok(7)));
        assert_eq!(
            content_length(b"\"}}Content-Length: 40"),
            Some(Ok(40)),
            "the rest of a body glued to the next header"
        );
        assert_eq!(
            content_length(b"Content-Length: -5"),
            Some(Err("-5".into()))
        );
        assert_eq!(content_length(b"Content-Type: x"), None);
    }

    #[test]
    fn only_json_rpc_messages_pass() {
        assert_eq!(
            check_body(br#"{"jsonrpc":"2.0","method":"initialized","params":{}}"#),
            Ok(MessageKind::Other)
        );
        assert_eq!(
            check_body(br#"{"jsonrpc":"2.0","id":"a","result":null}"#),
            Ok(MessageKind::Other)
        );
        assert_eq!(check_body(b"{}"), Err(BodyProblem::NotMessage));
        assert_eq!(
            check_body(br#"{"jsonrpc":"2.0","id":9,"error":"bad"}"#),
            Err(BodyProblem::NotMessage)
        );
        assert_eq!(
            check_body(br#"{"jsonrpc":"2.0","id":1,"method":5}"#),
            Err(BodyProblem::NotMessage)
        );
        assert_eq!(check_body(b"{"), Err(BodyProblem::NotJson));
        assert_eq!(check_body(b"\"\xff\""), Err(BodyProblem::NotJson));
    }
}
