//! Formatting: normalises spacing and letter case without changing what a block means. Words are
//! separated by one blank (`G0X10` becomes `G0 X10`), runs of blanks inside a statement shrink to one,
//! blanks after `(`/`[` and before `)`/`]`/`,` and at the end of a line go, names and addresses are
//! written in upper case. Comments and strings stay byte for byte, a trailing comment keeps its
//! column where the code still fits; leading indentation, the blanks after a block number (which
//! often indent the block) and line ends are kept.
//!
//! Every formatted line is lexed and parsed again and compared with the original (same tokens, same
//! parse, same findings); a line that would compare differently is left exactly as it was.

use crate::analysis::document::LineSource;
use crate::config::MachineConfig;
use crate::diagnostics::{Diagnostic, Span};
use crate::ide::names::repeat_count_letter;
use crate::ide::LineEdit;
use crate::syntax::ast::{Block, ExprKind, Statement, ValueExpr};
use crate::syntax::lexer::{lex_line_into, Lexeme, Token};
use crate::syntax::{LineParser, SyntaxContext};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FormatOptions {
    /// Write names, keywords and addresses in upper case (the language is case-insensitive).
    pub uppercase: bool,
}

impl Default for FormatOptions {
    fn default() -> FormatOptions {
        FormatOptions { uppercase: true }
    }
}

/// The edits that format a document: one whole-line replacement per line that changes.
pub fn format(
    source: &dyn LineSource,
    config: &MachineConfig,
    options: FormatOptions,
) -> Vec<LineEdit> {
    let mut formatter = LineFormatter::new(source, config, options);
    let mut edits = Vec::new();
    source.for_each_line(0, &mut |line_index, line| {
        if let Some(new_text) = formatter.format_line(line) {
            edits.push(LineEdit {
                line: line_index,
                span: Span::new(0, line.len()),
                new_text,
            });
        }
        true
    });
    edits
}

/// Formats a whole text (line ends kept).
pub fn format_text(text: &str, config: &MachineConfig, options: FormatOptions) -> String {
    let edits = format(
        &crate::analysis::document::TextLines::new(text),
        config,
        options,
    );
    crate::ide::apply_edits(text, &edits)
}

/// Formats one line at a time with reused buffers.
struct LineFormatter {
    context: SyntaxContext,
    options: FormatOptions,
    parser: LineParser,
    block: Block,
    diagnostics: Vec<Diagnostic>,
    lexemes: Vec<Lexeme>,
    new_block: Block,
    new_diagnostics: Vec<Diagnostic>,
    new_lexemes: Vec<Lexeme>,
}

impl LineFormatter {
    fn new(
        source: &dyn LineSource,
        config: &MachineConfig,
        options: FormatOptions,
    ) -> LineFormatter {
        LineFormatter {
            context: crate::ide::symbols::macro_context(source, config),
            options,
            parser: LineParser::new(),
            block: Block::default(),
            diagnostics: Vec::new(),
            lexemes: Vec::new(),
            new_block: Block::default(),
            new_diagnostics: Vec::new(),
            new_lexemes: Vec::new(),
        }
    }

    /// The formatted line, or `None` when it stays as it is.
    fn format_line(&mut self, line: &str) -> Option<String> {
        self.parser
            .parse(line, &self.context, &mut self.block, &mut self.diagnostics);
        if self.block.is_header {
            return None;
        }
        lex_line_into(line, &mut self.lexemes);
        let starts = element_starts(&self.block, &self.lexemes);
        let number_end = self.block.number.map(|number| number.span.end());
        let formatted = respace(line, &self.lexemes, &starts, number_end, self.options);
        if formatted == line {
            return None;
        }
        // The guard: the new line must lex and parse exactly like the old one.
        self.parser.parse(
            &formatted,
            &self.context,
            &mut self.new_block,
            &mut self.new_diagnostics,
        );
        lex_line_into(&formatted, &mut self.new_lexemes);
        let same_tokens = self.lexemes.len() == self.new_lexemes.len()
            && self
                .lexemes
                .iter()
                .zip(&self.new_lexemes)
                .all(|(old, new)| {
                    old.token == new.token
                        && line[old.span.start()..old.span.end()]
                            .eq_ignore_ascii_case(&formatted[new.span.start()..new.span.end()])
                });
        let same_parse = same_tokens
            && fingerprint(&self.block, &self.diagnostics, &self.lexemes)
                == fingerprint(&self.new_block, &self.new_diagnostics, &self.new_lexemes);
        same_parse.then_some(formatted)
    }
}

/// Byte offsets where an element of the block starts: the skip marker, the block number, the label
/// and each statement. A blank is written before each of them. The value of a CASE branch is no
/// element of its own, and the count `P` of a REPEAT is one, as they were before the parser kept them.
fn element_starts(block: &Block, lexemes: &[Lexeme]) -> Vec<usize> {
    let mut starts: Vec<usize> = Vec::new();
    if let Some((_, span)) = block.skip {
        starts.push(span.start());
    }
    if let Some(number) = block.number {
        starts.push(number.span.start());
    }
    if let Some(label) = block.label {
        starts.push(label.start());
    }
    for statement in &block.statements {
        match statement {
            Statement::CaseBranch { .. } => {}
            Statement::SectionRepeat { span, .. } | Statement::BlockRepeat { span, .. } => {
                starts.push(span.start());
                if let Some(letter) = repeat_count_letter(lexemes, *span) {
                    starts.push(letter.start());
                }
            }
            _ => starts.push(statement.span().start()),
        }
    }
    starts.sort_unstable();
    starts
}

/// Whether a token's text keeps its letter case and content: data and what the lexer did not know.
fn is_literal(token: Option<Token>) -> bool {
    matches!(
        token,
        None | Some(Token::Comment)
            | Some(Token::String)
            | Some(Token::UnterminatedString)
            | Some(Token::BadQuoted)
    )
}

fn respace(
    line: &str,
    lexemes: &[Lexeme],
    element_starts: &[usize],
    number_end: Option<usize>,
    options: FormatOptions,
) -> String {
    let Some(first) = lexemes.first() else {
        // Blanks (or nothing) only.
        return String::new();
    };
    let mut out = String::with_capacity(line.len() + 8);
    out.push_str(&line[..first.span.start()]);
    let mut previous: Option<&Lexeme> = None;
    for lexeme in lexemes {
        let text = &line[lexeme.span.start()..lexeme.span.end()];
        if let Some(previous) = previous {
            let gap = &line[previous.span.end()..lexeme.span.start()];
            let is_element_start = element_starts.binary_search(&lexeme.span.start()).is_ok();
            if lexeme.token == Some(Token::Comment) {
                if !gap.is_empty() {
                    if gap.contains('\t') {
                        out.push_str(gap);
                    } else {
                        let column = line[..lexeme.span.start()].chars().count();
                        let current = out.chars().count();
                        let padding = if column > current {
                            column - current
                        } else {
                            1
                        };
                        out.extend(std::iter::repeat_n(' ', padding));
                    }
                }
            } else if is_element_start && number_end == Some(previous.span.end()) && !gap.is_empty()
            {
                // Blanks after the block number indent the block (often by its nesting): kept.
                out.push_str(gap);
            } else if is_element_start {
                out.push(' ');
            } else if !gap.is_empty() {
                let tight = matches!(
                    previous.token,
                    Some(Token::LeftParen) | Some(Token::LeftBracket)
                ) || matches!(
                    lexeme.token,
                    Some(Token::RightParen) | Some(Token::RightBracket) | Some(Token::Comma)
                );
                if !tight {
                    out.push(' ');
                }
            }
        }
        if options.uppercase && !is_literal(lexeme.token) {
            out.extend(text.chars().map(|character| character.to_ascii_uppercase()));
        } else {
            out.push_str(text);
        }
        previous = Some(lexeme);
    }
    out
}

/// What the parser made of a line, with spans as token index ranges so that blanks do not count.
fn fingerprint(block: &Block, diagnostics: &[Diagnostic], lexemes: &[Lexeme]) -> Vec<u64> {
    let range = |span: Span| -> [u64; 2] {
        let start = lexemes.partition_point(|lexeme| lexeme.span.start() < span.start());
        let end = lexemes.partition_point(|lexeme| lexeme.span.end() <= span.end());
        [start as u64, end as u64]
    };
    let mut out: Vec<u64> = Vec::new();
    let push_span = |out: &mut Vec<u64>, tag: u64, span: Span| {
        out.push(tag);
        out.extend(range(span));
    };
    out.push(block.is_header as u64);
    out.push(
        block
            .sync_actions_from
            .map_or(u64::MAX, |index| index as u64),
    );
    if let Some((level, span)) = block.skip {
        push_span(&mut out, 1, span);
        out.push(u64::from(level));
    }
    if let Some(number) = block.number {
        push_span(&mut out, 2, number.span);
        out.extend([number.value, number.main as u64]);
    }
    if let Some(label) = block.label {
        push_span(&mut out, 3, label);
    }
    if let Some(comment) = block.comment {
        push_span(&mut out, 4, comment);
    }
    for statement in &block.statements {
        push_span(&mut out, 10 + statement_tag(statement), statement.span());
        match statement {
            Statement::Address(word) => {
                push_span(&mut out, 40, word.name);
                out.push(word.value.has_equals as u64);
                if let Some((modifier, span)) = word.value.modifier {
                    push_span(&mut out, 41 + modifier as u64, span);
                }
                if let ValueExpr::Constant { value, span } = word.value.expr {
                    push_span(&mut out, 60, span);
                    out.push(value.to_bits());
                }
            }
            Statement::GCode { code, .. } => {
                out.push(code.index_in_group() as u64 * 100 + code.group() as u64)
            }
            Statement::Call {
                name: Some(name),
                args,
                ..
            } => {
                push_span(&mut out, 61, *name);
                out.push(args.len() as u64);
            }
            Statement::Definition { names, .. } => {
                names.iter().for_each(|name| push_span(&mut out, 62, *name))
            }
            Statement::ProcedureHeader { parameters, .. } => parameters
                .iter()
                .for_each(|name| push_span(&mut out, 63, *name)),
            Statement::SectionRepeat { start, end, .. } => {
                push_span(&mut out, 64, *start);
                if let Some(end) = end {
                    push_span(&mut out, 65, *end);
                }
            }
            Statement::BlockRepeat {
                label: Some(label), ..
            } => push_span(&mut out, 66, *label),
            _ => {}
        }
    }
    for expr in &block.exprs {
        push_span(&mut out, 70 + expr_tag(&expr.kind), expr.span);
        if let ExprKind::Number(value) = expr.kind {
            out.push(value.to_bits());
        }
    }
    for diagnostic in diagnostics {
        push_span(&mut out, 200, diagnostic.span);
        out.push(diagnostic.code as u64);
    }
    out
}

fn statement_tag(statement: &Statement) -> u64 {
    match statement {
        Statement::GCode { .. } => 0,
        Statement::UnknownGCode { .. } => 1,
        Statement::Address(_) => 2,
        Statement::Assignment { .. } => 3,
        Statement::Structure { .. } => 4,
        Statement::Jump { .. } => 5,
        Statement::Call { .. } => 6,
        Statement::Definition { .. } => 7,
        Statement::MacroDefinition { .. } => 8,
        Statement::ProcedureHeader { .. } => 9,
        Statement::ExternDeclaration { .. } => 10,
        Statement::Return { .. } => 11,
        Statement::Instruction { .. } => 12,
        Statement::SyncCondition { .. } => 13,
        Statement::SectionRepeat { .. } => 14,
        Statement::BlockRepeat { .. } => 15,
        Statement::CaseBranch { .. } => 16,
    }
}

fn expr_tag(kind: &ExprKind) -> u64 {
    match kind {
        ExprKind::Number(_) => 0,
        ExprKind::String => 1,
        ExprKind::RParameter(number) => 100 + u64::from(*number),
        ExprKind::RParameterIndexed(_) => 2,
        ExprKind::Name { indexes } => 3 + 1000 * indexes.len() as u64,
        ExprKind::SystemVariable { indexes } => 4 + 1000 * indexes.len() as u64,
        ExprKind::Call { args, .. } => 5 + 1000 * args.len() as u64,
        ExprKind::Unary(op, _) => 6 + 10 * *op as u64,
        ExprKind::Binary(op, _, _) => 7 + 10 * *op as u64,
        ExprKind::Parenthesized(_) => 8,
        ExprKind::List(items) => 9 + 1000 * items.len() as u64,
        ExprKind::Error => 10,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn formatted(text: &str) -> String {
        format_text(text, &MachineConfig::default(), FormatOptions::default())
    }

    #[test]
    fn words_are_separated_and_upper_cased() {
        assert_eq!(formatted("n10 g0x10y5 t0d0\n"), "N10 G0 X10 Y5 T0 D0\n");
        assert_eq!(formatted("msg( \"a;b  c\" , 1 )\n"), "MSG(\"a;b  c\", 1)\n");
        assert_eq!(
            formatted("if r1  ==  1   gotof lbl1\n"),
            "IF R1 == 1 GOTOF LBL1\n"
        );
        assert_eq!(formatted("call \"part\"\n"), "CALL \"part\"\n");
    }

    #[test]
    fn comments_keep_their_column_and_bytes() {
        assert_eq!(
            formatted("g0x1      ; Änderung  \r\n"),
            "G0 X1     ; Änderung  \r\n"
        );
        assert_eq!(formatted("g0x1;c\n"), "G0 X1;c\n");
        assert_eq!(formatted("  ; only a comment\n"), "  ; only a comment\n");
    }

    #[test]
    fn indentation_and_blanks_after_the_block_number_are_kept() {
        assert_eq!(
            formatted("N10    if r1 > 0\n  g1 x1\n"),
            "N10    IF R1 > 0\n  G1 X1\n"
        );
        assert_eq!(formatted("   \n"), "\n");
        assert_eq!(formatted("/1n10g0x1\n"), "/1 N10 G0 X1\n");
    }

    #[test]
    fn repetitions_case_blocks_and_declarations_keep_their_layout() {
        assert_eq!(
            formatted("n20 repeat  lbl1   lbl2  p=3 ; c\n"),
            "N20 REPEAT LBL1 LBL2 P=3     ; c\n"
        );
        assert_eq!(formatted("repeatb lbl1 p=2\n"), "REPEATB LBL1 P=2\n");
        // The value of a CASE branch is no element of its own: no blank is put before it.
        assert_eq!(
            formatted("case r1 of(1)gotof l1 default gotof l2\n"),
            "CASE R1 OF(1) GOTOF L1 DEFAULT GOTOF L2\n"
        );
        assert_eq!(
            formatted("def real  tab[3]=( 1 , 2 ,3 ), bb=sin( 30 )\n"),
            "DEF REAL TAB[3]=(1, 2,3), BB=SIN(30)\n"
        );
        assert_eq!(
            formatted("proc sub( real pa=5 , var real tt[ , ] ) save\n"),
            "PROC SUB(REAL PA=5, VAR REAL TT[,]) SAVE\n"
        );
    }

    #[test]
    fn headers_and_unchanged_lines_are_left_alone() {
        let text = "%_N_part_MPF\nN10 G0 X1\n";
        assert_eq!(formatted(text), text);
    }
}
