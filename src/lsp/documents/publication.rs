//! What a document's worker publishes: the `publishDiagnostics` body of an analysis, whether it is
//! still the newest, and the report of a slow one.

use super::{OpenDocument, PublishedText, TextState, WorkerContext};
use crate::diagnostics::LineDiagnostic;
use crate::lsp::convert::PositionEncoding;
use crate::lsp::locks::lock;
use crate::lsp::log;
use crate::lsp::publish::limit::{note, note_diagnostic, within_limit};
use crate::lsp::publish::wire::WireDiagnostic;
use crate::lsp::publish::{self, Publisher};
use crate::lsp::transport::outbox::Part;

impl OpenDocument {
    /// The `publishDiagnostics` body of the analysis's diagnostics (at most `limit` of them, and
    /// then a note) and the cross-file findings `extra`, taking over what the last one wrote where
    /// it still holds (`publish/mod.rs`).
    pub(super) fn publication(
        &self,
        published: PublishedText<'_>,
        encoding: PositionEncoding,
        limit: Option<usize>,
        extra: &[LineDiagnostic],
    ) -> Vec<Part> {
        let PublishedText {
            analysis,
            lines,
            all_ascii,
            version,
        } = published;
        let (diagnostics, left_out) = within_limit(analysis.diagnostics(), limit);
        let ranges = publish::ranges(&diagnostics, |line| lines.line(line), all_ascii, encoding);
        let extra_ranges = publish::ranges(extra, |line| lines.line(line), all_ascii, encoding);
        let note_text = limit
            .filter(|_| left_out > 0)
            .map(|limit| note(left_out, limit));
        let more: Vec<WireDiagnostic<'_>> = note_text
            .as_deref()
            .map(note_diagnostic)
            .into_iter()
            .chain(
                extra
                    .iter()
                    .zip(extra_ranges)
                    .map(|(item, range)| WireDiagnostic::of(item, range)),
            )
            .collect();
        let mut published = lock(&self.published);
        if published.as_ref().is_none_or(|(last, _)| *last != encoding) {
            *published = Some((encoding, Publisher::default()));
        }
        let Some((_, publisher)) = published.as_mut() else {
            return Vec::new();
        };
        let items = publisher.encode_shared(&diagnostics, ranges);
        publish::publication_parts(&self.uri, Some(version), items, &more)
    }

    /// Whether a publication made for `revision` with the cross-file findings of
    /// `extra_generation` is still the newest: `text` is the locked text state.
    pub(super) fn is_current(
        &self,
        text: &TextState,
        revision: u64,
        extra_generation: u64,
    ) -> bool {
        text.revision == revision && lock(&self.extra).generation() == extra_generation
    }
}

impl WorkerContext {
    /// Reports an analysis and its publication that together took long (`log.rs`).
    pub(super) fn log_slow_publication(
        &self,
        analysed_in: std::time::Duration,
        count: usize,
        started: std::time::Instant,
    ) {
        log::slow_with_sender(
            || {
                format!(
                    "analysis ({} ms) and writing of {count} diagnostics",
                    analysed_in.as_millis()
                )
            },
            started.elapsed(),
            &self.outgoing,
        );
    }
}
