//! The config target: `sinumerik.toml` texts, valid and broken. Reading one must give a machine or a
//! clear error (never a panic), and every machine that is accepted must analyse a program with the
//! same properties as the built-in machines: moves with finite numbers only, sorted diagnostics, and
//! the document analysis equal to `check`.

use super::generate;
use super::random::Random;
use super::targets::{check_move_numbers, check_program_diagnostics, first_difference};
use sinumerik_lsp::analysis::document::{DocumentAnalysis, TextLines};
use sinumerik_lsp::analysis::{analyze_program, diagnose_program, ProgramKind};
use sinumerik_lsp::config::parse_config_text;
use sinumerik_lsp::syntax::lines;
use std::path::Path;
use std::sync::Arc;

/// A program that touches what a configuration changes: axes of every kind, diameter programming,
/// units, circles, polar moves, frames, skip levels, R parameters, and long blocks.
const PROGRAM: &str = "\
N10 G90 G0 X10 Y20 Z30 A45 B10 C370 U1 V2 W3 Q4
N20 G18 DIAMON G1 X40 Z-5 F0.2
/1 N30 X=DAC(20) Z=IC(-1)
/9 N40 G17 DIAMOF G2 X20 Y20 CR=10
N50 G70 X1 G71 Y1 G700 F10 G710
N60 G111 X0 Y0 G1 AP=45 RP=10
N70 TRANS X5 AROT RPL=30 G1 X1
N80 R99=5 R100=1 R1000=2 X=R99
N90 SPOS=10 C=ACP(10) A=ACN(5) X1=1 Z2=3
N100 G2 X0 Y0 I5 J0 K0 ; a long comment to reach the block length limit of small machines
";

/// A random configuration text: keys of every table with values that are valid, out of range, of the
/// wrong type or odd, sometimes damaged by character mutations.
pub fn generate_config(random: &mut Random) -> String {
    let mut text = String::new();
    if !random.one_in(4) {
        text.push_str("[machine]\n");
        // Each key: values that are valid, then values that are not; a wrong one is rare, so that
        // most machines are accepted and analyse the program.
        let entries: &[(&str, &[&str], &[&str])] = &[
            (
                "kind",
                &["\"mill\"", "\"turn\"", "\"TURN\""],
                &["\"lathe\"", "1", "\"\""],
            ),
            (
                "units",
                &["\"mm\"", "\"inch\"", "\"INCH\""],
                &["\"m\"", "[]"],
            ),
            (
                "reset_gcodes",
                &[
                    "[\"G18\", \"DIAMON\"]",
                    "[\"G91\", \"G70\", \"G2\"]",
                    "[\"DIAM90\", \"G112\", \"G54\"]",
                    "[\"G9999\"]",
                    "[]",
                ],
                &["[\"\"]", "[\"G1 X\"]"],
            ),
            (
                "circle_error_const",
                &["0.01", "1e308", "1e-300", "5"],
                &["0", "-1", "nan", "inf", "\"x\""],
            ),
            (
                "circle_error_factor",
                &["0.001", "0", "1e308"],
                &["-0.5", "nan"],
            ),
            (
                "max_skip_level",
                &["9", "0", "3"],
                &["10", "-1", "99999999999999999999"],
            ),
            (
                "max_block_length",
                &["512", "1", "9223372036854775807"],
                &["0", "-5"],
            ),
            (
                "r_parameters",
                &["100", "0", "1", "1000000"],
                &["-1", "4294967296"],
            ),
        ];
        for (key, valid, wrong) in entries {
            if random.one_in(2) {
                let value = if valid.is_empty() || random.one_in(8) {
                    random.word(wrong)
                } else {
                    random.word(valid)
                };
                text.push_str(&format!("{key} = {value}\n"));
            }
        }
    }
    if random.one_in(10) {
        text.push_str("misspelt_key = 1\n");
    }
    if random.one_in(2) {
        text.push_str("[axes]\n");
        let names = [
            "X",
            "Y",
            "Z",
            "A",
            "B",
            "C",
            "U",
            "V",
            "W",
            "Q",
            "X1",
            "Z2",
            "SP1",
            "AX_LONG_NAME",
        ];
        let odd_names = ["1X", "\"\"", "\"Ä\"", "G", "N", "R", "F", "x"];
        let kinds = ["\"linear\"", "\"transverse\"", "\"rotary\"", "\"modulo\""];
        let odd_kinds = ["\"spindle\"", "3"];
        let mut written: Vec<&str> = Vec::new();
        for _ in 0..random.length(4, 30) {
            let name = if random.one_in(40) {
                random.word(&odd_names)
            } else {
                random.word(&names)
            };
            let kind = if random.one_in(40) {
                random.word(&odd_kinds)
            } else {
                random.word(&kinds)
            };
            // A key twice is invalid TOML; the character mutations make that case often enough.
            if !written.contains(&name) {
                written.push(name);
                text.push_str(&format!("{name} = {kind}\n"));
            }
        }
    }
    if random.one_in(3) {
        text.push_str("[diagnostics]\n");
        let codes = ["S120", "S190", "A201", "S133", "S163", "A203"];
        let severities = [
            "\"error\"",
            "\"warning\"",
            "\"info\"",
            "\"hint\"",
            "\"off\"",
        ];
        let mut written: Vec<&str> = Vec::new();
        for _ in 0..random.length(3, 10) {
            let code = if random.one_in(10) {
                random.word(&["S999", "X1", "s163"])
            } else {
                random.word(&codes)
            };
            if !written.contains(&code) {
                written.push(code);
                text.push_str(&format!("{code} = {}\n", random.word(&severities)));
            }
        }
    }
    if random.one_in(4) {
        text.push_str(random.word(&[
            "[check]\nextensions = [\"mpf\", \"spf\"]\n",
            "[check]\nextensions = [\"MPF\", \"txt\"]\n",
            "[check]\nextensions = [\"mpf\"]\n",
            "[check]\nextensions = [\".mpf\", \"\"]\n",
            "[check]\nextensions = \"mpf\"\n",
        ]));
    }
    if random.one_in(6) {
        text = generate::mutate_line(random, &text);
    }
    text
}

/// Reads `text` as a configuration; an accepted machine analyses [`PROGRAM`] with every property.
pub fn check_config(text: &str) -> Result<(), String> {
    let config = match parse_config_text(text, Path::new("fuzz/sinumerik.toml")) {
        Ok(config) => Arc::new(config),
        Err(error) => {
            let message = error.to_string();
            return if message.trim().is_empty() {
                Err("a configuration error without a message".into())
            } else {
                Ok(())
            };
        }
    };
    let line_texts: Vec<&str> = lines::line_ranges(PROGRAM)
        .map(|(start, end)| &PROGRAM[start..end])
        .collect();
    for kind in [ProgramKind::Main, ProgramKind::Subprogram] {
        let analysis = analyze_program(PROGRAM, &config, kind);
        check_program_diagnostics(&line_texts, &analysis.diagnostics)?;
        for movement in &analysis.moves {
            check_move_numbers(movement)?;
        }
        let checked = diagnose_program(PROGRAM, &config, kind);
        let document = DocumentAnalysis::new(&TextLines::new(PROGRAM), config.clone(), kind);
        if document.diagnostics() != checked.as_slice() {
            return Err(format!(
                "the document analysis differs from check with this machine: {}",
                first_difference(document.diagnostics(), &checked)
            ));
        }
    }
    Ok(())
}
