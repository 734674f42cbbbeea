//! The fast path for plain blocks must give exactly what the general parser gives: same block, same
//! diagnostics, for every line. This compares both paths on tricky lines, on generated programs of every
//! style and on the real-program corpus.

use sinumerik_lsp::config::MachineConfig;
use sinumerik_lsp::syntax::{lines, Block, LineParser, SyntaxContext};
use std::path::{Path, PathBuf};

#[path = "support/generated.rs"]
mod generated;
use generated::generate;

fn assert_same(line: &str, context: &SyntaxContext, parser: &mut LineParser) {
    let mut fast = Block::default();
    let mut fast_diagnostics = Vec::new();
    parser.parse(line, context, &mut fast, &mut fast_diagnostics);
    let mut general = Block::default();
    let mut general_diagnostics = Vec::new();
    parser.parse_without_fast_path(line, context, &mut general, &mut general_diagnostics);
    assert_eq!(fast, general, "blocks differ for line {line:?}");
    assert_eq!(
        fast_diagnostics, general_diagnostics,
        "diagnostics differ for line {line:?}"
    );
}

fn check_text(text: &str, context: &SyntaxContext) -> usize {
    let mut parser = LineParser::new();
    let mut count = 0;
    for (start, end) in lines::line_ranges(text) {
        assert_same(&text[start..end], context, &mut parser);
        count += 1;
    }
    count
}

#[test]
fn tricky_lines_agree() {
    let lines = [
        "",
        "   ",
        "\t",
        "; only a comment",
        "N10",
        "N10 X1",
        "N 10 X1",
        "N10.5 X1",
        "N-10",
        "X5E3",
        "X1.5EX-3",
        "X5EX",
        "X-.5",
        "X+.5",
        "X.",
        "X5.",
        "X5.Y3",
        "X1.2.3",
        "G01",
        "G0X10Y5",
        "G1.0",
        "G-1",
        "G 1",
        "G12",
        "G600",
        "G505",
        "G17 G18",
        "G0 G1 X1",
        "X 10",
        "X- 5",
        "X -5",
        "X10;c",
        "X10 ;c",
        "N10 N20",
        "X10 X20",
        "T0D0",
        "M3 M8",
        "M2=5",
        "X1=10",
        "XR1",
        "X_1",
        "X10_A",
        "R1",
        "O10",
        "L10",
        "L10 P2",
        "F100 F200",
        "U10",
        "E5",
        "A10 B20 C30",
        "A2=1",
        "x10 y-2.5 z.5",
        "X10\u{0}",
        "X10&Y5",
        "/N10 X1",
        ":10 X1",
        "%_N_TEST_MPF",
        "N10 G0 X10 ; a comment with ; and \"",
        "X99999999999999999999999",
        "G99999999999999999999",
        "N99999999999999999999",
        "X00012.500",
        "I10 J-5 K0",
        "G4 F2",
        "S1000 M3",
        "Ä",
        "X10 Ä",
        "TRANS X10",
        "G111 X0 Y0",
        "G111 X0 Y0 F100",
    ];
    let mill = SyntaxContext::new(&MachineConfig::mill());
    let turn = SyntaxContext::new(&MachineConfig::turn());
    let mut parser = LineParser::new();
    for line in lines {
        assert_same(line, &mill, &mut parser);
        assert_same(line, &turn, &mut parser);
    }
    let long = "X1 ".repeat(400);
    assert_same(&long, &mill, &mut parser);
}

#[test]
fn generated_programs_agree() {
    let mill = SyntaxContext::new(&MachineConfig::mill());
    let turn = SyntaxContext::new(&MachineConfig::turn());
    let mut checked = 0;
    for style in ["cam3d", "inc", "turning", "mixed"] {
        match generate(style, 20_000) {
            Some(text) => {
                checked += check_text(&text, if style == "turning" { &turn } else { &mill })
            }
            None => println!("generator not available; skipping the {style} program"),
        }
    }
    println!("compared {checked} generated lines");
}

fn files_below(folder: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(folder) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            files_below(&path, out);
        } else {
            out.push(path);
        }
    }
}

#[test]
fn corpus_lines_agree() {
    let corpus = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/corpus/real");
    if !corpus.is_dir() {
        println!("corpus not found at {}; skipping", corpus.display());
        return;
    }
    let mut files = Vec::new();
    files_below(&corpus, &mut files);
    let mill = SyntaxContext::new(&MachineConfig::mill());
    let mut checked = 0;
    for file in files {
        let bytes = std::fs::read(&file).expect("corpus file is readable");
        let text = String::from_utf8_lossy(&bytes);
        checked += check_text(&text, &mill);
    }
    println!("compared {checked} corpus lines");
    assert!(
        checked > 10_000,
        "the corpus should have many lines, found {checked}"
    );
}
