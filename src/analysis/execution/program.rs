//! One program as the interpreter runs it: its text split into blocks, and the index of where control
//! can go (labels, block numbers, the partners of every control structure), built once per program.

use crate::config::MachineConfig;
use crate::syntax::ast::{Block, Statement, StructureKeyword};
use crate::syntax::{lines, macro_names, LineParser, SyntaxContext};
use std::collections::HashMap;
use std::sync::Arc;

/// Where the other keywords of a control structure are, by the line of each keyword.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Partner {
    /// An `IF`: its `ELSE` (if any) and its `ENDIF`.
    If {
        otherwise: Option<usize>,
        end: usize,
    },
    /// An `ELSE`: the `ENDIF` of its `IF`.
    Else { end: usize },
    /// A loop opener (`WHILE`, `FOR`, `REPEAT`, `LOOP`): its closer.
    Opens { end: usize },
    /// A loop closer (`ENDWHILE`, `ENDFOR`, `UNTIL`, `ENDLOOP`): its opener.
    Closes { start: usize },
}

/// Where control can go in one program.
#[derive(Debug, Clone, Default)]
pub struct FlowIndex {
    /// The lines that carry each label (upper case), in ascending order.
    labels: HashMap<String, Vec<usize>>,
    /// The lines that carry each block number, in ascending order.
    block_numbers: HashMap<u64, Vec<usize>>,
    /// The partners of every structure keyword whose nesting is sound.
    partners: HashMap<usize, Partner>,
    /// Whether the program has anything that makes execution differ from program order: labels,
    /// jumps, control structures, calls, returns or program ends before the last block.
    pub has_flow: bool,
    /// The first line after the definition part (DEF, DEFINE, PROC and comments): where `GOTOS`
    /// starts again.
    pub first_executable: usize,
}

impl FlowIndex {
    /// The lines carrying `label` (upper case).
    pub fn label_lines(&self, label: &str) -> &[usize] {
        self.labels.get(label).map_or(&[], Vec::as_slice)
    }

    /// The lines carrying block number `value`.
    pub fn block_number_lines(&self, value: u64) -> &[usize] {
        self.block_numbers.get(&value).map_or(&[], Vec::as_slice)
    }

    /// The partners of the structure keyword on `line`, when its nesting is sound.
    pub fn partner(&self, line: usize) -> Option<Partner> {
        self.partners.get(&line).copied()
    }
}

/// One program: its name, where it came from, its text and its flow index.
#[derive(Debug)]
pub struct ProgramUnit {
    /// The upper-case name a call uses (empty for the analysed program when it has no name).
    pub name: String,
    /// Where the program was found; `None` for the program being analysed.
    pub path: Option<Arc<str>>,
    text: Arc<str>,
    lines: Vec<(u32, u32)>,
    pub flow: FlowIndex,
    context: SyntaxContext,
}

impl ProgramUnit {
    /// Reads `text` as a program: its lines, and the flow index from one parse of every line.
    pub fn new(
        name: String,
        path: Option<Arc<str>>,
        text: Arc<str>,
        config: &MachineConfig,
    ) -> ProgramUnit {
        ProgramUnit::with_macro_names(name, path, text, config, std::iter::empty())
    }

    /// Like [`ProgramUnit::new`], with the names of macros defined outside the program (the
    /// library's definition files) known to its parser as well.
    pub fn with_macro_names<'n>(
        name: String,
        path: Option<Arc<str>>,
        text: Arc<str>,
        config: &MachineConfig,
        outside: impl Iterator<Item = &'n str>,
    ) -> ProgramUnit {
        let lines: Vec<(u32, u32)> = lines::line_ranges(&text)
            .map(|(start, end)| (start as u32, end as u32))
            .collect();
        let mut context = SyntaxContext::new(config);
        for name in outside {
            context.add_macro(name);
        }
        for name in macro_names(&text) {
            context.add_macro(name);
        }
        let mut unit = ProgramUnit {
            name,
            path,
            text,
            lines,
            flow: FlowIndex::default(),
            context,
        };
        unit.flow = unit.build_flow_index();
        unit
    }

    /// The program `text`, which differs from `earlier` only in lines where [`Self::same_flow`]
    /// holds: the flow index and the macros of `earlier` are its own.
    pub fn with_flow_of(earlier: &ProgramUnit, text: Arc<str>) -> ProgramUnit {
        let lines: Vec<(u32, u32)> = lines::line_ranges(&text)
            .map(|(start, end)| (start as u32, end as u32))
            .collect();
        ProgramUnit {
            name: earlier.name.clone(),
            path: earlier.path.clone(),
            text,
            lines,
            flow: earlier.flow.clone(),
            context: earlier.context.clone(),
        }
    }

    /// Whether line `index` of this program and line `other_index` of `other` play the same part
    /// in the program's flow: both are blocks of G functions, addresses (no program end) and
    /// assignments only, with the same label and block number. Their values may differ.
    pub fn same_flow(
        &self,
        index: usize,
        other: &ProgramUnit,
        other_index: usize,
        parser: &mut LineParser,
    ) -> bool {
        let mut mine = Block::default();
        let mut theirs = Block::default();
        self.parse(parser, index, &mut mine);
        other.parse(parser, other_index, &mut theirs);
        let label = |unit: &ProgramUnit, line: usize, block: &Block| {
            block
                .label
                .map(|label| unit.line(line)[label.start()..label.end()].to_ascii_uppercase())
        };
        plain_block(&mine)
            && plain_block(&theirs)
            && mine.number.map(|number| number.value) == theirs.number.map(|number| number.value)
            && label(self, index, &mine) == label(other, other_index, &theirs)
    }

    /// The text of the whole program.
    pub fn text(&self) -> &Arc<str> {
        &self.text
    }

    /// Whether the program is a subprogram by its `PROC` line.
    pub fn has_proc_header(&self) -> bool {
        crate::analysis::program_kind::has_proc_header(&self.text)
    }

    pub fn line_count(&self) -> usize {
        self.lines.len()
    }

    /// The text of line `index` without its terminator.
    pub fn line(&self, index: usize) -> &str {
        match self.lines.get(index) {
            Some(&(start, end)) => &self.text[start as usize..end as usize],
            None => "",
        }
    }

    /// Parses line `index` into `block` (its syntax findings are dropped: the program's linear
    /// reading reports them).
    pub fn parse(&self, parser: &mut LineParser, index: usize, block: &mut Block) {
        let mut findings = Vec::new();
        parser.parse(self.line(index), &self.context, block, &mut findings);
    }

    fn build_flow_index(&self) -> FlowIndex {
        let mut builder = FlowBuilder::new(self.line_count());
        for index in 0..self.line_count() {
            builder.line(index, self.line(index), &self.context);
        }
        builder.finish(self.line_count())
    }
}

/// The flow index built line by line in program order: by [`ProgramUnit`] over its text, and by
/// [`lines_have_flow`] over lines that are not one text (an editor's rope).
struct FlowBuilder {
    flow: FlowIndex,
    parser: LineParser,
    block: Block,
    /// Open structures: (keyword, line, the ELSE line of an IF).
    open: Vec<(StructureKeyword, usize, Option<usize>)>,
    broken: bool,
    in_definitions: bool,
    /// The block numbers in program order; indexed only when something can jump to them.
    numbered: Vec<(u64, usize)>,
    last_line: usize,
}

impl FlowBuilder {
    fn new(line_count: usize) -> FlowBuilder {
        FlowBuilder {
            flow: FlowIndex::default(),
            parser: LineParser::new(),
            block: Block::default(),
            open: Vec::new(),
            broken: false,
            in_definitions: true,
            numbered: Vec::new(),
            last_line: line_count.saturating_sub(1),
        }
    }

    /// Takes line `index` (its text without the terminator), the lines before it taken already.
    fn line(&mut self, index: usize, text: &str, context: &SyntaxContext) {
        let mut findings = Vec::new();
        self.parser
            .parse(text, context, &mut self.block, &mut findings);
        let flow = &mut self.flow;
        if let Some(label) = self.block.label {
            let name = text[label.start()..label.end()].to_ascii_uppercase();
            flow.labels.entry(name).or_default().push(index);
            flow.has_flow = true;
        }
        if let Some(number) = self.block.number {
            self.numbered.push((number.value, index));
        }
        let statements = self.block.interpreted_statements();
        let mut executable = false;
        for statement in statements {
            match statement {
                Statement::Definition { .. }
                | Statement::MacroDefinition { .. }
                | Statement::ProcedureHeader { .. }
                | Statement::ExternDeclaration { .. } => {}
                _ => executable = true,
            }
            match statement {
                Statement::Structure { keyword, .. } => {
                    flow.has_flow = true;
                    self.broken |= !link_structure(flow, &mut self.open, *keyword, index);
                }
                Statement::Jump { .. }
                | Statement::Call { .. }
                | Statement::Return { .. }
                | Statement::Instruction { .. } => flow.has_flow = true,
                Statement::Address(word) if index != self.last_line => {
                    flow.has_flow |=
                        crate::analysis::execution::outcome::ends_program(word).is_some();
                }
                _ => {}
            }
        }
        if self.in_definitions && executable {
            self.in_definitions = false;
            flow.first_executable = index;
        }
    }

    fn finish(mut self, line_count: usize) -> FlowIndex {
        let flow = &mut self.flow;
        if self.in_definitions {
            flow.first_executable = line_count;
        }
        if self.broken || !self.open.is_empty() {
            // Structures that do not nest soundly are reported by the syntax check (12640); the
            // interpreter does not follow them: their lines have no partners.
            flow.partners.retain(|_, _| false);
            flow.has_flow = true;
        }
        // A program without flow runs in order: nothing jumps to a block number, and a CAM program
        // numbers every block (a million entries to build and free for nothing).
        if flow.has_flow {
            for (value, index) in self.numbered {
                flow.block_numbers.entry(value).or_default().push(index);
            }
        }
        self.flow
    }
}

/// A walk over a program's lines in order: it hands each line (index, text without terminator) to the
/// visitor until the visitor returns false or the lines end.
pub type LineWalk<'a> = &'a dyn Fn(&mut dyn FnMut(usize, &str) -> bool);

/// Whether the program whose `line_count` lines `walk` hands out in order (stopping when the visitor
/// returns false) has flow, as [`ProgramUnit`]'s `flow.has_flow` would say, with the names of macros
/// defined outside it (`outside`): read without a copy of the text, which for a large program open
/// in the editor is tens of MB. It stops at the first line with flow: a flow that was found stays.
pub fn lines_have_flow<'n>(
    line_count: usize,
    walk: LineWalk<'_>,
    config: &MachineConfig,
    outside: impl Iterator<Item = &'n str>,
) -> bool {
    let mut context = SyntaxContext::new(config);
    for name in outside {
        context.add_macro(name);
    }
    // A macro may be used before the line that defines it: all definitions first, as with a text.
    walk(&mut |_, line| {
        for name in macro_names(line) {
            context.add_macro(name);
        }
        true
    });
    let mut builder = FlowBuilder::new(line_count);
    walk(&mut |index, line| {
        builder.line(index, line, &context);
        !builder.flow.has_flow
    });
    builder.finish(line_count).has_flow
}

/// Whether a block has nothing the interpreter treats as flow: only G functions, addresses that do
/// not end the program, and assignments, without synchronized actions.
fn plain_block(block: &Block) -> bool {
    block.sync_actions_from.is_none()
        && block.statements.iter().all(|statement| match statement {
            Statement::GCode { .. } | Statement::UnknownGCode { .. } => true,
            Statement::Assignment { .. } => true,
            Statement::Address(word) => {
                crate::analysis::execution::outcome::ends_program(word).is_none()
            }
            _ => false,
        })
}

/// Records the partners of a structure keyword on `line`; false when the nesting is broken.
fn link_structure(
    flow: &mut FlowIndex,
    open: &mut Vec<(StructureKeyword, usize, Option<usize>)>,
    keyword: StructureKeyword,
    line: usize,
) -> bool {
    use StructureKeyword::*;
    match keyword {
        If | While | For | Repeat | Loop => {
            open.push((keyword, line, None));
            true
        }
        Else => match open.last_mut() {
            Some((If, _, otherwise @ None)) => {
                *otherwise = Some(line);
                true
            }
            _ => false,
        },
        EndIf | EndWhile | EndFor | Until | EndLoop => {
            let opener = match keyword {
                EndIf => If,
                EndWhile => While,
                EndFor => For,
                Until => Repeat,
                _ => Loop,
            };
            match open.pop() {
                Some((found, start, otherwise)) if found == opener => {
                    if opener == If {
                        flow.partners.insert(
                            start,
                            Partner::If {
                                otherwise,
                                end: line,
                            },
                        );
                        if let Some(otherwise) = otherwise {
                            flow.partners.insert(otherwise, Partner::Else { end: line });
                        }
                    } else {
                        flow.partners.insert(start, Partner::Opens { end: line });
                        flow.partners.insert(line, Partner::Closes { start });
                    }
                    true
                }
                _ => false,
            }
        }
        Case => true,
    }
}
