//! The symbol table of one document: labels, block numbers, `DEF` variables, R parameters, the `PROC`
//! header, `DEFINE` macros, `EXTERN` declarations, calls, jumps, tool changes, comment sections and
//! the names read or written as variables. Everything comes from the parser's blocks; the type of a
//! `DEF` and the types of `PROC` parameters are described as written (`STRING[32]`, `VAR REAL`), from
//! the lexer's tokens of the statement.

use crate::analysis::document::LineSource;
use crate::config::MachineConfig;
use crate::diagnostics::{Code, Span};
use crate::ide::comment_sections::{
    classify_comment_line, documentation_above, find_sections, CommentLine,
};
use crate::ide::names::{
    expressions_outside_declarations, identifier_prefix, is_type_name, text_of, upper,
};
pub use crate::ide::statement_text::is_executable;
use crate::ide::statement_text::{
    bracket_text, describe_parameters, extern_parameter_types, indirect_program_name,
    jump_keyword_before,
};
pub use crate::ide::symbol_types::{
    BlockNumberEntry, BlockNumbers, CallSite, CallStyle, CommentSection, ExternDeclaration,
    JumpDestination, JumpSite, LabelDefinition, MacroDefinition, NameUse, Parameter,
    ProcedureDefinition, RParameterUse, StructureMark, SymbolTable, ToolChange, VariableDefinition,
};
use crate::syntax::ast::{
    AddressKind, AssignTarget, Block, CallKind, ExprKind, JumpTarget, Statement, StructureKeyword,
    ValueExpr,
};
use crate::syntax::lexer::{lex_line_into, Lexeme, Token};
use crate::syntax::{LineParser, SyntaxContext};
use std::collections::HashMap;

impl SymbolTable {
    /// Collects the symbol table of a document with the machine's axes.
    pub fn build(source: &dyn LineSource, config: &MachineConfig) -> SymbolTable {
        let context = macro_context(source, config);
        let mut table = SymbolTable::default();
        let mut parser = LineParser::new();
        let mut block = Block::default();
        let mut diagnostics = Vec::new();
        let mut lexemes = Vec::new();
        let mut comment_lines: Vec<(usize, CommentLine)> = Vec::new();
        source.for_each_line(0, &mut |line_index, line| {
            parser.parse(line, &context, &mut block, &mut diagnostics);
            let calls_before = table.calls.len();
            table.add_block(line_index, line, &block, &mut lexemes);
            for call in &mut table.calls[calls_before..] {
                call.reads_as_address_word = diagnostics.iter().any(|diagnostic| {
                    diagnostic.code == Code::NameReadAsCall
                        && diagnostic.span.start() < call.span.end()
                        && call.span.start() < diagnostic.span.end()
                });
            }
            if let Some(class) = classify_comment_line(line, &block) {
                comment_lines.push((line_index, class));
            }
            table.line_count = line_index + 1;
            true
        });
        table.sections = find_sections(&comment_lines);
        if let Some(procedure) = &mut table.procedure {
            procedure.documentation = documentation_above(&comment_lines, procedure.line);
        }
        table
    }

    /// The parser's context for this document: the machine's axes and the document's macros, so that
    /// a feature that parses lines again reads them as the table did.
    pub fn syntax_context(&self, config: &MachineConfig) -> SyntaxContext {
        let mut context = SyntaxContext::new(config);
        for definition in &self.macros {
            context.add_macro(&definition.name);
        }
        context
    }

    /// The lines of each label, in ascending order, for resolving many jumps at once.
    pub fn label_lines(&self) -> HashMap<&str, Vec<usize>> {
        let mut lines: HashMap<&str, Vec<usize>> = HashMap::new();
        for label in &self.labels {
            lines
                .entry(label.name.as_str())
                .or_default()
                .push(label.line);
        }
        lines
    }

    /// The lines of each block number, in ascending order.
    pub fn block_number_lines(&self) -> HashMap<u64, Vec<usize>> {
        let mut lines: HashMap<u64, Vec<usize>> = HashMap::new();
        for entry in &self.block_numbers {
            lines.entry(entry.value).or_default().push(entry.line);
        }
        lines
    }

    /// Collects the symbol table of a whole text.
    pub fn of_text(text: &str, config: &MachineConfig) -> SymbolTable {
        SymbolTable::build(&crate::analysis::document::TextLines::new(text), config)
    }

    fn add_block(
        &mut self,
        line_index: usize,
        line: &str,
        block: &Block,
        lexemes: &mut Vec<Lexeme>,
    ) {
        if let Some(number) = block.number {
            self.block_numbers.push(BlockNumberEntry {
                value: number.value,
                main: number.main,
                line: line_index,
                span: number.span,
            });
        }
        if let Some(span) = block.label {
            self.labels.push(LabelDefinition {
                name: upper(text_of(line, span)),
                line: line_index,
                span,
            });
        }
        let mut tool_words: Vec<Span> = Vec::new();
        let mut in_case = false;
        for statement in &block.statements {
            self.add_statement(
                line_index,
                line,
                statement,
                &mut tool_words,
                &mut in_case,
                lexemes,
            );
        }
        for expr in expressions_outside_declarations(block) {
            match &expr.kind {
                ExprKind::Name { .. } => {
                    let span = identifier_prefix(line, expr.span);
                    self.name_uses.push(NameUse {
                        name: upper(text_of(line, span)),
                        line: line_index,
                        span,
                        write: false,
                    });
                }
                ExprKind::RParameter(number) => self.r_parameters.push(RParameterUse {
                    number: Some(*number),
                    line: line_index,
                    span: expr.span,
                    write: false,
                }),
                ExprKind::RParameterIndexed(_) => self.r_parameters.push(RParameterUse {
                    number: None,
                    line: line_index,
                    span: Span::new(expr.span.start(), expr.span.start() + 1),
                    write: false,
                }),
                _ => {}
            }
        }
        if let (Some(first), Some(last)) = (tool_words.first(), tool_words.last()) {
            let text = tool_words
                .iter()
                .map(|span| text_of(line, *span))
                .collect::<Vec<_>>()
                .join(" ");
            self.tool_changes.push(ToolChange {
                line: line_index,
                span: first.to(*last),
                text,
            });
        }
        if self.first_executable_line.is_none() && is_executable(line, block) {
            self.first_executable_line = Some(line_index);
        }
    }

    fn add_statement(
        &mut self,
        line_index: usize,
        line: &str,
        statement: &Statement,
        tool_words: &mut Vec<Span>,
        in_case: &mut bool,
        lexemes: &mut Vec<Lexeme>,
    ) {
        match statement {
            Statement::Address(word) => match word.kind {
                AddressKind::Tool => tool_words.push(word.span),
                AddressKind::MFunction
                    if word.extension.is_none()
                        && matches!(word.value.expr, ValueExpr::Constant { value, .. } if value == 6.0) =>
                {
                    tool_words.push(word.span)
                }
                AddressKind::SubprogramNumber => {
                    self.calls.push(CallSite {
                        name: upper(text_of(line, word.span)),
                        style: CallStyle::Number,
                        line: line_index,
                        span: word.span,
                        argument_count: None,
                        statement_span: word.span,
                        reads_as_address_word: false,
                    });
                }
                _ => {}
            },
            Statement::Assignment {
                target,
                target_span,
                ..
            } => match target {
                AssignTarget::Variable { .. } => {
                    let span = identifier_prefix(line, *target_span);
                    self.name_uses.push(NameUse {
                        name: upper(text_of(line, span)),
                        line: line_index,
                        span,
                        write: true,
                    });
                }
                AssignTarget::RParameter(number) => self.r_parameters.push(RParameterUse {
                    number: Some(*number),
                    line: line_index,
                    span: *target_span,
                    write: true,
                }),
                AssignTarget::RParameterIndexed(_) => self.r_parameters.push(RParameterUse {
                    number: None,
                    line: line_index,
                    span: Span::new(target_span.start(), target_span.start() + 1),
                    write: true,
                }),
                _ => {}
            },
            Statement::Structure { keyword, span, .. } => {
                if *keyword == StructureKeyword::Case {
                    *in_case = true;
                }
                let keyword_span = identifier_prefix(line, *span);
                self.structures.push(StructureMark {
                    keyword: *keyword,
                    line: line_index,
                    span: keyword_span,
                });
            }
            Statement::Jump {
                kind, target, span, ..
            } => {
                let target_start = match target {
                    JumpTarget::Label(span) | JumpTarget::BlockNumber { span, .. } => span.start(),
                    JumpTarget::Computed(_) | JumpTarget::None => span.end(),
                };
                // A computed target has no span here: its jump is never resolved, the keyword is then the
                // statement's first word.
                let keyword_span = match target {
                    JumpTarget::Computed(_) => identifier_prefix(line, *span),
                    _ => jump_keyword_before(line, *span, target_start),
                };
                let destination = match target {
                    JumpTarget::Label(span) => JumpDestination::Label {
                        name: upper(text_of(line, *span)),
                        span: *span,
                    },
                    JumpTarget::BlockNumber { value, span } => JumpDestination::BlockNumber {
                        value: *value,
                        span: *span,
                    },
                    JumpTarget::Computed(_) => JumpDestination::Computed,
                    JumpTarget::None => JumpDestination::None,
                };
                self.jumps.push(JumpSite {
                    kind: *kind,
                    destination,
                    line: line_index,
                    keyword_span,
                    in_case: *in_case,
                });
            }
            Statement::Call {
                kind,
                name: Some(name_span),
                args,
                span,
            } => {
                let has_parentheses = line.as_bytes()
                    [name_span.end().min(line.len())..span.end().min(line.len())]
                    .contains(&b'(');
                let argument_count = has_parentheses.then_some(args.len());
                let (name, style, name_span) = match kind {
                    CallKind::Named => (
                        upper(text_of(line, *name_span)),
                        CallStyle::Named,
                        *name_span,
                    ),
                    CallKind::Modal => (
                        upper(text_of(line, *name_span)),
                        CallStyle::Modal,
                        *name_span,
                    ),
                    CallKind::Indirect => match indirect_program_name(line, *name_span) {
                        Some((name, span)) => (name, CallStyle::Indirect, span),
                        None => return,
                    },
                };
                self.calls.push(CallSite {
                    name,
                    style,
                    line: line_index,
                    span: name_span,
                    argument_count,
                    statement_span: *span,
                    reads_as_address_word: false,
                });
            }
            Statement::Definition { names, span, .. } => {
                self.add_definitions(line_index, line, names, *span, lexemes);
            }
            Statement::MacroDefinition {
                name: Some(name),
                body,
                ..
            } => self.macros.push(MacroDefinition {
                name: upper(text_of(line, *name)),
                body: text_of(line, *body).trim().to_string(),
                line: line_index,
                span: *name,
            }),
            Statement::ProcedureHeader {
                name: Some(name),
                parameters,
                span,
                ..
            } if self.procedure.is_none() => {
                let (described, has_parameter_list) =
                    describe_parameters(line, *span, parameters, lexemes);
                self.procedure = Some(ProcedureDefinition {
                    name: upper(text_of(line, *name)),
                    line: line_index,
                    span: *name,
                    parameters: described
                        .into_iter()
                        .map(
                            |(name_span, type_name, by_reference, dimensions)| Parameter {
                                name: upper(text_of(line, name_span)),
                                type_name,
                                by_reference,
                                dimensions,
                                line: line_index,
                                span: name_span,
                            },
                        )
                        .collect(),
                    has_parameter_list,
                    documentation: None,
                });
            }
            Statement::ExternDeclaration {
                name: Some(name),
                span,
            } => self.externs.push(ExternDeclaration {
                name: upper(text_of(line, *name)),
                parameter_types: extern_parameter_types(line, name.end(), span.end()),
                line: line_index,
                span: *name,
            }),
            _ => {}
        }
    }

    fn add_definitions(
        &mut self,
        line_index: usize,
        line: &str,
        names: &[Span],
        span: Span,
        lexemes: &mut Vec<Lexeme>,
    ) {
        let statement = text_of(line, span);
        lex_line_into(statement, lexemes);
        let offset = span.start();
        let mut type_name = String::new();
        let mut global_attribute = None;
        for (index, lexeme) in lexemes.iter().enumerate() {
            if lexeme.token != Some(Token::Identifier) {
                continue;
            }
            let word = upper(text_of(statement, lexeme.span));
            if matches!(word.as_str(), "NCK" | "CHAN") && global_attribute.is_none() {
                global_attribute = Some(word);
            } else if is_type_name(&word) {
                type_name = word;
                if type_name == "STRING" {
                    if let Some(dimensions) = bracket_text(statement, lexemes, index + 1) {
                        type_name.push_str(&dimensions);
                    }
                }
                break;
            }
        }
        for name_span in names {
            let relative = Span::new(
                name_span.start().saturating_sub(offset),
                name_span.end().saturating_sub(offset),
            );
            let after = lexemes
                .iter()
                .position(|lexeme| lexeme.span.start() >= relative.end());
            let dimensions = after.and_then(|index| bracket_text(statement, lexemes, index));
            self.variables.push(VariableDefinition {
                name: upper(text_of(line, *name_span)),
                type_name: type_name.clone(),
                dimensions,
                global_attribute: global_attribute.clone(),
                line: line_index,
                span: *name_span,
            });
        }
    }
}

/// The parser's context with the macros a document defines anywhere (`DEFINE name AS ...`): a macro
/// may be used above its definition when it comes from a definition file.
pub fn macro_context(source: &dyn LineSource, config: &MachineConfig) -> SyntaxContext {
    let mut context = SyntaxContext::new(config);
    source.for_each_line(0, &mut |_, line| {
        if let Some(name) = crate::syntax::lines_containing(line, b"DEFINE")
            .next()
            .and_then(crate::syntax::macro_defined_by)
        {
            context.add_macro(name);
        }
        true
    });
    context
}
