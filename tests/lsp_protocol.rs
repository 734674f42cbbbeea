//! Protocol tests of the language server in this process, over an in-memory pipe: initialize and
//! encodings, diagnostics, hovers on the seed example, edits with CRLF and non-ASCII text, quick
//! fixes, inlay hints, the preview command, settings, and bad input that must not stop the server.

#[path = "support/lsp_client.rs"]
mod lsp_client;

use lsp_client::{file_uri, position_of, seed_text, temp_folder, TestClient};
use serde_json::{json, Value};
use sinumerik_lsp::analysis::document::{DocumentAnalysis, TextLines};
use sinumerik_lsp::analysis::ProgramKind;
use sinumerik_lsp::config::MachineConfig;
use sinumerik_lsp::diagnostics::Severity;
use std::sync::Arc;

const SEED_URI: &str = "file:///nonexistent/turning_seed.mpf";

async fn initialized_client() -> TestClient {
    let mut client = TestClient::in_process();
    client.initialize(json!({}), Value::Null).await;
    client
}

/// The diagnostics a from-scratch analysis gives, as (line, code) pairs.
fn expected_codes(text: &str, kind: ProgramKind) -> Vec<(u64, String)> {
    let analysis = DocumentAnalysis::new(
        &TextLines::new(text),
        Arc::new(MachineConfig::default()),
        kind,
    );
    analysis
        .diagnostics()
        .iter()
        .map(|item| (item.line as u64, item.diagnostic.code.as_str().to_string()))
        .collect()
}

fn codes(diagnostics: &[Value]) -> Vec<(u64, String)> {
    diagnostics
        .iter()
        .map(|diagnostic| {
            (
                diagnostic["range"]["start"]["line"].as_u64().unwrap(),
                diagnostic["code"].as_str().unwrap().to_string(),
            )
        })
        .collect()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn initialize_announces_the_features_and_negotiates_the_encoding() {
    let mut client = TestClient::in_process();
    let result = client.initialize(json!({}), Value::Null).await;
    let capabilities = &result["capabilities"];
    assert_eq!(capabilities["positionEncoding"], "utf-16");
    assert_eq!(capabilities["textDocumentSync"]["change"], 2);
    assert_eq!(capabilities["hoverProvider"], true);
    assert_eq!(capabilities["inlayHintProvider"], true);
    assert_eq!(
        capabilities["executeCommandProvider"]["commands"],
        json!([
            "sinumerik.endpointPreview",
            "sinumerik.renumber",
            "sinumerik.format"
        ])
    );
    assert_eq!(
        capabilities["codeActionProvider"]["codeActionKinds"],
        json!(["quickfix"])
    );
    client.shutdown().await;

    let mut client = TestClient::in_process();
    let result = client
        .initialize(
            json!({"general": {"positionEncodings": ["utf-16", "utf-8"]}}),
            Value::Null,
        )
        .await;
    assert_eq!(result["capabilities"]["positionEncoding"], "utf-8");
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_seed_example_gets_its_diagnostics_and_hovers() {
    let mut client = initialized_client().await;
    let text = seed_text();
    client.open(SEED_URI, 1, &text).await;
    let diagnostics = client.diagnostics(SEED_URI, 1).await;
    assert_eq!(
        codes(&diagnostics),
        expected_codes(&text, ProgramKind::Main)
    );

    let (line, character) = position_of(&text, "Z=IC(-32)");
    let hover = client.hover(SEED_URI, line, character + 3).await;
    assert!(
        hover.contains("Z = 90.000 + (-32.000) = **58.000** mm"),
        "{hover}"
    );
    assert!(
        hover.contains("IC: incremental for this block only; G90 stays active"),
        "{hover}"
    );

    let (line, character) = position_of(&text, "X-12");
    let hover = client.hover(SEED_URI, line, character).await;
    assert!(
        hover.contains("X = 115.000 + (-12.000) = **103.000** mm (G91: incremental)"),
        "{hover}"
    );

    let (line, character) = position_of(&text, "G91 X40");
    let hover = client.hover(SEED_URI, line, character + 1).await;
    assert!(
        hover.contains("**G91** — Incremental dimensions: axis values are distances"),
        "{hover}"
    );
    assert!(
        hover.contains("Group 14 (absolute / incremental), modal"),
        "{hover}"
    );
    assert!(hover.contains("Before this block: **G90**"), "{hover}");

    let (line, character) = position_of(&text, "N190");
    let hover = client.hover(SEED_URI, line, character + 1).await;
    assert!(hover.contains("G91"), "{hover}");
    assert!(hover.contains("**End point** (G1): X103 Z17"), "{hover}");
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn edits_after_crlf_umlauts_and_an_emoji_land_on_the_right_column_and_a_fix_applies() {
    let mut client = initialized_client().await;
    let uri = "file:///nonexistent/umlauts.mpf";
    let text =
        "N10 G90 G0 X1 Z1\r\nN20 MSG(\"Grüße 😀\") Z=AC17 F100\r\nN30 G1 X=IC(5) ; Ä 😀 Ü\r\n";
    client.open(uri, 1, text).await;
    let diagnostics = client.diagnostics(uri, 1).await;
    let s101 = diagnostics
        .iter()
        .find(|diagnostic| diagnostic["code"] == "S101")
        .expect("S101 for Z=AC17");
    // 21 characters before `AC17`, the emoji counting as two UTF-16 code units.
    assert_eq!(
        s101["range"],
        json!({"start": {"line": 1, "character": 22}, "end": {"line": 1, "character": 26}})
    );

    // Typing in the comment after the emoji of line 2: UTF-16 column 22 is right after "😀 ".
    client.change(uri, 2, json!([{"range": {"start": {"line": 2, "character": 22}, "end": {"line": 2, "character": 22}}, "text": "ö"}])).await;
    let expected = text.replace("; Ä 😀 Ü", "; Ä 😀 öÜ");
    assert_eq!(client.document_text(uri).await, (2, expected.clone()));

    let actions = client
        .request("textDocument/codeAction", json!({"textDocument": {"uri": uri}, "range": s101["range"], "context": {"diagnostics": [s101]}}))
        .await
        .unwrap();
    let action = actions
        .as_array()
        .unwrap()
        .iter()
        .find(|action| action["kind"] == "quickfix")
        .expect("a quick fix");
    let edits = action["edit"]["changes"][uri].as_array().unwrap().clone();
    assert_eq!(edits.len(), 1);
    client
        .change(
            uri,
            3,
            json!([{"range": edits[0]["range"], "text": edits[0]["newText"]}]),
        )
        .await;
    let fixed = expected.replace(
        "Z=AC17",
        &format!("Z={}", edits[0]["newText"].as_str().unwrap()),
    );
    assert!(fixed.contains("Z=AC(17)"), "{fixed}");
    assert_eq!(client.document_text(uri).await, (3, fixed.clone()));
    let diagnostics = client.diagnostics(uri, 3).await;
    assert_eq!(
        codes(&diagnostics),
        expected_codes(&fixed, ProgramKind::Main)
    );
    assert!(!codes(&diagnostics).iter().any(|(_, code)| code == "S101"));
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn utf8_positions_count_bytes() {
    let mut client = TestClient::in_process();
    client
        .initialize(
            json!({"general": {"positionEncodings": ["utf-8"]}}),
            Value::Null,
        )
        .await;
    let uri = "file:///nonexistent/bytes.mpf";
    client
        .open(uri, 1, "N20 MSG(\"Grüße 😀\") Z=AC17 F100\n")
        .await;
    let diagnostics = client.diagnostics(uri, 1).await;
    let s101 = diagnostics
        .iter()
        .find(|diagnostic| diagnostic["code"] == "S101")
        .unwrap();
    assert_eq!(s101["range"]["start"]["character"], 26);
    assert_eq!(s101["range"]["end"]["character"], 30);
    client.shutdown().await;
}

async fn inlay_hints(client: &mut TestClient, uri: &str) -> Vec<(u64, String)> {
    client.inlay_hint_labels(uri, 0, 100).await
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn inlay_hints_show_end_points_that_are_not_plain_and_follow_the_setting() {
    let mut client = TestClient::in_process();
    client
        .initialize(
            json!({"workspace": {"configuration": true, "inlayHint": {"refreshSupport": true}}}),
            Value::Null,
        )
        .await;
    let text = seed_text();
    client.open(SEED_URI, 1, &text).await;
    let line_of = |needle: &str| position_of(&text, needle).0 as u64;
    assert_eq!(
        inlay_hints(&mut client, SEED_URI).await,
        vec![
            (line_of("N20"), "⟶ X75 Z58".to_string()),
            (line_of("N180"), "⟶ X115 Z60".to_string()),
            (line_of("N190"), "⟶ X103 Z17".to_string()),
        ]
    );
    // The hint sits at the end of its line.
    let hints = client
        .request("textDocument/inlayHint", json!({"textDocument": {"uri": SEED_URI}, "range": {"start": {"line": 3, "character": 0}, "end": {"line": 3, "character": 0}}}))
        .await
        .unwrap();
    let n20_line = text.lines().nth(3).unwrap();
    assert_eq!(
        hints[0]["position"]["character"],
        n20_line.encode_utf16().count()
    );

    // A pushed setting: every moving block. The server asks the client to refresh its hints.
    client
        .notify(
            "workspace/didChangeConfiguration",
            json!({"settings": {"sinumerik": {"inlayHints": "all"}}}),
        )
        .await;
    client.server_request("workspace/inlayHint/refresh").await;
    let all = inlay_hints(&mut client, SEED_URI).await;
    assert_eq!(all.len(), 4, "{all:?}");
    assert_eq!(all[0], (line_of("N10"), "⟶ X20 Z90".to_string()));

    // A pulled setting: the notification carries nothing, the server asks for the section.
    *client.configuration.lock().unwrap() = json!([{"inlayHints": "off"}]);
    client
        .notify(
            "workspace/didChangeConfiguration",
            json!({"settings": null}),
        )
        .await;
    client.server_request("workspace/configuration").await;
    client.server_request("workspace/inlayHint/refresh").await;
    assert_eq!(inlay_hints(&mut client, SEED_URI).await, vec![]);
    client.shutdown().await;
}

/// The CLI's `preview` JSON of a file.
fn cli_preview(path: &std::path::Path) -> Value {
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_sinumerik-lsp"))
        .arg("preview")
        .arg(path)
        .output()
        .unwrap();
    serde_json::from_slice(&output.stdout).unwrap()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_preview_command_matches_the_cli_for_open_and_unopened_files() {
    let mut client = initialized_client().await;
    let seed_path = std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/fixtures/examples/turning_seed.mpf"
    ));
    let seed_uri = file_uri(seed_path);
    client.open(&seed_uri, 1, &seed_text()).await;
    let preview = client.preview(json!({"uri": seed_uri})).await.unwrap();
    let expected = cli_preview(seed_path);
    assert_eq!(preview["moves"], expected["moves"]);
    assert_eq!(preview["diagnostics"], expected["diagnostics"]);
    assert_eq!(preview["units"], "mm");
    assert_eq!(preview["moves"].as_array().unwrap().len(), 4);

    // A file that is not open, in Windows-1252, and only some of its lines.
    let folder = temp_folder("preview");
    let path = folder.join("CLOSED.MPF");
    std::fs::write(
        &path,
        b"N10 G90 G0 X10 Z5 ; \xC4nderung\r\nN20 G91 X5\r\nN30 Z=AC17\r\n",
    )
    .unwrap();
    let uri = file_uri(&path);
    let preview = client.preview(json!({"uri": uri})).await.unwrap();
    let expected = cli_preview(&path);
    assert_eq!(preview["moves"], expected["moves"]);
    assert_eq!(preview["diagnostics"], expected["diagnostics"]);
    assert_eq!(preview["file"], path.display().to_string());
    let part = client
        .preview(json!({"uri": uri, "startLine": 1, "endLine": 1}))
        .await
        .unwrap();
    assert_eq!(part["moves"], json!([expected["moves"][1]]));
    assert_eq!(part["moves"][0]["end"], json!({"X": 15.0, "Z": 5.0}));
    assert_eq!(part["diagnostics"], json!([]));

    let missing = client
        .preview(json!({"uri": file_uri(&folder.join("missing.mpf"))}))
        .await
        .unwrap_err();
    assert!(
        missing["message"].as_str().unwrap().contains("missing.mpf"),
        "{missing}"
    );
    let _ = std::fs::remove_dir_all(&folder);
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn sinumerik_toml_is_found_from_the_documents_folder_upward() {
    let folder = temp_folder("config");
    std::fs::write(
        folder.join("sinumerik.toml"),
        "[diagnostics]\nS101 = \"hint\"\n",
    )
    .unwrap();
    std::fs::create_dir_all(folder.join("sub")).unwrap();
    let uri = file_uri(&folder.join("sub").join("part.mpf"));
    let mut client = initialized_client().await;
    client.open(&uri, 1, "N10 G0 Z=AC17\n").await;
    let diagnostics = client.diagnostics(&uri, 1).await;
    let s101 = diagnostics
        .iter()
        .find(|diagnostic| diagnostic["code"] == "S101")
        .unwrap();
    assert_eq!(s101["severity"], 4);

    // A configuration file that cannot be read is reported on itself; the program is still checked.
    let broken = temp_folder("broken-config");
    std::fs::write(
        broken.join("sinumerik.toml"),
        "[machine]\nkind = \"drill\"\n",
    )
    .unwrap();
    let uri = file_uri(&broken.join("part.mpf"));
    client.open(&uri, 1, "N10 G0 Z=AC17\n").await;
    let toml_uri = file_uri(&broken.join("sinumerik.toml"));
    let config_diagnostics = client
        .notification("textDocument/publishDiagnostics", |params| {
            params["uri"] == toml_uri.as_str()
        })
        .await;
    assert_eq!(
        config_diagnostics["diagnostics"][0]["range"]["start"]["line"],
        1
    );
    let diagnostics = client.diagnostics(&uri, 1).await;
    assert_eq!(
        diagnostics
            .iter()
            .find(|diagnostic| diagnostic["code"] == "S101")
            .unwrap()["severity"],
        1
    );
    let _ = std::fs::remove_dir_all(&folder);
    let _ = std::fs::remove_dir_all(&broken);
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn settings_come_from_initialization_options() {
    let mut client = TestClient::in_process();
    client
        .initialize(json!({}), json!({"inlayHints": "all"}))
        .await;
    client.open(SEED_URI, 1, &seed_text()).await;
    assert_eq!(inlay_hints(&mut client, SEED_URI).await.len(), 4);
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_machine_kind_setting_makes_documents_without_a_configuration_file_lathe_programs() {
    let text = "G90 G0 X40 Z5\nG1 X50\n";
    let uri = "file:///nonexistent/lathe/part.mpf";
    let mut mill = TestClient::in_process();
    mill.initialize(json!({}), json!({})).await;
    mill.open(uri, 1, text).await;
    let on_a_mill = mill.hover(uri, 1, 4).await;
    let mut lathe = TestClient::in_process();
    lathe
        .initialize(json!({}), json!({"machineKind": "turn"}))
        .await;
    lathe.open(uri, 1, text).await;
    let on_a_lathe = lathe.hover(uri, 1, 4).await;
    assert!(
        on_a_lathe.to_lowercase().contains("diameter") && on_a_lathe.contains("radius 25"),
        "X50 on a lathe is a diameter, radius 25: {on_a_lathe}"
    );
    assert!(
        !on_a_mill.to_lowercase().contains("diameter"),
        "{on_a_mill}"
    );
    // Switching the setting analyses the open documents again.
    mill.notify(
        "workspace/didChangeConfiguration",
        json!({"settings": {"sinumerik": {"machineKind": "turn"}}}),
    )
    .await;
    mill.diagnostics(uri, 1).await;
    assert_eq!(mill.hover(uri, 1, 4).await, on_a_lathe);
    mill.shutdown().await;
    lathe.shutdown().await;
}

fn is_warning_about(params: &Value, words: &str) -> bool {
    params["message"]
        .as_str()
        .is_some_and(|message| message.contains(words))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_requests_and_notifications_are_answered_or_logged_and_the_server_keeps_serving() {
    let mut client = initialized_client().await;
    let unknown = "file:///nonexistent/unknown.mpf";
    let error = client
        .request(
            "textDocument/hover",
            json!({"textDocument": {"uri": unknown}, "position": {"line": 0, "character": 0}}),
        )
        .await
        .unwrap_err();
    assert!(
        error["message"].as_str().unwrap().contains("not open"),
        "{error}"
    );

    client.change(unknown, 2, json!([{"text": "N10"}])).await;
    client
        .notification("window/logMessage", |params| {
            is_warning_about(params, "not open")
        })
        .await;

    client.open(SEED_URI, 5, &seed_text()).await;
    client.diagnostics(SEED_URI, 5).await;
    // A version going backwards is refused and the text stays.
    client
        .change(SEED_URI, 4, json!([{"text": "garbage"}]))
        .await;
    client
        .notification("window/logMessage", |params| {
            is_warning_about(params, "not newer")
        })
        .await;
    assert_eq!(client.document_text(SEED_URI).await, (5, seed_text()));

    // Positions past the end are clamped: the last line's end, and a line past the end.
    client
        .change(SEED_URI, 6, json!([{"range": {"start": {"line": 6, "character": 500}, "end": {"line": 6, "character": 900}}, "text": " ; end"}]))
        .await;
    let (_, text) = client.document_text(SEED_URI).await;
    assert!(text.contains("M30 ; end\n"), "{text}");
    let hover = client
        .request("textDocument/hover", json!({"textDocument": {"uri": SEED_URI}, "position": {"line": 4000, "character": 4000}}))
        .await;
    assert_eq!(hover, Ok(Value::Null));
    let hover = client.hover(SEED_URI, 3, 4000).await;
    assert!(hover.contains("Modal state"), "{hover}");

    // A cancelled request is answered (with its result or as cancelled) and the server goes on.
    let id = client
        .send_request(
            "textDocument/hover",
            json!({"textDocument": {"uri": SEED_URI}, "position": {"line": 3, "character": 9}}),
        )
        .await;
    client.notify("$/cancelRequest", json!({"id": id})).await;
    match client.response(id).await {
        Ok(result) => assert!(result["contents"]["value"].as_str().unwrap().contains("Z")),
        Err(error) => assert_eq!(error["code"], -32800),
    }

    // Malformed params, an unknown method, an unknown command, and bytes that are not JSON.
    let error = client
        .request("textDocument/hover", json!({"position": "nowhere"}))
        .await
        .unwrap_err();
    assert_eq!(error["code"], -32602);
    assert_eq!(
        client
            .request("sinumerik/nothing", json!({}))
            .await
            .unwrap_err()["code"],
        -32601
    );
    let error = client
        .request(
            "workspace/executeCommand",
            json!({"command": "rm", "arguments": []}),
        )
        .await
        .unwrap_err();
    assert!(error["message"]
        .as_str()
        .unwrap()
        .contains("unknown command"));
    let error = client.preview(json!({"url": 1})).await.unwrap_err();
    assert_eq!(error["code"], -32602);
    client
        .notify("textDocument/didChange", json!({"textDocument": 17}))
        .await;
    client.send_raw(&lsp_client::frame(b"{not json")).await;
    client.send_raw(&lsp_client::frame(b"\"\xff\xfe\"")).await;
    client.send_raw(b"Content-Type: nothing\r\n\r\n").await;
    // A range that ends before it starts cannot be applied: the document is dropped, loudly.
    client
        .change(SEED_URI, 7, json!([{"range": {"start": {"line": 2, "character": 5}, "end": {"line": 1, "character": 0}}, "text": "x"}]))
        .await;
    client
        .notification("window/logMessage", |params| {
            is_warning_about(params, "out of step")
        })
        .await;
    client
        .notification("textDocument/publishDiagnostics", |params| {
            params["uri"] == SEED_URI && params["version"].is_null()
        })
        .await;
    client.open(SEED_URI, 8, "N10 G0 Z=AC17\n").await;
    let diagnostics = client.diagnostics(SEED_URI, 8).await;
    assert!(diagnostics
        .iter()
        .any(|diagnostic| diagnostic["code"] == "S101"));
    client
        .notify(
            "textDocument/didClose",
            json!({"textDocument": {"uri": SEED_URI}}),
        )
        .await;
    let cleared = client
        .notification("textDocument/publishDiagnostics", |params| {
            params["uri"] == SEED_URI && params["version"].is_null()
        })
        .await;
    assert_eq!(cleared["diagnostics"], json!([]));
    client
        .notify(
            "textDocument/didClose",
            json!({"textDocument": {"uri": SEED_URI}}),
        )
        .await;
    client
        .notification("window/logMessage", |params| {
            is_warning_about(params, "was closed but was not open")
        })
        .await;
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn thousands_of_rapid_edits_are_applied_in_order() {
    let mut client = initialized_client().await;
    let uri = "file:///nonexistent/rapid.mpf";
    client.open(uri, 1, "").await;
    let mut expected = String::new();
    let mut random = lsp_client::Random::new(4711);
    let pieces = [
        "N10 ", "G1 ", "X", "1", "2", ".", "-", "Z=IC(", ")", " ", "\r\n", "\n", "ä", "😀", "F100",
        ";",
    ];
    let edit_count = 5000;
    for version in 2..2 + edit_count {
        // Mostly typing at a random place; sometimes deleting a few characters.
        let line = random.below(lsp_client::lsp_line_count(&expected)) as u32;
        let column = random.below(lsp_client::lsp_line_length(&expected, line) as usize + 1) as u32;
        let (end, text) = if random.below(6) == 0 {
            ((line, column + random.below(4) as u32), "")
        } else {
            ((line, column), random.pick(&pieces))
        };
        client
            .change(uri, version, json!([{"range": {"start": {"line": line, "character": column}, "end": {"line": end.0, "character": end.1}}, "text": text}]))
            .await;
        lsp_client::apply_edit(&mut expected, (line, column), end, text);
    }
    let last_version = 1 + edit_count;
    assert_eq!(
        client.document_text(uri).await,
        (last_version, expected.clone())
    );
    let diagnostics = client.diagnostics(uri, last_version).await;
    assert_eq!(
        codes(&diagnostics),
        expected_codes(&expected, ProgramKind::Main)
    );
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn every_version_gets_its_diagnostics_also_when_they_did_not_change() {
    let mut client = initialized_client().await;
    let uri = "file:///nonexistent/ascii.mpf";
    client.open(uri, 1, "N10 G0 Z=AC17\nN20 X1\n").await;
    let first = client.diagnostics(uri, 1).await;
    let s101 = |diagnostics: &[Value]| {
        diagnostics
            .iter()
            .find(|diagnostic| diagnostic["code"] == "S101")
            .map(|diagnostic| diagnostic["range"].clone())
            .expect("S101")
    };
    let insert_space = |line: u32| json!([{"range": {"start": {"line": line, "character": 0}, "end": {"line": line, "character": 0}}, "text": " "}]);
    // A space on the other line: the same diagnostics, published again for the new version.
    client.change(uri, 2, insert_space(1)).await;
    assert_eq!(client.diagnostics(uri, 2).await, first);
    // A space before the finding moves it by one column.
    client.change(uri, 3, insert_space(0)).await;
    let moved = s101(&client.diagnostics(uri, 3).await);
    let before = s101(&first);
    assert_eq!(
        moved["start"]["character"],
        before["start"]["character"].as_u64().unwrap() + 1
    );
    // A non-ASCII character before it: UTF-16 columns differ from bytes and are not taken from before.
    client
        .change(uri, 4, json!([{"range": {"start": {"line": 0, "character": 0}, "end": {"line": 0, "character": 1}}, "text": "ä"}]))
        .await;
    assert_eq!(s101(&client.diagnostics(uri, 4).await), moved);
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_modal_state_request_gives_the_state_after_a_block() {
    let mut client = initialized_client().await;
    let text = "N10 G18 G90 G71 DIAMON G0 X20 Z90\nN20 G91 G1 X2 F100\nN30 G70\n";
    client.open(SEED_URI, 1, text).await;
    client.diagnostics(SEED_URI, 1).await;
    let state = |line: u32| json!({"uri": SEED_URI, "line": line});
    let first = client
        .request("sinumerik/modalState", state(0))
        .await
        .expect("an answer");
    assert_eq!(first["motion"], "G0");
    assert_eq!(first["plane"], "G18");
    assert_eq!(first["distance"], "G90");
    assert_eq!(first["diameter"], "DIAMON");
    let second = client
        .request("sinumerik/modalState", state(1))
        .await
        .expect("an answer");
    assert_eq!(second["distance"], "G91");
    assert_eq!(second["motion"], "G1");
    assert_eq!(second["feed"], 100.0);
    let third = client
        .request("sinumerik/modalState", state(2))
        .await
        .expect("an answer");
    assert_eq!(third["units"], "G70");
    let unknown_document = client
        .request(
            "sinumerik/modalState",
            json!({"uri": "file:///nowhere/else.mpf", "line": 0}),
        )
        .await;
    assert!(unknown_document.is_err(), "{unknown_document:?}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_modal_state_says_whether_the_diameter_mode_belongs_to_the_machine() {
    // DIAMOF is the reset state of a mill too; only a lathe has the transverse axis it acts on.
    let text = "N10 G90 G1 X20 Z90 F100\n";
    let mut mill = initialized_client().await;
    mill.open(SEED_URI, 1, text).await;
    mill.diagnostics(SEED_URI, 1).await;
    let state = json!({"uri": SEED_URI, "line": 0});
    let on_mill = mill.request("sinumerik/modalState", state.clone()).await;
    let on_mill = on_mill.expect("an answer");
    assert_eq!(on_mill["diameter"], "DIAMOF", "{on_mill}");
    assert_eq!(on_mill["diameterAxis"], false, "{on_mill}");
    let mut lathe = TestClient::in_process();
    lathe
        .initialize(json!({}), json!({"machineKind": "turn"}))
        .await;
    lathe.open(SEED_URI, 1, text).await;
    lathe.diagnostics(SEED_URI, 1).await;
    let on_lathe = lathe.request("sinumerik/modalState", state).await;
    let on_lathe = on_lathe.expect("an answer");
    assert_eq!(on_lathe["diameter"], "DIAMON", "{on_lathe}");
    assert_eq!(on_lathe["diameterAxis"], true, "{on_lathe}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_outline_and_the_folding_ranges_follow_the_program() {
    let mut client = initialized_client().await;
    let uri = "file:///nonexistent/PART.SPF";
    let text = "PROC PART\n;=====\n; ROUGHING\n;=====\nN10 T1 M6\nIF R1 == 1\n  G0 X0\nENDIF\nSTART:\nM17\n";
    client.open(uri, 1, text).await;
    client.diagnostics(uri, 1).await;
    let symbols = client
        .request(
            "textDocument/documentSymbol",
            json!({"textDocument": {"uri": uri}}),
        )
        .await
        .expect("an outline");
    let procedure = &symbols[0];
    assert_eq!(procedure["name"], "PART", "{symbols}");
    assert_eq!(procedure["range"]["start"]["line"], 0, "{symbols}");
    let section = &procedure["children"][0];
    assert_eq!(section["name"], "ROUGHING", "{symbols}");
    let names: Vec<&str> = section["children"]
        .as_array()
        .expect("the section holds the tool change and the label")
        .iter()
        .map(|child| child["name"].as_str().unwrap_or(""))
        .collect();
    assert_eq!(names, ["T1 M6", "START"], "{symbols}");
    let start = &section["children"][1];
    assert_eq!(start["selectionRange"]["start"]["line"], 8, "{symbols}");
    let folds = client
        .request(
            "textDocument/foldingRange",
            json!({"textDocument": {"uri": uri}}),
        )
        .await
        .expect("folding ranges");
    let structure = folds
        .as_array()
        .expect("a list")
        .iter()
        .find(|fold| fold["kind"] == "region")
        .expect("the IF folds");
    assert_eq!(structure["startLine"], 5, "{folds}");
    assert_eq!(structure["endLine"], 6, "{folds}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_large_program_opened_arrives_whole_and_an_empty_one_stays_empty() {
    let mut client = initialized_client().await;
    // Over the size at which the input guard reads the didOpen itself, with text that JSON escapes.
    let mut text = String::from("G90 G17 G71\n");
    for index in 0..40_000 {
        text.push_str(&format!(
            "N{index} G1 X{}.5 Y=IC({}) F100 ; \"\u{e4}\\\r\n",
            index % 90,
            index % 7
        ));
        if index % 5000 == 0 {
            text.push_str("Z=AC17\n");
        }
    }
    let uri = "file:///nonexistent/large.mpf";
    client.open(uri, 3, &text).await;
    let diagnostics = client.diagnostics(uri, 3).await;
    assert_eq!(
        codes(&diagnostics),
        expected_codes(&text, ProgramKind::Main),
        "the diagnostics of the whole text"
    );
    assert!(!diagnostics.is_empty());
    assert_eq!(client.document_text(uri).await, (3, text));
    let empty = "file:///nonexistent/empty.mpf";
    client.open(empty, 1, "").await;
    client.diagnostics(empty, 1).await;
    assert_eq!(client.document_text(empty).await, (1, String::new()));
    client.shutdown().await;
}

/// The findings a limit of `limit` shows, worked out here from the core's analysis: as VS Code keeps
/// them, errors first, then warnings, information and hints, each in document order.
fn expected_within_limit(text: &str, limit: usize) -> Vec<(u64, String)> {
    let analysis = DocumentAnalysis::new(
        &TextLines::new(text),
        Arc::new(MachineConfig::default()),
        ProgramKind::Main,
    );
    let mut ranked: Vec<(usize, usize, usize)> = analysis
        .diagnostics()
        .iter()
        .enumerate()
        .map(|(index, item)| {
            let rank = match item.diagnostic.severity {
                Severity::Error => 0,
                Severity::Warning => 1,
                Severity::Information => 2,
                Severity::Hint => 3,
            };
            (rank, index, item.line)
        })
        .collect();
    ranked.sort();
    ranked.truncate(limit);
    ranked.sort_by_key(|&(_, index, _)| index);
    ranked
        .iter()
        .map(|&(_, index, _)| {
            let item = &analysis.diagnostics()[index];
            (item.line as u64, item.diagnostic.code.as_str().to_string())
        })
        .collect()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_diagnostics_limit_keeps_errors_first_adds_a_note_and_follows_the_setting() {
    let mut text = String::from("G90 G17 G71\n");
    for _ in 0..60 {
        text.push_str("N10 Z=AC17\nG3 X30 Y30 I1 J1\nN30 G91 X=IC(5)\nG1 X10 A10 B10 D1 D2\nG90\n");
    }
    let all = expected_codes(&text, ProgramKind::Main);
    let uri = "file:///nonexistent/limited.mpf";
    let mut client = TestClient::in_process();
    client
        .initialize(json!({}), json!({"maxDiagnostics": 100}))
        .await;
    client.open(uri, 1, &text).await;
    let published = client.diagnostics(uri, 1).await;
    let (note, shown) = published.split_last().expect("the note comes last");
    assert_eq!(codes(shown), expected_within_limit(&text, 100));
    assert_eq!(note["severity"], 3);
    let message = note["message"].as_str().unwrap();
    assert!(
        message.starts_with(&format!("{} more findings", all.len() - 100)),
        "{message}"
    );
    // More errors than the limit: only errors are shown.
    assert!(shown.iter().all(|diagnostic| diagnostic["severity"] == 1));

    // An edit: the new version is limited the same way.
    client
        .change(
            uri,
            2,
            json!([{"range": {"start": {"line": 1, "character": 0}, "end": {"line": 1, "character": 0}}, "text": "G1 X1 F100\n"}]),
        )
        .await;
    let edited = "G90 G17 G71\nG1 X1 F100\n".to_string() + &text["G90 G17 G71\n".len()..];
    let published = client.diagnostics(uri, 2).await;
    assert_eq!(
        codes(&published[..published.len() - 1]),
        expected_within_limit(&edited, 100)
    );

    // A limit above the number of errors shows every error and the first warnings; none: all.
    client
        .notify(
            "workspace/didChangeConfiguration",
            json!({"settings": {"sinumerik": {"maxDiagnostics": 250}}}),
        )
        .await;
    let published = client.diagnostics(uri, 2).await;
    assert_eq!(
        codes(&published[..published.len() - 1]),
        expected_within_limit(&edited, 250)
    );
    client
        .notify(
            "workspace/didChangeConfiguration",
            json!({"settings": {"sinumerik": {"maxDiagnostics": null}}}),
        )
        .await;
    let published = client.diagnostics(uri, 2).await;
    assert_eq!(
        codes(&published),
        expected_codes(&edited, ProgramKind::Main)
    );
    client.shutdown().await;
}
