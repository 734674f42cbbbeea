//! The server's hand-written wire code: the framing parser (`framing` target) and the encoding of
//! diagnostics publications (`publish` target).
//!
//! `framing`: a stream of messages, some well framed, some with damaged headers, wrong or huge
//! lengths, garbage and blank lines. The framer must give the same frames however the bytes are cut,
//! give back every well-framed message of an undamaged stream exactly, keep its buffer bounded, and
//! every body must read as a message or be answered with an error response that serializes, and read
//! in its own buffer (a large `didOpen`'s text unescaped in place) as it reads the ordinary way.
//!
//! `publish`: a program's lines with findings made from the text (spans anywhere, also inside
//! characters; messages with quotes, control characters and non-ASCII letters), published three times
//! with changes between. Each body must be the JSON the LSP types serialize to, and a publication
//! that took over items from the one before must equal one written from nothing.

use super::random::Random;
use sinumerik_lsp::diagnostics::{Code, Diagnostic, LineDiagnostic, Severity, Span};
use sinumerik_lsp::lsp::{
    diagnostic_ranges, publication_body, read_message, read_owned_message, Frame, Framer,
    InitializeGate, PositionEncoding, Publisher,
};
use std::borrow::Cow;
use tower_lsp_server::ls_types::{self, NumberOrString, PublishDiagnosticsParams, Uri};

/// The longest header line the framer keeps whole (`transport/framing.rs`).
const MAX_HEADER_LINE: usize = 64 * 1024;

fn framed(body: &str) -> String {
    format!("Content-Length: {}\r\n\r\n{body}", body.len())
}

/// A message body: a request, a notification, a response, or something that only looks like one.
fn body(random: &mut Random, donor: &[String]) -> String {
    let text = if donor.is_empty() {
        "N10 X1".to_string()
    } else {
        random.pick(donor).clone()
    };
    let text = serde_json::to_string(&text).unwrap_or_default();
    if random.one_in(3) {
        return open_body(random, &text);
    }
    match random.below(8) {
        0 => format!(
            r#"{{"jsonrpc":"2.0","id":{},"method":"initialize","params":{{"capabilities":{{}}}}}}"#,
            random.below(9)
        ),
        1 => format!(
            r#"{{"jsonrpc":"2.0","method":"textDocument/didOpen","params":{{"textDocument":{{"uri":"file:///a.mpf","languageId":"sinumerik","version":1,"text":{text}}}}}}}"#
        ),
        2 => format!(
            r#"{{"jsonrpc":"2.0","id":"x{}","result":null}}"#,
            random.below(99)
        ),
        3 => format!(
            r#"{{"jsonrpc":"2.0","id":{},"method":5}}"#,
            random.below(99)
        ),
        4 => r#"{"jsonrpc":"2.0","method":""}"#.to_string(),
        5 => format!(r#"{{"jsonrpc":"1.0","method":{text}}}"#),
        6 => format!("{{{text}"),
        _ => format!(
            r#"{{"jsonrpc":"2.0","id":null,"method":"textDocument/hover","params":{{"x":{text}}}}}"#
        ),
    }
}

/// A `didOpen` as a client sends it or slightly wrong: its text a literal with every kind of escape
/// (surrogate pairs, halves of one, escapes JSON does not have, raw control characters), its other
/// fields missing, doubled or of the wrong type. A large one is read in its own buffer
/// (`transport/open_in_place.rs`); it must give what the ordinary reading gives.
fn open_body(random: &mut Random, program_literal: &str) -> String {
    const PIECES: [&str; 22] = [
        "N10 G0 X1",
        "\\n",
        "\\r\\n",
        "\\\"",
        "\\\\",
        "\\/",
        "\\b\\f\\t",
        "\\u00e4",
        "\\u00C4",
        "\\ud83d\\udee0",
        "\\ud83d",
        "\\udee0",
        "\\ud83d\\u0041",
        "ä",
        "中",
        "🛠",
        "\\x",
        "\u{1}",
        "\\u12",
        "\\uZZZZ",
        "\\u0000",
        " ",
    ];
    let literal = if random.one_in(4) {
        program_literal.to_string()
    } else {
        let count = random.length(0, 40);
        let inner: String = (0..count).map(|_| *random.pick(&PIECES)).collect();
        format!("\"{inner}\"")
    };
    let jsonrpc = match random.below(8) {
        0 => "",
        1 => r#""jsonrpc":"1.0","#,
        _ => r#""jsonrpc":"2.0","#,
    };
    let id = match random.below(8) {
        0 => r#""id":null,"#,
        1 => r#""id":5,"#,
        _ => "",
    };
    let method = match random.below(10) {
        0 => r#""method":"textDocument\/didOpen""#,
        1 => r#""method":"textDocument/didChange""#,
        _ => r#""method":"textDocument/didOpen""#,
    };
    let version = match random.below(10) {
        0 => "1.5",
        1 => r#""1""#,
        2 => "99999999999",
        _ => "7",
    };
    let uri = match random.below(10) {
        0 => r#""not a uri""#,
        1 => r#""file:\/\/\/a%20b.mpf""#,
        _ => r#""file:///a.mpf""#,
    };
    let extra = match random.below(8) {
        0 => format!(r#","text":{literal}"#),
        1 => r#","extra":[1,{"a":null}]"#.to_string(),
        _ => String::new(),
    };
    let text = if random.one_in(12) {
        "5".to_string()
    } else {
        literal
    };
    // Another "text" key before the document's, and space around the colon.
    let before = match random.below(10) {
        0 => r#""x":{"text":"b"},"#,
        1 => r#""x":"\"text\":\"","#,
        _ => "",
    };
    let colon = if random.one_in(6) { " : " } else { ":" };
    format!(
        r#"{{{jsonrpc}{id}{method},"params":{{{before}"textDocument":{{"uri":{uri},"languageId":"sinumerik","version":{version},"text"{colon}{text}{extra}}}}}}}"#
    )
}

/// A body read by the caller's own buffer (`read_owned_message`) must give what the ordinary reading
/// gives: the same request with the same `didOpen` parameters, the same response, or the same error.
fn same_reading(body: &[u8]) -> Result<(), String> {
    use sinumerik_lsp::lsp::Incoming;
    let ordinary = read_message(body, &mut InitializeGate::default());
    let (owned, _) = read_owned_message(body.to_vec(), &mut InitializeGate::default());
    let differs = |what: &str| {
        Err(format!(
            "reading in place differs ({what}) for {}",
            String::from_utf8_lossy(body)
        ))
    };
    match (ordinary, owned) {
        (Incoming::Request(a), Incoming::Request(b)) => {
            if a.method() != b.method() || a.id() != b.id() {
                return differs("method or id");
            }
            let open = |request: &tower_lsp_server::jsonrpc::Request| {
                request
                    .params()
                    .cloned()
                    .map(serde_json::from_value::<ls_types::DidOpenTextDocumentParams>)
            };
            match (open(&a), open(&b)) {
                (Some(Ok(a)), Some(Ok(b))) if a == b => Ok(()),
                (Some(Err(_)), Some(Err(_))) | (None, None) => Ok(()),
                _ => differs("the didOpen parameters"),
            }
        }
        (Incoming::Response(a), Incoming::Response(b)) => {
            if serde_json::to_value(&a).ok() == serde_json::to_value(&b).ok() {
                Ok(())
            } else {
                differs("the response")
            }
        }
        (Incoming::Invalid { response: a, .. }, Incoming::Invalid { response: b, .. }) => {
            if serde_json::to_value(&a).ok() == serde_json::to_value(&b).ok() {
                Ok(())
            } else {
                differs("the error response")
            }
        }
        _ => differs("the kind of message"),
    }
}

/// A stream of framed messages, damaged where `damaged` says so.
pub fn generate_stream(random: &mut Random, donor: &[String]) -> String {
    let damaged = random.one_in(2);
    let count = random.length(6, 40).max(1);
    let mut stream = String::new();
    for _ in 0..count {
        let body = body(random, donor);
        if !damaged {
            stream.push_str(&framed(&body));
            continue;
        }
        let piece = match random.below(10) {
            0 => format!(
                "Content-Length: {}\r\n\r\n{body}",
                body.len() + random.below(30)
            ),
            1 => format!(
                "Content-Length: {}\r\n\r\n{body}",
                body.len().saturating_sub(random.below(30))
            ),
            2 => format!("content-length:{}\nContent-Type: x\n\n{body}", body.len()),
            3 => format!("Content-Length: -{}\r\n\r\n{body}", body.len()),
            4 => format!("Content-Length: 99999999999999\r\n\r\n{body}"),
            5 => format!("X-Nothing: 1\r\n\r\n{body}"),
            6 => "\r\n\n\r\n".to_string(),
            7 => body.repeat(random.length(2, 2_000)),
            8 => {
                format!("Content-Length: {}\r\n\r\n{body}", body.len()).replace("\r\n\r\n", "\r\n")
            }
            _ => framed(&body),
        };
        stream.push_str(&piece);
    }
    stream
}

/// Every frame of `bytes`, pushed in pieces of the sizes `cuts` cycles through.
fn frames_of(bytes: &[u8], cuts: &[usize]) -> Result<Vec<Frame>, String> {
    let mut framer = Framer::new();
    let mut frames = Vec::new();
    let mut rest = bytes;
    let mut turn = 0;
    while !rest.is_empty() {
        let size = cuts[turn % cuts.len()].clamp(1, rest.len());
        turn += 1;
        framer.push(&rest[..size]);
        rest = &rest[size..];
        while let Some(frame) = framer.next_frame() {
            frames.push(frame);
        }
        // What is kept beyond the body being read is at most one header line and one piece.
        let kept = framer.pending_bytes();
        let in_bodies: usize = frames
            .iter()
            .map(|frame| match frame {
                Frame::Body(body) => body.len(),
                Frame::Dropped(_) => 0,
            })
            .sum();
        if kept > bytes.len() - in_bodies + size {
            return Err(format!("the framer keeps {kept} bytes of {}", bytes.len()));
        }
    }
    if framer.pending_bytes() > bytes.len() {
        return Err("the framer holds more than it was given".into());
    }
    let _ = MAX_HEADER_LINE;
    Ok(frames)
}

pub fn check_framing(text: &str) -> Result<(), String> {
    let bytes = text.as_bytes();
    let whole = frames_of(bytes, &[usize::MAX])?;
    for cuts in [&[1][..], &[7, 1, 300], &[4096, 13]] {
        if frames_of(bytes, cuts)? != whole {
            return Err(format!(
                "cutting the bytes into pieces of {cuts:?} changes the frames"
            ));
        }
    }
    // An undamaged stream of framed messages comes back exactly.
    let mut expected = Vec::new();
    let mut rest = text;
    while let Some(after) = rest.strip_prefix("Content-Length: ") {
        let Some((length, after)) = after.split_once("\r\n\r\n") else {
            break;
        };
        let Ok(length) = length.parse::<usize>() else {
            break;
        };
        if after.len() < length || !after.is_char_boundary(length) {
            break;
        }
        expected.push(Frame::Body(after.as_bytes()[..length].to_vec()));
        rest = &after[length..];
    }
    if rest.is_empty() && whole != expected {
        return Err("a well-framed stream does not come back message by message".into());
    }
    let mut gate = InitializeGate::default();
    for frame in &whole {
        if let Frame::Body(body) = frame {
            same_reading(body)?;
            // The same body with a byte that is not UTF-8 somewhere (in the text, a field, a key).
            if !body.is_empty() {
                let mut damaged = body.clone();
                damaged[body.len() * 7 / 13] = 0xff;
                same_reading(&damaged)?;
            }
            if let sinumerik_lsp::lsp::Incoming::Invalid { response, .. } =
                read_message(body, &mut gate)
            {
                serde_json::to_vec(&response)
                    .map_err(|error| format!("an error response does not serialize: {error}"))?;
            }
        }
    }
    Ok(())
}

/// A seed for the findings made from `text`, so that a saved text replays the same case.
fn seed_of(text: &str) -> u64 {
    text.bytes().fold(0xcbf2_9ce4_8422_2325, |hash, byte| {
        (hash ^ byte as u64).wrapping_mul(0x100_0000_01b3)
    })
}

fn findings(random: &mut Random, lines: &[&str]) -> Vec<LineDiagnostic> {
    let codes = [Code::UnexpectedCharacter, Code::ModifierWithoutParentheses];
    let severities = [
        Severity::Error,
        Severity::Warning,
        Severity::Information,
        Severity::Hint,
    ];
    let mut items = Vec::new();
    for (line, text) in lines.iter().enumerate() {
        for _ in 0..random.below(3) {
            let start = random.below(text.len() + 3);
            let end = start + random.below(8);
            let from = random.below(text.len() + 1);
            let message: String = text
                .bytes()
                .skip(from)
                .take(random.below(40))
                .map(char::from)
                .collect();
            let message = format!(
                "{message}{}",
                random.word(&["", "\"", "\\", "\u{1}", "ä😀", "\n"])
            );
            let mut diagnostic = Diagnostic::new(
                *random.pick(&codes),
                Span::new(start, end.max(start)),
                message,
            );
            diagnostic.severity = *random.pick(&severities);
            items.push(LineDiagnostic { line, diagnostic });
        }
    }
    items
}

pub fn check_publish(text: &str) -> Result<(), String> {
    let mut random = Random::new(seed_of(text));
    let lines: Vec<&str> = text.split('\n').take(400).collect();
    let uri: Uri = "file:///fuzz/a%20b.mpf".parse().map_err(|_| "uri")?;
    let all_ascii = text.is_ascii();
    let mut publisher = Publisher::default();
    let mut items = findings(&mut random, &lines);
    for round in 0..3 {
        let encoding = if random.one_in(2) {
            PositionEncoding::Utf16
        } else {
            PositionEncoding::Utf8
        };
        let ranges = diagnostic_ranges(
            &items,
            |line| Cow::Borrowed(lines[line]),
            all_ascii,
            encoding,
        );
        let reused = publisher.encode(&items, ranges.clone()).to_vec();
        let fresh = Publisher::default().encode(&items, ranges.clone()).to_vec();
        if reused != fresh {
            return Err(format!(
                "round {round}: the items taken over differ from items written anew"
            ));
        }
        let body = publication_body(&uri, Some(round), &reused, &[]);
        let written: serde_json::Value = serde_json::from_slice(&body)
            .map_err(|error| format!("round {round}: not JSON: {error}"))?;
        let expected = PublishDiagnosticsParams {
            uri: uri.clone(),
            diagnostics: items
                .iter()
                .zip(&ranges)
                .map(|(item, range)| ls_types::Diagnostic {
                    range: *range,
                    severity: Some(match item.diagnostic.severity {
                        Severity::Error => ls_types::DiagnosticSeverity::ERROR,
                        Severity::Warning => ls_types::DiagnosticSeverity::WARNING,
                        Severity::Information => ls_types::DiagnosticSeverity::INFORMATION,
                        Severity::Hint => ls_types::DiagnosticSeverity::HINT,
                    }),
                    code: Some(NumberOrString::String(
                        item.diagnostic.code.as_str().to_string(),
                    )),
                    source: Some("sinumerik".to_string()),
                    message: item.diagnostic.message.clone(),
                    ..ls_types::Diagnostic::default()
                })
                .collect(),
            version: Some(round),
        };
        let expected = serde_json::json!({"jsonrpc": "2.0", "method": "textDocument/publishDiagnostics", "params": expected});
        if written != expected {
            return Err(format!(
                "round {round}: the body is not what the LSP types serialize to"
            ));
        }
        // Between publications: some findings go, some change, some come.
        let mut next = Vec::new();
        for item in items {
            match random.below(12) {
                0 => {}
                1 => {
                    let mut item = item;
                    item.diagnostic.message.push('x');
                    next.push(item);
                }
                _ => next.push(item),
            }
        }
        let mut added = findings(&mut random, &lines);
        added.retain(|_| random.one_in(10));
        next.extend(added);
        next.sort_by_key(|item| item.line);
        items = next;
    }
    Ok(())
}
