//! The server's run of a program over the protocol, in this process: the hover of a call (the
//! called file, the position after it), a subprogram's entry state from its call sites in the
//! workspace, and `sinumerik/modalState` with the first pass of a block that runs several times.

#[path = "support/lsp_client.rs"]
mod lsp_client;

use lsp_client::{file_uri, temp_folder, TestClient};
use serde_json::{json, Value};
use std::path::Path;

/// A server on `folder` with the indexing finished.
async fn start(folder: &Path) -> TestClient {
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

#[tokio::test]
async fn a_call_hover_names_the_file_and_the_position_after_it() {
    let folder = temp_folder("execution-call-hover");
    let main = "N10 G90 G0 X0 Y0\nN20 SIDE\nN30 G0 X5\nM30\n";
    std::fs::write(folder.join("MAIN.MPF"), main).unwrap();
    std::fs::write(folder.join("SIDE.SPF"), "N10 G91 G0 Y5\nN20 X2\nN30 M17\n").unwrap();
    let mut client = start(&folder).await;
    let uri = file_uri(&folder.join("MAIN.MPF"));
    client.open(&uri, 1, main).await;
    let hover = client.hover(&uri, 1, 5).await;
    assert!(hover.contains("SIDE.SPF`: 2 moves"), "{hover}");
    assert!(
        hover.contains("After the call (first pass): X2 Y5"),
        "{hover}"
    );
    client.shutdown().await;
}

#[tokio::test]
async fn a_subprogram_starts_from_the_state_its_call_sites_agree_on() {
    let folder = temp_folder("execution-call-sites");
    let sub = "PROC DRILL\nN10 G0 X10\nN20 M17\n";
    std::fs::write(folder.join("DRILL.SPF"), sub).unwrap();
    std::fs::write(
        folder.join("A.MPF"),
        "N10 G70 G90 G18\nN20 DRILL\nN30 DRILL\nM30\n",
    )
    .unwrap();
    std::fs::write(folder.join("B.MPF"), "N10 G70 G18 G90 DRILL\nM30\n").unwrap();
    let mut client = start(&folder).await;
    let uri = file_uri(&folder.join("DRILL.SPF"));
    client.open(&uri, 1, sub).await;
    let hover = client.hover(&uri, 1, 5).await;
    assert!(
        hover.contains("entry state from the 3 call sites in A.MPF, B.MPF"),
        "{hover}"
    );
    assert!(hover.contains("G70"), "{hover}");
    let preview = client
        .request(
            "workspace/executeCommand",
            json!({"command": "sinumerik.endpointPreview", "arguments": [{"uri": uri}]}),
        )
        .await
        .expect("a preview");
    assert_eq!(
        preview["assumed"]["source"], "entry state from the 3 call sites in A.MPF, B.MPF",
        "{preview}"
    );
    assert_eq!(preview["assumed"]["units"], "G70", "{preview}");
    // A call site that disagrees (G71) leaves the reset state as the assumption.
    std::fs::write(folder.join("C.MPF"), "N10 G71 G18 G90 DRILL\nM30\n").unwrap();
    let c_uri = file_uri(&folder.join("C.MPF"));
    client.open(&c_uri, 1, "N10 G71 G18 G90 DRILL\nM30\n").await;
    let mut answer = Value::Null;
    for _ in 0..100 {
        answer = client
            .request(
                "workspace/executeCommand",
                json!({"command": "sinumerik.endpointPreview", "arguments": [{"uri": uri}]}),
            )
            .await
            .expect("a preview");
        if answer["assumed"]["source"] == "assumed: reset state" {
            break;
        }
        tokio::time::sleep(std::time::Duration::from_millis(50)).await;
    }
    assert_eq!(
        answer["assumed"]["source"], "assumed: reset state",
        "{answer}"
    );
    client.shutdown().await;
}

#[tokio::test]
async fn the_modal_state_of_a_loop_block_is_its_first_pass() {
    let folder = temp_folder("execution-modal-state");
    let main = "N10 G90 G0 X0\nN20 FOR R1=1 TO 6\nN30 G1 X=R1 F100\nN40 G91\nN50 ENDFOR\nM30\n";
    std::fs::write(folder.join("MAIN.MPF"), main).unwrap();
    let mut client = start(&folder).await;
    let uri = file_uri(&folder.join("MAIN.MPF"));
    client.open(&uri, 1, main).await;
    let state = client
        .request("sinumerik/modalState", json!({"uri": uri, "line": 2}))
        .await
        .expect("a state");
    // The first pass runs under G90; later passes under the loop's G91.
    assert_eq!(state["distance"], "G90", "{state}");
    assert_eq!(state["motion"], "G1", "{state}");
    assert_eq!(state["passes"], 6, "{state}");
    let before = client
        .request("sinumerik/modalState", json!({"uri": uri, "line": 0}))
        .await
        .expect("a state");
    assert!(before.get("passes").is_none(), "{before}");
    client.shutdown().await;
}
