use super::*;
use crate::diagnostics::{Code, Diagnostic, Span};
use crate::lsp::convert::diagnostic_to_lsp;
use tower_lsp_server::ls_types::{self, PublishDiagnosticsParams};

fn finding(line: usize, start: usize, message: &str) -> LineDiagnostic {
    LineDiagnostic {
        line,
        diagnostic: Diagnostic::new(
            Code::UnexpectedCharacter,
            Span::new(start, start + 2),
            message,
        ),
    }
}

/// The body as the LSP types serialize it.
fn expected(
    uri: &Uri,
    version: Option<i32>,
    items: &[LineDiagnostic],
    lines: &[&str],
) -> serde_json::Value {
    let params = PublishDiagnosticsParams {
        uri: uri.clone(),
        diagnostics: items
            .iter()
            .map(|item| diagnostic_to_lsp(item, lines[item.line], PositionEncoding::Utf16))
            .collect(),
        version,
    };
    serde_json::json!({"jsonrpc": "2.0", "method": "textDocument/publishDiagnostics", "params": params})
}

fn published(
    publisher: &mut Publisher,
    uri: &Uri,
    items: &[LineDiagnostic],
    lines: &[&str],
) -> serde_json::Value {
    let ranges = ranges(
        items,
        |line| Cow::Borrowed(lines[line]),
        false,
        PositionEncoding::Utf16,
    );
    let array = publisher.encode(items, ranges).to_vec();
    serde_json::from_slice(&publication(uri, Some(7), &array, &[])).unwrap()
}

#[test]
fn the_written_notification_equals_the_lsp_types_serialization() {
    let lines = ["N10 G0 Z=AC17 ; \"quoted\" ä", "N20 😀 X\t1", "N30"];
    let uri: Uri = "file:///a%20b/c.mpf".parse().unwrap();
    let items = vec![
        finding(0, 9, "write `AC(17)` \"now\"\n"),
        finding(1, 4, "ünexpected"),
        finding(1, 6, "\u{1}control"),
    ];
    let mut publisher = Publisher::default();
    assert_eq!(
        published(&mut publisher, &uri, &items, &lines),
        expected(&uri, Some(7), &items, &lines)
    );
    assert_eq!(
        published(&mut publisher, &uri, &[], &lines),
        expected(&uri, Some(7), &[], &lines)
    );
    // An ASCII document needs no line text: the same ranges come from the spans alone.
    let ascii = ["N10 G0 Z=AC17 ; x", "N20 ?? X1"];
    let from_text = ranges(
        &items[..2],
        |line| Cow::Borrowed(ascii[line]),
        false,
        PositionEncoding::Utf16,
    );
    let from_spans = ranges(
        &items[..2],
        |_| unreachable!("no line is read"),
        true,
        PositionEncoding::Utf16,
    );
    assert_eq!(from_text, from_spans);
}

#[test]
fn a_publication_after_another_equals_one_written_from_nothing() {
    let lines: Vec<String> = (0..40).map(|line| format!("N{line} X1 Y2 ä")).collect();
    let lines: Vec<&str> = lines.iter().map(String::as_str).collect();
    let uri: Uri = "file:///p.mpf".parse().unwrap();
    let all: Vec<LineDiagnostic> = (0..40)
        .map(|line| finding(line, 1, &format!("m{line}")))
        .collect();
    let variants: Vec<Vec<LineDiagnostic>> = vec![
        all.clone(),
        all[..20].iter().chain(&all[21..]).cloned().collect(),
        all.iter()
            .cloned()
            .map(|mut item| {
                if item.line == 5 {
                    item.diagnostic.message = "changed".into();
                }
                item
            })
            .collect(),
        all[..3].to_vec(),
        all[37..].to_vec(),
        Vec::new(),
        all.clone(),
        all.iter().chain(&all[39..]).cloned().collect(),
    ];
    let mut publisher = Publisher::default();
    for (index, items) in variants.iter().enumerate() {
        assert_eq!(
            published(&mut publisher, &uri, items, &lines),
            expected(&uri, Some(7), items, &lines),
            "variant {index}"
        );
        let mut fresh = Publisher::default();
        let ranges_now = ranges(
            items,
            |line| Cow::Borrowed(lines[line]),
            false,
            PositionEncoding::Utf16,
        );
        assert_eq!(
            fresh.encode(items, ranges_now.clone()),
            publisher.encode(items, ranges_now),
            "variant {index}"
        );
    }
}

#[test]
fn more_diagnostics_follow_the_items_and_no_version_is_written_without_one() {
    let uri: Uri = "file:///p.mpf".parse().unwrap();
    let note = limit::note(3, 1);
    let body = publication(&uri, None, b"", &[limit::note_diagnostic(&note)]);
    let value: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(
        value["params"]["diagnostics"].as_array().map(Vec::len),
        Some(1)
    );
    assert_eq!(value["params"].get("version"), None);
    let _ = ls_types::Diagnostic::default();
}

#[test]
fn chunks_around_a_change_are_written_again_and_the_rest_taken_over() {
    let lines: Vec<String> = (0..2000).map(|line| format!("N{line} X1")).collect();
    let lines: Vec<&str> = lines.iter().map(String::as_str).collect();
    let all: Vec<LineDiagnostic> = (0..2000)
        .map(|line| finding(line, 1, &format!("m{line}")))
        .collect();
    let ranges_of = |items: &[LineDiagnostic]| {
        ranges(
            items,
            |line| Cow::Borrowed(lines[line]),
            true,
            PositionEncoding::Utf16,
        )
    };
    let mut publisher = Publisher::default();
    let mut items = all.clone();
    // Changes at a chunk's start, inside one, at the end; findings removed and added.
    for (step, at) in [0usize, 255, 256, 700, 1999, 1000, 3, 1500]
        .into_iter()
        .enumerate()
    {
        let at = at.min(items.len() - 1);
        match step % 3 {
            0 => items[at].diagnostic.message.push('!'),
            1 => {
                items.remove(at);
            }
            _ => items.insert(at, finding(at, 0, "new")),
        }
        let shared = publisher.encode_shared(&items, ranges_of(&items));
        let mut fresh = Publisher::default();
        assert_eq!(
            shared
                .iter()
                .flat_map(|(bytes, length)| bytes.as_slice()[..*length].iter().copied())
                .collect::<Vec<u8>>(),
            fresh.encode(&items, ranges_of(&items)),
            "step {step}"
        );
        assert!(
            shared.len() <= items.len() / 64 + 8,
            "{} pieces",
            shared.len()
        );
    }
}
