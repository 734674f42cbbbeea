//! Span checks shared by the fuzz targets and the hostile-input tests: every span of a block, of a
//! diagnostic and of a fix lies inside its line and on character boundaries.

use sinumerik_lsp::diagnostics::{Diagnostic, Span};
use sinumerik_lsp::syntax::ast::{Expr, ExprKind, Extension, JumpTarget, Statement, ValueExpr};
use sinumerik_lsp::syntax::Block;

/// `Err` names the span that is not inside `line` or not on character boundaries.
pub fn check_span(line: &str, span: Span, what: &str) -> Result<(), String> {
    let (start, end) = (span.start(), span.end());
    if !(start <= end && end <= line.len()) {
        return Err(format!(
            "{what}: span {start}..{end} is not inside the line of {} bytes",
            line.len()
        ));
    }
    if !(line.is_char_boundary(start) && line.is_char_boundary(end)) {
        return Err(format!(
            "{what}: span {start}..{end} does not lie on character boundaries"
        ));
    }
    Ok(())
}

/// Checks the spans of the diagnostics of one line and of their fixes.
pub fn check_diagnostic_spans(line: &str, diagnostics: &[Diagnostic]) -> Result<(), String> {
    for diagnostic in diagnostics {
        let what = format!("diagnostic {}", diagnostic.code.as_str());
        check_span(line, diagnostic.span, &what)?;
        if let Some(fix) = &diagnostic.fix {
            for edit in &fix.edits {
                check_span(line, edit.span, &format!("fix of {what}"))?;
            }
        }
    }
    Ok(())
}

/// Checks every span a block holds: its markers, its statements with their parts, its expression nodes.
pub fn check_block_spans(line: &str, block: &Block) -> Result<(), String> {
    let mut spans: Vec<Span> = Vec::new();
    spans.extend(block.skip.map(|(_, span)| span));
    spans.extend(block.number.map(|number| number.span));
    spans.extend(block.label);
    spans.extend(block.comment);
    for statement in &block.statements {
        spans.push(statement.span());
        match statement {
            Statement::Address(word) => {
                spans.push(word.name);
                match &word.extension {
                    Some(Extension::Number { span, .. }) | Some(Extension::Index { span, .. }) => {
                        spans.push(*span)
                    }
                    None => {}
                }
                spans.extend(word.value.modifier.map(|(_, span)| span));
                if let ValueExpr::Constant { span, .. } = word.value.expr {
                    spans.push(span);
                }
            }
            Statement::Assignment { target_span, .. } => spans.push(*target_span),
            Statement::Jump { target, .. } => match target {
                JumpTarget::Label(span) | JumpTarget::BlockNumber { span, .. } => spans.push(*span),
                JumpTarget::Computed(_) | JumpTarget::None => {}
            },
            Statement::Call { name, .. }
            | Statement::ExternDeclaration { name, .. }
            | Statement::MacroDefinition { name, .. } => spans.extend(*name),
            Statement::Definition { names, .. } => spans.extend(names),
            Statement::ProcedureHeader {
                name, parameters, ..
            } => {
                spans.extend(*name);
                spans.extend(parameters);
            }
            Statement::Instruction { name, .. } => spans.push(*name),
            _ => {}
        }
        if let Statement::MacroDefinition { body, .. } = statement {
            spans.push(*body);
        }
    }
    for Expr { kind, span } in &block.exprs {
        spans.push(*span);
        if let ExprKind::Call { name, .. } = kind {
            spans.push(*name);
        }
    }
    for span in spans {
        check_span(line, span, "block")?;
    }
    Ok(())
}
