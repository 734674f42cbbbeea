//! Semantic tokens as plain data: for each word of a line its kind (axis, address, position
//! modifier, G function with its group, variable, parameter, R parameter, system variable, label,
//! block number, comment, string, number, keyword, function, subprogram, macro) and modifiers. The
//! meaning comes from the parser's blocks; the lexer's tokens fill in the words the AST does not keep
//! (`DEF`, `TO`, `OF`, `DO`, type names, word operators).

use crate::analysis::document::LineSource;
use crate::config::MachineConfig;
use crate::diagnostics::Span;
use crate::ide::names::{
    expressions_outside_declarations, identifier_prefix, is_type_name, repeat_count_letter,
    text_of, upper,
};
use crate::ide::symbols::SymbolTable;
use crate::syntax::ast::{
    AddressKind, AssignTarget, Block, ExprKind, JumpTarget, Statement, ValueExpr,
};
use crate::syntax::keywords;
use crate::syntax::lexer::{lex_line_into, Lexeme, Token};
use crate::syntax::LineParser;
use std::ops::Range;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TokenKind {
    Comment,
    String,
    Number,
    Keyword,
    /// A G function, by its group (0 for a G number that does not exist).
    GCode {
        group: u8,
    },
    Axis,
    /// An address that is not an axis: F, S, T, D, M, H, I/J/K, CR, AP, ...
    Address,
    /// A position modifier: AC, IC, DC, ACP, ACN, DAC, ...
    Modifier,
    Variable,
    Parameter,
    RParameter,
    SystemVariable,
    Label,
    BlockNumber,
    Function,
    Subprogram,
    Macro,
}

/// The name is declared here (DEF, PROC parameter, label definition, DEFINE, PROC name).
pub const DECLARATION: u32 = 1;
/// The variable is written here.
pub const MODIFICATION: u32 = 2;
/// A non-modal G function (acts in its block only).
pub const NON_MODAL: u32 = 4;

/// One token: line, start byte and length in bytes within the line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SemanticToken {
    pub line: usize,
    pub start: usize,
    pub length: usize,
    pub kind: TokenKind,
    pub modifiers: u32,
}

/// The tokens of the lines in `lines` (clamped to the document), in order.
pub fn semantic_tokens(
    source: &dyn LineSource,
    table: &SymbolTable,
    config: &MachineConfig,
    lines: Range<usize>,
) -> Vec<SemanticToken> {
    let context = table.syntax_context(config);
    let mut parser = LineParser::new();
    let mut block = Block::default();
    let mut diagnostics = Vec::new();
    let mut lexemes = Vec::new();
    let mut out = Vec::new();
    let end = lines.end.min(source.line_count());
    source.for_each_line(lines.start, &mut |line_index, line| {
        if line_index >= end {
            return false;
        }
        parser.parse(line, &context, &mut block, &mut diagnostics);
        lex_line_into(line, &mut lexemes);
        line_tokens(line_index, line, &block, &lexemes, table, config, &mut out);
        true
    });
    out
}

/// The kind of a variable-like name in this document.
fn name_kind(name: &str, table: &SymbolTable, config: &MachineConfig) -> TokenKind {
    if table.procedure.as_ref().is_some_and(|procedure| {
        procedure
            .parameters
            .iter()
            .any(|parameter| parameter.name == name)
    }) {
        TokenKind::Parameter
    } else if table.variables.iter().any(|variable| variable.name == name) {
        TokenKind::Variable
    } else if table
        .macros
        .iter()
        .any(|definition| definition.name == name)
    {
        TokenKind::Macro
    } else if matches!(name, "TRUE" | "FALSE") {
        TokenKind::Keyword
    } else if config.axis(name).is_some() {
        TokenKind::Axis
    } else {
        TokenKind::Variable
    }
}

fn line_tokens(
    line_index: usize,
    line: &str,
    block: &Block,
    lexemes: &[Lexeme],
    table: &SymbolTable,
    config: &MachineConfig,
    out: &mut Vec<SemanticToken>,
) {
    let mut found: Vec<(Span, TokenKind, u32)> = Vec::new();
    if let Some(number) = block.number {
        found.push((number.span, TokenKind::BlockNumber, 0));
    }
    if let Some(label) = block.label {
        found.push((label, TokenKind::Label, DECLARATION));
    }
    if let Some(comment) = block.comment {
        found.push((comment, TokenKind::Comment, 0));
    }
    for statement in &block.statements {
        statement_tokens(line, statement, lexemes, table, config, &mut found);
    }
    for expr in expressions_outside_declarations(block) {
        match &expr.kind {
            ExprKind::Number(_) => found.push((expr.span, TokenKind::Number, 0)),
            ExprKind::String => found.push((expr.span, TokenKind::String, 0)),
            ExprKind::RParameter(_) => found.push((expr.span, TokenKind::RParameter, 0)),
            ExprKind::RParameterIndexed(_) => found.push((
                Span::new(expr.span.start(), expr.span.start() + 1),
                TokenKind::RParameter,
                0,
            )),
            ExprKind::Name { .. } => {
                let span = identifier_prefix(line, expr.span);
                found.push((
                    span,
                    name_kind(&upper(text_of(line, span)), table, config),
                    0,
                ));
            }
            ExprKind::SystemVariable { .. } => found.push((
                identifier_prefix(line, expr.span),
                TokenKind::SystemVariable,
                0,
            )),
            ExprKind::Call { name, .. } => found.push((*name, TokenKind::Function, 0)),
            _ => {}
        }
    }
    found.retain(|(span, _, _)| !span.is_empty());
    found.sort_by_key(|(span, _, _)| (span.start(), std::cmp::Reverse(span.end())));
    let mut tokens: Vec<(Span, TokenKind, u32)> = Vec::with_capacity(found.len() + 4);
    for item in found {
        if tokens
            .last()
            .is_none_or(|last| last.0.end() <= item.0.start())
        {
            tokens.push(item);
        }
    }
    // Words the AST does not keep, from the lexer.
    let mut extra = Vec::new();
    for lexeme in lexemes {
        let covered = {
            let position = tokens.partition_point(|(span, _, _)| span.end() <= lexeme.span.start());
            tokens
                .get(position)
                .is_some_and(|(span, _, _)| span.start() < lexeme.span.end())
        };
        if covered {
            continue;
        }
        let kind = match lexeme.token {
            Some(Token::Comment) => Some(TokenKind::Comment),
            Some(Token::String) | Some(Token::UnterminatedString) => Some(TokenKind::String),
            Some(Token::Number) | Some(Token::HexNumber) | Some(Token::BinaryNumber) => {
                Some(TokenKind::Number)
            }
            Some(Token::SystemVariable) => Some(TokenKind::SystemVariable),
            Some(Token::Identifier) => {
                let word = upper(text_of(line, lexeme.span));
                let is_keyword = keywords::statement_keyword(&word).is_some()
                    || keywords::word_operator(&word).is_some()
                    || is_type_name(&word)
                    || matches!(
                        word.as_str(),
                        "TO" | "OF"
                            | "DO"
                            | "AS"
                            | "VAR"
                            | "DEFAULT"
                            | "NOT"
                            | "B_NOT"
                            | "NCK"
                            | "CHAN"
                            | "SAVE"
                            | "DISPLOF"
                            | "SBLOF"
                    );
                is_keyword.then_some(TokenKind::Keyword)
            }
            _ => None,
        };
        if let Some(kind) = kind {
            extra.push((lexeme.span, kind, 0));
        }
    }
    tokens.extend(extra);
    tokens.sort_by_key(|(span, _, _)| span.start());
    out.extend(
        tokens
            .into_iter()
            .map(|(span, kind, modifiers)| SemanticToken {
                line: line_index,
                start: span.start(),
                length: span.len(),
                kind,
                modifiers,
            }),
    );
}

fn statement_tokens(
    line: &str,
    statement: &Statement,
    lexemes: &[Lexeme],
    table: &SymbolTable,
    config: &MachineConfig,
    found: &mut Vec<(Span, TokenKind, u32)>,
) {
    match statement {
        Statement::GCode { code, span } => found.push((
            *span,
            TokenKind::GCode {
                group: code.group(),
            },
            if code.is_modal() { 0 } else { NON_MODAL },
        )),
        Statement::UnknownGCode { span, .. } => {
            found.push((*span, TokenKind::GCode { group: 0 }, 0))
        }
        Statement::Address(word) => {
            let kind = match word.kind {
                AddressKind::Axis => TokenKind::Axis,
                AddressKind::SubprogramNumber => TokenKind::Subprogram,
                _ => TokenKind::Address,
            };
            if word.kind == AddressKind::SubprogramNumber {
                found.push((word.span, kind, 0));
                return;
            }
            let name_end = match &word.extension {
                Some(crate::syntax::ast::Extension::Number { span, .. }) => span.end(),
                _ => word.name.end(),
            };
            found.push((Span::new(word.name.start(), name_end), kind, 0));
            if let Some((_, span)) = word.value.modifier {
                found.push((span, TokenKind::Modifier, 0));
            }
            if let ValueExpr::Constant { span, .. } = word.value.expr {
                found.push((span, TokenKind::Number, 0));
            }
        }
        Statement::Assignment {
            target,
            target_span,
            ..
        } => {
            let (span, kind) = match target {
                AssignTarget::Variable { .. } => {
                    let span = identifier_prefix(line, *target_span);
                    (span, name_kind(&upper(text_of(line, span)), table, config))
                }
                AssignTarget::RParameter(_) => (*target_span, TokenKind::RParameter),
                AssignTarget::RParameterIndexed(_) => (
                    Span::new(target_span.start(), target_span.start() + 1),
                    TokenKind::RParameter,
                ),
                AssignTarget::SystemVariable { .. } => (
                    identifier_prefix(line, *target_span),
                    TokenKind::SystemVariable,
                ),
                AssignTarget::GGroup { .. } => (
                    Span::new(target_span.start(), target_span.start() + 1),
                    TokenKind::Keyword,
                ),
            };
            found.push((span, kind, MODIFICATION));
        }
        Statement::Structure { span, .. }
        | Statement::SyncCondition { span, .. }
        | Statement::Return { span } => {
            found.push((identifier_prefix(line, *span), TokenKind::Keyword, 0))
        }
        Statement::Jump { target, .. } => match target {
            JumpTarget::Label(span) => found.push((*span, TokenKind::Label, 0)),
            JumpTarget::BlockNumber { span, .. } => found.push((*span, TokenKind::BlockNumber, 0)),
            _ => {}
        },
        Statement::Call {
            name: Some(name), ..
        } => {
            let text = text_of(line, *name);
            let kind = if text.starts_with('"') {
                TokenKind::String
            } else if table
                .macros
                .iter()
                .any(|definition| definition.name.eq_ignore_ascii_case(text))
            {
                TokenKind::Macro
            } else {
                TokenKind::Subprogram
            };
            found.push((*name, kind, 0));
        }
        Statement::Definition { names, .. } => {
            for name in names {
                found.push((*name, TokenKind::Variable, DECLARATION));
            }
        }
        Statement::MacroDefinition {
            name: Some(name), ..
        } => found.push((*name, TokenKind::Macro, DECLARATION)),
        Statement::ProcedureHeader {
            name, parameters, ..
        } => {
            if let Some(name) = name {
                found.push((*name, TokenKind::Subprogram, DECLARATION));
            }
            for parameter in parameters {
                found.push((*parameter, TokenKind::Parameter, DECLARATION));
            }
        }
        Statement::ExternDeclaration {
            name: Some(name), ..
        } => found.push((*name, TokenKind::Subprogram, 0)),
        Statement::Instruction { name, .. } => found.push((*name, TokenKind::Function, 0)),
        // Marked as when the statement was an instruction followed by the address word `P`: the
        // keyword as an instruction, `P` as an address, the labels not at all.
        Statement::SectionRepeat { span, .. } | Statement::BlockRepeat { span, .. } => {
            found.push((identifier_prefix(line, *span), TokenKind::Function, 0));
            if let Some(letter) = repeat_count_letter(lexemes, *span) {
                found.push((letter, TokenKind::Address, 0));
            }
        }
        _ => {}
    }
}
