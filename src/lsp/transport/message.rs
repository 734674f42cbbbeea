//! What a framed body is: a request or notification for the server, a response to one of the
//! server's requests, or something that is dropped with the error response JSON-RPC asks for. Each
//! body is parsed once, straight into the framework's types (a `didOpen` of 30 MB included).

use crate::lsp::transport::measure::measured_without;
use crate::lsp::transport::open_in_place::{read_open_in_place, OpenRead};
use serde::de::IgnoredAny;
use serde::Deserialize;
use std::borrow::Cow;
use tower_lsp_server::jsonrpc::{Error, Id, Request, Response};
use tower_lsp_server::ls_types::InitializeParams;

/// A message from the client.
#[derive(Debug)]
pub enum Incoming {
    Request(Request),
    Response(Response),
    /// Dropped: the response to send and the reason (for the log).
    Invalid {
        response: Response,
        reason: String,
    },
}

/// Whether an `initialize` the server accepts went through: the framework would run an
/// `initialize` that arrives before the first is answered as a second initialization.
#[derive(Default)]
pub struct InitializeGate {
    passed: bool,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Problem {
    NotJson,
    NotMessage,
    SecondInitialize,
}

impl std::fmt::Display for Problem {
    fn fmt(&self, formatter: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        formatter.write_str(match self {
            Problem::NotJson => "that is not JSON was dropped",
            Problem::NotMessage => "that is not a JSON-RPC message was dropped",
            Problem::SecondInitialize => "is a second initialize",
        })
    }
}

/// The fields a request must have, read without its parameters: used only when the framework's type
/// cannot tell a missing method from an empty one (it reads both as ""). A message without a method
/// may well be a damaged response, which must not be answered with its id.
#[derive(Deserialize)]
struct RequestShape<'a> {
    #[serde(borrow)]
    #[allow(dead_code)]
    method: Cow<'a, str>,
}

/// Reads one body.
pub fn read_message(body: &[u8], gate: &mut InitializeGate) -> Incoming {
    // The parser does not check the bytes of what it skips (unknown fields); JSON is UTF-8 throughout.
    if std::str::from_utf8(body).is_err() {
        return invalid(Id::Null, Problem::NotJson, body.len());
    }
    let problem = match serde_json::from_slice::<Request>(body) {
        Ok(request)
            if !request.method().is_empty()
                || serde_json::from_slice::<RequestShape>(body).is_ok() =>
        {
            if request.method() == "initialize" && request.id().is_some() {
                if gate.passed {
                    let id = request.id().cloned().unwrap_or(Id::Null);
                    return invalid(id, Problem::SecondInitialize, body.len());
                }
                gate.passed = request
                    .params()
                    .is_some_and(|params| InitializeParams::deserialize(params).is_ok());
            }
            return Incoming::Request(request);
        }
        _ => {
            if let Ok(response) = serde_json::from_slice::<Response>(body) {
                return Incoming::Response(response);
            }
            if serde_json::from_slice::<IgnoredAny>(body).is_err() {
                Problem::NotJson
            } else {
                Problem::NotMessage
            }
        }
    };
    let id = match problem {
        Problem::NotMessage => id_of_request(body),
        _ => Id::Null,
    };
    invalid(id, problem, body.len())
}

/// Reads one body that the caller hands over: a large `didOpen` is read in its own buffer
/// (`open_in_place.rs`), anything else as by [`read_message`]. The body comes back when it was read
/// the ordinary way (the reader looks into a body that was no message for the next header).
pub fn read_owned_message(body: Vec<u8>, gate: &mut InitializeGate) -> (Incoming, Option<Vec<u8>>) {
    if measured_without("open-in-place") {
        return (read_message(&body, gate), Some(body));
    }
    let length = body.len();
    match read_open_in_place(body) {
        OpenRead::Request(request) => (Incoming::Request(request), None),
        OpenRead::LoneSurrogate => (invalid(Id::Null, Problem::NotMessage, length), None),
        OpenRead::NotJson => (invalid(Id::Null, Problem::NotJson, length), None),
        OpenRead::Other(body) => (read_message(&body, gate), Some(body)),
    }
}

/// The id to answer a message that is no valid request with: its own, when it has a method and an
/// id (a message without a method is no request, and a response is never answered with its id).
fn id_of_request(body: &[u8]) -> Id {
    let value: serde_json::Value = serde_json::from_slice(body).unwrap_or_default();
    match (value.get("method"), value.get("id")) {
        (Some(_), Some(id)) => serde_json::from_value(id.clone()).unwrap_or(Id::Null),
        _ => Id::Null,
    }
}

fn invalid(id: Id, problem: Problem, length: usize) -> Incoming {
    let error = match problem {
        Problem::NotJson => Error::parse_error(),
        Problem::NotMessage | Problem::SecondInitialize => Error::invalid_request(),
    };
    Incoming::Invalid {
        response: Response::from_error(id, error),
        reason: format!("a message of {length} bytes {problem}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lsp::transport::open_in_place::tests::open_body;
    use tower_lsp_server::ls_types::DidOpenTextDocumentParams;

    fn kind(body: &[u8]) -> &'static str {
        match read_message(body, &mut InitializeGate::default()) {
            Incoming::Request(_) => "request",
            Incoming::Response(_) => "response",
            Incoming::Invalid { response, .. } => match response.into_parts().1 {
                Err(error) if error.code == Error::parse_error().code => "not json",
                _ => "invalid",
            },
        }
    }

    #[test]
    fn only_json_rpc_messages_pass() {
        assert_eq!(
            kind(br#"{"jsonrpc":"2.0","method":"initialized","params":{}}"#),
            "request"
        );
        assert_eq!(kind(br#"{"jsonrpc":"2.0","method":""}"#), "request");
        assert_eq!(
            kind(br#"{"jsonrpc":"2.0","id":"a","result":null}"#),
            "response"
        );
        assert_eq!(kind(b"{}"), "invalid");
        assert_eq!(
            kind(br#"{"jsonrpc":"2.0","id":9,"error":"bad"}"#),
            "invalid"
        );
        assert_eq!(kind(br#"{"jsonrpc":"2.0","id":1,"method":5}"#), "invalid");
        assert_eq!(kind(br#"{"jsonrpc":"1.0","method":"x"}"#), "invalid");
        assert_eq!(kind(b"{"), "not json");
        assert_eq!(kind(b"\"\xff\""), "not json");
    }

    #[test]
    fn an_invalid_request_is_answered_with_its_id_and_a_response_never() {
        let id_of = |body: &[u8]| match read_message(body, &mut InitializeGate::default()) {
            Incoming::Invalid { response, .. } => response.into_parts().0,
            other => panic!("not dropped: {other:?}"),
        };
        assert_eq!(
            id_of(br#"{"jsonrpc":"2.0","id":7,"method":5}"#),
            Id::Number(7)
        );
        assert_eq!(id_of(br#"{"jsonrpc":"2.0","id":7,"error":"x"}"#), Id::Null);
    }

    #[test]
    fn a_second_accepted_initialize_is_refused() {
        let mut gate = InitializeGate::default();
        let bad = br#"{"jsonrpc":"2.0","id":1,"method":"initialize","params":{"capabilities":5}}"#;
        let good =
            br#"{"jsonrpc":"2.0","id":2,"method":"initialize","params":{"capabilities":{}}}"#;
        assert!(matches!(read_message(bad, &mut gate), Incoming::Request(_)));
        assert!(matches!(
            read_message(good, &mut gate),
            Incoming::Request(_)
        ));
        assert!(matches!(
            read_message(good, &mut gate),
            Incoming::Invalid { .. }
        ));
    }

    /// What a reading gave, in terms both paths share: the didOpen's text, or the error's code.
    fn outcome(incoming: Incoming) -> Result<String, i64> {
        match incoming {
            Incoming::Request(request) => {
                let params: DidOpenTextDocumentParams =
                    serde_json::from_value(request.params().cloned().unwrap_or_default())
                        .map_err(|_| 0)?;
                Ok(params.text_document.text)
            }
            Incoming::Invalid { response, .. } => Err(match response.into_parts().1 {
                Err(error) => error.code.code(),
                Ok(_) => 0,
            }),
            Incoming::Response(_) => Err(1),
        }
    }

    /// What the ordinary path makes of `body`.
    fn ordinary(body: &[u8]) -> Result<String, i64> {
        outcome(read_message(body, &mut InitializeGate::default()))
    }

    /// What reading in place makes of `body`.
    fn in_place(body: &[u8]) -> Result<String, i64> {
        outcome(read_owned_message(body.to_vec(), &mut InitializeGate::default()).0)
    }

    #[test]
    fn a_didopen_text_found_by_its_key_reads_as_the_ordinary_path_reads_it() {
        let program = "N10 G0 X1\nN20 \"text\":\"quoted\" Y2\r\n".repeat(3);
        let literal = serde_json::to_string(&program).unwrap();
        let bodies = [
            // As clients send it, with spaces around the colon, and with the text first.
            open_body(&literal),
            String::from_utf8(open_body(&literal))
                .unwrap()
                .replace(r#""text":"#, "\"text\" :\n ")
                .into_bytes(),
            format!(
                r#"{{"jsonrpc":"2.0","method":"textDocument/didOpen","params":{{"textDocument":{{"text":{literal},"uri":"file:///a.mpf","languageId":"sinumerik","version":3}}}}}}"#
            )
            .into_bytes(),
            // Another "text" key first, in an object and in a string.
            format!(
                r#"{{"jsonrpc":"2.0","method":"textDocument/didOpen","params":{{"x":{{"text":"decoy"}},"y":"\"text\":\"","textDocument":{{"uri":"file:///a.mpf","languageId":"sinumerik","version":3,"text":{literal}}}}}}}"#
            )
            .into_bytes(),
        ];
        for body in &bodies {
            assert_eq!(in_place(body), Ok(program.clone()));
            assert_eq!(ordinary(body), Ok(program.clone()));
        }
        // A decoy with megabytes after it is passed over without copying them.
        let large = "N10 G1 X1 Y2 Z3\n".repeat(80_000);
        let body = format!(
            r#"{{"jsonrpc":"2.0","method":"textDocument/didOpen","params":{{"x":{{"text":"decoy"}},"textDocument":{{"uri":"file:///a.mpf","languageId":"sinumerik","version":3,"text":{}}}}}}}"#,
            serde_json::to_string(&large).unwrap()
        );
        assert_eq!(in_place(body.as_bytes()), Ok(large));
        // Bytes that are not UTF-8, in the text or in a field nobody reads, make no JSON either way.
        let mut in_text = open_body(r#""N10 X1 and more to fill the words""#);
        let at = in_text.len() - 8;
        in_text[at] = 0xff;
        let mut in_field = open_body(r#""N10 X1""#);
        in_field.splice(1..1, b"\"x\":\"\xfe\",".iter().copied());
        for body in [in_text, in_field] {
            assert_eq!(in_place(&body), ordinary(&body));
            assert!(ordinary(&body).is_err());
        }
    }
}
