//! The syntax layer: lexer, block parser, syntax diagnostics. No IO and no protocol types: text in,
//! blocks and diagnostics out.

pub mod ast;
pub mod context;
pub mod gcodes;
pub mod keywords;
pub mod lexer;
pub mod lines;
pub mod parser;
pub mod structure;

pub use ast::Block;
pub use context::SyntaxContext;
pub use parser::{parse_line, LineParser};

use crate::config::MachineConfig;
use crate::diagnostics::LineDiagnostic;

/// All syntax diagnostics of a program text, lines 0-based, severities after the configuration's
/// overrides, sorted by line and column.
pub fn check_program(text: &str, config: &MachineConfig) -> Vec<LineDiagnostic> {
    let context = SyntaxContext::new(config);
    let mut parser = LineParser::new();
    let mut block = Block::default();
    let mut line_diagnostics = Vec::new();
    let mut structure = structure::StructureChecker::default();
    let mut out = Vec::new();
    for (line_index, (start, end)) in lines::line_ranges(text).enumerate() {
        parser.parse(&text[start..end], &context, &mut block, &mut line_diagnostics);
        out.extend(line_diagnostics.drain(..).map(|diagnostic| LineDiagnostic {
            line: line_index,
            diagnostic,
        }));
        structure.feed(line_index, &block, &mut out);
    }
    structure.finish(&mut out);
    for item in &mut out {
        item.diagnostic.severity = config.severity_of(item.diagnostic.code);
    }
    out.sort_by_key(|item| (item.line, item.diagnostic.span.start));
    out
}
