//! Protocol abuse against the built binary over stdio: malformed JSON and messages that are JSON but
//! not JSON-RPC, wrong and missing `Content-Length`, headers cut across reads, unknown methods,
//! requests before `initialize`, `initialize` twice, positions past the end and inside surrogate
//! pairs, edits of closed documents, versions going backwards, range edits across CRLF, a 50 MB
//! `didOpen`, and the exit codes. After each fault the server must still serve another open
//! document: a hover there resolves a value. Every wait has a deadline (tests/support/raw_lsp.rs),
//! so a hang fails the test.

#[path = "support/compare.rs"]
mod compare;
#[path = "support/edit_session.rs"]
mod edit_session;
#[path = "support/lsp_client.rs"]
mod lsp_client;
#[path = "support/raw_lsp.rs"]
mod raw_lsp;

use compare::{fresh, published};
use lsp_client::{apply_edit, position_of, seed_text};
use raw_lsp::{frame, RawServer};
use serde_json::{json, Value};
use std::time::{Duration, Instant};

/// The document that must stay served whatever else happens.
const SEED_URI: &str = "file:///nonexistent/turning_seed.mpf";

/// A server after `initialize`, with the seed example open and analysed.
fn serving_server() -> RawServer {
    let mut server = RawServer::spawn();
    server.initialize();
    server.open(SEED_URI, 1, &seed_text());
    assert_eq!(server.diagnostics(SEED_URI, 1), Vec::<Value>::new());
    server
}

/// The server answers a hover on the seed example with the resolved value of `Z=IC(-32)`.
fn assert_still_serves(server: &mut RawServer, after: &str) {
    let (line, character) = position_of(&seed_text(), "Z=IC(-32)");
    let hover = server.hover_text(SEED_URI, line as u64, character as u64);
    assert!(
        hover.contains("**58.000**"),
        "after {after}, the hover on the seed example is {hover:?}"
    );
}

fn hover_request(id: i64, line: u32, character: u32) -> Vec<u8> {
    frame(
        json!({"jsonrpc": "2.0", "id": id, "method": "textDocument/hover", "params": {"textDocument": {"uri": SEED_URI}, "position": {"line": line, "character": character}}})
            .to_string()
            .as_bytes(),
    )
}

/// Writes the damaged `message` and then a hover request with `id` on the seed example, which must be
/// answered with the resolved value, whatever the damaged message swallowed of it.
fn assert_next_request_answered(server: &mut RawServer, message: &[u8], id: i64, what: &str) {
    let (line, character) = position_of(&seed_text(), "Z=IC(-32)");
    server.write_raw(message);
    server.write_raw(&hover_request(id, line, character));
    let answer = server.response(id).expect(what);
    assert!(
        answer["contents"]["value"]
            .as_str()
            .unwrap()
            .contains("**58.000**"),
        "{what}: {answer}"
    );
}

/// An LSP change: start and end as (line, UTF-16 column), and the new text.
type Change = ((u32, u32), (u32, u32), &'static str);

/// Sends `changes` as one `didChange` of `version` and applies them to `text` as the protocol
/// defines.
fn send_changes(
    server: &mut RawServer,
    uri: &str,
    version: i64,
    changes: &[Change],
    text: &mut String,
) {
    let json_changes: Vec<Value> = changes
        .iter()
        .map(|(start, end, new_text)| json!({"range": {"start": {"line": start.0, "character": start.1}, "end": {"line": end.0, "character": end.1}}, "text": new_text}))
        .collect();
    server.change(uri, version, Value::Array(json_changes));
    for (start, end, new_text) in changes {
        apply_edit(text, *start, *end, new_text);
    }
}

/// Error responses without an id (to messages whose id could not be read).
fn errors_without_id(messages: &[Value]) -> Vec<i64> {
    messages
        .iter()
        .filter(|message| message.get("method").is_none() && message["id"].is_null())
        .map(|message| message["error"]["code"].as_i64().unwrap())
        .collect()
}

#[test]
fn bodies_that_are_not_json_are_answered_with_a_parse_error_and_dropped() {
    let mut server = serving_server();
    let nested = "[".repeat(100_000);
    let bodies: [(&str, &[u8]); 6] = [
        ("text that is not JSON", b"{not json"),
        ("invalid UTF-8", b"\"\xff\xfe\""),
        (
            "a truncated object",
            br#"{"jsonrpc": "2.0", "id": 1, "method": "#,
        ),
        (
            "two objects",
            br#"{"jsonrpc": "2.0", "method": "initialized"} {}"#,
        ),
        ("100,000 nested brackets", nested.as_bytes()),
        ("an empty body", b""),
    ];
    for (what, body) in bodies {
        server.write_raw(&frame(body));
        assert_still_serves(&mut server, what);
        let errors = errors_without_id(&server.take_received());
        assert_eq!(errors, vec![-32700], "{what}");
    }
    server.wait_for_log("that is not JSON was dropped");
    assert_eq!(server.shutdown(), Some(0));
}

#[test]
fn json_that_is_not_a_message_is_answered_with_invalid_request_and_the_server_goes_on() {
    let mut server = serving_server();
    let bodies = [
        ("an empty object", json!({}), None),
        ("an array", json!([1, 2]), None),
        ("a number", json!(42), None),
        (
            "JSON-RPC 1.0",
            json!({"jsonrpc": "1.0", "id": 7, "method": "textDocument/hover"}),
            Some(7),
        ),
        (
            "a method that is a number",
            json!({"jsonrpc": "2.0", "id": 8, "method": 5}),
            Some(8),
        ),
        (
            "an id that is an object",
            json!({"jsonrpc": "2.0", "id": {"a": 1}, "method": "textDocument/hover"}),
            None,
        ),
        (
            "a response with an error that is a string",
            json!({"jsonrpc": "2.0", "id": 9, "error": "bad"}),
            None,
        ),
        (
            "a request without a method",
            json!({"jsonrpc": "2.0", "id": "ten", "params": {}}),
            None,
        ),
    ];
    for (what, body, id) in bodies {
        server.write_raw(&frame(body.to_string().as_bytes()));
        assert_still_serves(&mut server, what);
        let received = server.take_received();
        match id {
            Some(id) => {
                let answer = received
                    .iter()
                    .find(|message| raw_lsp::is_response_to(message, id))
                    .unwrap_or_else(|| panic!("{what}: no answer to request {id}: {received:?}"));
                assert_eq!(answer["error"]["code"], -32600, "{what}");
            }
            None => assert_eq!(errors_without_id(&received), vec![-32600], "{what}"),
        }
    }
    server.wait_for_log("is not a JSON-RPC message");
    assert_eq!(server.shutdown(), Some(0));
}

#[test]
fn a_wrong_content_length_costs_only_its_own_message() {
    let mut server = serving_server();
    let (line, character) = position_of(&seed_text(), "Z=IC(-32)");
    let body = json!({"jsonrpc": "2.0", "id": 100, "method": "textDocument/hover", "params": {"textDocument": {"uri": SEED_URI}, "position": {"line": line, "character": character}}}).to_string();
    let with_length = |length: &str| {
        let mut message = format!("Content-Length: {length}\r\n\r\n").into_bytes();
        message.extend_from_slice(body.as_bytes());
        message
    };
    let cases = [
        (
            "a length that is too short",
            with_length(&(body.len() - 10).to_string()),
        ),
        // The next message's header and the start of its body are read as this message's end; the
        // server reads on from that header.
        (
            "a length that is too long",
            with_length(&(body.len() + 40).to_string()),
        ),
        ("a length that is not a number", with_length("many")),
        ("a negative length", with_length("-5")),
        (
            "a length beyond 64 bits",
            with_length("99999999999999999999999"),
        ),
        // Beyond the server's limit (1 GiB): refused at once instead of waiting for the bytes.
        ("a length of 5 GB", with_length("5000000000")),
    ];
    for (index, (what, message)) in cases.iter().enumerate() {
        assert_next_request_answered(&mut server, message, 200 + index as i64, what);
        assert_still_serves(&mut server, what);
    }
    // The damaged request itself was never answered.
    let received = server.take_received();
    assert!(
        !received
            .iter()
            .any(|message| raw_lsp::is_response_to(message, 100)),
        "{received:?}"
    );
    server.wait_for_log("Content-Length");
    assert_eq!(server.shutdown(), Some(0));
}

#[test]
fn a_missing_content_length_drops_the_message_and_the_next_one_is_read() {
    let mut server = serving_server();
    let (line, character) = position_of(&seed_text(), "Z=IC(-32)");
    let hover = hover_request(300, line, character);
    let body_start = hover.windows(4).position(|w| w == b"\r\n\r\n").unwrap() + 4;
    // The damaged message's body runs straight into the next message's header.
    let mut damaged = b"Content-Type: application/vscode-jsonrpc; charset=utf-8\r\n\r\n".to_vec();
    damaged.extend_from_slice(&hover[body_start..]);
    damaged.extend(hover_request(301, line, character));
    server.write_raw(&damaged);
    assert!(server.response(301).is_ok());
    // Empty lines and headers without a length between messages.
    server.write_raw(b"\r\n\r\n\r\nX-Nothing: at all\r\n\r\n");
    server.write_raw(&hover_request(302, line, character));
    assert!(server.response(302).is_ok());
    assert_still_serves(&mut server, "a message without Content-Length");
    assert!(!server
        .take_received()
        .iter()
        .any(|message| raw_lsp::is_response_to(message, 300)));
    server.wait_for_log("without a valid Content-Length");
    assert_eq!(server.shutdown(), Some(0));
}

#[test]
fn a_header_and_body_split_across_many_reads_are_put_together() {
    let mut server = serving_server();
    let (line, character) = position_of(&seed_text(), "Z=IC(-32)");
    for (id, piece) in [(400, 1), (401, 3), (402, 7), (403, 25)] {
        server.writer.write_in_pieces(
            &hover_request(id, line, character),
            piece,
            Duration::from_millis(2),
        );
        let answer = server.response(id).expect("the split request is answered");
        assert!(answer["contents"]["value"]
            .as_str()
            .unwrap()
            .contains("**58.000**"));
    }
    // Two whole messages and half of a third in one write, the rest later.
    let mut bytes = hover_request(410, line, character);
    bytes.extend(hover_request(411, line, character));
    let third = hover_request(412, line, character);
    bytes.extend_from_slice(&third[..30]);
    server.write_raw(&bytes);
    std::thread::sleep(Duration::from_millis(50));
    server.write_raw(&third[30..]);
    for id in [410, 411, 412] {
        assert!(server.response(id).is_ok(), "request {id}");
    }
    assert_still_serves(&mut server, "split messages");
    assert_eq!(server.shutdown(), Some(0));
}

#[test]
fn an_unknown_request_is_method_not_found_and_unknown_notifications_and_responses_are_ignored() {
    let mut server = serving_server();
    let error = server.request("sinumerik/nothing", json!({})).unwrap_err();
    assert_eq!(error["code"], -32601);
    let error = server
        .request(
            "textDocument/unheardOf",
            json!({"textDocument": {"uri": SEED_URI}}),
        )
        .unwrap_err();
    assert_eq!(error["code"], -32601);
    server.notify("sinumerik/unknownNotification", json!({"a": 1}));
    server.notify("$/somethingOptional", json!({}));
    server.notify("textDocument/unheardOf", Value::Null);
    // A response to a request the server never sent is ignored as well.
    server.write_raw(&frame(
        br#"{"jsonrpc": "2.0", "id": 12345, "result": {"answer": 42}}"#,
    ));
    assert_still_serves(&mut server, "unknown notifications");
    let received = server.take_received();
    assert!(
        received
            .iter()
            .all(|message| message.get("method").is_some()),
        "an unknown notification was answered: {received:?}"
    );
    assert_eq!(server.shutdown(), Some(0));
}

#[test]
fn requests_before_initialize_are_refused_and_notifications_dropped() {
    let mut server = RawServer::spawn();
    let hover = json!({"textDocument": {"uri": SEED_URI}, "position": {"line": 0, "character": 0}});
    assert_eq!(
        server.request("textDocument/hover", hover).unwrap_err()["code"],
        -32002
    );
    assert_eq!(
        server
            .request("sinumerik/documentText", json!({"uri": SEED_URI}))
            .unwrap_err()["code"],
        -32002
    );
    assert_eq!(
        server.request("shutdown", Value::Null).unwrap_err()["code"],
        -32002
    );
    // A document opened before initialize was dropped with its notification.
    server.open(SEED_URI, 1, &seed_text());
    // Bad params of `initialize` are an error; the server stays uninitialized and can be initialized.
    assert_eq!(
        server
            .request("initialize", json!({"capabilities": 5}))
            .unwrap_err()["code"],
        -32602
    );
    server.initialize();
    assert!(server.document_text(SEED_URI).is_err());
    server.open(SEED_URI, 1, &seed_text());
    server.diagnostics(SEED_URI, 1);
    assert_still_serves(&mut server, "requests before initialize");
    assert_eq!(server.shutdown(), Some(0));
}

#[test]
fn a_second_initialize_is_an_error_and_the_server_keeps_serving() {
    let mut server = serving_server();
    let params = json!({"processId": null, "rootUri": null, "capabilities": {}});
    let error = server.request("initialize", params.clone()).unwrap_err();
    assert_eq!(error["code"], -32600, "{error}");
    assert_still_serves(&mut server, "a second initialize");
    // Also when two come at once before the first is answered, exactly one succeeds.
    let mut fresh_server = RawServer::spawn();
    let first = fresh_server.writer.request("initialize", params.clone());
    let second = fresh_server.writer.request("initialize", params);
    let answers = [fresh_server.response(first), fresh_server.response(second)];
    assert_eq!(
        answers.iter().filter(|answer| answer.is_ok()).count(),
        1,
        "{answers:?}"
    );
    assert_eq!(fresh_server.shutdown(), Some(0));
    assert_eq!(server.shutdown(), Some(0));
}

#[test]
fn positions_past_the_end_of_a_line_or_the_file_are_clamped() {
    let mut server = serving_server();
    let uri = "file:///nonexistent/clamped.mpf";
    let mut text = "N10 G90 G0 X10 Z5\nN20 G91 Z2\n".to_string();
    server.open(uri, 1, &text);
    server.diagnostics(uri, 1);
    // A hover past the end of a line answers for that line's block; past the last line, nothing.
    let hover = server.hover_text(uri, 1, 4000);
    assert!(hover.contains("**7.000**"), "{hover}");
    assert_eq!(server.hover(uri, 4000, 4000), Ok(Value::Null));
    assert_eq!(
        server.hover(uri, u32::MAX as u64, u32::MAX as u64),
        Ok(Value::Null)
    );
    // A column that is not a u32 is invalid params.
    assert_eq!(server.hover(uri, 0, 1 << 40).unwrap_err()["code"], -32602);
    assert_eq!(
        server
            .request(
                "textDocument/hover",
                json!({"textDocument": {"uri": uri}, "position": {"line": -1, "character": 0}})
            )
            .unwrap_err()["code"],
        -32602
    );
    // Edits past the end of a line and of the file land at the ends.
    let edits: [Change; 2] = [
        ((0, 900), (0, 1000), " ; first"),
        ((50, 3), (60, 0), "N30 Z=IC(1)\n"),
    ];
    for (index, change) in edits.iter().enumerate() {
        send_changes(&mut server, uri, 2 + index as i64, &[*change], &mut text);
    }
    assert_eq!(server.document_text(uri), Ok((3, text.clone())));
    assert_eq!(text, "N10 G90 G0 X10 Z5 ; first\nN20 G91 Z2\nN30 Z=IC(1)\n");
    assert_eq!(published(&server.diagnostics(uri, 3)), fresh(&text));
    let hover = server.hover_text(uri, 2, 9);
    assert!(hover.contains("**8.000**"), "{hover}");
    // Inlay hints and previews of ranges past the end answer too.
    let hints = server.request(
        "textDocument/inlayHint",
        json!({"textDocument": {"uri": uri}, "range": {"start": {"line": 0, "character": 0}, "end": {"line": 100000, "character": 100000}}}),
    );
    assert!(hints.is_ok(), "{hints:?}");
    let id = server.writer.request_preview(uri, 1_000_000, 2_000_000);
    let preview = server.response(id).expect("a preview past the end answers");
    assert_eq!(preview["moves"], json!([]));
    assert_still_serves(&mut server, "positions past the end");
    assert_eq!(server.shutdown(), Some(0));
}

#[test]
fn utf16_columns_inside_a_surrogate_pair_mean_the_start_of_the_character() {
    let mut server = serving_server();
    let uri = "file:///nonexistent/emoji.mpf";
    // "N10 G0 " is 7 code units; the emoji takes units 7 and 8.
    let mut text = "N10 G0 😀 X1\nN20 Z=IC(2) 😀\n".to_string();
    server.open(uri, 1, &text);
    server.diagnostics(uri, 1);
    let changes: [Change; 3] = [
        // Inside the pair: before the emoji.
        ((0, 8), (0, 8), "A"),
        // From inside the second emoji to the line's end: the whole emoji goes.
        ((1, 13), (1, 14), ""),
        // From "G0" to inside the first emoji (now at 8 and 9): up to the emoji.
        ((0, 4), (0, 9), "G1 "),
    ];
    for (index, change) in changes.iter().enumerate() {
        send_changes(&mut server, uri, 2 + index as i64, &[*change], &mut text);
    }
    assert_eq!(text, "N10 G1 😀 X1\nN20 Z=IC(2) \n");
    assert_eq!(server.document_text(uri), Ok((4, text.clone())));
    assert_eq!(published(&server.diagnostics(uri, 4)), fresh(&text));
    // A hover inside the pair answers, and one on X1 after the emoji resolves it.
    assert!(server.hover(uri, 0, 8).is_ok());
    let hover = server.hover_text(uri, 0, 11);
    assert!(hover.contains("**1.000**"), "{hover}");
    assert_still_serves(&mut server, "columns inside a surrogate pair");
    assert_eq!(server.shutdown(), Some(0));
}

#[test]
fn an_edit_of_a_closed_document_is_ignored_with_a_log_line() {
    let mut server = serving_server();
    let uri = "file:///nonexistent/closed.mpf";
    server.open(uri, 1, "N10 X1\n");
    server.diagnostics(uri, 1);
    server.close(uri);
    server.change(uri, 2, json!([{"text": "N10 X2\n"}]));
    server.wait_for_log("which is not open, is ignored");
    assert_eq!(server.document_text(uri).unwrap_err()["code"], -32602);
    assert!(server.hover(uri, 0, 4).is_err());
    server.close(uri);
    server.wait_for_log("was closed but was not open");
    assert_still_serves(&mut server, "an edit of a closed document");
    assert_eq!(server.shutdown(), Some(0));
}

#[test]
fn versions_going_backwards_are_ignored_and_the_text_stays() {
    let mut server = serving_server();
    let uri = "file:///nonexistent/versions.mpf";
    server.open(uri, 5, "N10 X1\n");
    server.diagnostics(uri, 5);
    for version in [4, 5, -1, i32::MIN as i64] {
        server.change(uri, version, json!([{"text": "garbage"}]));
    }
    server.wait_for_log("version -2147483648 is not newer");
    assert_eq!(server.document_text(uri), Ok((5, "N10 X1\n".to_string())));
    server.change(uri, 6, json!([{"text": "N10 X2\n"}]));
    assert_eq!(server.document_text(uri), Ok((6, "N10 X2\n".to_string())));
    assert!(server.hover_text(uri, 0, 5).contains("**2.000**"));
    // A version beyond i32 is invalid params of a notification: dropped, the text stays.
    server.change(uri, 1 << 40, json!([{"text": "N10 X3\n"}]));
    assert_still_serves(&mut server, "versions going backwards");
    assert_eq!(server.document_text(uri), Ok((6, "N10 X2\n".to_string())));
    assert_eq!(server.shutdown(), Some(0));
}

#[test]
fn range_edits_across_crlf_and_lone_cr_give_the_protocols_text() {
    let mut server = serving_server();
    let uri = "file:///nonexistent/crlf.mpf";
    let mut text =
        "N10 G90 G0 X10 Z5\r\nN20 G91 Z2\r\nN30 Z3\r\nN40 G90 Z=AC(1)\r\nM30\r\n".to_string();
    server.open(uri, 1, &text);
    server.diagnostics(uri, 1);
    let didchanges: [&[Change]; 5] = [
        // From before N20's "2" across its CRLF to the end of N30: "N20 G91 Z7".
        &[((1, 9), (2, 6), "7")],
        // Past the end of line 0 is before its CR.
        &[((0, 500), (0, 600), " ; a")],
        // A CR typed at the end of line 0, then an LF right after it in the same didChange: the
        // two meet and become one more CRLF (an empty line).
        &[((0, 500), (0, 500), "\r"), ((1, 0), (1, 0), "\n")],
        // N20's CRLF replaced by a lone LF, and a lone CR ending an inserted block.
        &[((2, 10), (3, 0), "\nN25 Z1\r")],
        // Deleting from the middle of line 0 to the middle of the last block.
        &[((0, 18), (5, 4), "")],
    ];
    for (index, changes) in didchanges.iter().enumerate() {
        let version = 2 + index as i64;
        send_changes(&mut server, uri, version, changes, &mut text);
        assert_eq!(
            server.document_text(uri),
            Ok((version, text.clone())),
            "didChange {index}"
        );
        assert_eq!(
            published(&server.diagnostics(uri, version)),
            fresh(&text),
            "didChange {index}: {text:?}"
        );
        if index == 3 {
            assert_eq!(
                text,
                "N10 G90 G0 X10 Z5 ; a\r\n\r\nN20 G91 Z7\nN25 Z1\rN40 G90 Z=AC(1)\r\nM30\r\n"
            );
            // Lines counted as the protocol counts them: N25 is line 3, N40 line 4.
            let hover = server.hover_text(uri, 3, 5);
            assert!(hover.contains("**13.000**"), "{hover}");
            let hover = server.hover_text(uri, 4, 9);
            assert!(hover.contains("**1.000**"), "{hover}");
        }
    }
    assert_eq!(text, "N10 G90 G0 X10 Z5 \r\n");
    assert_still_serves(&mut server, "range edits across CRLF");
    assert_eq!(server.shutdown(), Some(0));
}

#[test]
fn a_50_mb_did_open_is_analysed_and_the_other_documents_stay_served() {
    let mut server = serving_server();
    let uri = "file:///nonexistent/huge.mpf";
    let mut random = edit_session::Random::new(50);
    let text = edit_session::program(&mut random, 1_450_000, "\n");
    assert!(text.len() >= 50_000_000, "{} bytes", text.len());
    let started = Instant::now();
    server.open(uri, 1, &text);
    let diagnostics = server.diagnostics(uri, 1);
    let elapsed = started.elapsed();
    eprintln!(
        "a didOpen of {:.1} MB: diagnostics ({} of them) after {:.2} s; server resident memory {} MB",
        text.len() as f64 / 1e6,
        diagnostics.len(),
        elapsed.as_secs_f64(),
        server.resident_kib().unwrap_or(0) / 1024
    );
    assert!(!diagnostics.is_empty());
    assert_eq!(published(&diagnostics), fresh(&text));
    assert_still_serves(&mut server, "a 50 MB didOpen");
    // The big document answers too: a hover on its last block but one, and an edit there.
    let last = text.lines().count() as u64 - 2;
    assert!(server.hover(uri, last, 2).is_ok());
    server.change(uri, 2, json!([{"range": {"start": {"line": last, "character": 0}, "end": {"line": last, "character": 0}}, "text": "; "}]));
    server.diagnostics(uri, 2);
    assert_eq!(server.shutdown(), Some(0));
}

#[test]
fn damaged_large_messages_cost_only_themselves() {
    // Large messages are read while they arrive (the text of a didOpen goes into its rope at once):
    // a wrong length, a text that is not a JSON string or a body that is no JSON must still cost
    // only that message, and a good large didOpen after them is opened.
    let mut server = serving_server();
    let uri = "file:///nonexistent/large.mpf";
    let text = "N10 G1 X1 Y2 F100 ; \"umlaut\" \u{e4}\r\n".repeat(20_000);
    let did_open = |version: i64, text: &str| {
        json!({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {"textDocument": {"uri": uri, "languageId": "sinumerik", "version": version, "text": text}}}).to_string().into_bytes()
    };
    let with_length = |body: &[u8], length: usize| {
        let mut message = format!("Content-Length: {length}\r\n\r\n").into_bytes();
        message.extend_from_slice(body);
        message
    };
    let body = did_open(1, &text);
    let mut raw_line_break = body.clone();
    let escape = memchr::memmem::find(&raw_line_break, b"\\r\\n").unwrap();
    raw_line_break.splice(escape..escape + 4, *b"\r\n");
    let cases = [
        (
            "a large didOpen whose length is too long",
            with_length(&body, body.len() + 40),
        ),
        (
            "a large didOpen whose length is too short",
            with_length(&body, body.len() - 3),
        ),
        (
            "a large didOpen with a raw line break in its text",
            with_length(&raw_line_break, raw_line_break.len()),
        ),
        (
            "a large body that is no JSON",
            frame("[".repeat(400_000).as_bytes()),
        ),
    ];
    for (index, (what, message)) in cases.iter().enumerate() {
        assert_next_request_answered(&mut server, message, 300 + index as i64, what);
    }
    // None of the damaged didOpen messages opened the document.
    let unopened = server.document_text(uri);
    assert!(unopened.is_err(), "{unopened:?}");
    let good = did_open(2, &text);
    server.write_raw(&frame(&good));
    let diagnostics = server.diagnostics(uri, 2);
    assert_eq!(published(&diagnostics), fresh(&text));
    assert_eq!(server.document_text(uri), Ok((2, text.clone())));
    assert_still_serves(&mut server, "damaged large messages");
    assert_eq!(server.shutdown(), Some(0));
}

#[test]
fn exit_without_shutdown_exits_with_1_and_after_shutdown_with_0() {
    let mut server = serving_server();
    server.notify("exit", Value::Null);
    assert_eq!(server.wait_for_exit(), Some(1));

    let mut server = serving_server();
    server
        .request("shutdown", Value::Null)
        .expect("shutdown succeeds");
    // After shutdown, requests are invalid; `exit` still ends the server with 0.
    let error = server
        .request("sinumerik/documentText", json!({"uri": SEED_URI}))
        .unwrap_err();
    assert_eq!(error["code"], -32600, "{error}");
    server.notify("exit", Value::Null);
    assert_eq!(server.wait_for_exit(), Some(0));

    // An input that ends without `exit` (the editor died) ends the server, with 1.
    let server = serving_server();
    server.close_input();
    let mut server = server;
    assert_eq!(server.wait_for_exit(), Some(1));

    // `exit` before initialize, too.
    let mut server = RawServer::spawn();
    server.notify("exit", Value::Null);
    assert_eq!(server.wait_for_exit(), Some(1));
}
