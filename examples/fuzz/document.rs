//! The document target: a program and a sequence of line edits. After every edit the incremental
//! `DocumentAnalysis::update` must give exactly the diagnostics of `DocumentAnalysis::new` on the new
//! text (and of `check`), and the same block reports and moves with positions equal to 1e-6.
//!
//! A case is written to a file as a small length-prefixed text format, so that any bytes survive:
//! `sinumerik-fuzz-document 1`, then `config`, `kind` and `terminator` lines, `lines COUNT BYTES` with
//! the lines joined by LF, and one `edit FIRST REMOVED COUNT BYTES` header per edit with its lines.

use super::approx::approx_equal;
use super::generate;
use super::random::Random;
use super::targets::{check_move_numbers, first_difference};
use sinumerik_lsp::analysis::document::{DocumentAnalysis, TextLines};
use sinumerik_lsp::analysis::{diagnose_program, ProgramKind};
use sinumerik_lsp::config::MachineConfig;
use std::sync::Arc;

const MAGIC: &str = "sinumerik-fuzz-document 1";

/// One replacement of whole lines: `removed` lines at `first` become `inserted`. Applying clamps the
/// range to the document, so every edit applies to every text (which keeps minimising simple).
#[derive(Debug, Clone, PartialEq)]
pub struct Edit {
    pub first: usize,
    pub removed: usize,
    pub inserted: Vec<String>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct DocumentCase {
    pub turn: bool,
    pub subprogram: bool,
    /// 0: LF, 1: CRLF, 2: CR.
    pub terminator: u8,
    pub lines: Vec<String>,
    pub edits: Vec<Edit>,
}

impl DocumentCase {
    pub fn config(&self) -> Arc<MachineConfig> {
        Arc::new(if self.turn {
            MachineConfig::turn()
        } else {
            MachineConfig::mill()
        })
    }

    pub fn kind(&self) -> ProgramKind {
        if self.subprogram {
            ProgramKind::Subprogram
        } else {
            ProgramKind::Main
        }
    }

    fn terminator_text(&self) -> &'static str {
        match self.terminator {
            1 => "\r\n",
            2 => "\r",
            _ => "\n",
        }
    }

    /// The document text of `lines`, each line ended.
    pub fn join(&self, lines: &[String]) -> String {
        let terminator = self.terminator_text();
        let mut text = String::with_capacity(lines.iter().map(|line| line.len() + 2).sum());
        for line in lines {
            text.push_str(line);
            text.push_str(terminator);
        }
        text
    }

    /// The text after all edits: what the other targets replay for a stored document case.
    pub fn final_text(&self) -> String {
        let mut lines = self.lines.clone();
        for edit in &self.edits {
            apply(&mut lines, edit);
        }
        self.join(&lines)
    }

    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = format!(
            "{MAGIC}\nconfig {}\nkind {}\nterminator {}\n",
            if self.turn { "turn" } else { "mill" },
            if self.subprogram { "sub" } else { "main" },
            self.terminator
        );
        let joined = self.lines.join("\n");
        out.push_str(&format!(
            "lines {} {}\n{joined}\n",
            self.lines.len(),
            joined.len()
        ));
        for edit in &self.edits {
            let joined = edit.inserted.join("\n");
            out.push_str(&format!(
                "edit {} {} {} {}\n{joined}\n",
                edit.first,
                edit.removed,
                edit.inserted.len(),
                joined.len()
            ));
        }
        out.into_bytes()
    }

    /// Reads a case written by [`DocumentCase::to_bytes`]; `None` when the bytes are not one.
    pub fn from_bytes(bytes: &[u8]) -> Option<DocumentCase> {
        let text = std::str::from_utf8(bytes).ok()?;
        let mut rest = text.strip_prefix(MAGIC)?.strip_prefix('\n')?;
        let header = |rest: &mut &str| -> Option<Vec<String>> {
            let end = rest.find('\n')?;
            let fields = rest[..end].split(' ').map(str::to_string).collect();
            *rest = &rest[end + 1..];
            Some(fields)
        };
        let config = header(&mut rest)?;
        let kind = header(&mut rest)?;
        let terminator = header(&mut rest)?;
        let mut case = DocumentCase {
            turn: config.get(1)? == "turn",
            subprogram: kind.get(1)? == "sub",
            terminator: terminator.get(1)?.parse().ok()?,
            lines: Vec::new(),
            edits: Vec::new(),
        };
        let take_lines = |rest: &mut &str, count: usize, length: usize| -> Option<Vec<String>> {
            let body = rest.get(..length)?;
            *rest = rest.get(length..)?.strip_prefix('\n')?;
            let lines: Vec<String> = if count == 0 {
                Vec::new()
            } else {
                body.split('\n').map(str::to_string).collect()
            };
            (lines.len() == count).then_some(lines)
        };
        let fields = header(&mut rest)?;
        case.lines = take_lines(
            &mut rest,
            fields.get(1)?.parse().ok()?,
            fields.get(2)?.parse().ok()?,
        )?;
        while !rest.is_empty() {
            let fields = header(&mut rest)?;
            let number = |index: usize| -> Option<usize> { fields.get(index)?.parse().ok() };
            let (first, removed) = (number(1)?, number(2)?);
            let inserted = take_lines(&mut rest, number(3)?, number(4)?)?;
            case.edits.push(Edit {
                first,
                removed,
                inserted,
            });
        }
        Some(case)
    }
}

/// Applies `edit` to `lines` with its range clamped to them; returns the range actually replaced
/// (first line, lines removed, lines inserted).
pub fn apply(lines: &mut Vec<String>, edit: &Edit) -> (usize, usize, usize) {
    let first = edit.first.min(lines.len());
    let removed = edit.removed.min(lines.len() - first);
    lines.splice(first..first + removed, edit.inserted.iter().cloned());
    (first, removed, edit.inserted.len())
}

/// A random case: a start program (a seed, a generated one, or a mix) and up to `max_edits` edits.
pub fn generate_case(random: &mut Random, seed_lines: &[String], max_edits: usize) -> DocumentCase {
    let mut lines = if seed_lines.is_empty() || random.one_in(4) {
        generate::program(random, 3_000)
    } else {
        let start = random.below(seed_lines.len());
        let count = random.length(600, 4_000).max(1);
        seed_lines[start..(start + count).min(seed_lines.len())].to_vec()
    };
    if random.one_in(3) {
        generate::mutate_lines(random, &mut lines, seed_lines);
    }
    // Lines never hold line ends: a generated piece with one becomes two lines.
    let lines = split_all(&lines);
    let edit_count = 1 + random.below(max_edits.max(1));
    let mut current = lines.clone();
    let mut edits = Vec::with_capacity(edit_count);
    for _ in 0..edit_count {
        let edit = random_edit(random, &current, seed_lines);
        apply(&mut current, &edit);
        edits.push(edit);
    }
    DocumentCase {
        turn: random.one_in(3),
        subprogram: random.one_in(4),
        terminator: *random.pick(&[0, 0, 0, 1, 2]),
        lines,
        edits,
    }
}

/// One edit of the kind an editor sends: typing in one line (most often a changed number), deleting or
/// pasting lines, or replacing a few lines with generated blocks.
pub fn random_edit(random: &mut Random, lines: &[String], donor: &[String]) -> Edit {
    let first = random.below(lines.len() + 1);
    let available = lines.len() - first;
    let removed = match random.below(6) {
        0 => 0,
        1..=3 => available.min(1),
        4 => available.min(random.length(4, 40)),
        _ => available.min(random.length(2, 3_000)),
    };
    let inserted: Vec<String> = match random.below(8) {
        // Typing: the removed lines come back changed.
        0..=3 if removed > 0 => lines[first..first + removed]
            .iter()
            .map(|line| {
                if random.one_in(2) {
                    generate::mutate_line(random, line)
                } else {
                    line.clone()
                }
            })
            .collect(),
        4 if !donor.is_empty() => {
            let start = random.below(donor.len());
            let count = random.length(3, 600);
            donor[start..(start + count).min(donor.len())].to_vec()
        }
        _ => (0..random.length(2, 40))
            .map(|_| generate::block(random))
            .collect(),
    };
    Edit {
        first,
        removed,
        inserted: split_all(&inserted),
    }
}

fn split_all(lines: &[String]) -> Vec<String> {
    let mut out = Vec::with_capacity(lines.len());
    for line in lines {
        if line.contains(['\n', '\r']) {
            let pieces = super::seeds::split_lines(line);
            if pieces.is_empty() {
                out.push(String::new());
            }
            out.extend(pieces);
        } else {
            out.push(line.clone());
        }
    }
    out
}

/// Runs the edits of `case` and compares the incremental analysis with a fresh one after each.
/// Returns how many edit steps were checked.
pub fn check_document(case: &DocumentCase) -> Result<usize, String> {
    let config = case.config();
    let kind = case.kind();
    let mut lines = case.lines.clone();
    let text = case.join(&lines);
    let mut analysis = DocumentAnalysis::new(&TextLines::new(&text), config.clone(), kind);
    for (step, edit) in case.edits.iter().enumerate() {
        let (first, removed, inserted) = apply(&mut lines, edit);
        let text = case.join(&lines);
        let source = TextLines::new(&text);
        analysis.update(&source, first, removed, inserted);
        let fresh = DocumentAnalysis::new(&source, config.clone(), kind);
        let at = |problem: String| {
            format!("step {step} (replacing {removed} lines at {first} by {inserted}): {problem}")
        };
        if analysis.diagnostics() != fresh.diagnostics() {
            return Err(at(format!(
                "the incremental diagnostics differ from a fresh analysis {}",
                first_difference(analysis.diagnostics(), fresh.diagnostics())
            )));
        }
        // The checker's whole-program pass is slower; once every few steps is enough to tie both.
        if step % 8 == 0 || step + 1 == case.edits.len() {
            let checked = diagnose_program(&text, &config, kind);
            if analysis.diagnostics() != checked.as_slice() {
                return Err(at(format!(
                    "the document's diagnostics differ from check's {}",
                    first_difference(analysis.diagnostics(), &checked)
                )));
            }
        }
        let line_count = lines.len();
        let probes = [
            first.saturating_sub(1),
            first,
            first + inserted,
            line_count.saturating_sub(1),
            line_count,
            (first * 7 + step * 131) % (line_count + 1),
        ];
        for line in probes {
            let report = analysis.block_report(&source, line);
            check_finite_debug(&report)
                .map_err(|problem| at(format!("block report of line {}: {problem}", line + 1)))?;
            approx_equal(&report, &fresh.block_report(&source, line), 1e-6)
                .map_err(|problem| at(format!("block report of line {}: {problem}", line + 1)))?;
        }
        let range = first.saturating_sub(3)..(first + inserted + 600).min(line_count);
        let incremental = analysis.moves(&source, range.clone());
        let expected = fresh.moves(&source, range);
        if incremental.len() != expected.len() {
            return Err(at(format!(
                "{} moves instead of {}",
                incremental.len(),
                expected.len()
            )));
        }
        for (incremental, expected) in incremental.iter().zip(&expected) {
            check_move_numbers(incremental).map_err(at)?;
            approx_equal(incremental, expected, 1e-6)
                .map_err(|problem| at(format!("move of line {}: {problem}", expected.line + 1)))?;
        }
    }
    Ok(case.edits.len())
}

/// A hover shows numbers only where they are known: no NaN or infinity anywhere in a block report
/// (states before and after, the move, every word's resolution).
pub fn check_finite_debug(value: &impl std::fmt::Debug) -> Result<(), String> {
    let text = format!("{value:?}");
    let bytes = text.as_bytes();
    let is_word = |byte: u8| byte.is_ascii_alphanumeric() || byte == b'_';
    for word in ["NaN", "inf"] {
        for (at, _) in text.match_indices(word) {
            let before = at.checked_sub(1).map(|index| bytes[index]);
            let after = bytes.get(at + word.len()).copied();
            if !before.is_some_and(is_word) && !after.is_some_and(is_word) {
                let mut from = at.saturating_sub(80);
                while !text.is_char_boundary(from) {
                    from -= 1;
                }
                return Err(format!("shows {word}: …{}", &text[from..at + word.len()]));
            }
        }
    }
    Ok(())
}
