//! An edit storm against the built binary: a 100,000-line program gets 10,000 edits as fast as the
//! pipe takes them while another thread sends hovers and `sinumerik.endpointPreview` commands. Then:
//! the server's text equals the edits applied here, the diagnostics published for the last version
//! equal a from-scratch analysis of that text, every request got a result or "content modified"
//! (-32801), and no publication for a version came after one for a newer version. A second test
//! sends edits while the first analysis of a 200,000-line program still reads the opened string.
//!
//! `STORM_EDITS` (default 10,000), `STORM_LINES` (default 100,000) and `STORM_SEED` change the run,
//! `STORM_LOG=1` prints the server's log (its slow analyses and handlers);
//! `cargo test --release --test lsp_storm -- --nocapture` prints the figures.

#[path = "support/compare.rs"]
mod compare;
#[path = "support/edit_session.rs"]
mod edit_session;
#[path = "support/env_setting.rs"]
mod env_setting;
#[path = "support/raw_lsp.rs"]
mod raw_lsp;

use edit_session::{program, LineDocument, Random};
use env_setting::setting;
use raw_lsp::RawServer;
use serde_json::Value;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

const URI: &str = "file:///nonexistent/storm.mpf";

/// A request (hover or preview) for every this many edits sent.
const EDITS_PER_REQUEST: usize = 10;

#[test]
fn an_edit_storm_with_hovers_and_previews_ends_in_step_with_a_fresh_analysis() {
    let edit_count = setting("STORM_EDITS", 10_000) as usize;
    let line_count = setting("STORM_LINES", 100_000) as usize;
    let mut random = Random::new(setting("STORM_SEED", 1));
    let text = program(&mut random, line_count, "\n");
    let mut document = LineDocument::new(&text, "\n");
    let mut server = RawServer::spawn();
    server.initialize();
    server.open(URI, 1, &text);
    server.diagnostics(URI, 1);

    // The requests come from a thread of their own, paced by the edits sent so far.
    let sent = Arc::new(AtomicUsize::new(0));
    let done = Arc::new(AtomicBool::new(false));
    let requester = {
        let writer = server.writer.clone();
        let (sent, done) = (Arc::clone(&sent), Arc::clone(&done));
        std::thread::spawn(move || {
            let mut random = Random::new(7);
            let mut hovers = Vec::new();
            let mut previews = Vec::new();
            let mut asked_at = 0;
            while !done.load(Ordering::SeqCst) {
                let edits = sent.load(Ordering::SeqCst);
                if edits < asked_at + EDITS_PER_REQUEST {
                    std::thread::sleep(Duration::from_micros(50));
                    continue;
                }
                asked_at = edits;
                let line = random.below(line_count) as u64;
                if random.one_in(4) {
                    previews.push(writer.request_preview(URI, line, line + 40));
                } else {
                    hovers.push(writer.request_hover(URI, line, random.below(40) as u64));
                }
            }
            (hovers, previews)
        })
    };

    let started = Instant::now();
    let mut version = 1;
    let mut changes_sent = 0;
    while changes_sent < edit_count {
        // Now and then two or three changes in one didChange, applied in order.
        let changes = if random.one_in(10) {
            2 + random.below(2)
        } else {
            1
        };
        let changes: Vec<Value> = (0..changes.min(edit_count - changes_sent))
            .map(|_| document.random_edit(&mut random).to_json())
            .collect();
        version += 1;
        changes_sent += changes.len();
        server.writer.change(URI, version, Value::Array(changes));
        sent.store(changes_sent, Ordering::SeqCst);
    }
    let sending = started.elapsed();
    done.store(true, Ordering::SeqCst);
    let (hovers, previews) = requester.join().unwrap();

    let expected = document.text();
    assert_eq!(
        server.document_text(URI),
        Ok((version, expected.clone())),
        "the server's text differs from the edits applied here"
    );
    let mut results = 0;
    let mut content_modified = 0;
    for (id, is_preview) in hovers
        .iter()
        .map(|id| (*id, false))
        .chain(previews.iter().map(|id| (*id, true)))
    {
        match server.response(id) {
            Ok(result) => {
                results += 1;
                if is_preview {
                    assert!(result["moves"].is_array(), "preview {id}: {result}");
                } else {
                    assert!(
                        result.is_null() || result["contents"]["value"].is_string(),
                        "hover {id}: {result}"
                    );
                }
            }
            Err(error) => {
                assert_eq!(error["code"], -32801, "request {id}: {error}");
                content_modified += 1;
            }
        }
    }
    let diagnostics = server.diagnostics(URI, version);
    let settled = started.elapsed();
    let expected_rows = compare::fresh(&expected);
    assert_eq!(
        compare::published(&diagnostics),
        expected_rows,
        "the last diagnostics differ from a fresh analysis of the final text"
    );
    let versions: Vec<i64> = server
        .publications()
        .into_iter()
        .filter(|(uri, _)| uri == URI)
        .map(|(_, version)| version.expect("diagnostics of an open document carry its version"))
        .collect();
    for pair in versions.windows(2) {
        assert!(
            pair[0] <= pair[1],
            "diagnostics of version {} came after those of version {}",
            pair[1],
            pair[0]
        );
    }
    assert_eq!(versions.last(), Some(&version));
    eprintln!(
        "edit storm: {changes_sent} edits in {} didChange on {line_count} lines sent in {:.2} s; \
         final diagnostics ({}) after {:.2} s; {} hovers and {} previews: {results} answered, \
         {content_modified} content modified; {} publications, in version order; server resident \
         memory {} MB",
        version - 1,
        sending.as_secs_f64(),
        expected_rows.len(),
        settled.as_secs_f64(),
        hovers.len(),
        previews.len(),
        versions.len(),
        server.resident_kib().unwrap_or(0) / 1024
    );
    if std::env::var_os("STORM_LOG").is_some() {
        eprintln!("the server's log:\n{}", server.log());
    }
    assert_eq!(server.shutdown(), Some(0));
}

/// Edits that come while the first analysis still reads the opened text (before the rope exists,
/// `lsp/opened_text.rs`) are applied in order, and the last diagnostics are those of the edited text.
#[test]
fn edits_during_the_first_analysis_end_in_step_with_a_fresh_analysis() {
    let line_count = 200_000;
    let mut random = Random::new(3);
    let text = program(&mut random, line_count, "\n");
    let mut document = LineDocument::new(&text, "\n");
    let mut server = RawServer::spawn();
    server.initialize();
    server.open(URI, 1, &text);
    // Sent without waiting for the first diagnostics, spread over the first analysis: before the
    // worker reads the string, while it does, and while the rope is built.
    let mut version = 1;
    for _ in 0..40 {
        std::thread::sleep(Duration::from_millis(2));
        version += 1;
        let change = document.random_edit(&mut random).to_json();
        server
            .writer
            .change(URI, version, Value::Array(vec![change]));
    }
    let expected = document.text();
    assert_eq!(
        server.document_text(URI),
        Ok((version, expected.clone())),
        "the server's text differs from the edits applied here"
    );
    let diagnostics = server.diagnostics(URI, version);
    assert_eq!(
        compare::published(&diagnostics),
        compare::fresh(&expected),
        "the last diagnostics differ from a fresh analysis of the final text"
    );
    let versions: Vec<i64> = server
        .publications()
        .into_iter()
        .filter(|(uri, _)| uri == URI)
        .filter_map(|(_, version)| version)
        .collect();
    assert!(
        versions.windows(2).all(|pair| pair[0] <= pair[1]),
        "diagnostics out of version order: {versions:?}"
    );
    assert_eq!(server.shutdown(), Some(0));
}

#[test]
fn the_local_copy_applies_edits_as_the_protocol_defines() {
    let mut document = LineDocument::new("N10 X1\r\nN20 😀X2\r\n", "\r\n");
    // Inside the surrogate pair of the emoji: the start of the character.
    document.apply(&edit_session::Edit {
        start: (1, 5),
        end: (1, 5),
        text: "A".to_string(),
    });
    assert_eq!(document.text(), "N10 X1\r\nN20 A😀X2\r\n");
    document.apply(&edit_session::Edit {
        start: (0, 500),
        end: (1, 4),
        text: " ".to_string(),
    });
    assert_eq!(document.text(), "N10 X1 A😀X2\r\n");
    document.apply(&edit_session::Edit {
        start: (9, 0),
        end: (9, 0),
        text: "M30".to_string(),
    });
    assert_eq!(document.text(), "N10 X1 A😀X2\r\nM30");
}
