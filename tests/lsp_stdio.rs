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

/// A program with a malformed `=AC` on every third line: thousands of diagnostics, so that their
/// JSON is large enough to leave the binary in pages of its own (handed to the pipe, not copied).
fn program_with_many_findings(lines: usize) -> String {
    let mut text = String::from("G17 G90 G71\n");
    for index in 1..lines {
        if index % 3 == 0 {
            text.push_str(&format!("N{index} G1 X=AC{index} Y1\n"));
        } else {
            text.push_str(&format!("N{index} G1 X{index} Y2\n"));
        }
    }
    text.push_str("M30\n");
    text
}

/// The edits of the session: a line inserted at the top (every later diagnostic moves), a finding
/// added and one mended in the middle, a line removed.
fn edits() -> Vec<Value> {
    let range = |line: u32, start: u32, end_line: u32, end: u32| json!({"start": {"line": line, "character": start}, "end": {"line": end_line, "character": end}});
    vec![
        json!([{"range": range(1, 0, 1, 0), "text": "; inserted\n"}]),
        json!([{"range": range(2001, 0, 2001, 0), "text": "N5 G1 X=AC5\n"}]),
        json!([{"range": range(3001, 0, 3002, 0), "text": ""}]),
        json!([{"range": range(10, 0, 10, 0), "text": " "}]),
        json!([{"range": range(4000, 0, 4000, 0), "text": "N9 X=IC\n"}]),
    ]
}

/// Every publication over the binary's stdout equals the in-process server's for the same version,
/// through edits that move, add and remove diagnostics, and after a burst of edits sent at once.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn large_publications_over_stdout_equal_the_in_process_servers() {
    let text = program_with_many_findings(6000);
    let uri = "file:///large_findings.mpf";
    let mut sessions = Vec::new();
    for mut client in [TestClient::in_process(), TestClient::spawn_binary(&[])] {
        client.initialize(json!({}), Value::Null).await;
        client.open(uri, 1, &text).await;
        let mut published = vec![client.diagnostics(uri, 1).await];
        for (index, change) in edits().into_iter().enumerate() {
            let version = 2 + index as i64;
            client.change(uri, version, change).await;
            published.push(client.diagnostics(uri, version).await);
        }
        // A burst: only the last version is sure to be published.
        let first = 2 + edits().len() as i64;
        for (index, change) in edits().into_iter().enumerate() {
            client.change(uri, first + index as i64, change).await;
        }
        published.push(
            client
                .diagnostics(uri, first + edits().len() as i64 - 1)
                .await,
        );
        client.shutdown().await;
        sessions.push(published);
    }
    let (in_process, binary) = (&sessions[0], &sessions[1]);
    assert!(
        in_process[0].len() >= 1999,
        "every malformed =AC is found: {}",
        in_process[0].len()
    );
    assert_eq!(in_process.len(), binary.len());
    for (version, (expected, got)) in in_process.iter().zip(binary).enumerate() {
        assert_eq!(expected.len(), got.len(), "publication {version}");
        assert!(expected == got, "publication {version} differs");
    }
    assert_ne!(
        in_process[0], in_process[1],
        "the first edit moved the diagnostics"
    );
}
