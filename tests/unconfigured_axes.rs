//! S180 (an axis the machine does not have) is reported once per axis and file, at the first block
//! that uses the axis, with the number of blocks that use it. The finding is a fact of the whole file:
//! after an edit of an open document (the server's incremental analysis) it must be where and what a
//! fresh analysis and `check` say, also when the edit removes the first use or one far below it.

use sinumerik_lsp::analysis::document::{DocumentAnalysis, TextLines};
use sinumerik_lsp::analysis::{diagnose_program, ProgramKind};
use sinumerik_lsp::config::MachineConfig;
use sinumerik_lsp::diagnostics::{Code, LineDiagnostic};
use std::sync::Arc;

/// The S180 findings as (line, message).
fn axis_findings(findings: &[LineDiagnostic]) -> Vec<(usize, String)> {
    findings
        .iter()
        .filter(|item| item.diagnostic.code == Code::AxisNotConfigured)
        .map(|item| (item.line, item.diagnostic.message.clone()))
        .collect()
}

/// A lathe program of `count` lines (X, Z, C configured) whose lines in `with_b` move B too, and
/// line 5 Y.
fn program(count: usize, with_b: &[usize]) -> Vec<String> {
    (0..count)
        .map(|line| match line {
            5 => "G1 Y2 F100".to_string(),
            _ if with_b.contains(&line) => format!("G1 X{line} B{line}"),
            _ => format!("G1 X{line} Z-{line}"),
        })
        .collect()
}

fn text(lines: &[String]) -> String {
    lines.join("\n") + "\n"
}

#[test]
fn one_finding_per_axis_with_the_count_follows_edits() {
    let config = Arc::new(MachineConfig::turn());
    let mut lines = program(1500, &[3, 40, 41, 1200]);
    let mut analysis = DocumentAnalysis::new(
        &TextLines::new(&text(&lines)),
        config.clone(),
        ProgramKind::Main,
    );
    let expect = |analysis: &DocumentAnalysis, lines: &[String], first_b: usize, blocks: usize| {
        let text = text(lines);
        let findings = axis_findings(analysis.diagnostics());
        assert_eq!(
            findings,
            axis_findings(&diagnose_program(&text, &config, ProgramKind::Main)),
            "the document and check"
        );
        let fresh =
            DocumentAnalysis::new(&TextLines::new(&text), config.clone(), ProgramKind::Main);
        assert_eq!(
            analysis.diagnostics(),
            fresh.diagnostics(),
            "incremental and fresh"
        );
        let b: Vec<&(usize, String)> = findings
            .iter()
            .filter(|(_, message)| message.starts_with("`B`"))
            .collect();
        assert_eq!(b.len(), 1, "{findings:#?}");
        assert_eq!(b[0].0, first_b, "{findings:#?}");
        let count = if blocks == 1 {
            "(1 block of this file uses it)".to_string()
        } else {
            format!("({blocks} blocks of this file use it")
        };
        assert!(b[0].1.contains(&count), "{}", b[0].1);
        assert!(b[0].1.contains("`[axes]`"), "{}", b[0].1);
        // Y, used once, has its own finding.
        assert_eq!(
            findings
                .iter()
                .filter(|(_, message)| message.starts_with("`Y`"))
                .count(),
            1
        );
    };
    expect(&analysis, &lines, 3, 4);

    // Removing the first use moves the finding to the next one, with the count one less.
    lines.remove(3);
    analysis.update(&TextLines::new(&text(&lines)), 3, 1, 0);
    expect(&analysis, &lines, 39, 3);

    // A use far below (after several checkpoints) changes the count at the first one.
    lines[1199] = "G1 X5 Z5".to_string();
    analysis.update(&TextLines::new(&text(&lines)), 1199, 1, 1);
    expect(&analysis, &lines, 39, 2);

    // A new use above the first becomes the first.
    lines.insert(0, "G0 B90".to_string());
    analysis.update(&TextLines::new(&text(&lines)), 0, 0, 1);
    expect(&analysis, &lines, 0, 3);

    // Two uses in one block count as one block.
    lines[0] = "G0 B90 B=IC(5)".to_string();
    analysis.update(&TextLines::new(&text(&lines)), 0, 1, 1);
    expect(&analysis, &lines, 0, 3);

    // The last uses removed: the finding goes.
    for line in [41, 40, 0] {
        lines.remove(line);
        analysis.update(&TextLines::new(&text(&lines)), line, 1, 0);
    }
    assert!(axis_findings(analysis.diagnostics())
        .iter()
        .all(|(_, message)| !message.starts_with("`B`")));
    assert_eq!(axis_findings(analysis.diagnostics()).len(), 1);
}
