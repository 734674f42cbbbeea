//! The symbol table of one document: labels, block numbers, `DEF` variables, R parameters, the `PROC`
//! header, `DEFINE` macros, `EXTERN` declarations, calls, jumps, tool changes, comment sections and
//! the names read or written as variables. Everything comes from the parser's blocks; the type of a
//! `DEF` and the types of `PROC` parameters are described as written (`STRING[32]`, `VAR REAL`), from
//! the lexer's tokens of the statement.

use crate::analysis::document::LineSource;
use crate::config::MachineConfig;
use crate::diagnostics::{Code, Span};
pub use crate::ide::block_numbers::{BlockNumberEntry, BlockNumbers};
use crate::ide::names::{
    expressions_outside_declarations, identifier_prefix, is_type_name, text_of, upper,
};
use crate::syntax::ast::{
    AddressKind, AssignTarget, Block, CallKind, ExprKind, JumpKind, JumpTarget, Statement,
    StructureKeyword, ValueExpr,
};
use crate::syntax::lexer::{lex_line_into, Lexeme, Token};
use crate::syntax::{LineParser, SyntaxContext};
use std::collections::HashMap;

/// `NAME:` at the start of a block.
#[derive(Debug, Clone, PartialEq)]
pub struct LabelDefinition {
    /// Upper case, without the colon.
    pub name: String,
    pub line: usize,
    pub span: Span,
}

/// A variable declared with `DEF`.
#[derive(Debug, Clone, PartialEq)]
pub struct VariableDefinition {
    pub name: String,
    /// `REAL`, `INT`, `STRING[32]`, ...; empty when the declaration names no type.
    pub type_name: String,
    /// `[3]` or `[2,3]` when the variable is an array.
    pub dimensions: Option<String>,
    /// `NCK` or `CHAN` for global user data (GUD), `None` for local data.
    pub global_attribute: Option<String>,
    pub line: usize,
    pub span: Span,
}

/// An R parameter read or written: `R1`, `$R1`, `R[expr]` (whose number is not known statically).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RParameterUse {
    pub number: Option<u32>,
    pub line: usize,
    pub span: Span,
    pub write: bool,
}

/// A formal parameter of a `PROC`.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    pub name: String,
    pub type_name: String,
    /// `VAR`: passed by reference, so the caller must give a variable.
    pub by_reference: bool,
    pub dimensions: Option<String>,
    pub line: usize,
    pub span: Span,
}

/// `PROC NAME(params) attributes`.
#[derive(Debug, Clone, PartialEq)]
pub struct ProcedureDefinition {
    pub name: String,
    pub line: usize,
    /// The span of the name.
    pub span: Span,
    pub parameters: Vec<Parameter>,
    /// Whether the header has a parameter list in parentheses.
    pub has_parameter_list: bool,
    /// The comment lines written directly above the header, without `;` and rule lines.
    pub documentation: Option<String>,
}

/// `DEFINE NAME AS body`.
#[derive(Debug, Clone, PartialEq)]
pub struct MacroDefinition {
    pub name: String,
    pub body: String,
    pub line: usize,
    pub span: Span,
}

/// `EXTERN NAME(types)`.
#[derive(Debug, Clone, PartialEq)]
pub struct ExternDeclaration {
    pub name: String,
    /// The parameter types as written (`REAL`, `VAR INT`); `None` without a parameter list.
    pub parameter_types: Option<Vec<String>>,
    pub line: usize,
    pub span: Span,
}

/// How a call names its program.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CallStyle {
    /// `NAME` or `NAME(args)`.
    Named,
    /// `MCALL NAME(args)`.
    Modal,
    /// `CALL "NAME"`, `PCALL /_N_DIR/_N_NAME_SPF`: the name inside a string or path.
    Indirect,
    /// `L123`: a subprogram by number (leading zeros count).
    Number,
}

/// A call of a subprogram or cycle (or the use of a macro, which reads like one).
#[derive(Debug, Clone, PartialEq)]
pub struct CallSite {
    /// The called program's name, upper case.
    pub name: String,
    pub style: CallStyle,
    pub line: usize,
    /// The span of the name alone (inside the quotes for `CALL "NAME"`).
    pub span: Span,
    /// The number of arguments written in parentheses, empty ones included; `None` without them.
    pub argument_count: Option<usize>,
    /// The span of the whole call statement.
    pub statement_span: Span,
    /// The parser reported the name as an address word that lacks its `=` (S120: `XR1`, `CR10`,
    /// `ZAC(17)`). Saying again that no program has that name would only repeat the finding.
    pub reads_as_address_word: bool,
}

/// Where a jump goes.
#[derive(Debug, Clone, PartialEq)]
pub enum JumpDestination {
    Label {
        name: String,
        span: Span,
    },
    BlockNumber {
        value: u64,
        span: Span,
    },
    /// A target computed at run time (a string variable): not resolved.
    Computed,
    /// `GOTOS`, or a jump without target.
    None,
}

/// `GOTOF`/`GOTOB`/`GOTO`/`GOTOC`/`GOTOS`, conditional or not.
#[derive(Debug, Clone, PartialEq)]
pub struct JumpSite {
    pub kind: JumpKind,
    pub destination: JumpDestination,
    pub line: usize,
    /// The span of the jump keyword.
    pub keyword_span: Span,
    /// Written in a `CASE` block.
    pub in_case: bool,
}

/// A block that changes the tool: a `T` word and/or `M6`.
#[derive(Debug, Clone, PartialEq)]
pub struct ToolChange {
    pub line: usize,
    /// From the first to the last tool word of the block.
    pub span: Span,
    /// The tool words as written, e.g. `T5 M6`.
    pub text: String,
}

/// A comment that titles a section of the program (`;--- ROUGHING ---`, or a title under a rule line).
#[derive(Debug, Clone, PartialEq)]
pub struct CommentSection {
    /// The first line of the section's header (the rule line above the title, if there is one).
    pub line: usize,
    pub title_line: usize,
    pub title: String,
}

/// A name read or written as a variable (or parameter, or macro) in an expression or assignment.
#[derive(Debug, Clone, PartialEq)]
pub struct NameUse {
    pub name: String,
    pub line: usize,
    pub span: Span,
    pub write: bool,
}

/// A control-structure keyword (IF, ELSE, ENDIF, WHILE, ... CASE) and where it stands.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StructureMark {
    pub keyword: StructureKeyword,
    pub line: usize,
    pub span: Span,
}

/// Everything one document declares and uses, in line order within each list.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SymbolTable {
    pub labels: Vec<LabelDefinition>,
    pub block_numbers: BlockNumbers,
    pub variables: Vec<VariableDefinition>,
    pub r_parameters: Vec<RParameterUse>,
    pub procedure: Option<ProcedureDefinition>,
    pub macros: Vec<MacroDefinition>,
    pub externs: Vec<ExternDeclaration>,
    pub calls: Vec<CallSite>,
    pub jumps: Vec<JumpSite>,
    pub tool_changes: Vec<ToolChange>,
    pub sections: Vec<CommentSection>,
    pub name_uses: Vec<NameUse>,
    pub structures: Vec<StructureMark>,
    /// The first block that executes something (not a declaration, label, number or comment).
    pub first_executable_line: Option<usize>,
    pub line_count: usize,
}

/// How a comment-only line may take part in a section header.
#[derive(Debug, Clone, PartialEq)]
enum CommentLine {
    /// `;*****`, `;-----`, `;=====`: a rule.
    Rule,
    /// `;--- TITLE ---`: a title framed by rule characters.
    FramedTitle(String),
    /// Plain comment text.
    Text(String),
    /// `;` alone.
    Empty,
}

const RULE_CHARACTERS: &[char] = &['*', '-', '=', '+', '#', '~', '_', '/'];

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

/// The text of a `[...]` group starting at lexeme `index`, brackets included.
fn bracket_text(text: &str, lexemes: &[Lexeme], index: usize) -> Option<String> {
    let first = lexemes.get(index)?;
    if first.token != Some(Token::LeftBracket) {
        return None;
    }
    let mut depth = 0;
    for lexeme in &lexemes[index..] {
        match lexeme.token {
            Some(Token::LeftBracket) => depth += 1,
            Some(Token::RightBracket) => {
                depth -= 1;
                if depth == 0 {
                    let span = Span::new(first.span.start(), lexeme.span.end());
                    return Some(
                        text_of(text, span)
                            .chars()
                            .filter(|c| !c.is_whitespace())
                            .collect(),
                    );
                }
            }
            _ => {}
        }
    }
    None
}

/// The keyword of a jump statement (whose span may start at its `IF`): the word that ends right
/// before the target, which starts at `target_start`.
fn jump_keyword_before(line: &str, statement: Span, target_start: usize) -> Span {
    let bytes = line.as_bytes();
    let mut end = target_start.min(bytes.len());
    while end > statement.start() && bytes[end - 1].is_ascii_whitespace() {
        end -= 1;
    }
    let mut start = end;
    while start > statement.start()
        && (bytes[start - 1].is_ascii_alphanumeric() || bytes[start - 1] == b'_')
    {
        start -= 1;
    }
    Span::new(start, end)
}

/// For `CALL "NAME"`, `CALL "/_N_DIR/_N_NAME_SPF"` and `PCALL /_N_DIR/_N_NAME_SPF`: the program name
/// and its span inside the line. `None` for a call through a variable.
fn indirect_program_name(line: &str, span: Span) -> Option<(String, Span)> {
    let text = text_of(line, span);
    let (content, content_start) = match text.strip_prefix('"') {
        Some(rest) => (rest.strip_suffix('"')?, span.start() + 1),
        None if text.contains('/') => (text, span.start()),
        None => return None,
    };
    let segment_start = content.rfind('/').map_or(0, |position| position + 1);
    let segment = &content[segment_start..];
    let (name_offset, name) = match segment
        .strip_prefix("_N_")
        .or_else(|| segment.strip_prefix("_n_"))
    {
        Some(rest) => {
            let end = rest.rfind('_').filter(|position| *position > 0)?;
            (3, &rest[..end])
        }
        None => (0, segment),
    };
    if !crate::ide::names::is_identifier(name) {
        return None;
    }
    let start = content_start + segment_start + name_offset;
    Some((upper(name), Span::new(start, start + name.len())))
}

/// A parameter of a `PROC` header as read from its tokens: name span, type, `VAR`, dimensions.
type DescribedParameter = (Span, String, bool, Option<String>);

/// The parameters of a `PROC` header: (name span, type, VAR, dimensions) per parameter name the
/// parser found, and whether there is a parameter list.
fn describe_parameters(
    line: &str,
    span: Span,
    parameters: &[Span],
    lexemes: &mut Vec<Lexeme>,
) -> (Vec<DescribedParameter>, bool) {
    let statement = text_of(line, span);
    lex_line_into(statement, lexemes);
    let offset = span.start();
    let has_list = lexemes
        .iter()
        .any(|lexeme| lexeme.token == Some(Token::LeftParen));
    let mut described = Vec::new();
    for name_span in parameters {
        let relative_start = name_span.start().saturating_sub(offset);
        let Some(name_index) = lexemes
            .iter()
            .position(|lexeme| lexeme.span.start() == relative_start)
        else {
            continue;
        };
        // Walk back to the comma or parenthesis that starts this parameter.
        let mut type_name = String::new();
        let mut by_reference = false;
        for lexeme in lexemes[..name_index].iter().rev() {
            match lexeme.token {
                Some(Token::Comma) | Some(Token::LeftParen) => break,
                Some(Token::Identifier) => {
                    let word = upper(text_of(statement, lexeme.span));
                    if word == "VAR" {
                        by_reference = true;
                    } else if is_type_name(&word) && type_name.is_empty() {
                        type_name = word;
                    }
                }
                _ => {}
            }
        }
        let dimensions = bracket_text(statement, lexemes, name_index + 1);
        described.push((*name_span, type_name, by_reference, dimensions));
    }
    (described, has_list)
}

/// The parameter types of `EXTERN NAME(REAL, VAR INT)` between `name_end` and `end` of the line.
fn extern_parameter_types(line: &str, name_end: usize, end: usize) -> Option<Vec<String>> {
    let rest = line.get(name_end..end)?.trim_start();
    let inner = rest.strip_prefix('(')?;
    let close = inner.rfind(')').unwrap_or(inner.len());
    let inner = inner[..close].trim();
    if inner.is_empty() {
        return Some(Vec::new());
    }
    let mut types = Vec::new();
    let mut depth = 0i32;
    let mut current = String::new();
    for character in inner.chars() {
        match character {
            '[' | '(' => depth += 1,
            ']' | ')' => depth -= 1,
            ',' if depth == 0 => {
                types.push(normalise_spaces(&current));
                current.clear();
                continue;
            }
            _ => {}
        }
        current.push(character);
    }
    types.push(normalise_spaces(&current));
    Some(types)
}

fn normalise_spaces(text: &str) -> String {
    text.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .to_ascii_uppercase()
}

/// Whether a block executes something: declarations (`DEF`, `DEFINE`, `PROC`, `EXTERN`, access
/// levels, `REDEF`), labels, block numbers and comments alone do not (reference §8.1, alarm 14500).
pub fn is_executable(line: &str, block: &Block) -> bool {
    block.statements.iter().any(|statement| match statement {
        Statement::Definition { .. }
        | Statement::MacroDefinition { .. }
        | Statement::ProcedureHeader { .. }
        | Statement::ExternDeclaration { .. } => false,
        Statement::Instruction { name, .. } => !matches!(
            upper(text_of(line, *name)).as_str(),
            "REDEF" | "APR" | "APW" | "APRP" | "APWP" | "APRB" | "APWB"
        ),
        _ => true,
    })
}

/// The class of a line that holds only a comment, `None` for other lines.
fn classify_comment_line(line: &str, block: &Block) -> Option<CommentLine> {
    let comment = block.comment?;
    if !block.statements.is_empty()
        || block.number.is_some()
        || block.label.is_some()
        || block.skip.is_some()
    {
        return None;
    }
    if !line[..comment.start()].trim().is_empty() {
        return None;
    }
    let text = text_of(line, comment)[1..].trim();
    if text.is_empty() {
        return Some(CommentLine::Empty);
    }
    let leading_rule = text
        .chars()
        .take_while(|c| RULE_CHARACTERS.contains(c))
        .count();
    let title =
        text.trim_matches(|c: char| RULE_CHARACTERS.contains(&c) || c.is_whitespace() || c == '\'');
    if !title.chars().any(char::is_alphabetic) {
        return (leading_rule >= 5
            || text
                .chars()
                .all(|c| RULE_CHARACTERS.contains(&c) || c.is_whitespace() || c == '\'')
                && leading_rule >= 3)
            .then_some(CommentLine::Rule);
    }
    if leading_rule >= 3 {
        return Some(CommentLine::FramedTitle(title.to_string()));
    }
    Some(CommentLine::Text(text.to_string()))
}

/// Section headers among the comment-only lines: framed titles, a title directly under a rule, or a
/// title directly above a rule that follows no other comment line (an underlined title).
fn find_sections(comment_lines: &[(usize, CommentLine)]) -> Vec<CommentSection> {
    let class_at = |line: usize| -> Option<&CommentLine> {
        comment_lines
            .binary_search_by_key(&line, |(index, _)| *index)
            .ok()
            .map(|position| &comment_lines[position].1)
    };
    let mut sections = Vec::new();
    for (line, class) in comment_lines {
        let line = *line;
        match class {
            CommentLine::FramedTitle(title) => sections.push(CommentSection {
                line: if line > 0 && class_at(line - 1) == Some(&CommentLine::Rule) {
                    line - 1
                } else {
                    line
                },
                title_line: line,
                title: title.clone(),
            }),
            CommentLine::Text(title) => {
                let above = line.checked_sub(1).and_then(class_at);
                let below = class_at(line + 1);
                if above == Some(&CommentLine::Rule) {
                    sections.push(CommentSection {
                        line: line - 1,
                        title_line: line,
                        title: title.clone(),
                    });
                } else if above.is_none() && below == Some(&CommentLine::Rule) {
                    sections.push(CommentSection {
                        line,
                        title_line: line,
                        title: title.clone(),
                    });
                }
            }
            _ => {}
        }
    }
    sections
}

/// The comment text directly above `line`, rule lines left out.
fn documentation_above(comment_lines: &[(usize, CommentLine)], line: usize) -> Option<String> {
    let mut texts = Vec::new();
    let mut expected = line.checked_sub(1)?;
    for (index, class) in comment_lines
        .iter()
        .rev()
        .skip_while(|(index, _)| *index >= line)
    {
        if *index != expected {
            break;
        }
        match class {
            CommentLine::Text(text) | CommentLine::FramedTitle(text) => texts.push(text.clone()),
            CommentLine::Rule | CommentLine::Empty => {}
        }
        if expected == 0 {
            break;
        }
        expected -= 1;
    }
    texts.reverse();
    (!texts.is_empty()).then(|| texts.join("\n"))
}
