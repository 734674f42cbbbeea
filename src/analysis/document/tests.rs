//! Unit tests of the document analysis: block reports, updates and how they say the findings changed.

use crate::analysis::document::document_state::DocumentAnalysis;
use crate::analysis::document::findings_change::FindingsChange;
use crate::analysis::document::line_source::TextLines;
use crate::analysis::program_kind::ProgramKind;
use crate::analysis::resolution::ResolutionMode;
use crate::config::MachineConfig;
use crate::diagnostics::LineDiagnostic;
use std::sync::Arc;

const SEED: &str = "N10 G18 G90 G0 X20 Z90\nN20 G1 X75 Z=IC(-32) F100\nN30 X=IC(5)\n";

#[test]
fn a_block_report_gives_the_state_before_and_the_end_point() {
    let config = Arc::new(MachineConfig::mill());
    let source = TextLines::new(SEED);
    let analysis = DocumentAnalysis::new(&source, config, ProgramKind::Main);
    let report = analysis.block_report(&source, 1);
    assert_eq!(report.before.motion.as_deref(), Some("G0"));
    assert_eq!(report.after.motion.as_deref(), Some("G1"));
    let movement = report.movement.expect("N20 moves");
    let z = movement
        .end
        .iter()
        .find(|(name, _)| &**name == "Z")
        .unwrap();
    assert_eq!(z.1, 58.0);
    type Row<'a> = (&'a str, ResolutionMode, Option<f64>, Option<f64>, bool);
    let words: Vec<Row> = report
        .words
        .iter()
        .map(|word| {
            (
                word.axis.as_str(),
                word.mode,
                word.start,
                word.end,
                word.explained,
            )
        })
        .collect();
    assert_eq!(
        words,
        [
            ("X", ResolutionMode::Absolute, Some(20.0), Some(75.0), true),
            (
                "Z",
                ResolutionMode::Override(crate::syntax::ast::Modifier::Ic),
                Some(90.0),
                Some(58.0),
                true
            ),
        ]
    );
}

#[test]
fn unknown_words_say_why() {
    let config = Arc::new(MachineConfig::mill());
    let text = "N10 G91 X5\nN20 X=R7\n";
    let source = TextLines::new(text);
    let analysis = DocumentAnalysis::new(&source, config, ProgramKind::Main);
    let first = &analysis.block_report(&source, 0).words[0];
    assert_eq!(first.end, None);
    assert!(first
        .unknown_reason
        .as_deref()
        .unwrap()
        .contains("incremental move from a position"));
    let second = &analysis.block_report(&source, 1).words[0];
    assert_eq!(second.programmed, None);
    assert!(second
        .unknown_reason
        .as_deref()
        .unwrap()
        .contains("variable"));
}

#[test]
fn an_update_sees_the_new_text() {
    let config = Arc::new(MachineConfig::mill());
    let mut analysis = DocumentAnalysis::new(&TextLines::new(SEED), config, ProgramKind::Main);
    assert!(analysis.diagnostics().is_empty());
    let changed = SEED.replace("Z=IC(-32)", "Z=IC(-32");
    analysis.update(&TextLines::new(&changed), 1, 1, 1);
    assert_eq!(analysis.diagnostics().len(), 1);
    assert_eq!(analysis.diagnostics()[0].line, 1);
}

/// Whether `change` turns `old` into `new`.
fn change_holds(old: &[LineDiagnostic], new: &[LineDiagnostic], change: FindingsChange) -> bool {
    let moved = |item: &LineDiagnostic| LineDiagnostic {
        line: item.line.saturating_add_signed(change.line_delta),
        diagnostic: item.diagnostic.clone(),
    };
    change.start <= change.old_end
        && change.start <= change.new_end
        && change.old_end <= old.len()
        && change.new_end <= new.len()
        && old.len() - change.old_end == new.len() - change.new_end
        && old[..change.start] == new[..change.start]
        && old[change.old_end..]
            .iter()
            .map(moved)
            .eq(new[change.new_end..].iter().cloned())
}

#[test]
fn the_findings_change_an_update_reports_turns_the_old_findings_into_the_new() {
    let config = Arc::new(MachineConfig::mill());
    let mut lines: Vec<String> = (0..3000)
        .map(|index| match index % 5 {
            0 => format!("N{index} G1 X=AC{index} F100"),
            _ => format!("N{index} G1 X{index} Y=IC(1) F100"),
        })
        .collect();
    let text = |lines: &[String]| lines.join("\n") + "\n";
    let mut analysis =
        DocumentAnalysis::new(&TextLines::new(&text(&lines)), config, ProgramKind::Main);
    let mut random = 0x9E37_79B9_7F4A_7C15_u64;
    let mut next = |bound: usize| {
        random ^= random << 13;
        random ^= random >> 7;
        random ^= random << 17;
        (random % bound as u64) as usize
    };
    let mut known = 0;
    for step in 0..300 {
        let old = analysis.diagnostics().to_vec();
        let revision = analysis.findings_revision();
        let line = next(lines.len() - 1);
        let (removed, inserted) = match step % 4 {
            0 => {
                lines[line].insert(0, ' ');
                (1, 1)
            }
            1 => {
                lines.insert(line, format!("N9 X=AC{step}"));
                (0, 1)
            }
            2 => {
                lines.remove(line);
                (1, 0)
            }
            _ => {
                lines[line] = format!("N{step} G1 X{step}");
                (1, 1)
            }
        };
        let current = text(&lines);
        analysis.update(&TextLines::new(&current), line, removed, inserted);
        assert_eq!(
            analysis.findings_change_since(analysis.findings_revision()),
            Some(FindingsChange::none(analysis.diagnostics().len()))
        );
        if let Some(change) = analysis.findings_change_since(revision) {
            known += 1;
            assert!(
                change_holds(&old, analysis.diagnostics(), change),
                "step {step}: {change:?}"
            );
        }
        assert_eq!(
            analysis.findings_change_since(revision.wrapping_sub(1)),
            None
        );
    }
    assert!(
        known > 200,
        "most edits say how they changed the findings: {known}"
    );
}

#[test]
fn an_update_of_a_program_with_end_of_program_findings_does_not_say_how_they_changed() {
    let config = Arc::new(MachineConfig::mill());
    let text = "IF R1 == 1\nN10 G1 X=AC1 F100\nN20 X2\n";
    let mut analysis = DocumentAnalysis::new(&TextLines::new(text), config, ProgramKind::Main);
    assert!(analysis.diagnostics().iter().any(|item| item.line == 0));
    let revision = analysis.findings_revision();
    analysis.update(&TextLines::new(&text.replace("X2", " X2")), 2, 1, 1);
    assert_eq!(analysis.findings_change_since(revision), None);
}
