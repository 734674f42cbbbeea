//! Data-driven tests of the hover and the inlay hints: each case is a program with a `$0` cursor
//! marker (and a machine configuration when it needs one) and the texts the answer must contain.

#[path = "support/lsp_client.rs"]
mod lsp_client;

use lsp_client::{file_uri, position_of, temp_folder, TestClient};
use serde_json::{json, Value};

const TURN: &str = "[machine]\nkind = \"turn\"\n";

struct Case {
    config: Option<&'static str>,
    file: &'static str,
    program: &'static str,
    expected: &'static [&'static str],
}

const HOVERS: &[Case] = &[
    Case { config: None, file: "ic.mpf", program: "N10 G90 G0 X20 Z90\nN20 X75 Z=IC(-3$02)", expected: &["Z = 90.000 + (-32.000) = **58.000** mm (IC: incremental for this block only; G90 stays active)"] },
    Case { config: None, file: "ac.mpf", program: "N10 G90 G0 X20 Z90\nN20 G91 X5 Z=A$0C(17)", expected: &["Z = **17.000** mm (AC: absolute for this block only; G91 stays active)"] },
    Case { config: None, file: "inch.mpf", program: "N10 G90 G0 X0 Z0\nN20 G70 X$01", expected: &["X = 1.000 in (25.400 mm) = **25.400** mm (G90: absolute)"] },
    Case { config: None, file: "inch_inc.mpf", program: "N10 G90 G0 X10 Z0\nN20 G70\nN30 G91 X$01", expected: &["X = 10.000 + 1.000 in (25.400 mm) = **35.400** mm (G91: incremental)"] },
    Case { config: Some(TURN), file: "diameter.mpf", program: "N10 G90 G0 X4$00 Z5", expected: &["X = **40.000** mm (G90: absolute)", "Diameter 40.000 mm, radius 20.000 mm"] },
    Case { config: Some(TURN), file: "diameter_ic.mpf", program: "N10 G90 G0 X40 Z5\nN20 X=I$0C(10)", expected: &["X = 40.000 + 10.000 = **50.000** mm (IC: incremental", "radius 25.000 mm"] },
    Case { config: Some(TURN), file: "dac.mpf", program: "N10 DIAMOF G90 G0 X10 Z5\nN20 X=DA$0C(40)", expected: &["X = **20.000** mm", "The value is read as a diameter; the position is shown as a radius."] },
    Case { config: None, file: "frame.mpf", program: "N10 G90 G0 X0 Z0\nN20 TRANS X10\nN30 X$05", expected: &["X = **5.000** mm (G90: absolute)", "After the programmable frame (machine coordinates): X = **15.000** mm"] },
    Case { config: None, file: "inherited.spf", program: "N10 X=I$0C(5)", expected: &["X = **unknown**"] },
    Case { config: None, file: "ac_no_brackets.mpf", program: "N10 G90 G0 X0 Y0\nN20 X$0=AC 5", expected: &["X = **unknown**: `AC` needs its value in parentheses, `X=AC(...)` (S101)"] },
    Case { config: None, file: "plane.mpf", program: "N10 G1$07 X0", expected: &["**G17** — Working plane X/Y", "Group 6 (working plane), modal", "Before this block: **G17**"] },
    Case { config: None, file: "dwell.mpf", program: "N10 G$04 F2", expected: &["**G4** — Dwell", "non-modal: acts in this block only"] },
    Case { config: Some(TURN), file: "diamof.mpf", program: "N10 DIAMO$0F", expected: &["Group 29 (diameter / radius programming)", "Before this block: **DIAMON**"] },
    Case { config: None, file: "offset.mpf", program: "N10 G5$04", expected: &["**G54**", "Group 8 (settable work offset)", "Before this block: **G500**"] },
    Case { config: None, file: "block.mpf", program: "N10 G90 G0 X20 Z90 ; comm$0ent", expected: &["Modal state before this block", "**End point** (G0): X20 Z90"] },
    Case { config: None, file: "number.mpf", program: "N10 G90 G0 X20 Z90\nN2$00 G91 X5", expected: &["G90", "**End point** (G0): X25 Z90"] },
    Case { config: Some(TURN), file: "diam90_g91.mpf", program: "N10 G90 DIAM90 G0 X40 Z5\nN20 G91 X$05", expected: &["X = 40.000 + 2 × 5.000 = **50.000** mm (G91: incremental)", "The increment is a radius"] },
    Case { config: None, file: "g53.mpf", program: "N10 G90 G0 X0 Z0\nN20 TRANS X10\nN30 G53 X$05", expected: &["X = **5.000** mm in machine coordinates (G53/G153/SUPA", "In workpiece coordinates: X = **-5.000** mm"] },
    Case { config: None, file: "flow.mpf", program: "N10 G90 G0 X1\nMARKE:\nN20 X$02", expected: &["A label, jump or loop comes before this block"] },
];

/// Opens the case's program (in a folder with its sinumerik.toml, if any) and returns its URI, the
/// text without the marker and the marker's position.
async fn open_case(
    client: &mut TestClient,
    case: &Case,
    folder: &std::path::Path,
) -> (String, String, (u32, u32)) {
    let case_folder = folder.join(case.file.replace('.', "_"));
    std::fs::create_dir_all(&case_folder).unwrap();
    if let Some(config) = case.config {
        std::fs::write(case_folder.join("sinumerik.toml"), config).unwrap();
    }
    let uri = file_uri(&case_folder.join(case.file));
    let position = position_of(case.program, "$0");
    let text = case.program.replace("$0", "");
    client.open(&uri, 1, &text).await;
    client.diagnostics(&uri, 1).await;
    (uri, text, position)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn hovers_explain_what_they_point_at() {
    let folder = temp_folder("hover");
    let mut client = TestClient::in_process();
    client.initialize(json!({}), Value::Null).await;
    let mut failures = Vec::new();
    for case in HOVERS {
        let (uri, _, (line, character)) = open_case(&mut client, case, &folder).await;
        let hover = client.hover(&uri, line, character).await;
        for expected in case.expected {
            if !hover.contains(expected) {
                failures.push(format!("{}: {expected:?} not in\n{hover}\n", case.file));
            }
        }
    }
    let _ = std::fs::remove_dir_all(&folder);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    client.shutdown().await;
}

struct HintCase {
    config: Option<&'static str>,
    file: &'static str,
    program: &'static str,
    /// (0-based line, label) of every hint in the default mode.
    expected: &'static [(u64, &'static str)],
}

const HINTS: &[HintCase] = &[
    HintCase {
        config: None,
        file: "plain.mpf",
        program: "N10 G90 G0 X20 Z90\nN20 G1 X30 F100\nN30 G2 X40 Z100 CR=10$0",
        expected: &[],
    },
    HintCase {
        config: None,
        file: "incremental.mpf",
        program: "N10 G90 G0 X20 Z90\nN20 G91 X5\nN30 X=AC(5)\nN40 G90 X7 Z=IC(1)$0",
        expected: &[(1, "⟶ X25 Z90"), (2, "⟶ X5 Z90"), (3, "⟶ X7 Z91")],
    },
    HintCase {
        config: None,
        file: "inch.mpf",
        program: "N10 G90 G0 X0 Z0\nN20 G70 X1$0",
        expected: &[(1, "⟶ X25.4 Z0")],
    },
    HintCase {
        config: None,
        file: "frame.mpf",
        program: "N10 G90 G0 X0 Z0\nN20 TRANS X10\nN30 X5$0",
        expected: &[(2, "⟶ X5 Z0 (machine X15 Z0)")],
    },
    HintCase {
        config: None,
        file: "polar.mpf",
        program: "N10 G90 G17 G0 X0 Y0 Z0\nN20 G111 X10 Y10\nN30 G1 AP=90 RP=5 F100$0",
        expected: &[(2, "⟶ X10 Y15 Z0")],
    },
    HintCase {
        config: None,
        file: "unknown.spf",
        program: "N10 G90 G71 G1 X1 Z=IC(2) F100$0",
        expected: &[(0, "⟶ X1 Z?")],
    },
    HintCase {
        config: None,
        file: "order.spf",
        program: "N10 G90 G71 G1 Y40 Z-2 X=IC(2) F100$0",
        expected: &[(0, "⟶ X? Y40 Z-2")],
    },
];

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn inlay_hints_mark_end_points_that_are_not_plain() {
    let folder = temp_folder("hints");
    let mut client = TestClient::in_process();
    client.initialize(json!({}), Value::Null).await;
    for case in HINTS {
        let hover_case = Case {
            config: case.config,
            file: case.file,
            program: case.program,
            expected: &[],
        };
        let (uri, _, _) = open_case(&mut client, &hover_case, &folder).await;
        let labels = client.inlay_hint_labels(&uri, 0, 50).await;
        let expected: Vec<(u64, String)> = case
            .expected
            .iter()
            .map(|(line, label)| (*line, label.to_string()))
            .collect();
        assert_eq!(labels, expected, "{}", case.file);
    }
    let _ = std::fs::remove_dir_all(&folder);
    client.shutdown().await;
}
