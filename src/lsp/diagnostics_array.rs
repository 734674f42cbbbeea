//! The JSON array of a document's diagnostics as last published, and the next array built from it.
//! A large program has tens of thousands of findings and every version must carry all of them, but an
//! edit changes only a few. The array is kept in chunks of [`CHUNK`] diagnostics, each written once and
//! shared: the next array takes over every chunk whose diagnostics did not change, writes anew only
//! the chunks around the change, and rewrites only the line numbers of chunks that moved by inserted
//! or removed lines (in an ASCII document a diagnostic's JSON depends on the diagnostic alone). The
//! message then goes out as the list of pieces, without being copied into one buffer.

use crate::analysis::document::FindingsChange;
use crate::diagnostics::LineDiagnostic;
use crate::lsp::convert::{
    ascii_range, span_to_range, write_diagnostic_json, PositionEncoding, DIAGNOSTIC_JSON_END_LINE,
    DIAGNOSTIC_JSON_START,
};
use crate::lsp::frozen_bytes::FrozenBytes;
use crate::lsp::stdio::Piece;
use std::borrow::Cow;
use std::io::Write;
use std::sync::Arc;
use tower_lsp_server::ls_types::Range;

/// Diagnostics per chunk: an edit writes one or two chunks (about 60 KB each) anew.
const CHUNK: usize = 256;

/// Arrays of at least this many diagnostics are written on two threads when nothing can be taken
/// over (the first publication after opening a large program).
const PARALLEL_MIN_DIAGNOSTICS: usize = 8 * CHUNK;

/// A JSON array in shared pieces: runs of its elements' JSON, written with brackets and commas.
#[derive(Clone, Default)]
pub struct JsonArray {
    /// Each a comma and a non-empty run of elements separated by commas. The first run goes out
    /// without its comma: every run is then one piece, and the large ones leave in their own pages.
    runs: Vec<Arc<FrozenBytes>>,
}

impl JsonArray {
    /// The length of the JSON text.
    pub fn len(&self) -> usize {
        let runs: usize = self.runs.iter().map(|run| run.len()).sum();
        2 + runs - usize::from(!self.runs.is_empty())
    }

    /// The JSON text, piece by piece.
    pub fn pieces(&self) -> impl Iterator<Item = Piece<'_>> {
        let runs = self.runs.iter().enumerate().map(|(index, run)| Piece {
            bytes: &run[usize::from(index == 0)..],
            own_pages: run.has_own_pages(),
        });
        std::iter::once(Piece::copied(b"["))
            .chain(runs)
            .chain(std::iter::once(Piece::copied(b"]")))
    }

    /// The whole text in one buffer.
    #[cfg(test)]
    pub fn to_vec(&self) -> Vec<u8> {
        self.pieces()
            .flat_map(|piece| piece.bytes.iter().copied())
            .collect()
    }

    /// This array with the elements of the array `json` (`[...]`) added at its end.
    pub fn join_array(&self, json: &[u8]) -> JsonArray {
        let inner = json
            .strip_prefix(b"[")
            .and_then(|rest| rest.strip_suffix(b"]"))
            .unwrap_or_default();
        let mut joined = self.clone();
        if !inner.is_empty() {
            let mut run = Vec::with_capacity(1 + inner.len());
            run.push(b',');
            run.extend_from_slice(inner);
            joined.runs.push(Arc::new(FrozenBytes::new(run)));
        }
        joined
    }
}

/// How the columns of a diagnostic's range are found.
pub enum Columns<'a> {
    /// The byte offsets are the columns: an ASCII document, or positions counted in UTF-8. The JSON
    /// of a diagnostic then depends on the diagnostic alone.
    Bytes,
    /// The columns are counted in the text of the diagnostic's line (UTF-16 positions in a document
    /// that is not ASCII): equal diagnostics on lines of different texts have different JSON.
    InLine {
        line_text: &'a dyn Fn(usize) -> Cow<'a, str>,
        encoding: PositionEncoding,
    },
}

impl Columns<'_> {
    fn range(&self, item: &LineDiagnostic) -> Range {
        match self {
            Columns::Bytes => ascii_range(item),
            Columns::InLine {
                line_text,
                encoding,
            } => span_to_range(
                item.line,
                &line_text(item.line),
                item.diagnostic.span,
                *encoding,
            ),
        }
    }
}

/// Diagnostics with their JSON objects, each after a comma, without brackets.
struct Chunk {
    diagnostics: Vec<LineDiagnostic>,
    json: Arc<FrozenBytes>,
    /// Where each diagnostic's object starts in `json`.
    starts: Vec<usize>,
}

/// A chunk being written.
struct ChunkWriter {
    json: Vec<u8>,
    starts: Vec<usize>,
}

impl ChunkWriter {
    fn with_capacity(count: usize) -> ChunkWriter {
        ChunkWriter {
            json: Vec::with_capacity(count * 200),
            starts: Vec::with_capacity(count),
        }
    }

    fn begin_object(&mut self) {
        self.json.push(b',');
        self.starts.push(self.json.len());
    }

    fn finish(self, diagnostics: &[LineDiagnostic]) -> Arc<Chunk> {
        Arc::new(Chunk {
            diagnostics: diagnostics.to_vec(),
            json: Arc::new(FrozenBytes::new(self.json)),
            starts: self.starts,
        })
    }
}

impl Chunk {
    fn written(diagnostics: &[LineDiagnostic], columns: &Columns<'_>) -> Arc<Chunk> {
        let mut writer = ChunkWriter::with_capacity(diagnostics.len());
        for item in diagnostics {
            writer.begin_object();
            write_diagnostic_json(&mut writer.json, columns.range(item), item);
        }
        writer.finish(diagnostics)
    }

    /// `old` with its diagnostics moved to other lines: `new`, the same diagnostics at their lines
    /// (whose texts are those of their old lines, so the columns stay).
    fn moved(old: &Chunk, new: &[LineDiagnostic], columns: &Columns<'_>) -> Arc<Chunk> {
        let mut writer = ChunkWriter::with_capacity(new.len());
        for (index, item) in new.iter().enumerate() {
            writer.begin_object();
            if !write_with_line(&mut writer.json, old.object(index), item.line) {
                write_diagnostic_json(&mut writer.json, columns.range(item), item);
            }
        }
        writer.finish(new)
    }

    fn object(&self, index: usize) -> &[u8] {
        let end = match self.starts.get(index + 1) {
            Some(next) => next - 1,
            None => self.json.len(),
        };
        &self.json[self.starts[index]..end]
    }
}

/// A written array of diagnostics.
pub struct DiagnosticsArray {
    chunks: Vec<Arc<Chunk>>,
    json: JsonArray,
    /// Whether every chunk's JSON depends on its diagnostics alone (all were written with
    /// [`Columns::Bytes`]): only then may a diagnostic found equal to an old one take over its JSON.
    by_diagnostic: bool,
}

impl DiagnosticsArray {
    /// The JSON text: `[`, the objects separated by commas, `]`.
    pub fn json(&self) -> &JsonArray {
        &self.json
    }

    /// The array of `diagnostics`, reusing what `previous` wrote. `change`, when known, says how
    /// `diagnostics` differ from those of `previous`: then only the findings it says were replaced
    /// are compared, instead of all of them. Where the columns depend on the lines' texts, nothing
    /// is compared: only what `change` says is unchanged is taken over (those findings are on lines
    /// the edit did not touch), and without it everything is written anew.
    pub fn build(
        previous: Option<&DiagnosticsArray>,
        diagnostics: &[LineDiagnostic],
        change: Option<FindingsChange>,
        columns: &Columns<'_>,
    ) -> Self {
        let by_diagnostic = matches!(columns, Columns::Bytes);
        let written_anew =
            || DiagnosticsArray::from_chunks(written_chunks(diagnostics, columns), by_diagnostic);
        let Some(previous) = previous.filter(|previous| !previous.chunks.is_empty()) else {
            return written_anew();
        };
        let comparable = by_diagnostic && previous.by_diagnostic;
        let old_count: usize = previous
            .chunks
            .iter()
            .map(|chunk| chunk.diagnostics.len())
            .sum();
        let change = change.filter(|change| {
            change.start <= change.old_end.min(change.new_end)
                && change.old_end <= old_count
                && change.new_end <= diagnostics.len()
                && old_count - change.old_end == diagnostics.len() - change.new_end
        });
        let (prefix, suffix, delta) = match (change, comparable) {
            (Some(change), true) => known_ends(previous, diagnostics, change),
            (Some(change), false) => exact_ends(diagnostics.len(), change),
            (None, true) => common_ends(previous, old_count, diagnostics),
            (None, false) => return written_anew(),
        };
        let mut chunks = Vec::with_capacity(diagnostics.len() / CHUNK + 2);
        // The old chunks wholly within the common start are taken over.
        let mut taken = 0;
        for chunk in &previous.chunks {
            if taken + chunk.diagnostics.len() > prefix {
                break;
            }
            taken += chunk.diagnostics.len();
            chunks.push(Arc::clone(chunk));
        }
        // The old chunks wholly within the common end, from the back.
        let mut kept_at_end = Vec::new();
        let mut kept = 0;
        for chunk in previous.chunks.iter().rev() {
            if kept + chunk.diagnostics.len() > suffix
                || old_count - kept - chunk.diagnostics.len() < taken
            {
                break;
            }
            kept += chunk.diagnostics.len();
            kept_at_end.push(chunk);
        }
        let middle = &diagnostics[taken..diagnostics.len() - kept];
        chunks.extend(written_chunks(middle, columns));
        let mut new_start = diagnostics.len() - kept;
        for old in kept_at_end.into_iter().rev() {
            let new = &diagnostics[new_start..new_start + old.diagnostics.len()];
            new_start += old.diagnostics.len();
            chunks.push(if delta == 0 {
                Arc::clone(old)
            } else {
                Chunk::moved(old, new, columns)
            });
        }
        let took_over = taken > 0 || kept > 0;
        DiagnosticsArray::from_chunks(
            chunks,
            by_diagnostic && (previous.by_diagnostic || !took_over),
        )
    }

    fn from_chunks(chunks: Vec<Arc<Chunk>>, by_diagnostic: bool) -> DiagnosticsArray {
        let json = JsonArray {
            runs: chunks
                .iter()
                .filter(|chunk| !chunk.json.is_empty())
                .map(|chunk| Arc::clone(&chunk.json))
                .collect(),
        };
        DiagnosticsArray {
            chunks,
            json,
            by_diagnostic,
        }
    }

    /// Whether the array is that of exactly `diagnostics`.
    #[cfg(test)]
    pub fn is_of(&self, diagnostics: &[LineDiagnostic]) -> bool {
        let mut rest = diagnostics;
        for chunk in &self.chunks {
            let Some(own) = rest.get(..chunk.diagnostics.len()) else {
                return false;
            };
            if own != chunk.diagnostics.as_slice() {
                return false;
            }
            rest = &rest[own.len()..];
        }
        rest.is_empty()
    }
}

/// `diagnostics` written in chunks; a large array with byte columns on two threads.
fn written_chunks(diagnostics: &[LineDiagnostic], columns: &Columns<'_>) -> Vec<Arc<Chunk>> {
    if diagnostics.len() < PARALLEL_MIN_DIAGNOSTICS || !matches!(columns, Columns::Bytes) {
        return diagnostics
            .chunks(CHUNK)
            .map(|chunk| Chunk::written(chunk, columns))
            .collect();
    }
    let write = |diagnostics: &[LineDiagnostic]| -> Vec<Arc<Chunk>> {
        diagnostics
            .chunks(CHUNK)
            .map(|chunk| Chunk::written(chunk, &Columns::Bytes))
            .collect()
    };
    let (first, second) = diagnostics.split_at(diagnostics.len() / CHUNK / 2 * CHUNK);
    std::thread::scope(|scope| {
        let helper = scope.spawn(|| write(second));
        let mut chunks = write(first);
        // A thread that failed (it cannot, short of running out of memory) has its part written here.
        chunks.extend(helper.join().unwrap_or_else(|_| write(second)));
        chunks
    })
}

/// How many diagnostics the `old_count` of `old` and `new` share at the start, how many at the end
/// (where the new ones may all be `delta` lines further), and that `delta`.
fn common_ends(
    old: &DiagnosticsArray,
    old_count: usize,
    new: &[LineDiagnostic],
) -> (usize, usize, isize) {
    let old_items = || old.chunks.iter().flat_map(|chunk| chunk.diagnostics.iter());
    let prefix = old_items()
        .zip(new)
        .take_while(|(old, new)| old == new)
        .count();
    let (Some(old_last), Some(new_last)) = (old_items().next_back(), new.last()) else {
        return (prefix, 0, 0);
    };
    let delta = new_last.line as isize - old_last.line as isize;
    let most = old_count.min(new.len()) - prefix;
    let suffix = old_items()
        .rev()
        .zip(new.iter().rev())
        .take(most)
        .take_while(|(old, new)| {
            old.line.checked_add_signed(delta) == Some(new.line) && old.diagnostic == new.diagnostic
        })
        .count();
    (prefix, suffix, delta)
}

/// The old diagnostics of `old`'s chunks from index `start` on.
fn old_items_from(old: &DiagnosticsArray, start: usize) -> impl Iterator<Item = &LineDiagnostic> {
    let mut skipped = 0;
    let first = old
        .chunks
        .iter()
        .position(|chunk| {
            let past = skipped + chunk.diagnostics.len() > start;
            if !past {
                skipped += chunk.diagnostics.len();
            }
            past
        })
        .unwrap_or(old.chunks.len());
    old.chunks[first..]
        .iter()
        .flat_map(|chunk| chunk.diagnostics.iter())
        .skip(start - skipped)
}

/// The old diagnostics of `old`'s chunks before index `end`, from the last one back.
fn old_items_before(
    old: &DiagnosticsArray,
    old_count: usize,
    end: usize,
) -> impl Iterator<Item = &LineDiagnostic> {
    let mut skipped = 0;
    let last = old
        .chunks
        .iter()
        .rposition(|chunk| {
            let past = skipped + chunk.diagnostics.len() > old_count - end;
            if !past {
                skipped += chunk.diagnostics.len();
            }
            past
        })
        .map_or(0, |index| index + 1);
    old.chunks[..last]
        .iter()
        .rev()
        .flat_map(|chunk| chunk.diagnostics.iter().rev())
        .skip(old_count - end - skipped)
}

/// The common start and end `change` gives for `count` new findings, as they are: without comparing
/// anything, only a change that replaced nothing by nothing in place says that all are common.
fn exact_ends(count: usize, change: FindingsChange) -> (usize, usize, isize) {
    let replaced_nothing = change.start == change.old_end && change.start == change.new_end;
    if replaced_nothing && change.line_delta == 0 {
        return (count, 0, 0);
    }
    (change.start, count - change.new_end, change.line_delta)
}

/// Like [`common_ends`], from what `change` says: the common start and end it gives, each grown by
/// the replaced findings that are equal all the same (an edit that wrote the same finding again).
fn known_ends(
    old: &DiagnosticsArray,
    new: &[LineDiagnostic],
    change: FindingsChange,
) -> (usize, usize, isize) {
    let old_count = new.len() - change.new_end + change.old_end;
    let delta = change.line_delta;
    let replaced_new = &new[change.start..change.new_end];
    let grown_prefix = old_items_from(old, change.start)
        .take(change.old_end - change.start)
        .zip(replaced_new)
        .take_while(|(old, new)| old == new)
        .count();
    let prefix = change.start + grown_prefix;
    if prefix == change.old_end && prefix == change.new_end && delta == 0 {
        // Nothing was replaced by anything else, and nothing moved: the whole list is common.
        return (new.len(), 0, 0);
    }
    let most = (change.old_end - prefix).min(change.new_end - prefix);
    let grown_suffix = old_items_before(old, old_count, change.old_end)
        .zip(new[prefix..change.new_end].iter().rev())
        .take(most)
        .take_while(|(old, new)| {
            old.line.checked_add_signed(delta) == Some(new.line) && old.diagnostic == new.diagnostic
        })
        .count();
    (prefix, new.len() - change.new_end + grown_suffix, delta)
}

/// Writes `object` (a diagnostic's JSON) with `line` as its start and end line; false when the object
/// is not in the expected shape (nothing is written then).
fn write_with_line(out: &mut Vec<u8>, object: &[u8], line: usize) -> bool {
    let Some(rest) = object.strip_prefix(DIAGNOSTIC_JSON_START) else {
        return false;
    };
    let first_digits = rest.iter().take_while(|byte| byte.is_ascii_digit()).count();
    let rest = &rest[first_digits..];
    let Some(end_line) = memchr::memmem::find(rest, DIAGNOSTIC_JSON_END_LINE) else {
        return false;
    };
    let between = &rest[..end_line + DIAGNOSTIC_JSON_END_LINE.len()];
    let after = &rest[between.len()..];
    let second_digits = after
        .iter()
        .take_while(|byte| byte.is_ascii_digit())
        .count();
    out.extend_from_slice(DIAGNOSTIC_JSON_START);
    let _ = write!(out, "{line}");
    out.extend_from_slice(between);
    let _ = write!(out, "{line}");
    out.extend_from_slice(&after[second_digits..]);
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostics::{Code, Diagnostic, Span};
    use crate::lsp::convert::{diagnostics_json, PositionEncoding};
    use std::borrow::Cow;

    struct Random(u64);

    impl Random {
        fn below(&mut self, bound: usize) -> usize {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 % bound.max(1) as u64) as usize
        }
    }

    fn diagnostic(random: &mut Random, line: usize) -> LineDiagnostic {
        let codes = &Code::ALL[..5];
        let start = random.below(30);
        LineDiagnostic {
            line,
            diagnostic: Diagnostic::new(
                codes[random.below(codes.len())],
                Span::new(start, start + random.below(9)),
                format!("finding \"{}\"\n", random.below(4)),
            ),
        }
    }

    fn full(diagnostics: &[LineDiagnostic]) -> Vec<u8> {
        diagnostics_json(
            diagnostics,
            |_| Cow::Borrowed(""),
            true,
            PositionEncoding::Utf16,
        )
    }

    fn findings_every_third_line(random: &mut Random, count: usize) -> Vec<LineDiagnostic> {
        (0..count)
            .map(|index| diagnostic(random, index * 3))
            .collect()
    }

    #[test]
    fn arrays_built_from_the_last_one_equal_arrays_written_anew() {
        // Within one chunk, over a few, and over enough to be written on two threads.
        for count in [100, 300, 3 * PARALLEL_MIN_DIAGNOSTICS / 2] {
            let mut random = Random(0x1234_5678 ^ count as u64);
            let mut diagnostics = findings_every_third_line(&mut random, count);
            let mut array = DiagnosticsArray::build(None, &diagnostics, None, &Columns::Bytes);
            assert_eq!(array.json().to_vec(), full(&diagnostics));
            for step in 0..300 {
                // An edit at one line: its findings change, and the later lines may move.
                let at = random.below(diagnostics.len() + 1);
                let removed = random.below(3).min(diagnostics.len() - at);
                let delta = random.below(5) as isize - 2;
                let base_line = diagnostics.get(at).map_or(1000, |item| item.line);
                let inserted: Vec<LineDiagnostic> = (0..random.below(3))
                    .map(|_| diagnostic(&mut random, base_line))
                    .collect();
                let mut next: Vec<LineDiagnostic> = diagnostics[..at].to_vec();
                next.extend(inserted);
                next.extend(diagnostics[at + removed..].iter().map(|item| {
                    let mut moved = item.clone();
                    moved.line = moved.line.saturating_add_signed(delta).max(base_line);
                    moved
                }));
                match step % 100 {
                    // Every finding goes, and then all come back.
                    50 => next.clear(),
                    51 => next = findings_every_third_line(&mut random, count),
                    // Nothing changes.
                    70 => next = diagnostics.clone(),
                    _ => {}
                }
                let built = DiagnosticsArray::build(Some(&array), &next, None, &Columns::Bytes);
                assert_eq!(
                    String::from_utf8_lossy(&built.json().to_vec()),
                    String::from_utf8_lossy(&full(&next)),
                    "{count} findings, step {step}"
                );
                assert!(built.is_of(&next));
                assert!(next.is_empty() || !built.is_of(&next[1..]));
                array = built;
                diagnostics = next;
            }
        }
    }

    #[test]
    fn an_edit_writes_only_the_chunks_around_it() {
        let mut random = Random(7);
        let diagnostics = findings_every_third_line(&mut random, 10 * CHUNK);
        let array = DiagnosticsArray::build(None, &diagnostics, None, &Columns::Bytes);
        let mut next = diagnostics.clone();
        next[5 * CHUNK + 3] = diagnostic(&mut random, next[5 * CHUNK + 3].line);
        let built = DiagnosticsArray::build(Some(&array), &next, None, &Columns::Bytes);
        let shared = built
            .chunks
            .iter()
            .filter(|chunk| array.chunks.iter().any(|old| Arc::ptr_eq(old, chunk)))
            .count();
        assert_eq!(shared, 9, "every chunk but the changed one is taken over");
        assert_eq!(built.json().to_vec(), full(&next));
        let again = DiagnosticsArray::build(Some(&built), &next, None, &Columns::Bytes);
        assert!(
            again
                .chunks
                .iter()
                .zip(&built.chunks)
                .all(|(new, old)| Arc::ptr_eq(new, old)),
            "nothing changed: every chunk is taken over"
        );
        assert_eq!(again.chunks.len(), built.chunks.len());
    }

    #[test]
    fn arrays_join_also_when_one_is_empty() {
        let join =
            |first: &[u8], second: &[u8]| JsonArray::default().join_array(first).join_array(second);
        assert_eq!(join(b"[1,2]", b"[3]").to_vec(), b"[1,2,3]");
        assert_eq!(join(b"[]", b"[3]").to_vec(), b"[3]");
        assert_eq!(join(b"[1]", b"[]").to_vec(), b"[1]");
        assert_eq!(join(b"[]", b"[]").to_vec(), b"[]");
        assert_eq!(join(b"[1]", b"[]").len(), 3);
        assert_eq!(join(b"[1,2]", b"[3]").len(), 7);
    }

    #[test]
    fn extra_objects_join_the_array() {
        let mut random = Random(3);
        for count in [0, 1, 2 * CHUNK + 5] {
            let diagnostics = findings_every_third_line(&mut random, count);
            let array = DiagnosticsArray::build(None, &diagnostics, None, &Columns::Bytes);
            for extra in [&b"[]"[..], b"[{\"a\":1}]", b"[{\"a\":1},{\"b\":2}]"] {
                let joined = array.json().join_array(extra);
                let value: serde_json::Value = serde_json::from_slice(&joined.to_vec())
                    .unwrap_or_else(|error| panic!("{count} + {extra:?}: {error}"));
                let extra_count = serde_json::from_slice::<Vec<serde_json::Value>>(extra)
                    .unwrap()
                    .len();
                assert_eq!(value.as_array().unwrap().len(), count + extra_count);
            }
        }
    }

    #[test]
    fn line_numbers_of_every_length_are_rewritten() {
        let mut random = Random(99);
        let old: Vec<LineDiagnostic> = [7, 99, 100, 12345]
            .iter()
            .map(|&line| diagnostic(&mut random, line))
            .collect();
        let array = DiagnosticsArray::build(None, &old, None, &Columns::Bytes);
        for delta in [-7isize, 1, 3, 900_000] {
            let new: Vec<LineDiagnostic> = old
                .iter()
                .map(|item| {
                    let mut moved = item.clone();
                    moved.line = item.line.saturating_add_signed(delta);
                    moved
                })
                .collect();
            let built = DiagnosticsArray::build(Some(&array), &new, None, &Columns::Bytes);
            assert_eq!(built.json().to_vec(), full(&new), "delta {delta}");
        }
    }

    /// Arrays built from what the analysis says an edit changed equal arrays written anew, through
    /// edits that insert, remove and change lines with and without findings.
    #[test]
    fn arrays_built_from_the_analysis_s_changes_equal_arrays_written_anew() {
        use crate::analysis::document::{DocumentAnalysis, TextLines};
        use crate::analysis::ProgramKind;
        use crate::config::MachineConfig;
        let mut lines: Vec<String> = (0..4000)
            .map(|index| match index % 4 {
                0 => format!("N{index} G1 X=AC{index} F100"),
                _ => format!("N{index} G1 X{index} F100"),
            })
            .collect();
        let text = |lines: &[String]| lines.join("\n") + "\n";
        let config = std::sync::Arc::new(MachineConfig::mill());
        let mut analysis =
            DocumentAnalysis::new(&TextLines::new(&text(&lines)), config, ProgramKind::Main);
        let mut array =
            DiagnosticsArray::build(None, analysis.diagnostics(), None, &Columns::Bytes);
        let mut revision = analysis.findings_revision();
        let mut random = Random(0xC0FF_EE11);
        let mut known = 0;
        for step in 0..200 {
            let line = random.below(lines.len() - 1);
            let (removed, inserted) = match step % 5 {
                0 => {
                    lines[line].insert(0, ' ');
                    (1, 1)
                }
                1 => {
                    lines.insert(line, format!("N7 X=AC{step}"));
                    (0, 1)
                }
                2 => {
                    lines.remove(line);
                    (1, 0)
                }
                3 => {
                    lines[line] = format!("N{step} X{step}");
                    (1, 1)
                }
                _ => {
                    lines.insert(line, String::new());
                    (0, 1)
                }
            };
            analysis.update(&TextLines::new(&text(&lines)), line, removed, inserted);
            let change = analysis.findings_change_since(revision);
            known += usize::from(change.is_some());
            array = DiagnosticsArray::build(
                Some(&array),
                analysis.diagnostics(),
                change,
                &Columns::Bytes,
            );
            revision = analysis.findings_revision();
            assert!(array.is_of(analysis.diagnostics()), "step {step}");
            assert!(
                array.json().to_vec() == full(analysis.diagnostics()),
                "step {step}: {change:?}"
            );
        }
        assert!(known > 150, "{known} of 200 edits said what they changed");
    }

    /// In a document that is not ASCII, under UTF-16 positions, arrays built from the last one equal
    /// arrays written anew with the lines' texts: through edits that put umlauts and an emoji before
    /// findings on their lines, take them out again, and insert and remove lines.
    #[test]
    fn arrays_of_a_document_that_is_not_ascii_equal_arrays_written_anew() {
        use crate::analysis::document::{DocumentAnalysis, LineSource, TextLines};
        use crate::analysis::ProgramKind;
        use crate::config::MachineConfig;
        let mut lines: Vec<String> = (0..3000)
            .map(|index| match index % 4 {
                0 => format!("N{index} MSG(\"ab\") G1 X=AC{index} F100"),
                1 => format!("N{index} G1 X{index} F100 ; Bohrung für Ø{index}"),
                _ => format!("N{index} G1 X{index} F100"),
            })
            .collect();
        let text = |lines: &[String]| lines.join("\n") + "\n";
        let config = std::sync::Arc::new(MachineConfig::mill());
        let written = |text: &str, analysis: &DocumentAnalysis| {
            let source = TextLines::new(text);
            diagnostics_json(
                analysis.diagnostics(),
                |line| Cow::Owned(source.line(line).into_owned()),
                false,
                PositionEncoding::Utf16,
            )
        };
        let current = text(&lines);
        let mut analysis =
            DocumentAnalysis::new(&TextLines::new(&current), config, ProgramKind::Main);
        let built = |previous: Option<&DiagnosticsArray>,
                     text: &str,
                     analysis: &DocumentAnalysis,
                     change: Option<FindingsChange>| {
            let source = TextLines::new(text);
            let line_text = |line: usize| Cow::Owned(source.line(line).into_owned());
            let columns = Columns::InLine {
                line_text: &line_text,
                encoding: PositionEncoding::Utf16,
            };
            DiagnosticsArray::build(previous, analysis.diagnostics(), change, &columns)
        };
        let mut array = built(None, &current, &analysis, None);
        assert!(array.json().to_vec() == written(&current, &analysis));
        let mut revision = analysis.findings_revision();
        let mut random = Random(0x51DE_C0DE);
        for step in 0..200 {
            let line = random.below(lines.len() - 1);
            let (line, removed, inserted) = match step % 6 {
                // A skip mark and two letters before the findings of the line.
                0 => {
                    lines[line].insert_str(0, "/ab ");
                    (line, 1, 1)
                }
                // Two letters before the findings replaced by an umlaut of the same bytes, or back:
                // the findings' byte spans stay as they were, their UTF-16 columns do not.
                1 => {
                    let (from, to) = match step % 4 {
                        1 => ("MSG(\"ab\")", "MSG(\"ä\")"),
                        _ => ("MSG(\"ä\")", "MSG(\"ab\")"),
                    };
                    let found = (line..lines.len())
                        .chain(0..line)
                        .find(|&index| lines[index].contains(from));
                    let index = found.unwrap_or(line);
                    lines[index] = lines[index].replacen(from, to, 1);
                    (index, 1, 1)
                }
                2 => {
                    lines[line].insert_str(0, "/😀 ");
                    (line, 1, 1)
                }
                3 => {
                    lines.insert(line, format!("N7 X=AC{step} ; Maß"));
                    (line, 0, 1)
                }
                4 => {
                    lines.remove(line);
                    (line, 1, 0)
                }
                _ => {
                    lines[line].insert(0, ' ');
                    (line, 1, 1)
                }
            };
            let current = text(&lines);
            analysis.update(&TextLines::new(&current), line, removed, inserted);
            let change = analysis.findings_change_since(revision);
            array = built(Some(&array), &current, &analysis, change);
            revision = analysis.findings_revision();
            assert!(
                array.json().to_vec() == written(&current, &analysis),
                "step {step}"
            );
        }
        // After the document became ASCII again, byte columns take over what was written before.
        let ascii: Vec<String> = lines
            .iter()
            .map(|line| line.replace(['ä', 'ü', 'ß', 'Ø'], "a").replace('😀', "e"))
            .collect();
        let current = text(&ascii);
        analysis = DocumentAnalysis::new(
            &TextLines::new(&current),
            std::sync::Arc::new(MachineConfig::mill()),
            ProgramKind::Main,
        );
        let next =
            DiagnosticsArray::build(Some(&array), analysis.diagnostics(), None, &Columns::Bytes);
        assert!(next.json().to_vec() == full(analysis.diagnostics()));
    }
}
