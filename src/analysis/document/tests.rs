//! Unit tests of the document analysis: block reports, updates and how they say the findings changed.

use crate::analysis::document::document_state::DocumentAnalysis;
use crate::analysis::document::line_source::TextLines;
use crate::analysis::program_kind::ProgramKind;
use crate::analysis::resolution::ResolutionMode;
use crate::config::MachineConfig;
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

/// Whether the block reports say that flow is uncertain at `line`.
fn flow_uncertain_replayed(analysis: &DocumentAnalysis, source: &TextLines, line: usize) -> bool {
    let report = analysis.block_report(source, line);
    report.before.flow_uncertain || report.after.flow_uncertain
}

#[test]
fn the_checkpoints_tell_flow_uncertainty_as_the_block_reports_do() {
    let config = Arc::new(MachineConfig::mill());
    let interval = crate::analysis::document::document_state::CHECKPOINT_INTERVAL;
    // Straight-line blocks with a label in the fourth interval; then with a jump added in the
    // second interval by an edit, and removed again.
    let blocks = |jump_at: Option<usize>| -> String {
        (0..6 * interval)
            .map(|line| match line {
                _ if line == 3 * interval + 7 => "MARK1:\n".to_string(),
                _ if Some(line) == jump_at => "GOTOF MARK1\n".to_string(),
                _ => format!("N{line} G1 X{} Y1 F100\n", line % 50),
            })
            .collect()
    };
    let text = blocks(None);
    let mut analysis = DocumentAnalysis::new(
        &TextLines::new(&text),
        Arc::clone(&config),
        ProgramKind::Main,
    );
    let edited = blocks(Some(interval + 3));
    let checks: [(&str, Option<usize>); 3] = [
        (&text, None),
        (&edited, Some(interval + 3)),
        (&text, Some(interval + 3)),
    ];
    for (text, changed) in checks {
        let source = TextLines::new(text);
        if let Some(line) = changed {
            analysis.update(&source, line, 1, 1);
        }
        let mut told = 0;
        let mut uncertain = 0;
        for line in 0..6 * interval {
            let replayed = flow_uncertain_replayed(&analysis, &source, line);
            uncertain += usize::from(replayed);
            if let Some(by_checkpoints) = analysis.flow_uncertain_by_checkpoints(line) {
                told += 1;
                assert_eq!(by_checkpoints, replayed, "line {line} after {changed:?}");
            }
        }
        assert!(uncertain > 0 && uncertain < 6 * interval);
        // Only the interval where flow becomes uncertain needs the replay (and the last one when
        // flow is certain before it, not the case here).
        assert_eq!(told, 5 * interval, "after {changed:?}");
    }
}
