//! The outline of a document: its symbols as a tree (the `PROC`, comment sections, labels, blocks
//! that change the tool), folding ranges (IF/ELSE/ENDIF, WHILE, FOR, REPEAT/UNTIL, LOOP, CASE and
//! comment sections), and document highlights (a label and its jumps, a variable and its uses).

use crate::diagnostics::Span;
use crate::ide::symbols::{JumpDestination, SymbolTable};
use crate::syntax::ast::StructureKeyword;

pub use crate::ide::navigation::highlights as document_highlights;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutlineKind {
    Procedure,
    Section,
    Label,
    ToolChange,
}

/// One entry of the outline with the lines it covers and the name to select.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OutlineItem {
    pub name: String,
    pub detail: String,
    pub kind: OutlineKind,
    /// First and last line (inclusive) the entry covers.
    pub lines: (usize, usize),
    pub selection_line: usize,
    pub selection_span: Span,
    pub children: Vec<OutlineItem>,
}

/// The document symbols: the `PROC` (if any) holds the sections, which hold the labels and tool
/// changes that follow them.
pub fn document_symbols(table: &SymbolTable) -> Vec<OutlineItem> {
    let last_line = table.line_count.saturating_sub(1);
    let mut leaves: Vec<OutlineItem> = Vec::new();
    for label in &table.labels {
        leaves.push(OutlineItem {
            name: label.name.clone(),
            detail: "label".to_string(),
            kind: OutlineKind::Label,
            lines: (label.line, label.line),
            selection_line: label.line,
            selection_span: label.span,
            children: Vec::new(),
        });
    }
    for change in &table.tool_changes {
        leaves.push(OutlineItem {
            name: change.text.clone(),
            detail: "tool change".to_string(),
            kind: OutlineKind::ToolChange,
            lines: (change.line, change.line),
            selection_line: change.line,
            selection_span: change.span,
            children: Vec::new(),
        });
    }
    leaves.sort_by_key(|item| (item.lines.0, item.selection_span.start()));
    let mut top: Vec<OutlineItem> = Vec::new();
    let mut leaves = leaves.into_iter().peekable();
    for (position, section) in table.sections.iter().enumerate() {
        let end = table
            .sections
            .get(position + 1)
            .map_or(last_line, |next| next.line.saturating_sub(1));
        while let Some(leaf) = leaves.next_if(|leaf| leaf.lines.0 < section.line) {
            top.push(leaf);
        }
        let mut children = Vec::new();
        while let Some(leaf) = leaves.next_if(|leaf| leaf.lines.0 <= end) {
            children.push(leaf);
        }
        top.push(OutlineItem {
            name: section.title.clone(),
            detail: "section".to_string(),
            kind: OutlineKind::Section,
            lines: (section.line, end.max(section.line)),
            selection_line: section.title_line,
            selection_span: Span::new(0, 0),
            children,
        });
    }
    top.extend(leaves);
    match &table.procedure {
        Some(procedure) => {
            let parameters: Vec<String> = procedure
                .parameters
                .iter()
                .map(|parameter| parameter.name.clone())
                .collect();
            vec![OutlineItem {
                name: procedure.name.clone(),
                detail: format!("PROC({})", parameters.join(", ")),
                kind: OutlineKind::Procedure,
                lines: (procedure.line, last_line.max(procedure.line)),
                selection_line: procedure.line,
                selection_span: procedure.span,
                children: top,
            }]
        }
        None => top,
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FoldingKind {
    /// A control structure.
    Structure,
    /// A section introduced by a comment title.
    Section,
}

/// A range of lines that can be folded; the last line stays visible (the closing keyword).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FoldingRange {
    pub start_line: usize,
    pub end_line: usize,
    pub kind: FoldingKind,
}

/// The folding ranges of a document, sorted by start line.
pub fn folding_ranges(table: &SymbolTable) -> Vec<FoldingRange> {
    let mut out = Vec::new();
    let push =
        |out: &mut Vec<FoldingRange>, start_line: usize, end_line: usize, kind: FoldingKind| {
            if end_line > start_line {
                out.push(FoldingRange {
                    start_line,
                    end_line,
                    kind,
                });
            }
        };
    // Open structures: (keyword, line where the current part starts).
    let mut open: Vec<(StructureKeyword, usize)> = Vec::new();
    for mark in &table.structures {
        match mark.keyword {
            StructureKeyword::Else => {
                if let Some(top) = open.last_mut().filter(|top| top.0 == StructureKeyword::If) {
                    push(
                        &mut out,
                        top.1,
                        mark.line.saturating_sub(1),
                        FoldingKind::Structure,
                    );
                    top.1 = mark.line;
                }
            }
            StructureKeyword::Case => {
                // The branches of a CASE run from its block to the last label it jumps to.
                let last_target = table
                    .jumps
                    .iter()
                    .filter(|jump| jump.in_case && jump.line == mark.line)
                    .filter_map(|jump| match &jump.destination {
                        JumpDestination::Label { name, .. } => table
                            .labels
                            .iter()
                            .find(|label| &label.name == name && label.line > mark.line)
                            .map(|label| label.line),
                        _ => None,
                    })
                    .max();
                if let Some(last_target) = last_target {
                    push(
                        &mut out,
                        mark.line,
                        last_target.saturating_sub(1),
                        FoldingKind::Structure,
                    );
                }
            }
            keyword if crate::syntax::structure::closer(keyword).is_some() => {
                open.push((keyword, mark.line))
            }
            closing => {
                if let Some(position) = open.iter().rposition(|(keyword, _)| {
                    crate::syntax::structure::closer(*keyword) == Some(closing)
                }) {
                    let start = open[position].1;
                    open.truncate(position);
                    push(
                        &mut out,
                        start,
                        mark.line.saturating_sub(1),
                        FoldingKind::Structure,
                    );
                }
            }
        }
    }
    let last_line = table.line_count.saturating_sub(1);
    for (position, section) in table.sections.iter().enumerate() {
        let end = table
            .sections
            .get(position + 1)
            .map_or(last_line, |next| next.line.saturating_sub(1));
        push(&mut out, section.line, end, FoldingKind::Section);
    }
    out.sort_by_key(|range| (range.start_line, std::cmp::Reverse(range.end_line)));
    out
}
