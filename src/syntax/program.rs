//! The syntax check of a whole program text: every block parsed once, the cross-block structure
//! checked, and a visitor handed each block so that later passes need no second parse.

use crate::config::MachineConfig;
use crate::diagnostics::LineDiagnostic;
use crate::syntax::ast::Block;
use crate::syntax::context::SyntaxContext;
use crate::syntax::keyword_lines::macro_names;
use crate::syntax::lines;
use crate::syntax::parser::LineParser;
use crate::syntax::structure;

/// All syntax diagnostics of a program text, lines 0-based, severities after the configuration's
/// overrides, sorted by line and column.
pub fn check_program(text: &str, config: &MachineConfig) -> Vec<LineDiagnostic> {
    visit_blocks(text, config, |_, _, _, _| {})
}

/// Parses every block of `text` once and hands it to `visit` (with its line number and text, and the
/// list to which the visitor may add findings of that line). Returns the syntax diagnostics together
/// with the visitor's, with the configured severities, sorted by line and column.
pub fn visit_blocks(
    text: &str,
    config: &MachineConfig,
    visit: impl FnMut(usize, &str, &Block, &mut Vec<crate::diagnostics::Diagnostic>),
) -> Vec<LineDiagnostic> {
    visit_blocks_with_macros(text, config, &[], visit)
}

/// Like [`visit_blocks`], with the macros of definition files (`library_macros`) known besides the
/// program's own.
pub fn visit_blocks_with_macros(
    text: &str,
    config: &MachineConfig,
    library_macros: &[&str],
    mut visit: impl FnMut(usize, &str, &Block, &mut Vec<crate::diagnostics::Diagnostic>),
) -> Vec<LineDiagnostic> {
    let mut context = SyntaxContext::new(config);
    for name in library_macros.iter().copied().chain(macro_names(text)) {
        context.add_macro(name);
    }
    let mut parser = LineParser::new();
    let mut block = Block::default();
    let mut line_diagnostics = Vec::new();
    let mut visitor_diagnostics = Vec::new();
    let mut structure = structure::StructureChecker::default();
    let mut out = Vec::new();
    for (line_index, (start, end)) in lines::line_ranges(text).enumerate() {
        let line = &text[start..end];
        parser.parse(line, &context, &mut block, &mut line_diagnostics);
        out.extend(line_diagnostics.drain(..).map(|diagnostic| LineDiagnostic {
            line: line_index,
            diagnostic,
        }));
        structure.feed(line_index, &block, &mut out);
        visit(line_index, line, &block, &mut visitor_diagnostics);
        out.extend(
            visitor_diagnostics
                .drain(..)
                .map(|diagnostic| LineDiagnostic {
                    line: line_index,
                    diagnostic,
                }),
        );
    }
    structure.finish(&mut out);
    for item in &mut out {
        item.diagnostic.severity = config.severity_of(item.diagnostic.code);
    }
    out.sort_by_key(|item| (item.line, item.diagnostic.span.start()));
    crate::syntax::unconfigured_axes::summarize(&mut out);
    out
}
