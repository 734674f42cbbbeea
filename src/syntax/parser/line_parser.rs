//! The parser's public face: [`LineParser`] reuses its buffers from line to line and takes the fast
//! path for plain blocks when it can; [`parse_line`] parses a single line.

use crate::diagnostics::Diagnostic;
use crate::syntax::ast::Block;
use crate::syntax::context::SyntaxContext;
use crate::syntax::lexer::{lex_line_into, Lexeme};
use crate::syntax::parser::cursor::Parser;

/// A reusable parser: keeps its token buffer between lines.
#[derive(Default)]
pub struct LineParser {
    lexemes: Vec<Lexeme>,
    /// The height of each expression node of the block being parsed (see [`MAX_TREE_HEIGHT`]).
    heights: Vec<u32>,
}

impl LineParser {
    pub fn new() -> LineParser {
        LineParser::default()
    }

    /// Parses `line` (without its line terminator) into `block` and appends the findings to
    /// `diagnostics`. Both are cleared first; their allocations are reused.
    pub fn parse(
        &mut self,
        line: &str,
        context: &SyntaxContext,
        block: &mut Block,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        self.parse_with(line, context, block, diagnostics, true);
    }

    /// Like [`LineParser::parse`], but never takes the fast path for plain blocks. Exists so that tests
    /// can prove both paths give the same result.
    #[doc(hidden)]
    pub fn parse_without_fast_path(
        &mut self,
        line: &str,
        context: &SyntaxContext,
        block: &mut Block,
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        self.parse_with(line, context, block, diagnostics, false);
    }

    fn parse_with(
        &mut self,
        line: &str,
        context: &SyntaxContext,
        block: &mut Block,
        diagnostics: &mut Vec<Diagnostic>,
        allow_fast_path: bool,
    ) {
        block.clear();
        diagnostics.clear();
        if allow_fast_path {
            let mut parser = Parser::new(line, &[], block, diagnostics, context, &mut self.heights);
            if parser.parse_plain_block() {
                return;
            }
            block.clear();
            diagnostics.clear();
        }
        lex_line_into(line, &mut self.lexemes);
        Parser::new(
            line,
            &self.lexemes,
            block,
            diagnostics,
            context,
            &mut self.heights,
        )
        .parse_block();
    }
}

/// Parses one line with a fresh parser; convenient for tests and single lookups.
pub fn parse_line(line: &str, context: &SyntaxContext) -> (Block, Vec<Diagnostic>) {
    let mut block = Block::default();
    let mut diagnostics = Vec::new();
    LineParser::new().parse(line, context, &mut block, &mut diagnostics);
    (block, diagnostics)
}
