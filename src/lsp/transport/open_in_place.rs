//! A large `didOpen` read in its own buffer. Parsed the ordinary way, the body of a 33 MB program is
//! held three times at once: the body, serde_json's scratch buffer for the escaped text, and the
//! string it becomes, which set the server's peak memory (`docs/performance.md`). Here serde_json
//! reads the message with the text left as its raw literal (`RawValue`, borrowed from the body, which
//! it checks as JSON), the literal is unescaped to the front of the body itself, and the body becomes
//! the text's `String` without a copy. The request handed on is the one the ordinary path gives, with
//! the same parameters; a message that is anything else goes the ordinary way.

use serde::de::IgnoredAny;
use serde::{Deserialize, Deserializer};
use serde_json::value::RawValue;
use serde_json::{Map, Value};
use std::borrow::Cow;
use tower_lsp_server::jsonrpc::Request;

const DID_OPEN: &str = "textDocument/didOpen";

#[derive(Deserialize)]
struct OpenMessage<'a> {
    jsonrpc: &'a str,
    method: &'a str,
    /// A `didOpen` with an id (even `null`) is a request to the framework: the ordinary path reads it.
    #[serde(default, deserialize_with = "present")]
    id: bool,
    #[serde(borrow)]
    params: OpenParams<'a>,
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct OpenParams<'a> {
    #[serde(borrow)]
    text_document: OpenItem<'a>,
}

#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct OpenItem<'a> {
    #[serde(borrow)]
    uri: Cow<'a, str>,
    #[serde(borrow)]
    language_id: Cow<'a, str>,
    version: i32,
    #[serde(borrow)]
    text: &'a RawValue,
}

fn present<'de, D: Deserializer<'de>>(deserializer: D) -> Result<bool, D::Error> {
    IgnoredAny::deserialize(deserializer).map(|_| true)
}

/// What reading `body` in place gave.
pub enum OpenRead {
    /// The `didOpen` notification, its text taken from the body's own buffer.
    Request(Request),
    /// Not a `didOpen` notification this path reads: the body, untouched, for the ordinary path.
    Other(Vec<u8>),
    /// A `didOpen` whose text has a `\u` escape of half a surrogate pair, which no string can hold:
    /// the ordinary path drops such a message as no JSON-RPC message, and so does this one.
    LoneSurrogate,
}

/// Reads `body` as a `didOpen` notification with the text unescaped in place (see the module).
pub fn read_open_in_place(mut body: Vec<u8>) -> OpenRead {
    let Ok(message) = serde_json::from_slice::<OpenMessage<'_>>(&body) else {
        return OpenRead::Other(body);
    };
    if message.jsonrpc != "2.0" || message.method != DID_OPEN || message.id {
        return OpenRead::Other(body);
    }
    let item = message.params.text_document;
    let literal = item.text.get().as_bytes();
    // The literal lies inside the body (it is borrowed from it); its place is found from the two
    // addresses, without reading through them.
    let start = literal.as_ptr() as usize - body.as_ptr() as usize;
    let end = start + literal.len();
    if literal.len() < 2 || literal[0] != b'"' || literal[literal.len() - 1] != b'"' {
        // The text is not a string: the ordinary path answers that.
        return OpenRead::Other(body);
    }
    // The small fields are taken out before the body's bytes change under the borrowed message.
    let (uri, language_id, version) = (
        item.uri.into_owned(),
        item.language_id.into_owned(),
        item.version,
    );
    let Some(length) = unescape_to_front(&mut body, start + 1, end - 1) else {
        return OpenRead::LoneSurrogate;
    };
    body.truncate(length);
    let Ok(text) = String::from_utf8(body) else {
        // JSON is UTF-8 and the escapes give UTF-8: this does not happen, and costs nothing to keep.
        return OpenRead::LoneSurrogate;
    };
    // Built by hand: `json!` would serialize the text, a copy of it.
    let mut item = Map::new();
    item.insert("uri".into(), Value::String(uri));
    item.insert("languageId".into(), Value::String(language_id));
    item.insert("version".into(), Value::from(version));
    item.insert("text".into(), Value::String(text));
    let mut params = Map::new();
    params.insert("textDocument".into(), Value::Object(item));
    let params = Value::Object(params);
    OpenRead::Request(Request::build(DID_OPEN).params(params).finish())
}

/// Unescapes the contents of a JSON string literal, `bytes[start..end]` (between its quotes, checked
/// as JSON by serde_json), to the front of `bytes`, and returns their length. Every escape is at
/// least as long as what it stands for, so the writing never overtakes the reading. `None` for half
/// a surrogate pair (which serde_json checks only when it makes a string) or an escape JSON does not
/// have.
pub fn unescape_to_front(bytes: &mut [u8], start: usize, end: usize) -> Option<usize> {
    let end = end.min(bytes.len());
    let mut read = start.min(end);
    let mut write = 0;
    while read < end {
        let run_end = memchr::memchr(b'\\', &bytes[read..end]).map_or(end, |offset| read + offset);
        bytes.copy_within(read..run_end, write);
        write += run_end - read;
        read = run_end;
        if read == end {
            break;
        }
        let (character, consumed) = match *bytes.get(read + 1).filter(|_| read + 1 < end)? {
            b'"' => ('"', 2),
            b'\\' => ('\\', 2),
            b'/' => ('/', 2),
            b'b' => ('\u{8}', 2),
            b'f' => ('\u{c}', 2),
            b'n' => ('\n', 2),
            b'r' => ('\r', 2),
            b't' => ('\t', 2),
            b'u' => unicode_escape(&bytes[read..end])?,
            _ => return None,
        };
        let mut encoded = [0; 4];
        let encoded = character.encode_utf8(&mut encoded).as_bytes();
        bytes[write..write + encoded.len()].copy_from_slice(encoded);
        write += encoded.len();
        read += consumed;
    }
    Some(write)
}

/// The character of the `\uXXXX` escape at the start of `bytes` (with its low half when it is the
/// high half of a surrogate pair) and how many bytes it took.
fn unicode_escape(bytes: &[u8]) -> Option<(char, usize)> {
    let first = hex4(bytes.get(2..6)?)?;
    match first {
        0xD800..=0xDBFF => {
            if bytes.get(6..8) != Some(b"\\u") {
                return None;
            }
            let second = hex4(bytes.get(8..12)?)?;
            if !(0xDC00..=0xDFFF).contains(&second) {
                return None;
            }
            let code = 0x10000 + ((first - 0xD800) << 10) + (second - 0xDC00);
            Some((char::from_u32(code)?, 12))
        }
        0xDC00..=0xDFFF => None,
        _ => Some((char::from_u32(first)?, 6)),
    }
}

fn hex4(digits: &[u8]) -> Option<u32> {
    digits.iter().try_fold(0u32, |value, &digit| {
        let nibble = (digit as char).to_digit(16)?;
        Some(value * 16 + nibble)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use tower_lsp_server::ls_types::DidOpenTextDocumentParams;

    fn open_body(text_literal: &str) -> Vec<u8> {
        format!(
            r#"{{"jsonrpc":"2.0","method":"textDocument/didOpen","params":{{"textDocument":{{"uri":"file:///a.mpf","languageId":"sinumerik","version":3,"text":{text_literal}}}}}}}"#
        )
        .into_bytes()
    }

    fn opened_text(body: Vec<u8>) -> Option<String> {
        match read_open_in_place(body) {
            OpenRead::Request(request) => {
                let params: DidOpenTextDocumentParams =
                    serde_json::from_value(request.params()?.clone()).ok()?;
                assert_eq!(params.text_document.version, 3);
                assert_eq!(params.text_document.uri.as_str(), "file:///a.mpf");
                Some(params.text_document.text)
            }
            _ => None,
        }
    }

    #[test]
    fn every_escape_gives_what_serde_json_gives() {
        for text in [
            "N10 G0 X1\nN20 G1 Z=IC(-32)\r\n",
            "quote \" backslash \\ slash / tab \t bell \u{8} feed \u{c}",
            "Grüße, 中文, 🛠 and \u{1} control",
            "",
        ] {
            let literal = serde_json::to_string(text).unwrap();
            assert_eq!(opened_text(open_body(&literal)).as_deref(), Some(text));
        }
        // Escapes serde_json does not write itself: \/, \u of any letter case, a surrogate pair.
        assert_eq!(
            opened_text(open_body(r#""a\/b\u00e4\u00C4\ud83d\udee0""#)).as_deref(),
            Some("a/bäÄ🛠")
        );
    }

    #[test]
    fn half_a_surrogate_pair_is_no_message() {
        for literal in [r#""\ud83d""#, r#""\udee0x""#, r#""\ud83d\u0041""#] {
            assert!(matches!(
                read_open_in_place(open_body(literal)),
                OpenRead::LoneSurrogate
            ));
        }
    }

    #[test]
    fn other_messages_are_handed_back_untouched() {
        let bodies = [
            br#"{"jsonrpc":"2.0","method":"textDocument/didChange","params":{}}"#.to_vec(),
            br#"{"jsonrpc":"2.0","id":null,"method":"textDocument/didOpen","params":{"textDocument":{"uri":"file:///a","languageId":"x","version":1,"text":"a"}}}"#.to_vec(),
            br#"{"jsonrpc":"1.0","method":"textDocument/didOpen","params":{"textDocument":{"uri":"file:///a","languageId":"x","version":1,"text":"a"}}}"#.to_vec(),
            open_body("5"),
            open_body(r#""not closed"#),
        ];
        for body in bodies {
            match read_open_in_place(body.clone()) {
                OpenRead::Other(back) => assert_eq!(back, body),
                _ => panic!("{} was read in place", String::from_utf8_lossy(&body)),
            }
        }
    }
}
