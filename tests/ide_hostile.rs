//! The language features never panic, whatever the text and wherever the cursor: binary garbage,
//! multi-byte characters, unbalanced structures, huge lines. Every feature is run at every byte of
//! every line of a set of hostile programs.

use sinumerik_lsp::analysis::document::{DocumentAnalysis, TextLines};
use sinumerik_lsp::analysis::library::NoLibrary;
use sinumerik_lsp::analysis::ProgramKind;
use sinumerik_lsp::config::MachineConfig;
use sinumerik_lsp::ide::completion::completion;
use sinumerik_lsp::ide::cross_file_diagnostics::cross_file_diagnostics;
use sinumerik_lsp::ide::documentation::documentation_at;
use sinumerik_lsp::ide::format::format_text;
use sinumerik_lsp::ide::hover::hover_at;
use sinumerik_lsp::ide::inlay::{end_point_hints, HintScope};
use sinumerik_lsp::ide::navigation::{definition, highlights, references, rename};
use sinumerik_lsp::ide::outline::{document_symbols, folding_ranges};
use sinumerik_lsp::ide::program_run::RunOnce;
use sinumerik_lsp::ide::renumber::{renumber_text, NumberingMode, RenumberOptions};
use sinumerik_lsp::ide::semantic_tokens::semantic_tokens;
use sinumerik_lsp::ide::signature_help::signature_help;
use sinumerik_lsp::ide::WorkspaceIndex;
use sinumerik_lsp::syntax::lines::line_ranges;
use std::sync::Arc;

fn hostile_programs() -> Vec<String> {
    // A fixed pseudo-random byte sequence read as Windows-1252 would be by the CLI.
    let mut state: u32 = 7;
    let garbage: Vec<u8> = (0..3000)
        .map(|_| {
            state = state.wrapping_mul(1_103_515_245).wrapping_add(12345);
            (state >> 16) as u8
        })
        .collect();
    vec![
        sinumerik_lsp::io::source_file::decode_windows_1252(&garbage),
        "PROC ÄÖÜ(REAL 1A, VAR, INT[ ) ; ünïcödé\nDEF DEF DEF\nDEFINE AS AS\nEXTERN (\nGOTOF\nGOTOB N\nCASE OF GOTOF\nIF (((\nENDIF ENDIF\n".to_string(),
        "N10 GOTOF N10\nN10 GOTOB N10\n:0 GOTO :0\nL0 P\nCALL \"\"\nCALL \"/_N_\"\nPCALL /\nMCALL\nT=\"😀\" M6\n$R[ R[ R[1\n".to_string(),
        format!("N1 G0 X{}\nLBL{}: GOTOB LBL{}\n", "9".repeat(5000), "A".repeat(3000), "A".repeat(3000)),
        "\r\r\n\n;\n;---\n; title\n;---\n\t \u{0}\u{7f}\n".to_string(),
    ]
}

#[test]
fn every_feature_at_every_byte_of_hostile_programs_answers_without_panic() {
    let config = MachineConfig::mill();
    for (number, text) in hostile_programs().iter().enumerate() {
        let mut index = WorkspaceIndex::new();
        index.update(Arc::from("A.MPF"), "A.MPF", &TextLines::new(text), &config);
        index.update(Arc::from("B.SPF"), "B.SPF", &TextLines::new(text), &config);
        index.set_complete(true);
        let table = index.document("A.MPF").unwrap().symbols.clone();
        let _ = cross_file_diagnostics(&index, "A.MPF", &config);
        let _ = document_symbols(&table);
        let _ = folding_ranges(&table);
        let _ = semantic_tokens(&TextLines::new(text), &table, &config, 0..usize::MAX);
        let formatted = format_text(text, &config, Default::default());
        assert_eq!(
            line_ranges(&formatted).count(),
            line_ranges(text).count(),
            "program {number}"
        );
        for mode in [NumberingMode::Keep, NumberingMode::All, NumberingMode::Drop] {
            let _ = renumber_text(
                text,
                &config,
                RenumberOptions {
                    start: 0,
                    step: 1,
                    mode,
                },
            );
        }
        let _ = renumber_text(
            text,
            &config,
            RenumberOptions {
                start: u64::MAX - 1,
                step: u64::MAX,
                mode: NumberingMode::All,
            },
        );
        for (line_index, (start, end)) in line_ranges(text).enumerate() {
            let line = &text[start..end];
            // Long lines are probed at a few places only, to keep the test fast.
            let positions: Vec<usize> = if line.len() > 200 {
                vec![0, 1, line.len() / 2, line.len()]
            } else {
                (0..=line.len() + 1).collect()
            };
            for byte in positions {
                let _ = completion(&index, "A.MPF", line, line_index, byte, &config);
                let _ = signature_help(&index, "A.MPF", line, byte);
                let _ = documentation_at(&index, "A.MPF", line, line_index, byte);
                let _ = definition(&index, "A.MPF", line_index, byte);
                let _ = references(&index, "A.MPF", line_index, byte, true);
                let _ = highlights(&index, "A.MPF", line_index, byte);
                let _ = rename(&index, &config, "A.MPF", line_index, byte, "NEW_NAME");
                let _ = rename(&index, &config, "A.MPF", line_index, byte, "ü");
            }
        }
    }
}

#[test]
fn hover_and_inlay_hints_answer_within_the_line_on_hostile_programs() {
    for config in [MachineConfig::mill(), MachineConfig::turn()] {
        for (number, text) in hostile_programs().iter().enumerate() {
            for kind in [ProgramKind::Main, ProgramKind::Subprogram] {
                let lines = TextLines::new(text);
                let analysis = DocumentAnalysis::new(&lines, Arc::new(config.clone()), kind);
                let run = RunOnce::new(&lines, &config, kind, &NoLibrary);
                for (line_index, (start, end)) in line_ranges(text).enumerate() {
                    let line = &text[start..end];
                    for byte in (0..=line.len()).filter(|byte| line.is_char_boundary(*byte)) {
                        let Some(hover) =
                            hover_at(&lines, &analysis, &run, line_index, byte, |_, _, _| None)
                        else {
                            continue;
                        };
                        assert!(!hover.markdown.is_empty(), "program {number}");
                        if let Some(span) = hover.span {
                            assert!(
                                line.get(span.start()..span.end()).is_some(),
                                "program {number} line {line_index}: {span:?} outside the line"
                            );
                        }
                    }
                }
                let line_count = line_ranges(text).count();
                for scope in [HintScope::NotPlain, HintScope::All] {
                    for hint in end_point_hints(&lines, &analysis, &run, 0..usize::MAX, scope) {
                        assert!(hint.line < line_count, "program {number}");
                        assert!(hint.label.starts_with('⟶'), "program {number}");
                    }
                }
                assert!(
                    hover_at(&lines, &analysis, &run, line_count + 1, 0, |_, _, _| None).is_none()
                );
            }
        }
    }
}
