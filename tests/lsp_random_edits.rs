//! Property tests of incremental editing: random edit sequences (CRLF, lone CR, umlauts, emoji,
//! multi-change events, whole-text replacements) must leave the same text as the protocol's
//! definition, report exactly the lines they touched, and give the analysis, diagnostics and end
//! points of a from-scratch analysis of that text.

#[path = "support/lsp_client.rs"]
mod lsp_client;

use lsp_client::{apply_edit, lsp_line_count, lsp_line_length, Random, TestClient};
use serde_json::{json, Value};
use sinumerik_lsp::analysis::document::RopeLines;
use sinumerik_lsp::analysis::document::{DocumentAnalysis, LineSource, TextLines};
use sinumerik_lsp::analysis::ProgramKind;
use sinumerik_lsp::config::MachineConfig;
use sinumerik_lsp::lsp::{apply_changes, DocumentText, PositionEncoding};
use std::sync::Arc;
use tower_lsp_server::ls_types::{Position, Range, TextDocumentContentChangeEvent};

const PIECES: &[&str] = &[
    "N10 ",
    "G90 ",
    "G91 ",
    "G0 ",
    "G1 ",
    "X",
    "Z",
    "1",
    "7",
    ".5",
    "-",
    "=IC(",
    "=AC(",
    "AC",
    ")",
    " ",
    "\r\n",
    "\n",
    "\r",
    "ä",
    "😀",
    "F100",
    "; Ä 😀 ",
    "DIAMON ",
    "G70 ",
    "AP=45 RP=10 ",
    "G2 X10 Z5 CR=5 ",
];

const START: &str = "; Kommentar äöü 😀\r\nN10 G90 G0 X20 Z90\r\nN20 G1 X75 Z=IC(-32) F100\r\nN30 G91 X40 Z2\rN40 X-12 Z=AC(17)\nM30\n";

/// One random edit of `text`: a range (start, end) and the new text.
fn random_edit(random: &mut Random, text: &str) -> ((u32, u32), (u32, u32), String) {
    let line = random.below(lsp_line_count(text) + 1) as u32;
    let column = random.below(lsp_line_length(text, line) as usize + 3) as u32;
    let end = match random.below(4) {
        0 => (line, column),
        1 => (line, column + random.below(6) as u32),
        2 => (line + random.below(3) as u32, random.below(20) as u32),
        _ => (line, column),
    };
    let new_text = match random.below(5) {
        0 => String::new(),
        _ => (0..1 + random.below(3))
            .map(|_| random.pick(PIECES))
            .collect(),
    };
    // The protocol requires start <= end; clamping both keeps them in order for the oracle too.
    let (start, end) = if (end.0, end.1) < (line, column) {
        (end, (line, column))
    } else {
        ((line, column), end)
    };
    (start, end, new_text)
}

fn change_json(start: (u32, u32), end: (u32, u32), text: &str) -> Value {
    json!({"range": {"start": {"line": start.0, "character": start.1}, "end": {"line": end.0, "character": end.1}}, "text": text})
}

/// The diagnostics of a from-scratch analysis in the protocol's terms, computed here independently.
fn expected_diagnostics(text: &str) -> Vec<Value> {
    let lines = TextLines::new(text);
    let analysis = DocumentAnalysis::new(
        &lines,
        Arc::new(MachineConfig::default()),
        ProgramKind::Main,
    );
    let utf16 = |line: &str, byte: usize| line[..byte.min(line.len())].encode_utf16().count();
    analysis
        .diagnostics()
        .iter()
        .map(|item| {
            let line = lines.line(item.line);
            let span = item.diagnostic.span;
            json!({
                "line": item.line,
                "start": utf16(&line, span.start()),
                "end": utf16(&line, span.end()),
                "code": item.diagnostic.code.as_str(),
                "message": item.diagnostic.message,
            })
        })
        .collect()
}

fn published(diagnostics: &[Value]) -> Vec<Value> {
    diagnostics
        .iter()
        .map(|diagnostic| {
            json!({
                "line": diagnostic["range"]["start"]["line"],
                "start": diagnostic["range"]["start"]["character"],
                "end": diagnostic["range"]["end"]["character"],
                "code": diagnostic["code"],
                "message": diagnostic["message"],
            })
        })
        .collect()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn random_edits_through_the_protocol_equal_a_fresh_analysis() {
    let mut client = TestClient::in_process();
    client.initialize(json!({}), Value::Null).await;
    let folder = std::env::temp_dir().join(format!("sinumerik-lsp-random-{}", std::process::id()));
    std::fs::create_dir_all(&folder).unwrap();
    let mut random = Random::new(20_251_201);
    for round in 0..25 {
        let uri = format!("file:///nonexistent/random{round}.mpf");
        let mut expected = START.to_string();
        client.open(&uri, 1, &expected).await;
        let mut version = 1;
        for _ in 0..40 {
            version += 1;
            let mut changes = Vec::new();
            // Several changes in one event apply one after the other; now and then the whole text.
            if random.below(25) == 0 {
                expected = (0..random.below(8)).map(|_| random.pick(PIECES)).collect();
                changes.push(json!({"text": expected}));
            } else {
                for _ in 0..1 + random.below(3) {
                    let (start, end, new_text) = random_edit(&mut random, &expected);
                    apply_edit(&mut expected, start, end, &new_text);
                    changes.push(change_json(start, end, &new_text));
                }
            }
            client.change(&uri, version, Value::Array(changes)).await;
        }
        assert_eq!(
            client.document_text(&uri).await,
            (version, expected.clone()),
            "round {round}"
        );
        let diagnostics = client.diagnostics(&uri, version).await;
        assert_eq!(
            published(&diagnostics),
            expected_diagnostics(&expected),
            "round {round}: {expected:?}"
        );

        // End points: the preview of the open document equals that of the same text read from disk.
        let path = folder.join(format!("random{round}.mpf"));
        std::fs::write(&path, &expected).unwrap();
        let open = client.preview(json!({"uri": uri})).await.unwrap();
        let fresh = client
            .preview(json!({"uri": lsp_client::file_uri(&path)}))
            .await
            .unwrap();
        assert_eq!(open["moves"], fresh["moves"], "round {round}: {expected:?}");
        client
            .notify(
                "textDocument/didClose",
                json!({"textDocument": {"uri": uri}}),
            )
            .await;
    }
    let _ = std::fs::remove_dir_all(&folder);
    client.shutdown().await;
}

fn core_lines(text: &str) -> Vec<String> {
    let lines = TextLines::new(text);
    (0..lines.line_count())
        .map(|index| lines.line(index).into_owned())
        .collect()
}

#[test]
fn the_lines_an_edit_touched_are_exact_and_updating_by_them_equals_a_fresh_analysis() {
    let config = Arc::new(MachineConfig::default());
    let mut random = Random::new(99);
    for round in 0..60 {
        let mut document = DocumentText::new(START, 1);
        let mut expected = START.to_string();
        let mut analysis = DocumentAnalysis::new(
            &RopeLines::new(&document.rope),
            config.clone(),
            ProgramKind::Main,
        );
        for step in 0..30 {
            let old_lines = core_lines(&expected);
            let (start, end, new_text) = random_edit(&mut random, &expected);
            apply_edit(&mut expected, start, end, &new_text);
            let change = TextDocumentContentChangeEvent {
                range: Some(Range::new(
                    Position::new(start.0, start.1),
                    Position::new(end.0, end.1),
                )),
                range_length: None,
                text: new_text.clone(),
            };
            let next_version = document.version + 1;
            let touched = apply_changes(
                &mut document,
                &[change],
                next_version,
                PositionEncoding::Utf16,
            )
            .unwrap()
            .unwrap();
            assert_eq!(
                document.rope.to_string(),
                expected,
                "round {round} step {step}"
            );
            let new_lines = core_lines(&expected);
            let line_change = touched.to_core(old_lines.len(), new_lines.len());
            let context = format!("round {round} step {step}: {line_change:?} {start:?}..{end:?} {new_text:?}\n{old_lines:?}\n{new_lines:?}");
            // Lines before the range and after it are unchanged; the count adds up.
            assert_eq!(
                old_lines.len() - line_change.removed,
                new_lines.len() - line_change.inserted,
                "{context}"
            );
            assert_eq!(
                old_lines[..line_change.first],
                new_lines[..line_change.first],
                "{context}"
            );
            assert_eq!(
                old_lines[line_change.first + line_change.removed..],
                new_lines[line_change.first + line_change.inserted..],
                "{context}"
            );
            // Exact: no more lines than the edit's own lines, plus one for a line end it joined.
            let edit_lines = (end.0 - start.0) as usize + 1;
            assert!(line_change.removed <= edit_lines + 1, "{context}");
            let source = RopeLines::new(&document.rope);
            analysis.update(
                &source,
                line_change.first,
                line_change.removed,
                line_change.inserted,
            );
            let fresh = DocumentAnalysis::new(
                &TextLines::new(&expected),
                config.clone(),
                ProgramKind::Main,
            );
            assert_eq!(analysis.diagnostics(), fresh.diagnostics(), "{context}");
            assert_eq!(
                analysis.moves(&source, 0..usize::MAX),
                fresh.moves(&TextLines::new(&expected), 0..usize::MAX),
                "{context}"
            );
        }
    }
}
