//! The one parser of the protocol's framing: `Content-Length` headers and the bodies they announce.
//! It is written without IO (bytes are pushed in, frames come out) so that the reader, the tests and
//! the fuzzer drive the same code. A malformed header costs only itself: the framer reports it and
//! reads on from the next header. Rules kept from the protocol's practice:
//!
//! - header lines end with `\n` (a `\r` before it is dropped); empty lines before a header are skipped;
//! - the last `Content-Length:` of a header line counts, wherever it starts (the rest of a body whose
//!   length was given too short runs into the next message's header), case-insensitively;
//! - a "line" longer than [`MAX_HEADER_LINE`] is read in pieces of that size, so garbage without line
//!   ends cannot grow the buffer without bound;
//! - a length over [`MAX_MESSAGE_LENGTH`] is refused and the bytes behind it are read as what follows
//!   the header, so a wrong length cannot make the server wait for gigabytes that never come.

/// Larger messages are refused: no editor sends a program this large (VS Code stops at 50 MB).
pub const MAX_MESSAGE_LENGTH: usize = 1 << 30;

/// A header line is short; a "line" of megabytes is garbage and is read in pieces of this size.
pub const MAX_HEADER_LINE: usize = 64 * 1024;

/// A body's buffer is reserved up to this size at once and grows as the bytes come beyond it: a
/// length is what the client claims, not what it sends.
const MOST_RESERVED: usize = 64 << 20;

const CONTENT_LENGTH: &[u8] = b"content-length:";

/// What the framer found.
#[derive(Debug, PartialEq, Eq)]
pub enum Frame {
    /// A whole body of the announced length.
    Body(Vec<u8>),
    /// A header that announced no usable length; the text says why (for the log).
    Dropped(String),
}

/// The body being read after its header.
struct Body {
    bytes: Vec<u8>,
    length: usize,
}

/// The framing state of one input stream.
#[derive(Default)]
pub struct Framer {
    /// Bytes received and not yet framed, from `start` on.
    buffer: Vec<u8>,
    start: usize,
    /// Header lines of the header being read, and the last `Content-Length` value among them.
    header_lines: usize,
    length: Option<Result<usize, String>>,
    body: Option<Body>,
}

impl Framer {
    pub fn new() -> Framer {
        Framer::default()
    }

    /// Adds bytes as they came from the client. The bytes of a body being read go straight into it.
    pub fn push(&mut self, mut bytes: &[u8]) {
        if let Some(body) = &mut self.body {
            if self.start == self.buffer.len() {
                let wanted = (body.length - body.bytes.len()).min(bytes.len());
                body.bytes.extend_from_slice(&bytes[..wanted]);
                bytes = &bytes[wanted..];
            }
        }
        if bytes.is_empty() {
            return;
        }
        if self.start == self.buffer.len() {
            self.buffer.clear();
            self.start = 0;
        } else if self.start >= MAX_HEADER_LINE && self.start * 2 >= self.buffer.len() {
            self.buffer.drain(..self.start);
            self.start = 0;
        }
        self.buffer.extend_from_slice(bytes);
    }

    /// How many bytes the framer has received and not yet handed out (the body being read included).
    pub fn pending_bytes(&self) -> usize {
        self.buffer.len() - self.start + self.body.as_ref().map_or(0, |body| body.bytes.len())
    }

    /// Puts `bytes` back in front of what is not framed yet: the rest of a damaged message's body
    /// from the next header on, which a length given too long had swallowed.
    pub fn put_back(&mut self, bytes: &[u8]) {
        let mut buffer = Vec::with_capacity(bytes.len() + self.buffer.len() - self.start);
        buffer.extend_from_slice(bytes);
        buffer.extend_from_slice(&self.buffer[self.start..]);
        self.buffer = buffer;
        self.start = 0;
    }

    /// The next frame, or `None` until more bytes come.
    pub fn next_frame(&mut self) -> Option<Frame> {
        loop {
            if let Some(body) = &mut self.body {
                let available = &self.buffer[self.start..];
                let wanted = (body.length - body.bytes.len()).min(available.len());
                body.bytes.extend_from_slice(&available[..wanted]);
                self.start += wanted;
                if body.bytes.len() < body.length {
                    return None;
                }
                return self.body.take().map(|body| Frame::Body(body.bytes));
            }
            let rest = &self.buffer[self.start..];
            let window = &rest[..rest.len().min(MAX_HEADER_LINE)];
            let line_end = match memchr::memchr(b'\n', window) {
                Some(index) => index + 1,
                None if rest.len() >= MAX_HEADER_LINE => MAX_HEADER_LINE,
                None => return None,
            };
            let line = &rest[..line_end];
            let text = line.strip_suffix(b"\n").unwrap_or(line);
            let text = text.strip_suffix(b"\r").unwrap_or(text);
            if !text.is_empty() {
                self.header_lines += 1;
                if let Some(value) = content_length(text) {
                    self.length = Some(value);
                }
                self.start += line_end;
                continue;
            }
            self.start += line_end;
            if self.header_lines == 0 {
                continue;
            }
            self.header_lines = 0;
            match self.length.take() {
                Some(Ok(length)) if length <= MAX_MESSAGE_LENGTH => {
                    self.body = Some(Body {
                        bytes: Vec::with_capacity(length.min(MOST_RESERVED)),
                        length,
                    });
                }
                Some(Ok(length)) => {
                    return Some(Frame::Dropped(format!(
                        "a Content-Length of {length} bytes is over the limit of {MAX_MESSAGE_LENGTH}; the header is ignored"
                    )))
                }
                Some(Err(value)) => {
                    return Some(Frame::Dropped(format!(
                        "a message with the Content-Length {value:?}, which is not a length, was dropped"
                    )))
                }
                None => {
                    return Some(Frame::Dropped(
                        "a message without a valid Content-Length header was dropped".to_string(),
                    ))
                }
            }
        }
    }
}

/// The value of a `Content-Length` header in `line`. The last one counts, wherever it starts.
fn content_length(line: &[u8]) -> Option<Result<usize, String>> {
    let lower = line.to_ascii_lowercase();
    let start = memchr::memmem::rfind(&lower, CONTENT_LENGTH)? + CONTENT_LENGTH.len();
    let value = String::from_utf8_lossy(&line[start..]);
    let value = value.trim();
    Some(value.parse::<usize>().map_err(|_| value.to_string()))
}

/// Where the next header starts in a damaged body, if it holds one.
pub fn next_header_in(body: &[u8]) -> Option<usize> {
    memchr::memmem::find(body, b"Content-Length:")
}

/// The header of a body of `length` bytes.
pub fn header(length: usize) -> Vec<u8> {
    format!("Content-Length: {length}\r\n\r\n").into_bytes()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frames_of(pieces: &[&[u8]]) -> Vec<Frame> {
        let mut framer = Framer::new();
        let mut frames = Vec::new();
        for piece in pieces {
            framer.push(piece);
            while let Some(frame) = framer.next_frame() {
                frames.push(frame);
            }
        }
        frames
    }

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
    fn messages_come_out_whole_however_the_bytes_are_cut() {
        let stream = b"\r\nContent-Length: 3\r\nContent-Type: x\r\n\r\nabcContent-Length: 2\n\nde";
        let expected = vec![Frame::Body(b"abc".to_vec()), Frame::Body(b"de".to_vec())];
        for cut in 0..stream.len() {
            let (first, second) = stream.split_at(cut);
            assert_eq!(frames_of(&[first, second]), expected, "cut at {cut}");
        }
        let bytes: Vec<&[u8]> = stream.chunks(1).collect();
        assert_eq!(frames_of(&bytes), expected);
    }

    #[test]
    fn a_header_without_a_usable_length_is_dropped_and_reading_goes_on() {
        let frames = frames_of(&[
            b"X-Other: 1\r\n\r\nContent-Length: x\r\n\r\nContent-Length: 99999999999\r\n\r\nContent-Length: 1\r\n\r\nz",
        ]);
        assert_eq!(frames.len(), 4);
        assert!(matches!(frames[0], Frame::Dropped(_)));
        assert!(matches!(frames[1], Frame::Dropped(_)));
        assert!(matches!(frames[2], Frame::Dropped(_)));
        assert_eq!(frames[3], Frame::Body(b"z".to_vec()));
    }

    #[test]
    fn a_line_without_end_is_read_in_pieces_and_the_buffer_stays_bounded() {
        let mut framer = Framer::new();
        let garbage = vec![b'a'; 10 * MAX_HEADER_LINE];
        framer.push(&garbage);
        assert_eq!(framer.next_frame(), None);
        assert!(framer.pending_bytes() < MAX_HEADER_LINE);
        framer.push(b"\r\n\r\n");
        assert!(matches!(framer.next_frame(), Some(Frame::Dropped(_))));
        framer.push(b"Content-Length: 2\r\n\r\nok");
        assert_eq!(framer.next_frame(), Some(Frame::Body(b"ok".to_vec())));
    }

    #[test]
    fn bytes_put_back_are_read_first() {
        let mut framer = Framer::new();
        framer.push(b"Content-Length: 1\r\n\r\n");
        framer.put_back(b"Content-Length: 2\r\n\r\nab");
        assert_eq!(framer.next_frame(), Some(Frame::Body(b"ab".to_vec())));
        assert_eq!(framer.next_frame(), None);
        framer.push(b"c");
        assert_eq!(framer.next_frame(), Some(Frame::Body(b"c".to_vec())));
    }
}
