//! Macros defined with `DEFINE name AS body` in the program (reference §8.10): a block that uses one is
//! interpreted as the control does, with the name replaced by its body, e.g. `N30 RETRACT` as
//! `N30 G0 G53 Z0 D0`. The interpreter also gives the engine the macros of the library's definition
//! files (`execution/library_macros.rs`); macros of files the analysis has not seen stay calls.

use crate::analysis::engine::engine_state::Engine;
use crate::diagnostics::{Diagnostic, Span};
use crate::syntax::ast::{AddressKind, Block, CallKind, Statement};

/// How deep macros may expand into other macros before the block is left as a call.
const MAX_EXPANSION_DEPTH: u8 = 8;

impl Engine<'_> {
    /// Knows the macros of the library's definition files before the program's first block (in
    /// reading order; the program's own definitions replace them when they are passed).
    pub(crate) fn define_library_macros(&mut self, definitions: &[(String, String)]) {
        for (name, body) in definitions {
            self.memory.macros.retain(|(known, _)| known != name);
            self.memory.macros.push((name.clone(), body.clone()));
        }
    }

    /// Whether `name` (any case) is a macro the engine knows at this point: a use of it is expanded,
    /// never run as a call.
    pub(crate) fn is_macro(&self, name: &str) -> bool {
        self.memory
            .macros
            .iter()
            .any(|(known, _)| known.eq_ignore_ascii_case(name))
    }

    /// Remembers the macros this block defines.
    pub(super) fn record_macro_definitions(&mut self, line: &str, block: &Block) {
        for statement in &block.statements {
            if let Some((upper, body)) = macro_definition(line, statement) {
                self.memory.macros.retain(|(known, _)| *known != upper);
                self.memory.macros.push((upper, body));
            }
        }
    }

    /// The block's text with its first use of a known macro replaced by the macro's body, and the span
    /// of that use; `None` when the block uses no macro (or expansion is nested too deeply).
    pub(super) fn expand_macro(&self, line: &str, block: &Block) -> Option<(String, Span)> {
        if self.memory.macros.is_empty() || self.expansion_depth >= MAX_EXPANSION_DEPTH {
            return None;
        }
        block
            .interpreted_statements()
            .iter()
            .find_map(|statement| match statement {
                Statement::Call {
                    kind: CallKind::Named,
                    name: Some(name),
                    args,
                    span,
                } if args.is_empty() => {
                    let written = &line[name.start()..name.end()];
                    let (_, body) = self
                        .memory
                        .macros
                        .iter()
                        .find(|(known, _)| known.eq_ignore_ascii_case(written))?;
                    let expanded =
                        format!("{} {body} {}", &line[..span.start()], &line[span.end()..]);
                    Some((expanded, *span))
                }
                // An M number may be a macro too (`DEFINE M101 AS ...`): the parser reads it as an
                // M function, so its written text is compared.
                Statement::Address(word) if word.kind == AddressKind::MFunction => {
                    let written = line.get(word.span.start()..word.span.end())?;
                    let (_, body) = self
                        .memory
                        .macros
                        .iter()
                        .find(|(known, _)| known.eq_ignore_ascii_case(written))?;
                    let expanded = format!(
                        "{} {body} {}",
                        &line[..word.span.start()],
                        &line[word.span.end()..]
                    );
                    Some((expanded, word.span))
                }
                _ => None,
            })
    }

    /// Interprets the expanded block in place of the written one. Analysis findings of the expansion
    /// are placed on the macro's use. Syntax findings inside the body are not reported: a body is text
    /// until it is used, and its findings would have no place in the written line.
    pub(super) fn step_expanded(
        &mut self,
        expanded: &str,
        used_at: Span,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> bool {
        let mut context = crate::syntax::context::SyntaxContext::new(self.config);
        for (name, _) in &self.memory.macros {
            context.add_macro(name);
        }
        let mut parser = crate::syntax::parser::LineParser::new();
        let mut block = Block::default();
        let mut syntax_findings = Vec::new();
        parser.parse(expanded, &context, &mut block, &mut syntax_findings);
        let mut findings = Vec::new();
        self.expansion_depth += 1;
        let moved = self.step(expanded, &block, &mut findings);
        self.expansion_depth -= 1;
        diagnostics.extend(findings.into_iter().map(|mut finding| {
            finding.span = used_at;
            finding
        }));
        moved
    }
}

/// The upper-case name and the body of the macro `statement` (of `line`) defines. The name is read
/// from the text: the parser splits a name made of an address letter and a number (`G300`, `M101`,
/// `A1`) into the letter and a value, and its body span then starts at the number.
pub(crate) fn macro_definition(line: &str, statement: &Statement) -> Option<(String, String)> {
    let Statement::MacroDefinition {
        name: Some(_),
        body,
        span,
    } = statement
    else {
        return None;
    };
    let definition = line.get(span.start()..body.end())?;
    let name = crate::syntax::macro_defined_by(definition)?;
    // The statement starts with its keyword, and the name follows it.
    let rest = definition.get("DEFINE".len()..)?.trim_start();
    let after_name = rest.get(name.len()..)?.trim_start();
    let body = after_name.get(2..)?.trim();
    Some((name.to_ascii_uppercase(), body.to_string()))
}
