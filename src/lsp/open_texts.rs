//! The texts of large `didOpen` messages, taken out by the input guard. The framework would read such
//! a message into a JSON tree and then into typed parameters, keeping its read buffer as large as the
//! message afterwards; the guard instead turns its text straight into the rope the document keeps,
//! while the message arrives (`arriving_open.rs`) or, failing that, from the whole body once
//! (`json_string.rs`), keeps that here and passes on the message with an empty text, which `didOpen`
//! fills in again from here.

use crate::lsp::documents::lock;
use crate::lsp::json_string::rope_from_literal;
use ropey::Rope;
use serde::Deserialize;
use serde_json::value::RawValue;
use std::borrow::Cow;
use std::collections::VecDeque;
use std::sync::Mutex;
use tower_lsp_server::ls_types::{DidOpenTextDocumentParams, TextDocumentItem, Uri};

/// Smaller messages go through the framework as they are.
pub const LARGE_MESSAGE_BYTES: usize = 256 * 1024;

/// At most this many texts wait for their `didOpen` handler. The handler takes each text right after
/// the guard put it here; only a message the framework drops (one sent before `initialize`) leaves
/// its text behind, and such texts are dropped when newer ones come.
const WAITING_TEXTS: usize = 4;

/// Texts by document and version, waiting for the `didOpen` handler.
#[derive(Default)]
pub struct OpenTexts {
    waiting: Mutex<VecDeque<(Uri, i32, Rope)>>,
}

impl OpenTexts {
    fn put(&self, uri: Uri, version: i32, text: Rope) {
        let mut waiting = lock(&self.waiting);
        waiting.retain(|(other, _, _)| *other != uri);
        waiting.push_back((uri, version, text));
        while waiting.len() > WAITING_TEXTS {
            waiting.pop_front();
        }
    }

    /// The text the guard took out of the `didOpen` of `uri` at `version`, if it did.
    pub fn take(&self, uri: &Uri, version: i32) -> Option<Rope> {
        let mut waiting = lock(&self.waiting);
        let index = waiting
            .iter()
            .position(|(other, other_version, _)| other == uri && *other_version == version)?;
        waiting.remove(index).map(|(_, _, text)| text)
    }

    #[cfg(test)]
    pub fn waiting_count(&self) -> usize {
        lock(&self.waiting).len()
    }
}

/// A `didOpen` notification as the protocol defines it, its text left as written.
#[derive(Deserialize)]
struct DidOpenMessage<'a> {
    #[serde(borrow)]
    method: Cow<'a, str>,
    #[serde(borrow)]
    params: DidOpenParams<'a>,
    /// A message with an id is a request, which `didOpen` must not be: it goes to the framework,
    /// which answers it.
    id: Option<serde::de::IgnoredAny>,
}

#[derive(Deserialize)]
struct DidOpenParams<'a> {
    #[serde(rename = "textDocument", borrow)]
    text_document: DocumentWithLiteralText<'a>,
}

/// `TextDocumentItem` with the text as its JSON literal.
#[derive(Deserialize)]
struct DocumentWithLiteralText<'a> {
    uri: Uri,
    #[serde(rename = "languageId")]
    language_id: String,
    version: i32,
    #[serde(borrow)]
    text: &'a RawValue,
}

/// When `body` is a large `didOpen` notification: keeps its text in `texts` and returns the message
/// to pass on, with an empty text. Any other message (or one that does not parse) is left alone.
pub fn take_text_out(body: &[u8], texts: &OpenTexts) -> Option<Vec<u8>> {
    if body.len() < LARGE_MESSAGE_BYTES
        || memchr::memmem::find(body, b"textDocument/didOpen").is_none()
    {
        return None;
    }
    let message: DidOpenMessage = serde_json::from_slice(body).ok()?;
    if !is_did_open_notification(&message) {
        return None;
    }
    // A text that is not a string is left to the framework, which refuses the message.
    let text = rope_from_literal(message.params.text_document.text.get())?;
    pass_on(message, text, texts)
}

/// The `didOpen` whose text was read while it arrived (`arriving_open.rs`): `without_text` is the
/// message with an empty string in place of the text literal, which started at byte `text_at`.
/// Returns the message to pass on and keeps `text`, when `without_text` is a `didOpen` notification
/// and its text is the literal that was read; otherwise `None`, and nothing is kept.
pub fn take_read_text(
    without_text: &[u8],
    text_at: usize,
    text: Rope,
    texts: &OpenTexts,
) -> Option<Vec<u8>> {
    let message: DidOpenMessage = serde_json::from_slice(without_text).ok()?;
    let literal = message.params.text_document.text.get();
    let literal_at = literal.as_ptr() as usize - without_text.as_ptr() as usize;
    if literal != "\"\"" || literal_at != text_at {
        return None;
    }
    pass_on(message, text, texts)
}

fn is_did_open_notification(message: &DidOpenMessage) -> bool {
    message.method == "textDocument/didOpen" && message.id.is_none()
}

/// Keeps the text of a `didOpen` notification and returns the message to pass on; `None` for a
/// message of another method or a request.
fn pass_on(message: DidOpenMessage, text: Rope, texts: &OpenTexts) -> Option<Vec<u8>> {
    if !is_did_open_notification(&message) {
        return None;
    }
    let document = message.params.text_document;
    let params = DidOpenTextDocumentParams {
        text_document: TextDocumentItem {
            uri: document.uri,
            language_id: document.language_id,
            version: document.version,
            text: String::new(),
        },
    };
    let forwarded = serde_json::to_vec(&serde_json::json!({
        "jsonrpc": "2.0",
        "method": "textDocument/didOpen",
        "params": params,
    }))
    .ok()?;
    let document = params.text_document;
    texts.put(document.uri, document.version, text);
    Some(forwarded)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::{json, Value};

    fn message(method: &str, text: &str, id: Option<u64>) -> Vec<u8> {
        let mut value = json!({
            "jsonrpc": "2.0",
            "method": method,
            "params": {"textDocument": {"uri": "file:///a.mpf", "languageId": "sinumerik", "version": 7, "text": text}},
        });
        if let Some(id) = id {
            value["id"] = json!(id);
        }
        serde_json::to_vec(&value).unwrap()
    }

    fn uri() -> Uri {
        "file:///a.mpf".parse().unwrap()
    }

    #[test]
    fn a_large_did_open_is_passed_on_without_its_text_which_waits_for_the_handler() {
        let text = "N10 G0 X\u{e4}1 ; \"quoted\"\r\n".repeat(20_000);
        let texts = OpenTexts::default();
        let forwarded = take_text_out(&message("textDocument/didOpen", &text, None), &texts)
            .expect("a large didOpen is taken apart");
        let forwarded: Value = serde_json::from_slice(&forwarded).unwrap();
        assert_eq!(forwarded["method"], "textDocument/didOpen");
        assert_eq!(forwarded["params"]["textDocument"]["text"], "");
        assert_eq!(forwarded["params"]["textDocument"]["version"], 7);
        assert_eq!(forwarded["params"]["textDocument"]["uri"], "file:///a.mpf");
        assert_eq!(texts.take(&uri(), 6), None, "another version");
        assert_eq!(
            texts
                .take(&uri(), 7)
                .map(|rope| rope.to_string())
                .as_deref(),
            Some(text.as_str())
        );
        assert_eq!(texts.take(&uri(), 7), None, "taken once");
    }

    #[test]
    fn small_messages_other_methods_requests_and_bad_json_are_left_alone() {
        let large = "X1\n".repeat(100_000);
        let texts = OpenTexts::default();
        for body in [
            message("textDocument/didOpen", "X1\n", None),
            message("textDocument/didChange", &large, None),
            message("textDocument/didOpen", &large, Some(1)),
            format!("{{\"method\": \"textDocument/didOpen\", \"params\": \"{large}").into_bytes(),
            // The text is not a string.
            serde_json::to_vec(&json!({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {"textDocument": {"uri": "file:///a.mpf", "languageId": "sinumerik", "version": 7, "text": [large]}}})).unwrap(),
        ] {
            assert_eq!(take_text_out(&body, &texts), None);
        }
        assert_eq!(texts.take(&uri(), 7), None);
    }

    #[test]
    fn texts_left_behind_are_dropped_when_newer_ones_come() {
        let texts = OpenTexts::default();
        for index in 0..10 {
            let uri: Uri = format!("file:///{index}.mpf").parse().unwrap();
            texts.put(uri, 1, Rope::from_str(&index.to_string()));
        }
        assert_eq!(lock(&texts.waiting).len(), WAITING_TEXTS);
        let newest: Uri = "file:///9.mpf".parse().unwrap();
        assert_eq!(
            texts
                .take(&newest, 1)
                .map(|rope| rope.to_string())
                .as_deref(),
            Some("9")
        );
    }
}
