//! Renumbering blocks: new block numbers from a start value in steps, for the blocks that carry one
//! (`Keep`), for every block that can (`All`), or only for the blocks a jump targets (`Drop`, which
//! removes the other numbers). Jumps that use block numbers as targets follow their block. Only
//! the parser's block numbers are touched: never strings, comments or an `N` inside a word.

use crate::analysis::document::LineSource;
use crate::config::MachineConfig;
use crate::ide::jumps::{resolve_jump, JumpResolution};
use crate::ide::symbols::{JumpDestination, SymbolTable};
use crate::ide::{LineEdit, Span};
use crate::syntax::ast::{Block, Statement};
use crate::syntax::LineParser;
use std::collections::HashMap;

/// Which blocks carry a number after renumbering.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NumberingMode {
    /// The blocks that have a number now get the new numbers; the others stay without.
    Keep,
    /// Every block with a statement or label gets a number (not the `PROC` line or a `%` header).
    All,
    /// Only blocks that a jump targets (and a numbered `PROC` line) keep a (new) number; every other
    /// number is removed.
    Drop,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RenumberOptions {
    pub start: u64,
    pub step: u64,
    pub mode: NumberingMode,
}

impl Default for RenumberOptions {
    fn default() -> RenumberOptions {
        RenumberOptions {
            start: 10,
            step: 10,
            mode: NumberingMode::Keep,
        }
    }
}

/// Why a program cannot be renumbered as asked.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum RenumberError {
    /// A step of 0, or numbers beyond what a block number can hold.
    InvalidNumbers(String),
    /// A jump to a block number that does not exist would reach one of the new numbers.
    JumpWouldGainTarget { line: usize, value: u64 },
}

impl std::fmt::Display for RenumberError {
    fn fmt(&self, formatter: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RenumberError::InvalidNumbers(message) => formatter.write_str(message),
            RenumberError::JumpWouldGainTarget { line, value } => write!(
                formatter,
                "line {}: the jump to N{value} has no target now, but one of the new block numbers would be N{value}; fix the jump first",
                line + 1
            ),
        }
    }
}

/// The largest block number written; the control's limit is not documented, so block numbers stay
/// in the range of a signed 32-bit integer like other NC integers.
const MAX_BLOCK_NUMBER: u64 = 2_147_483_647;

/// What one line holds for renumbering.
struct LineLayout {
    number: Option<Span>,
    /// Where a new number is inserted: after the skip marker and blanks, else at the first character.
    insert_at: usize,
    numberable: bool,
    /// The `PROC` header: its number is never added or removed, because whether a `PROC` line
    /// starts with a number decides for the analysis whether the file is a subprogram.
    is_procedure: bool,
}

/// The edits that renumber a program.
pub fn renumber(
    source: &dyn LineSource,
    config: &MachineConfig,
    options: RenumberOptions,
) -> Result<Vec<LineEdit>, RenumberError> {
    if options.step == 0 {
        return Err(RenumberError::InvalidNumbers(
            "the step between block numbers must be at least 1".into(),
        ));
    }
    let table = SymbolTable::build(source, config);
    let layouts = line_layouts(source, config, &table);

    // Which numbered lines a jump reaches, and jumps whose target is missing.
    let lines_by_value = table.block_number_lines();
    let mut jump_targets: Vec<(usize, Span, Option<usize>, u64)> = Vec::new();
    for jump in &table.jumps {
        if let JumpDestination::BlockNumber { value, span } = &jump.destination {
            let candidates = lines_by_value.get(value).map(Vec::as_slice).unwrap_or(&[]);
            let target = match resolve_jump(jump.kind, jump.line, candidates) {
                JumpResolution::Found(line) | JumpResolution::WrongDirection(line) => Some(line),
                JumpResolution::Missing => None,
            };
            jump_targets.push((jump.line, *span, target, *value));
        }
    }
    let targeted: std::collections::HashSet<usize> = jump_targets
        .iter()
        .filter_map(|(_, _, target, _)| *target)
        .collect();

    let mut edits = Vec::new();
    let mut new_numbers: HashMap<usize, u64> = HashMap::new();
    let mut next = options.start;
    for (line_index, layout) in layouts.iter().enumerate() {
        let gets_number = match options.mode {
            NumberingMode::Keep => layout.number.is_some(),
            NumberingMode::All => layout.number.is_some() || layout.numberable,
            NumberingMode::Drop => {
                layout.number.is_some() && (targeted.contains(&line_index) || layout.is_procedure)
            }
        };
        match (gets_number, layout.number) {
            (true, number) => {
                if next > MAX_BLOCK_NUMBER {
                    return Err(RenumberError::InvalidNumbers(format!(
                        "block numbers would exceed {MAX_BLOCK_NUMBER}; choose a smaller start or step"
                    )));
                }
                new_numbers.insert(line_index, next);
                match number {
                    // `N` or `:` stays as written; only the digits change.
                    Some(span) => edits.push(LineEdit {
                        line: line_index,
                        span: Span::new(span.start() + 1, span.end()),
                        new_text: next.to_string(),
                    }),
                    None => edits.push(LineEdit {
                        line: line_index,
                        span: Span::new(layout.insert_at, layout.insert_at),
                        new_text: format!("N{next} "),
                    }),
                }
                next = next.saturating_add(options.step);
            }
            (false, Some(span)) => {
                let line = source.line(line_index);
                let mut end = span.end();
                while matches!(line.as_bytes().get(end), Some(b' ' | b'\t')) {
                    end += 1;
                }
                edits.push(LineEdit {
                    line: line_index,
                    span: Span::new(span.start(), end),
                    new_text: String::new(),
                });
            }
            (false, None) => {}
        }
    }
    let new_values: std::collections::HashSet<u64> = new_numbers.values().copied().collect();
    for (line, span, target, value) in jump_targets {
        match target.and_then(|target| new_numbers.get(&target)) {
            Some(new_value) => edits.push(LineEdit {
                line,
                span: Span::new(span.start() + 1, span.end()),
                new_text: new_value.to_string(),
            }),
            None if target.is_none() && new_values.contains(&value) => {
                return Err(RenumberError::JumpWouldGainTarget { line, value })
            }
            None => {}
        }
    }
    // A number that stays as it is is no change: the editor gets only real edits, and none at all
    // for a program that is numbered as asked already.
    edits.retain(|edit| {
        source
            .line(edit.line)
            .get(edit.span.start()..edit.span.end())
            != Some(edit.new_text.as_str())
    });
    Ok(edits)
}

/// Renumbers a whole text and returns the new text (line ends kept).
pub fn renumber_text(
    text: &str,
    config: &MachineConfig,
    options: RenumberOptions,
) -> Result<String, RenumberError> {
    let edits = renumber(
        &crate::analysis::document::TextLines::new(text),
        config,
        options,
    )?;
    Ok(crate::ide::apply_edits(text, &edits))
}

fn line_layouts(
    source: &dyn LineSource,
    config: &MachineConfig,
    table: &SymbolTable,
) -> Vec<LineLayout> {
    let context = table.syntax_context(config);
    let mut parser = LineParser::new();
    let mut block = Block::default();
    let mut diagnostics = Vec::new();
    let mut layouts = Vec::with_capacity(table.line_count);
    source.for_each_line(0, &mut |_, line| {
        parser.parse(line, &context, &mut block, &mut diagnostics);
        let mut insert_at = match block.skip {
            Some((_, span)) => span.end(),
            None => 0,
        };
        while matches!(line.as_bytes().get(insert_at), Some(b' ' | b'\t')) {
            insert_at += 1;
        }
        let is_procedure = block
            .statements
            .iter()
            .any(|statement| matches!(statement, Statement::ProcedureHeader { .. }));
        layouts.push(LineLayout {
            number: block.number.map(|number| number.span),
            insert_at,
            numberable: !block.is_header
                && !is_procedure
                && (!block.statements.is_empty() || block.label.is_some()),
            is_procedure,
        });
        true
    });
    layouts
}

#[cfg(test)]
mod tests {
    use super::*;

    fn renumbered(text: &str, mode: NumberingMode) -> String {
        let options = RenumberOptions {
            start: 1,
            step: 1,
            mode,
        };
        renumber_text(text, &MachineConfig::default(), options).unwrap()
    }

    #[test]
    fn a_program_numbered_as_asked_gets_no_edits() {
        let text = "N1 G0 X1\nN2 IF R1 > 0 GOTOF N4\nN3 G1 X2\nN4 M30\n";
        let options = RenumberOptions {
            start: 1,
            step: 1,
            mode: NumberingMode::All,
        };
        let source = crate::analysis::document::TextLines::new(text);
        let edits = renumber(&source, &MachineConfig::default(), options).unwrap();
        assert_eq!(edits, Vec::new());
        let shifted = RenumberOptions {
            start: 2,
            ..options
        };
        let edits = renumber(&source, &MachineConfig::default(), shifted).unwrap();
        assert_eq!(edits.len(), 5, "four numbers and the jump: {edits:?}");
    }

    #[test]
    fn main_blocks_keep_their_colon_and_skip_markers_come_first() {
        assert_eq!(
            renumbered(":10 G0 X1\nN20 G1 X2\n", NumberingMode::Keep),
            ":1 G0 X1\nN2 G1 X2\n"
        );
        assert_eq!(
            renumbered("/G0 X1\n/2 G1 X2\n; comment\n\nLBL:\n", NumberingMode::All),
            "/N1 G0 X1\n/2 N2 G1 X2\n; comment\n\nN3 LBL:\n"
        );
    }

    #[test]
    fn a_jump_to_a_main_block_follows_it() {
        assert_eq!(
            renumbered("N5 GOTOF N50\n:50 M30\n", NumberingMode::Keep),
            "N1 GOTOF N2\n:2 M30\n"
        );
    }

    #[test]
    fn a_step_of_zero_is_refused() {
        let options = RenumberOptions {
            start: 1,
            step: 0,
            mode: NumberingMode::Keep,
        };
        assert!(renumber_text("N1 G0\n", &MachineConfig::default(), options).is_err());
    }
}
