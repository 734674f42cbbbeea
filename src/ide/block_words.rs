//! The words of one block as the hover and the inlay hints read them: which word the cursor is on,
//! which axes a block writes and how, whether it moves by polar words or to machine positions. The
//! words and their spans are the parser's (`syntax::ast`), the same the analysis reads; what the
//! words mean comes from the analysis (`BlockReport`, `Move`).

use crate::config::MachineConfig;
use crate::diagnostics::Span;
use crate::syntax::ast::{
    AddressWord, Block, ExprKind, Extension, Modifier, Statement, UnaryOp, ValueExpr,
};
use crate::syntax::gcodes::GCode;
use crate::syntax::{LineParser, SyntaxContext};

/// One parsed block with its line.
pub struct BlockWords<'a> {
    line: &'a str,
    block: Block,
}

/// An axis word: an address word with a value whose name is a configured axis.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisWord {
    /// The whole word (`Z=IC(-32)`).
    pub span: Span,
    /// The configured axis's name.
    pub axis: String,
    /// The position modifier written with it (`IC` in `Z=IC(-32)`).
    pub modifier: Option<Modifier>,
    /// The number written, after the address or inside the modifier (`-32`); `None` for any other
    /// value (a variable, an expression).
    pub literal: Option<f64>,
    /// The number when it is written right after the address without `=` (`X-12`): the words whose
    /// end point is plain to read.
    pub constant: Option<f64>,
    /// `=` was written.
    pub has_equals: bool,
}

/// What the cursor is on.
#[derive(Debug, Clone, PartialEq)]
pub enum WordAt {
    Axis(AxisWord),
    GCode {
        code: GCode,
        span: Span,
    },
    /// Any other part of the block (block number, label, keyword, call, ...).
    Other,
}

impl<'a> BlockWords<'a> {
    /// Parses `line` as a block of a program for the machine `config`.
    pub fn parse(line: &'a str, config: &MachineConfig) -> BlockWords<'a> {
        BlockWords::parse_in(line, &SyntaxContext::new(config))
    }

    /// Parses `line` with a context prepared once for many lines.
    pub fn parse_in(line: &'a str, context: &SyntaxContext) -> BlockWords<'a> {
        let mut block = Block::default();
        let mut findings = Vec::new();
        LineParser::new().parse(line, context, &mut block, &mut findings);
        BlockWords { line, block }
    }

    /// Whether the block holds nothing to explain: no block number, label or statement, and no
    /// name before its comment (an empty line, a comment alone). A block the parser could not read
    /// (`G(89 + ABSINC_)`) still has its state and end point to show.
    pub fn is_empty(&self) -> bool {
        let code_end = self
            .block
            .comment
            .map_or(self.line.len(), |comment| comment.start());
        self.block.number.is_none()
            && self.block.label.is_none()
            && self.block.statements.is_empty()
            && !self.block.is_header
            && !self.line.as_bytes()[..code_end.min(self.line.len())]
                .iter()
                .any(|byte| byte.is_ascii_alphabetic() || matches!(byte, b'_' | b'$'))
    }

    /// The spans of the block's parts in order: block number, label, statements.
    fn parts(&self) -> impl Iterator<Item = (Span, Option<&Statement>)> {
        let number = self.block.number.map(|number| (number.span, None));
        let label = self.block.label.map(|label| (label, None));
        number.into_iter().chain(label).chain(
            self.block
                .statements
                .iter()
                .map(|statement| (statement.span(), Some(statement))),
        )
    }

    /// The word under the cursor at byte `offset`: the part of the block that holds it, else the one
    /// that ends right at it (a cursor after the last character of a word).
    pub fn at(&self, offset: usize, config: &MachineConfig) -> Option<WordAt> {
        let (_, statement) = self
            .parts()
            .find(|(span, _)| span.start() <= offset && offset < span.end())
            .or_else(|| self.parts().find(|(span, _)| span.end() == offset))?;
        Some(match statement {
            Some(Statement::Address(word)) => self
                .axis_word(word, config)
                .map_or(WordAt::Other, WordAt::Axis),
            Some(Statement::GCode { code, span }) => WordAt::GCode {
                code: *code,
                span: *span,
            },
            _ => WordAt::Other,
        })
    }

    /// The axis words of the block, in order.
    pub fn axis_words<'b>(
        &'b self,
        config: &'b MachineConfig,
    ) -> impl Iterator<Item = AxisWord> + 'b {
        self.block
            .statements
            .iter()
            .filter_map(move |statement| match statement {
                Statement::Address(word) => self.axis_word(word, config),
                _ => None,
            })
    }

    /// Whether the block programs machine positions (G53, G153, SUPA).
    pub fn is_machine_block(&self) -> bool {
        self.block.statements.iter().any(|statement| {
            matches!(statement, Statement::GCode { code, .. }
                if matches!(code.name().as_ref(), "G53" | "G153" | "SUPA"))
        })
    }

    /// Whether the block writes a polar angle or radius (AP, RP).
    pub fn has_polar_words(&self) -> bool {
        self.block.statements.iter().any(|statement| {
            matches!(statement, Statement::Address(word)
                if !matches!(word.value.expr, ValueExpr::Missing)
                    && ["AP", "RP"].iter().any(|name| name.eq_ignore_ascii_case(self.text(word.name))))
        })
    }

    /// Whether the block calls a program: its hover then shows what the call ran.
    pub fn calls_a_program(&self) -> bool {
        self.block.interpreted_statements().iter().any(|statement| {
            matches!(
                statement,
                Statement::Call {
                    kind: crate::syntax::ast::CallKind::Named
                        | crate::syntax::ast::CallKind::Indirect,
                    ..
                }
            )
        })
    }

    /// The position modifier written without its parentheses in an axis word (`X=AC 5`), which the
    /// control reads as a variable named `AC`; `None` for any other word. The parser reports S101
    /// there and may keep the modifier, so the text after `=` decides.
    pub fn modifier_without_brackets(&self, word: &AxisWord) -> Option<&'a str> {
        if !word.has_equals {
            return None;
        }
        let text = self.line.get(word.span.start()..)?;
        let after_equals = text[text.find('=')? + 1..].trim_start();
        let name_length = after_equals
            .bytes()
            .take_while(|byte| byte.is_ascii_alphabetic())
            .count();
        let name = &after_equals[..name_length];
        let next = after_equals[name_length..].trim_start().chars().next();
        (Modifier::from_name(name).is_some() && next != Some('(')).then_some(name)
    }

    fn text(&self, span: Span) -> &'a str {
        self.line.get(span.start()..span.end()).unwrap_or("")
    }

    fn axis_word(&self, word: &AddressWord, config: &MachineConfig) -> Option<AxisWord> {
        if matches!(word.value.expr, ValueExpr::Missing) && !word.value.has_equals {
            return None;
        }
        // The name as written with its numeric extension (`X1` in `X1=10`).
        let name_end = match &word.extension {
            None => word.name.end(),
            Some(Extension::Number { span, .. }) => span.end(),
            Some(Extension::Index { .. }) => return None,
        };
        let name = self.line.get(word.name.start()..name_end)?;
        let axis = config.axis(name)?.name.clone();
        let constant = match word.value.expr {
            ValueExpr::Constant { value, .. } if !word.value.has_equals => Some(value),
            _ => None,
        };
        let literal = match word.value.expr {
            ValueExpr::Constant { value, .. } => Some(value),
            ValueExpr::Expr(id) => self.number(id),
            ValueExpr::Missing => None,
        };
        Some(AxisWord {
            span: word.span,
            axis,
            modifier: word.value.modifier.map(|(modifier, _)| modifier),
            literal,
            constant,
            has_equals: word.value.has_equals,
        })
    }

    /// The value of a number written with its sign (`5`, `-32`, `+.5`), not of any other expression.
    fn number(&self, id: crate::syntax::ast::ExprId) -> Option<f64> {
        match &self.block.expr(id).kind {
            ExprKind::Number(value) => Some(*value),
            ExprKind::Unary(UnaryOp::Negate, inner) => match self.block.expr(*inner).kind {
                ExprKind::Number(value) => Some(-value),
                _ => None,
            },
            ExprKind::Unary(UnaryOp::Plus, inner) => match self.block.expr(*inner).kind {
                ExprKind::Number(value) => Some(value),
                _ => None,
            },
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axis_at(line: &str, offset: usize) -> Option<AxisWord> {
        let config = MachineConfig::mill();
        match BlockWords::parse(line, &config).at(offset, &config)? {
            WordAt::Axis(word) => Some(word),
            _ => None,
        }
    }

    #[test]
    fn the_word_under_the_cursor_is_found_from_the_parsers_spans() {
        let line = "N20 X75 Z=IC(-32)";
        let z = axis_at(line, 12).unwrap();
        assert_eq!(&line[z.span.start()..z.span.end()], "Z=IC(-32)");
        assert_eq!(z.modifier, Some(Modifier::Ic));
        assert_eq!(z.literal, Some(-32.0));
        assert_eq!(z.constant, None);
        let x = axis_at(line, 7).unwrap();
        assert_eq!((x.axis.as_str(), x.constant), ("X", Some(75.0)));
        assert_eq!(axis_at(line, 3), None);
        let config = MachineConfig::mill();
        assert_eq!(
            BlockWords::parse(line, &config).at(1, &config),
            Some(WordAt::Other)
        );
        assert!(BlockWords::parse("", &config).is_empty());
        assert!(BlockWords::parse("  ; only a comment", &config).is_empty());
        assert!(!BlockWords::parse("MARKE:", &config).is_empty());
    }

    #[test]
    fn words_run_together_split_where_the_parser_splits_them() {
        let config = MachineConfig::mill();
        let words = BlockWords::parse("G90X20Z.5 DIAMON", &config);
        let found: Vec<(String, Option<f64>)> = words
            .axis_words(&config)
            .map(|word| (word.axis, word.constant))
            .collect();
        assert_eq!(
            found,
            vec![("X".to_string(), Some(20.0)), ("Z".to_string(), Some(0.5))]
        );
        // Offset 3 ends G90 and starts X20: the word that holds it wins.
        assert!(matches!(words.at(3, &config), Some(WordAt::Axis(word)) if word.axis == "X"));
        assert!(
            matches!(words.at(2, &config), Some(WordAt::GCode { code, .. }) if code.name() == "G90")
        );
        assert!(
            matches!(words.at(16, &config), Some(WordAt::GCode { code, .. }) if code.name() == "DIAMON")
        );
    }

    #[test]
    fn a_modifier_without_parentheses_is_found() {
        let config = MachineConfig::mill();
        let line = "N20 X=AC 5";
        let words = BlockWords::parse(line, &config);
        let Some(WordAt::Axis(x)) = words.at(4, &config) else {
            panic!("no axis word at X");
        };
        assert_eq!(words.modifier_without_brackets(&x), Some("AC"));
        let line = "N20 X=AC(5) Y=R1";
        let words = BlockWords::parse(line, &config);
        assert!(words
            .axis_words(&config)
            .all(|word| words.modifier_without_brackets(&word).is_none()));
    }

    #[test]
    fn machine_positions_polar_words_and_calls_are_seen() {
        let config = MachineConfig::mill();
        assert!(BlockWords::parse("G53 X5", &config).is_machine_block());
        assert!(BlockWords::parse("supa z0", &config).is_machine_block());
        assert!(!BlockWords::parse("G54 X5", &config).is_machine_block());
        assert!(BlockWords::parse("G1 AP=90 RP=5", &config).has_polar_words());
        assert!(!BlockWords::parse("G1 X5", &config).has_polar_words());
        assert!(BlockWords::parse("N10 SUB_A", &config).calls_a_program());
        assert!(!BlockWords::parse("N10 G0 X1", &config).calls_a_program());
    }
}
