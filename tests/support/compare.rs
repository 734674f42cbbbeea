//! Published diagnostics against a from-scratch analysis, as (line, code, message) rows, for the
//! tests and runs that drive the server binary. Included with `#[path]`.

#![allow(dead_code)]

use serde_json::Value;
use sinumerik_lsp::analysis::document::{DocumentAnalysis, TextLines};
use sinumerik_lsp::analysis::ProgramKind;
use sinumerik_lsp::config::MachineConfig;
use std::sync::Arc;

pub type Row = (u64, String, String);

/// The rows of the diagnostics of a `publishDiagnostics`.
pub fn published(diagnostics: &[Value]) -> Vec<Row> {
    diagnostics
        .iter()
        .map(|diagnostic| {
            (
                diagnostic["range"]["start"]["line"].as_u64().unwrap(),
                diagnostic["code"].as_str().unwrap().to_string(),
                diagnostic["message"].as_str().unwrap().to_string(),
            )
        })
        .collect()
}

/// The rows a from-scratch analysis of `text` gives (a main program on the default machine, which
/// is what the server uses without a sinumerik.toml).
pub fn fresh(text: &str) -> Vec<Row> {
    let analysis = DocumentAnalysis::new(
        &TextLines::new(text),
        Arc::new(MachineConfig::default()),
        ProgramKind::Main,
    );
    analysis
        .diagnostics()
        .iter()
        .map(|item| {
            (
                item.line as u64,
                item.diagnostic.code.as_str().to_string(),
                item.diagnostic.message.clone(),
            )
        })
        .collect()
}
