//! Expressions of hostile length: a chain of a million operands and a hundred thousand nested
//! brackets. Chains are built by a loop in the parser, so only the bound on the height of an
//! expression's tree (`MAX_TREE_HEIGHT`) keeps the walks over the tree (evaluation, checks,
//! formatting) within a fixed stack. Each input must give a finding, through `check`, `preview`, `fmt`
//! and the language server, and never abort.

#[path = "support/lsp_client.rs"]
mod lsp_client;

use lsp_client::{file_uri, temp_folder, TestClient};
use serde_json::json;
use sinumerik_lsp::config::MachineConfig;
use sinumerik_lsp::syntax::parser::MAX_TREE_HEIGHT;
use std::process::Command;

/// `R1=1+1+...+1` with `operands` operands, in a program that goes on after it.
fn chain(operands: usize) -> String {
    let sum = vec!["1"; operands].join("+");
    format!("N10 R1={sum}\nN20 G0 X=R1\nN30 IF {sum}>0 GOTOF END\nN40 G1 X=SIN({sum}) F100\nEND:\nM30\n")
}

fn nested(depth: usize) -> String {
    format!(
        "N10 R1={}1{}\nN20 G0 X=R1\nM30\n",
        "(".repeat(depth),
        ")".repeat(depth)
    )
}

/// Runs the binary with `args` on a file holding `text`; returns the exit code and standard output.
fn run(args: &[&str], name: &str, text: &str) -> (Option<i32>, String) {
    let folder = temp_folder(name);
    let path = folder.join("PROGRAM.MPF");
    std::fs::write(&path, text).expect("the program can be written");
    let output = Command::new(env!("CARGO_BIN_EXE_sinumerik-lsp"))
        .args(args)
        .arg(&path)
        .output()
        .expect("the binary starts");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        !stderr.contains("overflow") && !stderr.contains("panicked"),
        "`{}` on {name}: {stderr}",
        args.join(" ")
    );
    (
        output.status.code(),
        String::from_utf8_lossy(&output.stdout).into_owned(),
    )
}

#[test]
fn a_short_chain_is_evaluated_and_a_long_one_is_reported() {
    let config = MachineConfig::default();
    let short = format!("R1={}\nG0 X=R1\n", vec!["1"; 200].join("+"));
    let findings = sinumerik_lsp::analysis::diagnose_program(
        &short,
        &config,
        sinumerik_lsp::analysis::ProgramKind::Main,
    );
    assert!(
        findings
            .iter()
            .all(|finding| finding.diagnostic.code.as_str() != "S170"),
        "200 operands are within the bound of {MAX_TREE_HEIGHT}"
    );
    let long = chain(MAX_TREE_HEIGHT as usize + 2);
    let findings = sinumerik_lsp::analysis::diagnose_program(
        &long,
        &config,
        sinumerik_lsp::analysis::ProgramKind::Main,
    );
    assert_eq!(
        findings
            .iter()
            .filter(|finding| finding.line == 0 && finding.diagnostic.code.as_str() == "S170")
            .count(),
        1,
        "one S170 on the line of the long chain"
    );
}

#[test]
fn the_command_line_reports_hostile_expressions_without_aborting() {
    for (name, text) in [
        ("chain_60k", chain(60_000)),
        ("chain_1m", chain(1_000_000)),
        ("nested_100k", nested(100_000)),
    ] {
        let (code, human) = run(&["check"], name, &text);
        assert_eq!(code, Some(1), "{name}: an error is exit code 1\n{human}");
        assert!(human.contains("[S170]"), "{name}: S170 is reported");
        let (code, json) = run(&["preview", "--format", "json"], name, &text);
        assert!(
            matches!(code, Some(0) | Some(1)),
            "{name}: preview exit {code:?}"
        );
        let preview: serde_json::Value = serde_json::from_str(&json).expect("the preview is JSON");
        assert!(
            preview["diagnostics"]
                .as_array()
                .is_some_and(|findings| findings.iter().any(|finding| finding["code"] == "S170")),
            "{name}: the preview lists S170"
        );
        let (code, _) = run(&["fmt", "--check"], name, &text);
        assert!(
            matches!(code, Some(0) | Some(1)),
            "{name}: fmt exit {code:?}"
        );
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_server_reports_hostile_expressions_and_keeps_serving() {
    let mut server = TestClient::spawn_binary(&[]);
    server.initialize(json!({}), json!({})).await;
    let folder = temp_folder("hostile_expressions_server");
    for (index, text) in [chain(1_000_000), nested(100_000)].iter().enumerate() {
        let uri = file_uri(&folder.join(format!("P{index}.MPF")));
        server.open(&uri, 1, text).await;
        let diagnostics = server.diagnostics(&uri, 1).await;
        assert!(
            diagnostics.iter().any(|finding| finding["code"] == "S170"),
            "document {index}: S170 is published"
        );
        // Hover and the toolpath run the program; formatting walks every expression.
        let hover = server.hover(&uri, 1, 4).await;
        assert!(!hover.is_empty(), "document {index}: the hover answers");
        let preview = server.preview(json!({"uri": uri})).await;
        assert!(preview.is_ok(), "document {index}: the toolpath answers");
        let formatting = server
            .request(
                "textDocument/formatting",
                json!({"textDocument": {"uri": uri}, "options": {"tabSize": 4, "insertSpaces": true}}),
            )
            .await;
        assert!(formatting.is_ok(), "document {index}: formatting answers");
    }
    assert_eq!(server.shutdown().await, Some(0), "the server exits cleanly");
}
