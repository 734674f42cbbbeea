//! The properties the parser and the full analysis must keep on any text. Each check returns `Err`
//! with a description when a property fails; a panic is caught by the caller.

use super::approx::approx_equal;
use super::spans::{check_block_spans, check_diagnostic_spans, check_span};
use sinumerik_lsp::analysis::document::{DocumentAnalysis, TextLines};
use sinumerik_lsp::analysis::{analyze_program, diagnose_program, visit_moves, Move, ProgramKind};
use sinumerik_lsp::config::MachineConfig;
use sinumerik_lsp::diagnostics::LineDiagnostic;
use sinumerik_lsp::syntax::parser::MAX_DIAGNOSTICS_PER_LINE;
use sinumerik_lsp::syntax::{lines, macro_names, Block, LineParser, SyntaxContext};
use std::sync::Arc;

/// The longest message a diagnostic may have: messages quote at most 60 characters of the line.
const MAX_MESSAGE_BYTES: usize = 1_000;

/// The machines and program kinds every text is analysed with.
pub fn configurations() -> [(Arc<MachineConfig>, ProgramKind); 2] {
    [
        (Arc::new(MachineConfig::mill()), ProgramKind::Main),
        (Arc::new(MachineConfig::turn()), ProgramKind::Subprogram),
    ]
}

/// The block parser: every line yields a block and diagnostics, with spans inside the line on
/// character boundaries, a bounded number of findings, short messages, and the fast path for plain
/// blocks gives what the general parser gives.
pub fn check_parser(text: &str) -> Result<(), String> {
    let config = MachineConfig::mill();
    let mut context = SyntaxContext::new(&config);
    for name in macro_names(text) {
        context.add_macro(name);
    }
    let mut parser = LineParser::new();
    let mut fast = (Block::default(), Vec::new());
    let mut general = (Block::default(), Vec::new());
    for (index, (start, end)) in lines::line_ranges(text).enumerate() {
        let line = &text[start..end];
        let at = |problem: String| format!("line {}: {problem}", index + 1);
        if line.contains(['\n', '\r']) {
            return Err(at("the line splitter left a line end inside a line".into()));
        }
        parser.parse(line, &context, &mut fast.0, &mut fast.1);
        check_block_spans(line, &fast.0).map_err(at)?;
        check_diagnostic_spans(line, &fast.1).map_err(at)?;
        if fast.1.len() > MAX_DIAGNOSTICS_PER_LINE {
            return Err(at(format!("{} diagnostics on one line", fast.1.len())));
        }
        check_messages(fast.1.iter()).map_err(at)?;
        parser.parse_without_fast_path(line, &context, &mut general.0, &mut general.1);
        if fast.0 != general.0 {
            return Err(at(
                "the fast path builds another block than the general parser".into(),
            ));
        }
        if fast.1 != general.1 {
            return Err(at(format!(
                "the fast path reports {:?}, the general parser {:?}",
                codes(&fast.1),
                codes(&general.1)
            )));
        }
    }
    Ok(())
}

/// The full analysis: `analyze_program`, `diagnose_program` and `visit_moves` agree, diagnostics are
/// sorted and inside their lines, moves hold only finite numbers, and the document analysis (what the
/// language server publishes) reports what `check` reports, with the same moves.
pub fn check_analysis(text: &str) -> Result<(), String> {
    let line_texts: Vec<&str> = lines::line_ranges(text)
        .map(|(start, end)| &text[start..end])
        .collect();
    for (config, kind) in configurations() {
        let analysis = analyze_program(text, &config, kind);
        let diagnosed = diagnose_program(text, &config, kind);
        let mut visited = 0usize;
        let mut visit_problem = Ok(());
        let visited_diagnostics = visit_moves(text, &config, kind, |movement| {
            if visit_problem.is_ok() {
                visit_problem = match analysis.moves.get(visited) {
                    Some(kept) if kept == movement => Ok(()),
                    _ => Err(format!("visit_moves gives another move {visited}")),
                };
            }
            visited += 1;
        });
        visit_problem?;
        if visited != analysis.moves.len() {
            return Err(format!(
                "visit_moves gives {visited} moves, analyze_program {}",
                analysis.moves.len()
            ));
        }
        if diagnosed != analysis.diagnostics || visited_diagnostics != analysis.diagnostics {
            return Err("diagnose_program, visit_moves and analyze_program disagree".into());
        }
        check_program_diagnostics(&line_texts, &analysis.diagnostics)?;
        for movement in &analysis.moves {
            check_move_numbers(movement)?;
        }
        let source = TextLines::new(text);
        let document = DocumentAnalysis::new(&source, config.clone(), kind);
        if document.diagnostics() != diagnosed.as_slice() {
            return Err(format!(
                "the document analysis reports {} diagnostics, check {}: first difference {}",
                document.diagnostics().len(),
                diagnosed.len(),
                first_difference(document.diagnostics(), &diagnosed)
            ));
        }
        let document_moves = document.moves(&source, 0..line_texts.len());
        if document_moves.len() != analysis.moves.len() {
            return Err(format!(
                "the document analysis gives {} moves, analyze_program {}",
                document_moves.len(),
                analysis.moves.len()
            ));
        }
        for (document_move, program_move) in document_moves.iter().zip(&analysis.moves) {
            approx_equal(document_move, program_move, 1e-6)
                .map_err(|problem| format!("move of line {}: {problem}", program_move.line + 1))?;
        }
    }
    Ok(())
}

/// Diagnostics of a whole program: sorted by line and column, on existing lines, spans inside them,
/// messages short.
pub fn check_program_diagnostics(
    line_texts: &[&str],
    diagnostics: &[LineDiagnostic],
) -> Result<(), String> {
    let sorted = diagnostics.windows(2).all(|pair| {
        (pair[0].line, pair[0].diagnostic.span.start())
            <= (pair[1].line, pair[1].diagnostic.span.start())
    });
    if !sorted {
        return Err("the diagnostics are not sorted by line and column".into());
    }
    for item in diagnostics {
        let Some(line) = line_texts.get(item.line) else {
            // An empty program has no line; a finding there may only sit at the start.
            if line_texts.is_empty() && item.line == 0 {
                check_span("", item.diagnostic.span, "diagnostic")?;
                continue;
            }
            return Err(format!(
                "{} on line {} of a program of {} lines",
                item.diagnostic.code.as_str(),
                item.line + 1,
                line_texts.len()
            ));
        };
        check_diagnostic_spans(line, std::slice::from_ref(&item.diagnostic))
            .map_err(|problem| format!("line {}: {problem}", item.line + 1))?;
    }
    check_messages(diagnostics.iter().map(|item| &item.diagnostic))
}

/// A move shows numbers only where they are known: never NaN or infinity.
pub fn check_move_numbers(movement: &Move) -> Result<(), String> {
    let mut numbers: Vec<(&str, f64)> = Vec::new();
    numbers.extend(movement.start.iter().map(|(_, value)| ("start", *value)));
    numbers.extend(movement.end.iter().map(|(_, value)| ("end", *value)));
    if let Some(machine) = &movement.machine {
        numbers.extend(machine.iter().map(|(_, value)| ("mcs", *value)));
    }
    numbers.extend(movement.feed.map(|feed| ("feed", feed)));
    if let Some(arc) = &movement.arc {
        numbers.extend(arc.centre.iter().map(|(_, value)| ("arc centre", *value)));
        numbers.push(("arc radius", arc.radius));
        numbers.push(("arc sweep", arc.sweep));
    }
    match numbers.iter().find(|(_, value)| !value.is_finite()) {
        Some((what, value)) => Err(format!(
            "the move of line {} shows {value} as its {what}",
            movement.line + 1
        )),
        None => Ok(()),
    }
}

fn check_messages<'a>(
    diagnostics: impl Iterator<Item = &'a sinumerik_lsp::diagnostics::Diagnostic>,
) -> Result<(), String> {
    for diagnostic in diagnostics {
        if diagnostic.message.len() > MAX_MESSAGE_BYTES {
            return Err(format!(
                "{} has a message of {} bytes",
                diagnostic.code.as_str(),
                diagnostic.message.len()
            ));
        }
    }
    Ok(())
}

fn codes(diagnostics: &[sinumerik_lsp::diagnostics::Diagnostic]) -> Vec<&'static str> {
    diagnostics.iter().map(|item| item.code.as_str()).collect()
}

/// The first differing diagnostic of two lists, for messages.
pub fn first_difference(actual: &[LineDiagnostic], expected: &[LineDiagnostic]) -> String {
    let index = actual
        .iter()
        .zip(expected)
        .position(|(a, b)| a != b)
        .unwrap_or(actual.len().min(expected.len()));
    format!(
        "at {index}: {:?} instead of {:?}",
        actual
            .get(index)
            .map(|item| (item.line, item.diagnostic.code, &item.diagnostic.message)),
        expected
            .get(index)
            .map(|item| (item.line, item.diagnostic.code, &item.diagnostic.message))
    )
}
