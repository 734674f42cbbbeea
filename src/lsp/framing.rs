//! A guard in front of the framework's message reader: it passes on only well-formed messages
//! (a `Content-Length` header and a UTF-8 JSON body of that length) and drops the rest with a log
//! line. The framework's reader stops for good at the first body that is not JSON, which would end
//! the server; with this guard a bad message costs only itself.

use crate::lsp::log;
use crate::lsp::open_texts::{take_text_out, OpenTexts, LARGE_MESSAGE_BYTES};
use std::sync::Arc;
use tokio::io::{AsyncBufReadExt, AsyncRead, AsyncReadExt, AsyncWriteExt, BufReader, DuplexStream};
use tower_lsp_server::ls_types::MessageType;

/// Larger messages are skipped: no editor sends a program this large (VS Code stops at 50 MB).
const MAX_MESSAGE_LENGTH: usize = 1 << 30;

/// The size of the pipe between the guard and the framework.
const PIPE_SIZE: usize = 1 << 20;

/// Returns a reader that yields the well-formed messages of `input`, framed again.
pub fn guard_input<R>(input: R, open_texts: Arc<OpenTexts>) -> DuplexStream
where
    R: AsyncRead + Unpin + Send + 'static,
{
    let (mut to_server, from_guard) = tokio::io::duplex(PIPE_SIZE);
    tokio::spawn(async move {
        let mut reader = BufReader::new(input);
        while let Some(body) = next_body(&mut reader).await {
            let Some(body) = body else { continue };
            let body = if body.len() >= LARGE_MESSAGE_BYTES {
                // Reading a message of megabytes takes milliseconds: not on the async threads.
                let texts = Arc::clone(&open_texts);
                let checked = tokio::task::spawn_blocking(move || {
                    take_text_out(&body, &texts).or_else(|| well_formed(body))
                })
                .await;
                match checked {
                    Ok(Some(body)) => body,
                    _ => continue,
                }
            } else {
                match well_formed(body) {
                    Some(body) => body,
                    None => continue,
                }
            };
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

/// The next message body: `None` at the end of the input, `Some(None)` for a message that was
/// dropped.
async fn next_body<R: AsyncRead + Unpin>(reader: &mut BufReader<R>) -> Option<Option<Vec<u8>>> {
    let mut content_length = None;
    let mut header_lines = 0;
    loop {
        let mut line = Vec::new();
        // A header line is short; a "line" of megabytes is garbage and is read in bounded pieces.
        let read = (&mut *reader)
            .take(64 * 1024)
            .read_until(b'\n', &mut line)
            .await
            .ok()?;
        if read == 0 {
            return None;
        }
        let text = String::from_utf8_lossy(&line);
        let text = text.trim_end_matches(['\r', '\n']);
        if text.is_empty() {
            if header_lines > 0 {
                break;
            }
            continue;
        }
        header_lines += 1;
        if let Some((name, value)) = text.split_once(':') {
            if name.trim().eq_ignore_ascii_case("content-length") {
                content_length = value.trim().parse::<usize>().ok();
            }
        }
    }
    let Some(length) = content_length else {
        log::to_stderr(
            MessageType::WARNING,
            "a message without a valid Content-Length header was dropped",
        );
        return Some(None);
    };
    if length > MAX_MESSAGE_LENGTH {
        log::to_stderr(
            MessageType::WARNING,
            &format!("a message of {length} bytes was skipped (the limit is {MAX_MESSAGE_LENGTH})"),
        );
        let skipped = tokio::io::copy(
            &mut (&mut *reader).take(length as u64),
            &mut tokio::io::sink(),
        )
        .await
        .ok()?;
        return (skipped == length as u64).then_some(None);
    }
    let mut body = vec![0; length];
    reader.read_exact(&mut body).await.ok()?;
    Some(Some(body))
}

/// `body` when the framework can read it: a UTF-8 JSON text (the framework reads the body as a
/// `str`, so invalid UTF-8 would stop it as well); `None`, with a log line, otherwise.
fn well_formed(body: Vec<u8>) -> Option<Vec<u8>> {
    if std::str::from_utf8(&body).is_err()
        || serde_json::from_slice::<serde::de::IgnoredAny>(&body).is_err()
    {
        log::to_stderr(
            MessageType::WARNING,
            &format!(
                "a message of {} bytes that is not JSON was dropped",
                body.len()
            ),
        );
        return None;
    }
    Some(body)
}
