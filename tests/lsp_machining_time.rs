//! The machining time over the protocol: a block's hover (its time over all passes, the time before
//! its first pass), `sinumerik/modalState`'s program total and `sinumerik.endpointPreview`'s `time`
//! (the lines asked for) and `program_time` (the whole document).

#[path = "support/lsp_client.rs"]
mod lsp_client;

use lsp_client::{file_uri, temp_folder, TestClient};
use serde_json::{json, Value};

/// A server on `folder` with the indexing finished (the times are kept per library generation,
/// which the finished index advances).
async fn start(folder: &std::path::Path) -> TestClient {
    let mut client = TestClient::in_process();
    let folder_uri = file_uri(folder);
    client
        .request(
            "initialize",
            json!({
                "processId": null,
                "rootUri": folder_uri,
                "workspaceFolders": [{"uri": folder_uri, "name": "fixture"}],
                "capabilities": {"window": {"workDoneProgress": true}}
            }),
        )
        .await
        .expect("initialize succeeds");
    client.notify("initialized", json!({})).await;
    loop {
        let params = client.notification("$/progress", |_| true).await;
        if params["value"]["kind"] == "end" {
            break;
        }
    }
    client
}

fn seconds(value: &Value) -> f64 {
    value
        .as_f64()
        .unwrap_or_else(|| panic!("a number: {value}"))
}

#[tokio::test]
async fn a_program_in_order_shows_block_times_and_its_total() {
    let folder = temp_folder("machining-time-in-order");
    // T116 of the reference: 12 s, 9.4248 s and a dwell of 2.5 s after a first move of unknown time.
    let text =
        "N10 G17 G90 G94 G1 X0 Y0 F500\nN20 X100\nN30 G3 X120 Y20 I0 J20 F200\nN40 G4 F2.5\n";
    std::fs::write(folder.join("T116.MPF"), text).unwrap();
    let mut client = start(&folder).await;
    let uri = file_uri(&folder.join("T116.MPF"));
    client.open(&uri, 1, text).await;
    let state = client
        .request("sinumerik/modalState", json!({"uri": uri, "line": 1}))
        .await
        .expect("a state");
    let hover = client.hover(&uri, 2, 1).await;
    assert!(hover.contains("**Time**: 9.425 s"), "{hover}");
    assert!(
        hover.contains("starts after at least 12 s (1 earlier moves unknown)"),
        "{hover}"
    );
    let dwell = client.hover(&uri, 3, 1).await;
    assert!(dwell.contains("**Time**: 2.5 s"), "{dwell}");
    assert!(
        (seconds(&state["time"]["total_s"]) - 23.9248).abs() < 1e-3,
        "{state}"
    );
    assert_eq!(state["time"]["unknown_moves"], 1, "{state}");
    let range = client
        .preview(json!({"uri": uri, "startLine": 1, "endLine": 1}))
        .await
        .expect("a preview");
    assert!(
        (seconds(&range["time"]["total_s"]) - 12.0).abs() < 1e-6,
        "{range}"
    );
    assert!(
        (seconds(&range["program_time"]["total_s"]) - 23.9248).abs() < 1e-3,
        "{range}"
    );
    assert_eq!(range["moves"][0]["time_s"], 12.0, "{range}");
    client.shutdown().await;
}

#[tokio::test]
async fn a_loop_block_counts_every_pass() {
    let folder = temp_folder("machining-time-loop");
    let text = "N10 G90 G0 X0\nN20 G1 F600\nN30 FOR R1=1 TO 3\nN40 G1 X=R1*10\nN50 G4 F0.5\nN60 ENDFOR\nM30\n";
    std::fs::write(folder.join("LOOP.MPF"), text).unwrap();
    let mut client = start(&folder).await;
    let uri = file_uri(&folder.join("LOOP.MPF"));
    client.open(&uri, 1, text).await;
    client
        .request("sinumerik/modalState", json!({"uri": uri, "line": 3}))
        .await
        .expect("a state");
    let hover = client.hover(&uri, 3, 1).await;
    // Three passes of 10 mm at 600 mm/min.
    assert!(hover.contains("**Time**: 3 s"), "{hover}");
    let dwell = client.hover(&uri, 4, 1).await;
    assert!(dwell.contains("**Time**: 1.5 s"), "{dwell}");
    assert!(dwell.contains("starts after at least 1 s"), "{dwell}");
    let preview = client
        .preview(json!({"uri": uri}))
        .await
        .expect("a preview");
    // The dwells count in the time but are not moves of the path.
    assert_eq!(
        preview["moves"].as_array().map(Vec::len),
        Some(4),
        "{preview}"
    );
    assert!(
        (seconds(&preview["time"]["dwell_s"]) - 1.5).abs() < 1e-9,
        "{preview}"
    );
    assert!(
        (seconds(&preview["time"]["total_s"]) - 4.5).abs() < 1e-9,
        "{preview}"
    );
    client.shutdown().await;
}
