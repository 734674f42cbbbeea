//! Diagnostics publication: the analysis's findings (values of the core) become one
//! `textDocument/publishDiagnostics` body, encoded in `wire.rs` only.
//!
//! - `limit.rs`: the findings published under the `maxDiagnostics` setting, and the note about the
//!   rest.
//! - `wire.rs`: the JSON of a diagnostic and of the message.
//!
//! A large program may have tens of thousands of findings, published again after every keystroke,
//! and a keystroke changes few of them. The [`Publisher`] of a document keeps the last array's
//! encoded items, in chunks of 256, with the findings they came from; the next publication takes
//! over the chunks of unchanged items at the start and at the end (compared as values, with their
//! ranges) without a copy, shared with the writer, and encodes only the chunks between. That is the
//! only state; the analysis knows nothing of it.

pub mod limit;
pub mod wire;

use crate::diagnostics::LineDiagnostic;
use crate::lsp::convert::{span_to_range, PositionEncoding};
use crate::lsp::transport::outbox::Part;
use crate::lsp::transport::FrozenBytes;
use std::borrow::Cow;
use std::sync::Arc;
use tower_lsp_server::ls_types::{Position, Range, Uri};
use wire::WireDiagnostic;

/// The range of a finding in an ASCII line, where byte offsets are the columns in either encoding.
pub fn ascii_range(item: &LineDiagnostic) -> Range {
    let line_number = u32::try_from(item.line).unwrap_or(u32::MAX);
    let span = item.diagnostic.span;
    let column = |byte: usize| u32::try_from(byte).unwrap_or(u32::MAX);
    Range::new(
        Position::new(line_number, column(span.start())),
        Position::new(line_number, column(span.end().max(span.start()))),
    )
}

/// The ranges of findings sorted by line, reading each line's text once from `line_text` (not at all
/// when `all_ascii` says the document is ASCII, or under UTF-8 positions, where byte offsets are the
/// columns).
pub fn ranges<'a>(
    diagnostics: &[LineDiagnostic],
    mut line_text: impl FnMut(usize) -> Cow<'a, str>,
    all_ascii: bool,
    encoding: PositionEncoding,
) -> Vec<Range> {
    if all_ascii || encoding == PositionEncoding::Utf8 {
        return diagnostics.iter().map(ascii_range).collect();
    }
    let mut current: Option<(usize, Cow<'a, str>)> = None;
    diagnostics
        .iter()
        .map(|item| {
            if current.as_ref().map(|(line_idx, _)| *line_idx) != Some(item.line) {
                current = Some((item.line, line_text(item.line)));
            }
            let line = current.as_ref().map_or("", |(_, text)| text.as_ref());
            span_to_range(item.line, line, item.diagnostic.span, encoding)
        })
        .collect()
}

/// Objects per chunk of the encoded array: an edit encodes the chunks it touches again.
const CHUNK_ITEMS: usize = 256;

/// Encoded objects, each followed by a comma; shared with the messages being written, in frozen pages
/// the writer may hand to the pipe.
#[derive(Clone)]
struct Chunk {
    bytes: Arc<FrozenBytes>,
    items: usize,
}

/// The findings of a document's last publication, with their ranges and encoded objects.
#[derive(Default)]
pub struct Publisher {
    items: Vec<LineDiagnostic>,
    ranges: Vec<Range>,
    chunks: Vec<Chunk>,
}

impl Publisher {
    /// The encoded array items (joined by commas) of `diagnostics` at `ranges` (the same length),
    /// taken over from the last publication where the findings at the start and at the end are the
    /// same; this becomes the last publication.
    pub fn encode(&mut self, diagnostics: &[LineDiagnostic], ranges: Vec<Range>) -> Vec<u8> {
        let mut items = Vec::new();
        for (bytes, length) in self.encode_shared(diagnostics, ranges) {
            items.extend_from_slice(&bytes.as_slice()[..length]);
        }
        items
    }

    /// Like [`Publisher::encode`], as pieces shared with the publisher (each the first `length`
    /// bytes of a buffer; together the objects joined by commas). Only the chunks of objects that
    /// hold a finding that changed are encoded again; the others are taken over without a copy.
    pub fn encode_shared(
        &mut self,
        diagnostics: &[LineDiagnostic],
        ranges: Vec<Range>,
    ) -> Vec<(Arc<FrozenBytes>, usize)> {
        let same = |old: usize, new: usize| {
            self.ranges[old] == ranges[new] && self.items[old] == diagnostics[new]
        };
        let reuse = !crate::lsp::transport::measure::measured_without("diagnostics-reuse");
        let most = if reuse {
            self.items.len().min(diagnostics.len())
        } else {
            0
        };
        let prefix = (0..most).take_while(|&index| same(index, index)).count();
        let suffix = (0..most - prefix)
            .take_while(|&back| same(self.items.len() - 1 - back, diagnostics.len() - 1 - back))
            .count();
        // The chunks wholly inside the unchanged ends are kept.
        let (mut front_chunks, mut front_items) = (0, 0);
        for chunk in &self.chunks {
            if front_items + chunk.items > prefix {
                break;
            }
            front_chunks += 1;
            front_items += chunk.items;
        }
        let (mut back_chunks, mut back_items) = (0, 0);
        for chunk in self.chunks[front_chunks..].iter().rev() {
            if back_items + chunk.items > suffix {
                break;
            }
            back_chunks += 1;
            back_items += chunk.items;
        }
        let mut chunks: Vec<Chunk> = self.chunks[..front_chunks].to_vec();
        let middle = front_items..diagnostics.len() - back_items;
        for (items, ranges) in diagnostics[middle.clone()]
            .chunks(CHUNK_ITEMS)
            .zip(ranges[middle].chunks(CHUNK_ITEMS))
        {
            let mut bytes = Vec::with_capacity(items.len() * 200);
            for (item, range) in items.iter().zip(ranges) {
                WireDiagnostic::of(item, *range).write(&mut bytes);
                bytes.push(b',');
            }
            chunks.push(Chunk {
                bytes: Arc::new(FrozenBytes::new(bytes)),
                items: items.len(),
            });
        }
        chunks.extend_from_slice(&self.chunks[self.chunks.len() - back_chunks..]);
        // Only the findings between the unchanged ends are copied.
        let old_middle = prefix..self.items.len() - suffix;
        self.items.splice(
            old_middle,
            diagnostics[prefix..diagnostics.len() - suffix]
                .iter()
                .cloned(),
        );
        self.ranges = ranges;
        self.chunks = chunks;
        let count = self.chunks.len();
        self.chunks
            .iter()
            .enumerate()
            .map(|(index, chunk)| {
                // The comma after the last object goes.
                let length = chunk.bytes.as_slice().len() - usize::from(index + 1 == count);
                (Arc::clone(&chunk.bytes), length)
            })
            .collect()
    }
}

fn encoded(more: &[WireDiagnostic<'_>]) -> Vec<Vec<u8>> {
    more.iter()
        .map(|item| {
            let mut out = Vec::new();
            item.write(&mut out);
            out
        })
        .collect()
}

/// The `publishDiagnostics` body of `items` (from [`Publisher::encode`]) followed by more
/// diagnostics (the cross-file findings, the note of a limit).
pub fn publication(
    uri: &Uri,
    version: Option<i32>,
    items: &[u8],
    more: &[WireDiagnostic<'_>],
) -> Vec<u8> {
    wire::publication(uri, version, items, &encoded(more))
}

/// The same body in parts, the items shared with the publisher (from
/// [`Publisher::encode_shared`]).
pub fn publication_parts(
    uri: &Uri,
    version: Option<i32>,
    items: Vec<(Arc<FrozenBytes>, usize)>,
    more: &[WireDiagnostic<'_>],
) -> Vec<Part> {
    let any_items = items.iter().any(|(_, length)| *length > 0);
    std::iter::once(Part::Owned(wire::head(uri, version)))
        .chain(
            items
                .into_iter()
                .map(|(bytes, length)| Part::Shared(bytes, length)),
        )
        .chain(std::iter::once(Part::Owned(wire::tail(
            any_items,
            &encoded(more),
        ))))
        .collect()
}

#[cfg(test)]
mod tests;
