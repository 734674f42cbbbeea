//! A large `didOpen` read in its own buffer. Parsed the ordinary way, the body of a 33 MB program is
//! held three times at once: the body, serde_json's scratch buffer for the escaped text, and the
//! string it becomes, which set the server's peak memory (`docs/performance.md`). Here the text's
//! literal is unescaped to the front of the body itself, and the body becomes the text's `String`
//! without a copy. The request handed on is the one the ordinary path gives, with the same
//! parameters; a message that is anything else goes the ordinary way.
//!
//! The literal is found by its key (`"text"`, then a colon and a string) and checked a word at a
//! time (`json_literal.rs`); serde_json then reads the rest of the message, with an empty string in
//! the literal's place, and must find the text there. Otherwise (a `"text"` key elsewhere in the
//! first few places, or a text that is no string) serde_json reads the whole message with the text left as its raw
//! literal (`RawValue`, borrowed from the body), which costs it a byte-by-byte reading of the text.

use crate::lsp::transport::json_literal::{closing_quote, unescape_to_front};
use crate::lsp::transport::measure::measured_without;
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
    /// A `didOpen` whose text is not JSON or not UTF-8: the ordinary path drops it as no JSON.
    NotJson,
}

/// The key of the text.
const TEXT_KEY: &[u8] = b"\"text\"";

/// How many places of [`TEXT_KEY`] are tried before serde_json looks for the text itself: in what
/// clients send, the first is the text's.
const TEXT_KEY_TRIES: usize = 4;

/// The most of the message outside the text that is copied to be read by serde_json.
const REST_BYTES_AT_MOST: usize = 1 << 20;

/// Reads `body` as a `didOpen` notification with the text unescaped in place (see the module).
pub fn read_open_in_place(body: Vec<u8>) -> OpenRead {
    let body = if measured_without("literal-scan") {
        body
    } else {
        match read_with_text_found(body) {
            Ok(read) => return read,
            Err(body) => body,
        }
    };
    read_with_serde(body)
}

/// The text's literal found by its key and its end by [`closing_quote`]; serde_json reads the
/// message with an empty string in its place. The literal is the text only when serde_json's text is
/// that empty string, at that place: anything else leaves the body untouched, for serde_json. The
/// rest of the message being a `didOpen`, the literal decides alone what the message is.
fn read_with_text_found(body: Vec<u8>) -> Result<OpenRead, Vec<u8>> {
    let mut from = 0;
    for _ in 0..TEXT_KEY_TRIES {
        let Some(found) = memchr::memmem::find(body.get(from..).unwrap_or_default(), TEXT_KEY)
        else {
            break;
        };
        let after_key = from + found + TEXT_KEY.len();
        let Some(open) = value_string_after(&body, after_key) else {
            from = after_key;
            continue;
        };
        let Some(end) = closing_quote(&body, open + 1) else {
            break;
        };
        // The rest of the message is copied and read by serde_json: a literal with megabytes around
        // it is not the text (clients put it among small fields), and is passed over without that.
        if open + (body.len() - end) > REST_BYTES_AT_MOST {
            from = end + 1;
            continue;
        }
        let mut rest = Vec::with_capacity(body.len() - (end - open) + 1);
        rest.extend_from_slice(&body[..open]);
        rest.extend_from_slice(b"\"\"");
        rest.extend_from_slice(&body[end + 1..]);
        if let Some(fields) = fields_around_empty_text(&rest, open) {
            return Ok(text_to_front(body, open + 1, end, fields));
        }
        from = end + 1;
    }
    Err(body)
}

/// The index of the opening quote of a string after `index`, when JSON's space, a colon and JSON's
/// space come first.
fn value_string_after(body: &[u8], index: usize) -> Option<usize> {
    let is_space = |byte: &u8| matches!(byte, b' ' | b'\t' | b'\n' | b'\r');
    let colon = index + body.get(index..)?.iter().position(|byte| !is_space(byte))?;
    if body[colon] != b':' {
        return None;
    }
    let quote = colon
        + 1
        + body
            .get(colon + 1..)?
            .iter()
            .position(|byte| !is_space(byte))?;
    (body[quote] == b'"').then_some(quote)
}

/// The fields of the `didOpen` that `rest` is, when its text is the empty string at `open`.
fn fields_around_empty_text(rest: &[u8], open: usize) -> Option<OpenFields> {
    // The ordinary path refuses a body that is not UTF-8 anywhere, in fields it ignores too.
    std::str::from_utf8(rest).ok()?;
    let (fields, literal) = open_notification(rest)?;
    let at = (literal.as_ptr() as usize).checked_sub(rest.as_ptr() as usize);
    (literal == b"\"\"" && at == Some(open)).then_some(fields)
}

/// serde_json checks the message with the text as its raw literal, found wherever it is.
fn read_with_serde(body: Vec<u8>) -> OpenRead {
    let Some((fields, literal)) = open_notification(&body) else {
        return OpenRead::Other(body);
    };
    // The literal lies inside the body (it is borrowed from it); its place is found from the two
    // addresses, without reading through them.
    let start = literal.as_ptr() as usize - body.as_ptr() as usize;
    let end = start + literal.len();
    if literal.len() < 2 || literal[0] != b'"' || literal[literal.len() - 1] != b'"' {
        // The text is not a string: the ordinary path answers that.
        return OpenRead::Other(body);
    }
    // serde_json does not check the bytes of fields it skips; the ordinary path refuses a body that
    // is not UTF-8 anywhere.
    if std::str::from_utf8(&body[..start]).is_err() || std::str::from_utf8(&body[end..]).is_err() {
        return OpenRead::Other(body);
    }
    text_to_front(body, start + 1, end - 1, fields)
}

/// The small fields of a `didOpen` (uri, language id, version), owned: the body's bytes change
/// after they are read.
type OpenFields = (String, String, i32);

/// The fields of `body` read as a `didOpen` notification, and its text's raw literal (borrowed from
/// `body`); `None` for anything else, which the ordinary path reads.
fn open_notification(body: &[u8]) -> Option<(OpenFields, &[u8])> {
    let message = serde_json::from_slice::<OpenMessage<'_>>(body).ok()?;
    if message.jsonrpc != "2.0" || message.method != DID_OPEN || message.id {
        return None;
    }
    let item = message.params.text_document;
    let fields = (
        item.uri.into_owned(),
        item.language_id.into_owned(),
        item.version,
    );
    Some((fields, item.text.get().as_bytes()))
}

/// The `didOpen` of `fields` and the text of the literal `body[start..end]` (between its quotes),
/// unescaped to the front of the body; the message dropped as the ordinary path drops it when the
/// literal is not JSON, not UTF-8, or holds half a surrogate pair.
fn text_to_front(mut body: Vec<u8>, start: usize, end: usize, fields: OpenFields) -> OpenRead {
    let unescaped = match unescape_to_front(&mut body, start, end) {
        Ok(unescaped) => unescaped,
        Err(_) => return OpenRead::NotJson,
    };
    body.truncate(unescaped.length);
    let Ok(text) = String::from_utf8(body) else {
        return OpenRead::NotJson;
    };
    if unescaped.lone_surrogate {
        return OpenRead::LoneSurrogate;
    }
    request_from(fields, text)
}

/// The `didOpen` request of the fields and the text.
fn request_from((uri, language_id, version): OpenFields, text: String) -> OpenRead {
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

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use tower_lsp_server::ls_types::DidOpenTextDocumentParams;

    /// A `didOpen` whose text is the JSON literal `text_literal`.
    pub(crate) fn open_body(text_literal: &str) -> Vec<u8> {
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
