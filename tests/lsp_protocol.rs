//! Protocol tests of the language server in this process, over an in-memory pipe: initialize and
//! encodings, diagnostics, hovers on the seed example, edits with CRLF and non-ASCII text, quick
//! fixes, inlay hints, the preview command, settings, and bad input that must not stop the server.

#[path = "support/lsp_client.rs"]
mod lsp_client;

use lsp_client::{position_of, seed_text, TestClient};
use serde_json::{json, Value};
use sinumerik_lsp::analysis::document::{DocumentAnalysis, TextLines};
use sinumerik_lsp::analysis::ProgramKind;
use sinumerik_lsp::config::MachineConfig;
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
        json!(["sinumerik.endpointPreview"])
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
    assert!(hover.contains("**G91**"), "{hover}");
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

fn hint_labels(hints: &Value) -> Vec<(u64, String)> {
    hints
        .as_array()
        .unwrap()
        .iter()
        .map(|hint| {
            (
                hint["position"]["line"].as_u64().unwrap(),
                hint["label"].as_str().unwrap().to_string(),
            )
        })
        .collect()
}

async fn inlay_hints(client: &mut TestClient, uri: &str) -> Vec<(u64, String)> {
    let hints = client
        .request("textDocument/inlayHint", json!({"textDocument": {"uri": uri}, "range": {"start": {"line": 0, "character": 0}, "end": {"line": 100, "character": 0}}}))
        .await
        .unwrap();
    hint_labels(&hints)
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
