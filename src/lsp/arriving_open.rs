//! A large `didOpen` read while it arrives. A client writes the 33 MB message of a 1,000,000-line
//! program in some 30 to 90 ms, during which the server would only copy bytes; the text is instead
//! unescaped into its rope piece by piece as the bytes come (`json_string.rs`), so that the rope is
//! ready soon after the last byte. Nothing is trusted before the whole message is there: the message
//! without its text is then parsed as a `didOpen`, and its text must be the literal that was read.
//! Any other message, or one where the guess of where the text starts was wrong, is read as before
//! from the complete body (`open_texts.rs`).

use crate::lsp::json_string::{LiteralReader, Read};
use crate::lsp::open_texts::{take_read_text, OpenTexts};

/// Where the reading of the message stands.
enum Stage {
    /// Before the text: looking for a `"text"` key outside strings, followed by a colon and a quote.
    Looking(KeySearch),
    /// In the text literal, which started at `at` (its opening quote).
    Text { at: usize, reader: LiteralReader },
    /// The text literal is the bytes `at..end` (quotes included) and its rope is made.
    Read {
        at: usize,
        end: usize,
        rope: ropey::Rope,
    },
    /// No text was found where one was expected, or it was not a valid string: the complete body is
    /// read the ordinary way.
    GaveUp,
}

/// The state of the search for the text's key, byte by byte (the part before the text is a few
/// hundred bytes).
#[derive(Clone, Copy)]
enum KeySearch {
    Outside,
    /// In a string that started after the quote at `start`; `escaped` after a backslash.
    InString {
        start: usize,
        escaped: bool,
    },
    /// After the string `"text"`: a colon makes it a key.
    AfterTextString,
    /// After `"text":`: a quote starts the text.
    AfterColon,
}

/// The body of one large message, as it arrives.
pub struct ArrivingMessage {
    /// Every piece as it came, never copied: together the whole body, read the ordinary way when the
    /// message turns out not to be a `didOpen` whose text was read here. One contiguous copy of
    /// 33 MB cost 17 ms of page faults, and over 100 ms where the system first had to gather free
    /// memory for huge pages.
    pieces: Vec<Vec<u8>>,
    /// The bytes in `pieces`.
    received: usize,
    /// While looking for the text: the body so far.
    start: Vec<u8>,
    /// The bytes of `start` before this one have been looked at.
    looked_at: usize,
    /// In the text: the bytes the literal reader left (an escape cut off at the end of a piece),
    /// which start at byte `left_at` of the body.
    left: Vec<u8>,
    left_at: usize,
    stage: Stage,
}

/// What a complete message turned out to be.
pub enum Arrived {
    /// A `didOpen` whose text was kept in the open texts: the message to pass on instead, and the
    /// body's pieces to free.
    TextTaken {
        forwarded: Vec<u8>,
        pieces: Vec<Vec<u8>>,
    },
    /// Anything else: the body, to be read as any other.
    Other(Vec<u8>),
}

impl ArrivingMessage {
    pub fn new() -> ArrivingMessage {
        ArrivingMessage {
            pieces: Vec::new(),
            received: 0,
            start: Vec::new(),
            looked_at: 0,
            left: Vec::new(),
            left_at: 0,
            stage: Stage::Looking(KeySearch::Outside),
        }
    }

    /// Takes the next bytes of the body.
    pub fn push(&mut self, piece: Vec<u8>) {
        let piece_at = self.received;
        self.received += piece.len();
        match &mut self.stage {
            Stage::Looking(search) => {
                self.start.extend_from_slice(&piece);
                if let Some(at) = find_text_start(&self.start, self.looked_at, search) {
                    self.left = self.start.split_off(at + 1);
                    self.left_at = at + 1;
                    self.stage = Stage::Text {
                        at,
                        reader: LiteralReader::new(),
                    };
                    self.read_left(false);
                } else {
                    self.looked_at = self.start.len();
                }
            }
            Stage::Text { .. } if self.left.is_empty() => {
                let read = self.read(&piece, piece_at, false);
                if let Some(used) = read {
                    self.left = piece[used..].to_vec();
                    self.left_at = piece_at + used;
                }
            }
            Stage::Text { .. } => {
                self.left.extend_from_slice(&piece);
                self.read_left(false);
            }
            Stage::Read { .. } | Stage::GaveUp => {}
        }
        self.pieces.push(piece);
    }

    /// Reads the bytes left over, keeping what the reader leaves again.
    fn read_left(&mut self, complete: bool) {
        let left = std::mem::take(&mut self.left);
        if let Some(used) = self.read(&left, self.left_at, complete) {
            self.left = left[used..].to_vec();
            self.left_at += used;
        }
    }

    /// Reads `bytes`, which start at byte `bytes_at` of the body, into the text; returns how many of
    /// them were used when the text goes on.
    fn read(&mut self, bytes: &[u8], bytes_at: usize, complete: bool) -> Option<usize> {
        let Stage::Text { at, reader } = &mut self.stage else {
            return None;
        };
        let at = *at;
        match reader.read(bytes, complete) {
            Read::More(used) => return Some(used),
            Read::End(used) => {
                let Stage::Text { reader, .. } = std::mem::replace(&mut self.stage, Stage::GaveUp)
                else {
                    unreachable!("the stage was matched above");
                };
                if let Some(rope) = reader.finish() {
                    let end = bytes_at + used;
                    self.stage = Stage::Read { at, end, rope };
                }
            }
            Read::Invalid => self.stage = Stage::GaveUp,
        }
        None
    }

    /// The message, once all of its bytes have been pushed.
    pub fn finish(mut self, texts: &OpenTexts) -> Arrived {
        if matches!(self.stage, Stage::Text { .. }) {
            self.read_left(true);
        }
        let Stage::Read { at, end, rope } = self.stage else {
            return Arrived::Other(self.pieces.concat());
        };
        let mut without_text = Vec::with_capacity(at + 2 + self.received - end);
        without_text.extend_from_slice(&self.start[..at]);
        without_text.extend_from_slice(b"\"\"");
        let mut piece_at = 0;
        for piece in &self.pieces {
            let after = end.saturating_sub(piece_at).min(piece.len());
            without_text.extend_from_slice(&piece[after..]);
            piece_at += piece.len();
        }
        match take_read_text(&without_text, at, rope, texts) {
            Some(forwarded) => Arrived::TextTaken {
                forwarded,
                pieces: self.pieces,
            },
            None => Arrived::Other(self.pieces.concat()),
        }
    }
}

/// Looks at `body[from..]` for the opening quote of a `"text"` key's string value; `search` holds
/// the state at `from` and is left as it is at the end.
fn find_text_start(body: &[u8], from: usize, search: &mut KeySearch) -> Option<usize> {
    for (index, &byte) in body.iter().enumerate().skip(from) {
        *search = match (*search, byte) {
            (KeySearch::InString { start, escaped }, _) => match (escaped, byte) {
                (true, _) => KeySearch::InString {
                    start,
                    escaped: false,
                },
                (false, b'\\') => KeySearch::InString {
                    start,
                    escaped: true,
                },
                (false, b'"') if &body[start..index] == b"text" => KeySearch::AfterTextString,
                (false, b'"') => KeySearch::Outside,
                (false, _) => KeySearch::InString {
                    start,
                    escaped: false,
                },
            },
            (KeySearch::AfterTextString | KeySearch::AfterColon, b' ' | b'\t' | b'\r' | b'\n') => {
                *search
            }
            (KeySearch::AfterTextString, b':') => KeySearch::AfterColon,
            (KeySearch::AfterColon, b'"') => return Some(index),
            // Anything else after `"text"` (it was a value) or after its colon (a value that is no
            // string) is read as outside a string.
            (_, b'"') => KeySearch::InString {
                start: index + 1,
                escaped: false,
            },
            _ => KeySearch::Outside,
        };
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::{json, Value};
    use tower_lsp_server::ls_types::Uri;

    fn did_open(text: &str) -> Vec<u8> {
        serde_json::to_vec(&json!({
            "jsonrpc": "2.0",
            "method": "textDocument/didOpen",
            "params": {"textDocument": {"uri": "file:///a.mpf", "languageId": "sinumerik", "version": 3, "text": text}},
        }))
        .unwrap()
    }

    /// The message `body` pushed in pieces of `piece` bytes.
    fn arrive(body: &[u8], piece: usize, texts: &OpenTexts) -> Arrived {
        let mut message = ArrivingMessage::new();
        for bytes in body.chunks(piece) {
            message.push(bytes.to_vec());
        }
        message.finish(texts)
    }

    fn uri() -> Uri {
        "file:///a.mpf".parse().unwrap()
    }

    #[test]
    fn a_did_open_in_any_pieces_gives_its_text_and_the_message_without_it() {
        let text = "N10 G1 X\u{e4}1 ; \"quoted\" \\ \u{1F600}\r\nN20 X2\t\u{7f}\n".repeat(300);
        let body = did_open(&text);
        // Pieces of every size cut escapes, surrogate pairs and the key at every place.
        for piece in [1, 2, 3, 5, 7, 11, 64, 1000, body.len()] {
            let texts = OpenTexts::default();
            let Arrived::TextTaken { forwarded, pieces } = arrive(&body, piece, &texts) else {
                panic!("pieces of {piece}: the text was not taken");
            };
            assert_eq!(
                pieces.concat(),
                body,
                "pieces of {piece}: the body is kept whole"
            );
            let forwarded: Value = serde_json::from_slice(&forwarded).unwrap();
            assert_eq!(forwarded["params"]["textDocument"]["text"], "");
            assert_eq!(forwarded["params"]["textDocument"]["version"], 3);
            let rope = texts.take(&uri(), 3).expect("the text is kept");
            assert_eq!(rope.to_string(), text, "pieces of {piece}");
        }
    }

    #[test]
    fn the_text_key_is_found_in_any_order_but_not_inside_strings() {
        let text = "N10 X1\n".repeat(50);
        let body = serde_json::to_vec(&json!({
            "params": {"textDocument": {"languageId": "\"text\":\"x", "uri": "file:///a.mpf", "text": text, "version": 3}},
            "method": "textDocument/didOpen",
            "jsonrpc": "2.0",
        }))
        .unwrap();
        for piece in [1, 3, body.len()] {
            let texts = OpenTexts::default();
            assert!(matches!(
                arrive(&body, piece, &texts),
                Arrived::TextTaken { .. }
            ));
            assert_eq!(
                texts.take(&uri(), 3).map(|rope| rope.to_string()),
                Some(text.clone())
            );
        }
    }

    #[test]
    fn other_messages_come_back_byte_for_byte() {
        let text = "N10 X1\n".repeat(50);
        let decoy_first = serde_json::to_vec(&json!({
            "jsonrpc": "2.0",
            "method": "textDocument/didOpen",
            "params": {"other": {"text": "decoy"}, "textDocument": {"uri": "file:///a.mpf", "languageId": "sinumerik", "version": 3, "text": text}},
        }))
        .unwrap();
        let change = serde_json::to_vec(&json!({
            "jsonrpc": "2.0",
            "method": "textDocument/didChange",
            "params": {"textDocument": {"uri": "file:///a.mpf", "version": 4}, "contentChanges": [{"text": text}]},
        }))
        .unwrap();
        let mut request = did_open(&text);
        request.pop();
        request.extend_from_slice(br#","id":1}"#);
        let mut control_character = did_open("N10 X1");
        let at = memchr::memmem::find(&control_character, b"X1").unwrap();
        control_character[at] = b'\n';
        let cut_off = did_open(&text)[..200].to_vec();
        let no_text = br#"{"jsonrpc":"2.0","method":"initialized","params":{}}"#.to_vec();
        for body in [
            decoy_first,
            change,
            request,
            control_character,
            cut_off,
            no_text,
        ] {
            for piece in [1, 4, 100, body.len()] {
                let texts = OpenTexts::default();
                match arrive(&body, piece, &texts) {
                    Arrived::Other(back) => assert_eq!(back, body),
                    Arrived::TextTaken { .. } => {
                        panic!("taken: {}", String::from_utf8_lossy(&body))
                    }
                }
                assert_eq!(texts.waiting_count(), 0);
            }
        }
    }
}
