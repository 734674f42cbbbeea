//! The JSON array of a document's diagnostics as last published, and the next array built from it.
//! A large program has tens of thousands of findings and every version must carry all of them, but an
//! edit changes only a few: in an ASCII document a diagnostic's JSON depends on the diagnostic alone,
//! so the objects before and after the changed ones are copied as bytes, and those after an inserted
//! or removed line get only their line numbers rewritten.

use crate::diagnostics::LineDiagnostic;
use crate::lsp::convert::{
    ascii_range, write_diagnostic_json, DIAGNOSTIC_JSON_END_LINE, DIAGNOSTIC_JSON_START,
};
use std::io::Write;
use std::sync::Arc;

/// A written array of the diagnostics of an ASCII document.
pub struct DiagnosticsArray {
    diagnostics: Vec<LineDiagnostic>,
    json: Arc<Vec<u8>>,
    /// Where each diagnostic's object starts in `json`.
    starts: Vec<usize>,
}

impl DiagnosticsArray {
    /// The JSON text: `[`, the objects separated by commas, `]`.
    pub fn json(&self) -> &Arc<Vec<u8>> {
        &self.json
    }

    /// The array of `diagnostics` (of an ASCII document), reusing what `previous` wrote.
    pub fn build(previous: Option<&DiagnosticsArray>, diagnostics: &[LineDiagnostic]) -> Self {
        let mut writer = Writer {
            json: Vec::with_capacity(previous.map_or(2 + diagnostics.len() * 200, |previous| {
                previous.json.len() + previous.json.len() / 8 + 1024
            })),
            starts: Vec::with_capacity(diagnostics.len()),
        };
        writer.json.push(b'[');
        let (prefix, suffix, delta) = match previous {
            Some(previous) => common_ends(&previous.diagnostics, diagnostics),
            None => (0, 0, 0),
        };
        if let Some(previous) = previous {
            writer.copy(previous, 0..prefix);
        }
        for item in &diagnostics[prefix..diagnostics.len() - suffix] {
            writer.begin_object();
            write_diagnostic_json(&mut writer.json, ascii_range(item), item);
        }
        if let Some(previous) = previous {
            let old_suffix = previous.diagnostics.len() - suffix..previous.diagnostics.len();
            if delta == 0 {
                writer.copy(previous, old_suffix);
            } else {
                let new_lines = diagnostics[diagnostics.len() - suffix..]
                    .iter()
                    .map(|item| item.line);
                for (old, line) in old_suffix.zip(new_lines) {
                    writer.begin_object();
                    let object = previous.object(old);
                    if !write_with_line(&mut writer.json, object, line) {
                        let item =
                            &diagnostics[old + diagnostics.len() - previous.diagnostics.len()];
                        write_diagnostic_json(&mut writer.json, ascii_range(item), item);
                    }
                }
            }
        }
        writer.json.push(b']');
        DiagnosticsArray {
            diagnostics: diagnostics.to_vec(),
            json: Arc::new(writer.json),
            starts: writer.starts,
        }
    }

    /// Whether the array is that of exactly `diagnostics`.
    pub fn is_of(&self, diagnostics: &[LineDiagnostic]) -> bool {
        self.diagnostics == diagnostics
    }

    fn object(&self, index: usize) -> &[u8] {
        let end = match self.starts.get(index + 1) {
            Some(next) => next - 1,
            None => self.json.len() - 1,
        };
        &self.json[self.starts[index]..end]
    }
}

struct Writer {
    json: Vec<u8>,
    starts: Vec<usize>,
}

impl Writer {
    fn begin_object(&mut self) {
        if !self.starts.is_empty() {
            self.json.push(b',');
        }
        self.starts.push(self.json.len());
    }

    /// Copies the objects `range` of `previous` in one piece.
    fn copy(&mut self, previous: &DiagnosticsArray, range: std::ops::Range<usize>) {
        if range.is_empty() {
            return;
        }
        if !self.starts.is_empty() {
            self.json.push(b',');
        }
        let from = previous.starts[range.start];
        let to = previous.starts[range.end - 1] + previous.object(range.end - 1).len();
        let base = self.json.len();
        self.json.extend_from_slice(&previous.json[from..to]);
        self.starts.extend(
            previous.starts[range]
                .iter()
                .map(|start| start - from + base),
        );
    }
}

/// How many diagnostics `old` and `new` share at the start, how many at the end (where the new ones
/// may all be `delta` lines further), and that `delta`.
fn common_ends(old: &[LineDiagnostic], new: &[LineDiagnostic]) -> (usize, usize, isize) {
    let prefix = old
        .iter()
        .zip(new)
        .take_while(|(old, new)| old == new)
        .count();
    let (Some(old_last), Some(new_last)) = (old.last(), new.last()) else {
        return (prefix, 0, 0);
    };
    let delta = new_last.line as isize - old_last.line as isize;
    let most = old.len().min(new.len()) - prefix;
    let suffix = old
        .iter()
        .rev()
        .zip(new.iter().rev())
        .take(most)
        .take_while(|(old, new)| {
            old.line.checked_add_signed(delta) == Some(new.line) && old.diagnostic == new.diagnostic
        })
        .count();
    (prefix, suffix, delta)
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

    #[test]
    fn arrays_built_from_the_last_one_equal_arrays_written_anew() {
        let mut random = Random(0x1234_5678);
        let mut lines_with_findings: Vec<usize> = (0..300).map(|line| line * 3).collect();
        let mut diagnostics: Vec<LineDiagnostic> = lines_with_findings
            .iter()
            .map(|&line| diagnostic(&mut random, line))
            .collect();
        let mut array = DiagnosticsArray::build(None, &diagnostics);
        assert_eq!(**array.json(), full(&diagnostics));
        for step in 0..400 {
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
            if step % 50 == 0 {
                next.clear();
            }
            let built = DiagnosticsArray::build(Some(&array), &next);
            assert_eq!(
                String::from_utf8_lossy(built.json()),
                String::from_utf8_lossy(&full(&next)),
                "step {step}"
            );
            assert!(built.is_of(&next));
            array = built;
            diagnostics = next;
            lines_with_findings.clear();
        }
    }

    #[test]
    fn line_numbers_of_every_length_are_rewritten() {
        let mut random = Random(99);
        let old: Vec<LineDiagnostic> = [7, 99, 100, 12345]
            .iter()
            .map(|&line| diagnostic(&mut random, line))
            .collect();
        let array = DiagnosticsArray::build(None, &old);
        for delta in [-7isize, 1, 3, 900_000] {
            let new: Vec<LineDiagnostic> = old
                .iter()
                .map(|item| {
                    let mut moved = item.clone();
                    moved.line = item.line.saturating_add_signed(delta);
                    moved
                })
                .collect();
            let built = DiagnosticsArray::build(Some(&array), &new);
            assert_eq!(**built.json(), full(&new), "delta {delta}");
        }
    }
}
