//! The text of a just-opened document before its rope exists (`opened_text.rs`): its first
//! analysis, read from the `didOpen`'s string and published first, and the rope built after.

use super::{lock, Analysed, OpenDocument, Pending, PublishedText, TextState, WorkerContext};
use crate::analysis::document::FlatLines;
use crate::analysis::document::{DocumentAnalysis, LineSource};
use crate::lsp::cross_file::extra_findings;
use crate::lsp::opened_text::rope_from_string;
use crate::lsp::text_document::DocumentText;
use ropey::Rope;
use std::sync::{Arc, Mutex};

impl TextState {
    /// The text with its rope, which is built now if it was not yet.
    pub(super) fn with_rope(&mut self) -> &mut DocumentText {
        if let Some(opened) = self.opened.take() {
            self.text.rope = match Arc::try_unwrap(opened) {
                Ok(string) => rope_from_string(string),
                // The first analysis still reads the string: the rope is a copy of it.
                Err(shared) => Rope::from_str(&shared),
            };
        }
        &mut self.text
    }
}

impl OpenDocument {
    /// Analyses and publishes the text of the `didOpen` from its string, then builds the rope and
    /// keeps the analysis for the edits to come. Returns whether the worker is done: false when there
    /// was no such text (the rope was built already), or when something newer came meanwhile, which
    /// the worker's loop then brings up to date.
    pub(super) fn publish_opened_text(&self, context: &WorkerContext) -> bool {
        let mut slot = lock(&self.analysis);
        let (opened, version, revision, config) = {
            let text = lock(&self.text);
            match (&text.opened, slot.as_ref()) {
                (Some(opened), None) if !text.closed => (
                    Arc::clone(opened),
                    text.text.version,
                    text.revision,
                    Arc::clone(&text.config),
                ),
                _ => return false,
            }
        };
        let started = std::time::Instant::now();
        let lines = FlatLines::new(&opened);
        let analysis = DocumentAnalysis::new_in_parallel(
            &lines,
            &mut lines.clone(),
            Arc::clone(&config),
            self.kind,
        );
        let analysed_in = started.elapsed();
        let (extra, extra_generation) = extra_findings(&self.extra, lines.line_count());
        let published = PublishedText {
            analysis: &analysis,
            lines: &lines,
            // Read only when there are ranges to compute: a check of 33 MB costs milliseconds.
            all_ascii: (analysis.diagnostics().is_empty() && extra.is_empty()) || opened.is_ascii(),
            version,
        };
        let message =
            self.publication(published, context.encoding, context.max_diagnostics, &extra);
        let count = analysis.diagnostics().len();
        context.log_slow_publication(analysed_in, count, started);
        drop(lines);
        let mut text = lock(&self.text);
        if text.closed {
            text.worker_running = false;
            return true;
        }
        let current = self.is_current(&text, revision, extra_generation);
        if current {
            // Sent under the lock: a newer revision's publication cannot overtake it.
            context.outgoing.send_parts(message);
        }
        // An edit built the rope meanwhile from a copy of the string: this analysis is of an older
        // text, which the loop replaces.
        if !text
            .opened
            .as_ref()
            .is_some_and(|still| Arc::ptr_eq(still, &opened))
        {
            return false;
        }
        // With this reference gone the rope is built from the string itself, which shrinks.
        drop(opened);
        let rope = text.with_rope().rope.clone();
        // Unless the configuration changed meanwhile, the analysis is of the text as it is.
        if text.revision == revision {
            text.pending = Pending::Nothing;
        }
        *slot = Some(Analysed {
            analysis,
            rope,
            version,
            revision,
            config,
            execution: Arc::new(Mutex::new(None)),
            times: Arc::new(Mutex::new(None)),
        });
        if current {
            text.worker_running = false;
        }
        current
    }
}
