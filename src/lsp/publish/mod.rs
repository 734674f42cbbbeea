//! Diagnostics publication: the analysis's findings (values of the core) become one
//! `textDocument/publishDiagnostics` body, encoded in `wire.rs` only.
//!
//! - `limit.rs`: the findings published under the `maxDiagnostics` setting, and the note about the
//!   rest.
//! - `wire.rs`: the JSON of a diagnostic and of the message.
//!
//! A large program may have tens of thousands of findings, published again after every keystroke,
//! and a keystroke changes few of them. The [`Publisher`] of a document keeps the last array's
//! encoded items with the findings they came from; the next publication takes over the unchanged
//! items at the start and at the end (compared as values, with their ranges) and encodes only those
//! between. That is the only state; the analysis knows nothing of it.

pub mod limit;
pub mod wire;

use crate::diagnostics::LineDiagnostic;
use crate::lsp::convert::{span_to_range, PositionEncoding};
use crate::lsp::transport::outbox::Part;
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

/// The findings of a document's last publication, with their ranges and encoded objects.
#[derive(Default)]
pub struct Publisher {
    items: Vec<LineDiagnostic>,
    ranges: Vec<Range>,
    /// The objects, each followed by a comma; shared with the message being written.
    json: Arc<Vec<u8>>,
    /// Where each object's text (with its comma) ends in `json`.
    ends: Vec<usize>,
    /// The buffer of the publication before the last, once the writer is done with it: its pages
    /// are mapped already.
    spare: Vec<u8>,
}

impl Publisher {
    /// The encoded array items (joined by commas) of `diagnostics` at `ranges` (the same length),
    /// taken over from the last publication where the findings at the start and at the end are the
    /// same; this becomes the last publication.
    pub fn encode(&mut self, diagnostics: &[LineDiagnostic], ranges: Vec<Range>) -> &[u8] {
        let (_, length) = self.encode_shared(diagnostics, ranges);
        &self.json[..length]
    }

    /// Like [`Publisher::encode`]: the items are the first `length` bytes (the objects joined by
    /// commas) of the buffer returned.
    pub fn encode_shared(
        &mut self,
        diagnostics: &[LineDiagnostic],
        ranges: Vec<Range>,
    ) -> (Arc<Vec<u8>>, usize) {
        let same = |old: usize, new: usize| {
            self.ranges[old] == ranges[new] && self.items[old] == diagnostics[new]
        };
        let reuse = !crate::lsp::transport::measured_without("diagnostics-reuse");
        let most = if reuse {
            self.items.len().min(diagnostics.len())
        } else {
            0
        };
        let prefix = (0..most).take_while(|&index| same(index, index)).count();
        let suffix = (0..most - prefix)
            .take_while(|&back| same(self.items.len() - 1 - back, diagnostics.len() - 1 - back))
            .count();
        let object_start =
            |ends: &[usize], index: usize| if index == 0 { 0 } else { ends[index - 1] };
        let mut json = std::mem::take(&mut self.spare);
        json.clear();
        let mut ends = Vec::with_capacity(diagnostics.len());
        json.extend_from_slice(&self.json[..object_start(&self.ends, prefix)]);
        ends.extend_from_slice(&self.ends[..prefix]);
        for (item, range) in diagnostics[prefix..diagnostics.len() - suffix]
            .iter()
            .zip(&ranges[prefix..])
        {
            WireDiagnostic::of(item, *range).write(&mut json);
            json.push(b',');
            ends.push(json.len());
        }
        let old_suffix_start = object_start(&self.ends, self.items.len() - suffix);
        let shift = json.len() as isize - old_suffix_start as isize;
        json.extend_from_slice(&self.json[old_suffix_start..]);
        ends.extend(
            self.ends[self.items.len() - suffix..]
                .iter()
                .map(|&end| (end as isize + shift) as usize),
        );
        // Only the findings between the unchanged ends are copied.
        let old_middle = prefix..self.items.len() - suffix;
        self.items.splice(
            old_middle,
            diagnostics[prefix..diagnostics.len() - suffix]
                .iter()
                .cloned(),
        );
        self.ranges = ranges;
        let last = std::mem::replace(&mut self.json, Arc::new(json));
        // The buffer is used again if the writer is done with it (a publication is written before
        // the next edit's comes, as a rule); otherwise the writer frees it.
        if let Ok(buffer) = Arc::try_unwrap(last) {
            self.spare = buffer;
        }
        self.ends = ends;
        let length = self.json.len().saturating_sub(1);
        (Arc::clone(&self.json), length)
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

/// The same body in parts, the items shared with the publisher (`items` and `length` from
/// [`Publisher::encode_shared`]).
pub fn publication_parts(
    uri: &Uri,
    version: Option<i32>,
    (items, length): (Arc<Vec<u8>>, usize),
    more: &[WireDiagnostic<'_>],
) -> Vec<Part> {
    vec![
        Part::Owned(wire::head(uri, version)),
        Part::Shared(items, length),
        Part::Owned(wire::tail(length > 0, &encoded(more))),
    ]
}

#[cfg(test)]
mod tests;
