//! The parts of `DEF` and `PROC` that a program's execution needs: array sizes, initial values, the
//! parameters of a subprogram with their types, `VAR` and defaults.
//!
//! Both statements are first read token by token (in `definitions.rs` and `calls.rs`): that reading finds the declared
//! names and reports what is wrong with the declaration. The reading here comes second, over the same
//! tokens, and builds the values with the expression parser (so they are nodes of the block's arena,
//! read with its depth limit). Its findings are dropped: the first reading has already said what is
//! wrong with the line, and the expression parser would say some of it again in other words. It only
//! ever moves forward from where the first reading found a name, so a line costs linear time.

use crate::diagnostics::Span;
use crate::syntax::ast::{DataType, Declarator, Initializer, ProcParameter};
use crate::syntax::lexer::Token;
use crate::syntax::parser::cursor::Parser;

/// What the second reading must give back to the parser: its findings so far and the flags that keep a
/// finding from being reported twice.
struct SavedFindings {
    count: usize,
    depth_reported: bool,
    unclosed_reported: bool,
    precedence_reported: bool,
}

impl Parser<'_> {
    fn save_findings(&self) -> SavedFindings {
        SavedFindings {
            count: self.diagnostics.len(),
            depth_reported: self.depth_reported,
            unclosed_reported: self.unclosed_reported,
            precedence_reported: self.precedence_reported,
        }
    }

    fn restore_findings(&mut self, saved: SavedFindings) {
        self.diagnostics.truncate(saved.count);
        self.depth_reported = saved.depth_reported;
        self.unclosed_reported = saved.unclosed_reported;
        self.precedence_reported = saved.precedence_reported;
    }

    /// The declarators of a `DEF` whose names the first reading found, read from the token after each
    /// name. Leaves the position where it was (at the end of the statement).
    pub(super) fn parse_declarators(&mut self, names: &[Span]) -> Vec<Declarator> {
        let end = self.position;
        let saved = self.save_findings();
        let mut declarators = Vec::with_capacity(names.len());
        let mut reached = 0;
        for name in names {
            let index = self
                .lexemes
                .partition_point(|lexeme| lexeme.span.start() < name.start());
            let mut declarator = Declarator {
                name: *name,
                dimensions: Vec::new(),
                initial: None,
            };
            // A declarator that ran over the next name (possible only on broken input) leaves that
            // name without sizes or value: going back would make the work grow with the square of
            // the line's length.
            if index >= reached && index < end {
                self.position = index + 1;
                declarator.name = self.whole_name(*name);
                if self.is_at(Token::LeftBracket) {
                    declarator.dimensions = self.parse_index_list().0;
                }
                if self.is_at(Token::Assign) {
                    self.advance();
                    let is_array = !declarator.dimensions.is_empty();
                    declarator.initial = self.parse_initializer(is_array);
                }
                reached = self.position;
            }
            declarators.push(declarator);
        }
        self.restore_findings(saved);
        self.position = end;
        declarators
    }

    /// `V1AR` lexes as a letter, a number and a name written together; the first reading of a DEF
    /// reports it as one name (S162) and keeps the span of its letter, that of a PROC reads over it.
    /// Declarators and parameters have the whole name. Called after the name's first token.
    fn whole_name(&mut self, name: Span) -> Span {
        let mut whole = name;
        if self.token_at(self.position - 1) == Some(Token::Letter)
            && self.is_at(Token::Number)
            && self.adjacent(self.position)
        {
            whole = whole.to(self.advance());
            if self.is_at(Token::Identifier) && self.adjacent(self.position) {
                whole = whole.to(self.advance());
            }
        }
        whole
    }

    /// The value after `=`: `SET(..)`, `REP(value[, count])`, a bracketed list for an array, or an
    /// expression. `None` when no value is written, or `REP` has none.
    fn parse_initializer(&mut self, is_array: bool) -> Option<Initializer> {
        if self.at_end() || self.is_at(Token::Comma) {
            return None;
        }
        if self.is_at(Token::Identifier) && self.peek_nth(1) == Some(Token::LeftParen) {
            let upper = self.upper_name(self.current_span());
            if upper == "SET" || upper == "REP" {
                self.advance();
                let args = self.parse_argument_list().0;
                if upper == "SET" {
                    return Some(Initializer::Set(args));
                }
                let mut args = args.into_iter();
                let value = args.next().flatten()?;
                let count = args.next().flatten();
                return Some(Initializer::Repeat { value, count });
            }
        }
        if is_array && self.is_at(Token::LeftParen) {
            return Some(Initializer::List(self.parse_argument_list().0));
        }
        Some(Initializer::Value(self.parse_expression()))
    }

    /// The parameters of a `PROC` whose list starts at the token `list_start` (when that token is `(`),
    /// one per comma-separated entry that names one. Leaves the position where it was (at the end of
    /// the statement).
    pub(super) fn parse_procedure_params(&mut self, list_start: usize) -> Vec<ProcParameter> {
        let end = self.position;
        let mut params = Vec::new();
        if self.token_at(list_start) != Some(Token::LeftParen) || list_start >= end {
            return params;
        }
        let saved = self.save_findings();
        self.position = list_start + 1;
        while !self.at_end() && !self.is_at(Token::RightParen) {
            if let Some(param) = self.parse_procedure_param() {
                params.push(param);
            }
            self.skip_to_entry_end();
            if self.is_at(Token::Comma) {
                self.advance();
            } else {
                break;
            }
        }
        self.restore_findings(saved);
        self.position = end;
        params
    }

    /// One entry of a parameter list: `[VAR] type name[[,]] [= default]`. The name is found as the
    /// first reading finds it: a name that ends the entry or is followed by `[` or `=`, and is not a
    /// type or `VAR`; other words before it are read over.
    fn parse_procedure_param(&mut self) -> Option<ProcParameter> {
        let mut by_reference = false;
        let mut data_type = None;
        let name = loop {
            if self.at_end() || matches!(self.peek(), Some(Token::Comma | Token::RightParen)) {
                return None;
            }
            match self.peek() {
                Some(Token::Identifier | Token::Letter) => {
                    let span = self.advance();
                    let span = self.whole_name(span);
                    let upper = self.upper_name(span);
                    let ends_name = self.at_end()
                        || matches!(
                            self.peek(),
                            Some(
                                Token::Comma
                                    | Token::RightParen
                                    | Token::LeftBracket
                                    | Token::Assign
                            )
                        );
                    if upper == "VAR" {
                        by_reference = true;
                    } else if let Some(named_type) = DataType::from_name(&upper) {
                        data_type = data_type.or(Some(named_type));
                        if self.is_at(Token::LeftBracket) {
                            // The length of `STRING[n]`.
                            self.skip_group();
                        }
                    } else if ends_name {
                        break span;
                    }
                }
                Some(Token::LeftParen | Token::LeftBracket) => {
                    self.skip_group();
                }
                _ => {
                    self.advance();
                }
            }
        };
        let dimensions = if self.is_at(Token::LeftBracket) {
            self.skip_group() + 1
        } else {
            0
        };
        let mut default = None;
        if self.is_at(Token::Assign) {
            self.advance();
            if !self.at_end() && !matches!(self.peek(), Some(Token::Comma | Token::RightParen)) {
                default = Some(self.parse_expression());
            }
        }
        Some(ProcParameter {
            name,
            data_type,
            by_reference,
            dimensions,
            default,
        })
    }

    /// Skips a bracketed group that starts at the current token, and returns the number of commas at
    /// its top level. An unclosed group ends with the statement.
    fn skip_group(&mut self) -> usize {
        let mut depth = 0usize;
        let mut commas = 0;
        while !self.at_end() {
            match self.peek() {
                Some(Token::LeftParen | Token::LeftBracket) => depth += 1,
                Some(Token::RightParen | Token::RightBracket) => {
                    depth = depth.saturating_sub(1);
                    if depth == 0 {
                        self.advance();
                        break;
                    }
                }
                Some(Token::Comma) if depth == 1 => commas += 1,
                _ => {}
            }
            self.advance();
        }
        commas
    }

    /// Skips to the comma that ends the current entry of a parameter list, or to its closing `)`.
    fn skip_to_entry_end(&mut self) {
        while !self.at_end() && !matches!(self.peek(), Some(Token::Comma | Token::RightParen)) {
            if matches!(self.peek(), Some(Token::LeftParen | Token::LeftBracket)) {
                self.skip_group();
            } else {
                self.advance();
            }
        }
    }
}
