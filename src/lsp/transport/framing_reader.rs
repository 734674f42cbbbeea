//! The reader: bytes from the client through the framer, each body read into a message.

use crate::lsp::transport::framing::{next_header_in, Frame, Framer};
use crate::lsp::transport::message::{read_message, read_owned_message, Incoming, InitializeGate};
use crate::lsp::transport::stderr;
use tokio::io::{AsyncRead, AsyncReadExt};
use tower_lsp_server::ls_types::MessageType;

/// Bodies from this size on are parsed on a blocking thread (a `didOpen` of a large program).
pub(super) const LARGE_BODY_BYTES: usize = 1 << 20;

/// Bytes asked of the input at a time.
const READ_BYTES: usize = 1 << 20;

pub struct MessageReader<R> {
    input: R,
    framer: Framer,
    chunk: Vec<u8>,
}

impl<R: AsyncRead + Unpin> MessageReader<R> {
    pub fn new(input: R) -> MessageReader<R> {
        MessageReader {
            input,
            framer: Framer::new(),
            chunk: vec![0; READ_BYTES],
        }
    }

    /// The next message; `None` at the end of the input (or when it fails).
    pub async fn next(&mut self, gate: &mut InitializeGate) -> Option<Incoming> {
        loop {
            match self.framer.next_frame() {
                Some(Frame::Body(body)) => {
                    let incoming = if body.len() >= LARGE_BODY_BYTES {
                        // Tens of megabytes are parsed off the async threads, and given back to the
                        // system after the message is on its way.
                        let mut moved_gate = std::mem::take(gate);
                        let (incoming, returned_gate, body) =
                            tokio::task::spawn_blocking(move || {
                                let (incoming, body) = read_owned_message(body, &mut moved_gate);
                                (incoming, moved_gate, body)
                            })
                            .await
                            .ok()?;
                        *gate = returned_gate;
                        if let Some(body) = body {
                            self.resynchronize(&incoming, &body);
                            tokio::task::spawn_blocking(move || drop(body));
                        }
                        incoming
                    } else {
                        let incoming = read_message(&body, gate);
                        self.resynchronize(&incoming, &body);
                        incoming
                    };
                    return Some(incoming);
                }
                Some(Frame::Dropped(reason)) => {
                    stderr::to_stderr(MessageType::WARNING, &reason);
                    continue;
                }
                None => {}
            }
            let read = self.input.read(&mut self.chunk).await.ok()?;
            if read == 0 {
                return None;
            }
            self.framer.push(&self.chunk[..read]);
        }
    }

    /// A length given too long swallowed the start of the next message: reading goes on from its
    /// header.
    fn resynchronize(&mut self, incoming: &Incoming, body: &[u8]) {
        if let Incoming::Invalid { .. } = incoming {
            if let Some(next) = next_header_in(body) {
                self.framer.put_back(&body[next..]);
            }
        }
    }
}
