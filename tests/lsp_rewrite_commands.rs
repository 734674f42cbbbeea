//! The renumber and format commands and the formatting requests of the language server, in this
//! process: the edits the server sends with `workspace/applyEdit` (versioned), the text after the
//! client applies them, resolved end points that stay the same, and the errors for programs that
//! cannot be renumbered and for documents that are not open.

#[path = "support/lsp_client.rs"]
mod lsp_client;

use lsp_client::{apply_text_edits, TestClient};
use serde_json::{json, Value};

const URI: &str = "file:///nonexistent/rewrite.mpf";

const PROGRAM: &str =
    "N10 G90 G0X10 Y5\nN20 G1 x20 F100\nN25 GOTOF N40\nN30 X30  Y7\nN40 X40 ; end\nM30\n";

/// A client that takes versioned workspace edits.
async fn client_with_program(text: &str) -> TestClient {
    let mut client = TestClient::in_process();
    client
        .initialize(
            json!({"workspace": {"workspaceEdit": {"documentChanges": true}}}),
            Value::Null,
        )
        .await;
    client.open(URI, 1, text).await;
    client.diagnostics(URI, 1).await;
    client
}

async fn command(client: &mut TestClient, name: &str, argument: Value) -> Result<Value, Value> {
    client
        .request(
            "workspace/executeCommand",
            json!({"command": name, "arguments": [argument]}),
        )
        .await
}

/// The resolved end points of every move of the open document, as (line, end).
async fn end_points(client: &mut TestClient) -> Vec<(Value, Value)> {
    let preview = client
        .preview(json!({"uri": URI}))
        .await
        .expect("a preview");
    preview["moves"]
        .as_array()
        .expect("moves")
        .iter()
        .map(|one| (one["line"].clone(), one["end"].clone()))
        .collect()
}

/// Runs a rewrite command, checks the `workspace/applyEdit` request, applies its edits as the client
/// does and sends the new text; returns the command's answer and the new text.
async fn run_rewrite(
    client: &mut TestClient,
    name: &str,
    argument: Value,
    text: &str,
    label: &str,
) -> (Value, String) {
    let id = client
        .send_request(
            "workspace/executeCommand",
            json!({"command": name, "arguments": [argument]}),
        )
        .await;
    let request = client.server_request("workspace/applyEdit").await;
    assert_eq!(request["params"]["label"], label);
    let changes = request["params"]["edit"]["documentChanges"]
        .as_array()
        .expect("versioned document changes");
    assert_eq!(changes.len(), 1);
    assert_eq!(changes[0]["textDocument"]["uri"], URI);
    assert_eq!(changes[0]["textDocument"]["version"], 1);
    let edits = changes[0]["edits"].as_array().unwrap();
    let new_text = apply_text_edits(text, edits);
    let answer = client.response(id).await.expect("the command succeeds");
    assert_eq!(answer["edits"], edits.len());
    client
        .change(URI, 2, json!([{"text": new_text.clone()}]))
        .await;
    client.diagnostics(URI, 2).await;
    (answer, new_text)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn renumbering_updates_numbers_and_jumps_and_keeps_the_end_points() {
    let mut client = client_with_program(PROGRAM).await;
    let before = end_points(&mut client).await;
    // The program runs N10, N20 and jumps over N30 to N40.
    assert_eq!(before.len(), 3, "{before:?}");
    let (answer, text) = run_rewrite(
        &mut client,
        "sinumerik.renumber",
        json!({"uri": URI, "start": 100, "step": 5}),
        PROGRAM,
        "Renumber blocks",
    )
    .await;
    assert_eq!(answer["applied"], true);
    assert_eq!(
        text,
        "N100 G90 G0X10 Y5\nN105 G1 x20 F100\nN110 GOTOF N120\nN115 X30  Y7\nN120 X40 ; end\nM30\n"
    );
    assert_eq!(end_points(&mut client).await, before);
    assert_eq!(client.document_text(URI).await, (2, text));
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn renumbering_every_block_and_dropping_numbers() {
    let mut client = client_with_program(PROGRAM).await;
    let (_, all) = run_rewrite(
        &mut client,
        "sinumerik.renumber",
        json!({"uri": URI, "mode": "all"}),
        PROGRAM,
        "Renumber blocks",
    )
    .await;
    assert_eq!(
        all,
        "N10 G90 G0X10 Y5\nN20 G1 x20 F100\nN30 GOTOF N50\nN40 X30  Y7\nN50 X40 ; end\nN60 M30\n"
    );
    client.shutdown().await;

    let mut client = client_with_program(PROGRAM).await;
    let (_, dropped) = run_rewrite(
        &mut client,
        "sinumerik.renumber",
        json!({"uri": URI, "mode": "drop", "start": 1, "step": 1}),
        PROGRAM,
        "Renumber blocks",
    )
    .await;
    assert_eq!(
        dropped,
        "G90 G0X10 Y5\nG1 x20 F100\nGOTOF N1\nX30  Y7\nN1 X40 ; end\nM30\n"
    );
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn formatting_by_command_and_by_request() {
    let mut client = client_with_program(PROGRAM).await;
    let before = end_points(&mut client).await;
    let formatted =
        "N10 G90 G0 X10 Y5\nN20 G1 X20 F100\nN25 GOTOF N40\nN30 X30 Y7\nN40 X40 ; end\nM30\n";

    // The request returns the edits without applying them.
    let edits = client
        .request(
            "textDocument/formatting",
            json!({"textDocument": {"uri": URI}, "options": {"tabSize": 4, "insertSpaces": true}}),
        )
        .await
        .expect("formatting succeeds");
    assert_eq!(
        apply_text_edits(PROGRAM, edits.as_array().unwrap()),
        formatted
    );
    // A range touches lines 1 and 2 only (it ends at the start of line 3).
    let edits = client
        .request(
            "textDocument/rangeFormatting",
            json!({"textDocument": {"uri": URI}, "range": {"start": {"line": 1, "character": 2}, "end": {"line": 3, "character": 0}}, "options": {"tabSize": 4, "insertSpaces": true}}),
        )
        .await
        .expect("range formatting succeeds");
    assert_eq!(
        apply_text_edits(PROGRAM, edits.as_array().unwrap()),
        "N10 G90 G0X10 Y5\nN20 G1 X20 F100\nN25 GOTOF N40\nN30 X30  Y7\nN40 X40 ; end\nM30\n"
    );

    let (answer, text) = run_rewrite(
        &mut client,
        "sinumerik.format",
        json!({"uri": URI}),
        PROGRAM,
        "Format program",
    )
    .await;
    assert_eq!(answer["applied"], true);
    assert_eq!(text, formatted);
    assert_eq!(end_points(&mut client).await, before);

    // Formatting a formatted program changes nothing, and the client is not asked.
    let answer = command(&mut client, "sinumerik.format", json!({"uri": URI}))
        .await
        .expect("the command succeeds");
    assert_eq!(answer, json!({"applied": true, "edits": 0}));
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_edit_the_client_refuses_is_reported_as_not_applied() {
    let mut client = client_with_program(PROGRAM).await;
    client.replies.lock().unwrap().insert(
        "workspace/applyEdit".to_string(),
        json!({"applied": false, "failureReason": "the document changed"}),
    );
    let answer = command(&mut client, "sinumerik.format", json!({"uri": URI}))
        .await
        .expect("the command answers");
    assert_eq!(answer["applied"], false);
    assert!(answer["edits"].as_u64().unwrap() > 0, "{answer}");
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn renumber_errors_and_closed_documents_are_invalid_params() {
    // N30 does not exist now; renumbering from 10 in steps of 10 would create it.
    let text = "N10 G0 X1\nGOTOF N30\nN20 X2\nN25 X3\nM30\n";
    let mut client = client_with_program(text).await;
    let error = command(&mut client, "sinumerik.renumber", json!({"uri": URI}))
        .await
        .expect_err("the renumbering is refused");
    assert_eq!(error["code"], -32602);
    assert!(
        error["message"]
            .as_str()
            .unwrap()
            .contains("fix the jump first"),
        "{error}"
    );
    let error = command(
        &mut client,
        "sinumerik.renumber",
        json!({"uri": URI, "step": 0}),
    )
    .await
    .expect_err("a step of 0 is refused");
    assert!(
        error["message"].as_str().unwrap().contains("step"),
        "{error}"
    );
    let error = command(
        &mut client,
        "sinumerik.format",
        json!({"uri": "file:///nonexistent/closed.mpf"}),
    )
    .await
    .expect_err("a closed document cannot be formatted");
    assert_eq!(error["code"], -32602);
    assert!(
        error["message"].as_str().unwrap().contains("not open"),
        "{error}"
    );
    let error = command(
        &mut client,
        "sinumerik.renumber",
        json!({"uri": URI, "mode": "some"}),
    )
    .await
    .expect_err("an unknown mode is refused");
    assert_eq!(error["code"], -32602);
    let result = client
        .request("initialize", json!({"capabilities": {}}))
        .await;
    assert!(result.is_err(), "a second initialize is refused");
    client.shutdown().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_commands_are_announced() {
    let mut client = TestClient::in_process();
    let result = client.initialize(json!({}), Value::Null).await;
    let capabilities = &result["capabilities"];
    let commands = capabilities["executeCommandProvider"]["commands"]
        .as_array()
        .unwrap();
    for name in [
        "sinumerik.endpointPreview",
        "sinumerik.renumber",
        "sinumerik.format",
    ] {
        assert!(commands.contains(&json!(name)), "{name}: {commands:?}");
    }
    assert_eq!(capabilities["documentFormattingProvider"], true);
    assert_eq!(capabilities["documentRangeFormattingProvider"], true);
    client.shutdown().await;
}
