//! End-to-end tests of the built binary as a language server over stdin and stdout, the way an
//! editor starts it: without arguments, as `serve`, and with `--stdio`.

#[path = "support/lsp_client.rs"]
mod lsp_client;

use lsp_client::{file_uri, position_of, seed_text, TestClient};
use serde_json::{json, Value};

fn seed_path() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/examples/turning_seed.mpf")
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_binary_serves_the_seed_example_over_stdio() {
    let mut client = TestClient::spawn_binary(&[]);
    let result = client.initialize(json!({}), Value::Null).await;
    assert_eq!(result["serverInfo"]["name"], "sinumerik-lsp");
    let uri = file_uri(&seed_path());
    let text = seed_text();
    client.open(&uri, 1, &text).await;
    assert_eq!(client.diagnostics(&uri, 1).await, Vec::<Value>::new());

    let (line, character) = position_of(&text, "Z=IC(-32)");
    let hover = client.hover(&uri, line, character).await;
    assert!(hover.contains("**58.000**"), "{hover}");
    let (line, character) = position_of(&text, "X-12");
    let hover = client.hover(&uri, line, character + 2).await;
    assert!(hover.contains("**103.000**"), "{hover}");

    // An edit that breaks N20, with its diagnostics for the new version.
    client
        .change(&uri, 2, json!([{"range": {"start": {"line": 3, "character": 12}, "end": {"line": 3, "character": 13}}, "text": ""}]))
        .await;
    let diagnostics = client.diagnostics(&uri, 2).await;
    assert!(
        diagnostics
            .iter()
            .any(|diagnostic| diagnostic["code"] == "S101"),
        "{diagnostics:?}"
    );

    let hints = client.inlay_hint_labels(&uri, 0, 9).await;
    assert!(
        hints.iter().any(|(_, label)| label == "⟶ X103 Z17"),
        "{hints:?}"
    );
    assert_eq!(client.shutdown().await, Some(0));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn serve_and_stdio_arguments_start_the_server_and_preview_reads_files_from_disk() {
    for args in [&["serve"][..], &["--stdio"][..], &["serve", "--stdio"][..]] {
        let mut client = TestClient::spawn_binary(args);
        client.initialize(json!({}), Value::Null).await;
        let preview = client
            .preview(json!({"uri": file_uri(&seed_path()), "startLine": 4}))
            .await
            .unwrap();
        let ends: Vec<&Value> = preview["moves"]
            .as_array()
            .unwrap()
            .iter()
            .map(|movement| &movement["end"])
            .collect();
        assert_eq!(
            ends,
            vec![
                &json!({"X": 115.0, "Z": 60.0}),
                &json!({"X": 103.0, "Z": 17.0})
            ],
            "{args:?}"
        );
        assert_eq!(client.shutdown().await, Some(0), "{args:?}");
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn exit_without_shutdown_gives_exit_code_1() {
    let mut client = TestClient::spawn_binary(&[]);
    client.initialize(json!({}), Value::Null).await;
    client.notify("exit", Value::Null).await;
    let code = client.wait_for_exit().await;
    assert_eq!(code, Some(1));
}
