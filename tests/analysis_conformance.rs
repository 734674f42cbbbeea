//! Checks the analysis against the conformance fixtures in `fixtures/conformance`: each block may say in
//! its comment where the axes must be after it (`; => X75 Z58`, `X?` for unknown, `F254` for the feed)
//! and which analysis findings it must report (`!! A201`). See `fixtures/conformance/README.md`.

use sinumerik_lsp::analysis::{analyze_program, Move, ProgramKind};
use sinumerik_lsp::config::{parse_config_text, MachineConfig};
use sinumerik_lsp::syntax::lines;
use std::path::{Path, PathBuf};

/// What one annotated block expects.
#[derive(Debug, Default)]
struct Expectation {
    /// Axis name with its value and the number of decimals written, or `None` for unknown.
    positions: Vec<(String, Option<(f64, usize)>)>,
    /// The same for machine coordinates, written after `MCS`.
    machine: Vec<(String, Option<(f64, usize)>)>,
    feed: Option<f64>,
    /// After `ARC`: the centre per axis, the radius (`R10`), the direction (`CW`, `CCW`; in machine
    /// coordinates `MCSCW`, `MCSCCW`) and the
    /// sweep in degrees (`SWEEP90`).
    arc: Option<ArcExpectation>,
    /// Whether the block has a `=>` part (and so must move).
    moves: bool,
    /// `=> none`: the block must not move.
    no_move: bool,
    codes: Vec<String>,
}

#[derive(Debug, Default)]
struct ArcExpectation {
    centre: Vec<(String, Option<(f64, usize)>)>,
    radius: Option<(f64, usize)>,
    clockwise: Option<bool>,
    /// `MCSCW` or `MCSCCW`: the direction after the programmable frame.
    machine_clockwise: Option<bool>,
    sweep: Option<(f64, usize)>,
}

/// A written number with the decimals it is written with.
fn written_number(text: &str) -> (f64, usize) {
    let number: f64 = text
        .parse()
        .unwrap_or_else(|_| panic!("`{text}` is not a number"));
    let decimals = text
        .split_once('.')
        .map_or(0, |(_, fraction)| fraction.len());
    (number, decimals)
}

/// `X10` is axis X with 10; an axis name with digits is written with `=`: `X1=10`, `X1=?`.
fn split_axis_word(word: &str) -> (&str, &str) {
    match word.split_once('=') {
        Some(parts) => parts,
        None => word.split_at(
            word.find(|c: char| !c.is_ascii_alphabetic())
                .unwrap_or(word.len()),
        ),
    }
}

fn parse_expectation(comment: &str) -> Expectation {
    let mut expectation = Expectation::default();
    let (moves_part, codes_part) = match comment.find("!!") {
        Some(position) => (&comment[..position], &comment[position + 2..]),
        None => (comment, ""),
    };
    if let Some(position) = moves_part.find("=>") {
        if moves_part[position + 2..].trim() == "none" {
            expectation.no_move = true;
            expectation.codes = codes_part.split_whitespace().map(str::to_string).collect();
            return expectation;
        }
        expectation.moves = true;
        let mut in_machine = false;
        for word in moves_part[position + 2..].split_whitespace() {
            if word == "MCS" {
                in_machine = true;
                continue;
            }
            if word == "ARC" {
                expectation.arc = Some(ArcExpectation::default());
                continue;
            }
            if let Some(arc) = expectation.arc.as_mut() {
                if word == "CW" || word == "CCW" {
                    arc.clockwise = Some(word == "CW");
                } else if word == "MCSCW" || word == "MCSCCW" {
                    arc.machine_clockwise = Some(word == "MCSCW");
                } else if let Some(value) = word.strip_prefix("SWEEP") {
                    arc.sweep = Some(written_number(value));
                } else if let Some(value) = word.strip_prefix('R') {
                    arc.radius = Some(written_number(value));
                } else {
                    let (name, value) = split_axis_word(word);
                    arc.centre
                        .push((name.to_string(), Some(written_number(value))));
                }
                continue;
            }
            let (name, value) = split_axis_word(word);
            if name == "F" {
                expectation.feed = Some(value.parse().expect("a number after F"));
            } else if value == "?" {
                let list = if in_machine {
                    &mut expectation.machine
                } else {
                    &mut expectation.positions
                };
                list.push((name.to_string(), None));
            } else {
                let number: f64 = value
                    .parse()
                    .unwrap_or_else(|_| panic!("`{word}` is not an axis value"));
                let decimals = value
                    .split_once('.')
                    .map_or(0, |(_, fraction)| fraction.len());
                let list = if in_machine {
                    &mut expectation.machine
                } else {
                    &mut expectation.positions
                };
                list.push((name.to_string(), Some((number, decimals))));
            }
        }
    }
    expectation.codes = codes_part.split_whitespace().map(str::to_string).collect();
    expectation
}

fn close(left: f64, right: f64) -> bool {
    (left - right).abs() <= 1e-6
}

/// An expectation is the value rounded to the decimals it is written with (the reference gives four);
/// whole numbers are compared to 1e-6.
fn matches_written(actual: f64, expected: f64, decimals: usize) -> bool {
    if decimals == 0 {
        return close(actual, expected);
    }
    (actual - expected).abs() <= 0.5 * 10f64.powi(-(decimals as i32)) + 1e-9
}

fn check_fixture(path: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).expect("fixture is readable");
    // `; toml: ...` lines give the machine configuration as sinumerik.toml would.
    let toml: String = text
        .lines()
        .filter_map(|line| line.strip_prefix("; toml: "))
        .flat_map(|line| [line, "\n"])
        .collect();
    let config = if !toml.is_empty() {
        parse_config_text(&toml, path).unwrap_or_else(|error| panic!("{error}"))
    } else if text.starts_with("; config: turn") {
        MachineConfig::turn()
    } else {
        MachineConfig::mill()
    };
    let kind =
        ProgramKind::from_extension(path.extension().and_then(|extension| extension.to_str()));
    let analysis = analyze_program(&text, &config, kind);
    let mut failures = Vec::new();
    let name = path.file_name().unwrap().to_string_lossy().to_string();
    for (line_index, (start, end)) in lines::line_ranges(&text).enumerate() {
        let line = &text[start..end];
        let expectation = match line.find(';') {
            Some(position)
                if line[position..].contains("=>") || line[position..].contains("!!") =>
            {
                parse_expectation(&line[position + 1..])
            }
            _ => Expectation::default(),
        };
        let reported: Vec<String> = analysis
            .diagnostics
            .iter()
            .filter(|item| {
                item.line == line_index && item.diagnostic.code.as_str().starts_with('A')
            })
            .map(|item| item.diagnostic.code.as_str().to_string())
            .collect();
        if reported != expectation.codes {
            failures.push(format!(
                "{name}:{}: expected findings {:?}, got {:?}",
                line_index + 1,
                expectation.codes,
                reported
            ));
        }
        if expectation.no_move {
            if analysis
                .moves
                .iter()
                .any(|movement| movement.line == line_index)
            {
                failures.push(format!(
                    "{name}:{}: expected no move, found one",
                    line_index + 1
                ));
            }
            continue;
        }
        if !expectation.moves {
            continue;
        }
        let Some(movement) = analysis
            .moves
            .iter()
            .find(|movement| movement.line == line_index)
        else {
            failures.push(format!(
                "{name}:{}: expected a move, found none",
                line_index + 1
            ));
            continue;
        };
        failures.extend(compare_move(&name, line_index, &expectation, movement));
    }
    failures
}

fn compare_move(
    name: &str,
    line_index: usize,
    expectation: &Expectation,
    movement: &Move,
) -> Vec<String> {
    let mut failures = Vec::new();
    let at = format!("{name}:{}", line_index + 1);
    for (axis, expected) in &expectation.positions {
        let actual = movement
            .end
            .iter()
            .find(|(end_axis, _)| end_axis.as_ref() == axis.as_str())
            .map(|(_, value)| *value);
        match (expected, actual) {
            (Some((expected, decimals)), Some(actual))
                if matches_written(actual, *expected, *decimals) => {}
            (None, None)
                if movement
                    .uncertain
                    .iter()
                    .any(|name| name.as_ref() == axis.as_str()) => {}
            _ => failures.push(format!(
                "{at}: {axis} expected {}, got {} (uncertain: {:?})",
                expected.map_or("unknown".to_string(), |(value, _)| value.to_string()),
                actual.map_or("unknown".to_string(), |value| value.to_string()),
                movement.uncertain
            )),
        }
    }
    for (axis, expected) in &expectation.machine {
        let actual = movement
            .machine
            .as_ref()
            .and_then(|values| {
                values
                    .iter()
                    .find(|(name, _)| name.as_ref() == axis.as_str())
            })
            .map(|(_, value)| *value);
        let agrees = match (expected, actual) {
            (Some((expected, decimals)), Some(actual)) => {
                matches_written(actual, *expected, *decimals)
            }
            (None, None) => true,
            _ => false,
        };
        if !agrees {
            failures.push(format!(
                "{at}: MCS {axis} expected {}, got {}",
                expected.map_or("unknown".to_string(), |(value, _)| value.to_string()),
                actual.map_or("unknown".to_string(), |value| value.to_string()),
            ));
        }
    }
    if let Some(expected) = &expectation.arc {
        match &movement.arc {
            None => failures.push(format!("{at}: expected an arc, found none")),
            Some(arc) => {
                for (axis, value) in &expected.centre {
                    let actual = arc
                        .centre
                        .iter()
                        .find(|(name, _)| name.as_ref() == axis.as_str())
                        .map(|(_, value)| *value);
                    let agrees = match (value, actual) {
                        (Some((value, decimals)), Some(actual)) => {
                            matches_written(actual, *value, *decimals)
                        }
                        _ => false,
                    };
                    if !agrees {
                        failures.push(format!(
                            "{at}: arc centre {axis} expected {value:?}, got {actual:?}"
                        ));
                    }
                }
                if let Some((radius, decimals)) = expected.radius {
                    if !matches_written(arc.radius, radius, decimals) {
                        failures.push(format!(
                            "{at}: arc radius expected {radius}, got {}",
                            arc.radius
                        ));
                    }
                }
                if let Some((sweep, decimals)) = expected.sweep {
                    if !matches_written(arc.sweep, sweep, decimals) {
                        failures.push(format!(
                            "{at}: arc sweep expected {sweep}, got {}",
                            arc.sweep
                        ));
                    }
                }
                if expected
                    .machine_clockwise
                    .is_some_and(|clockwise| Some(clockwise) != arc.machine_clockwise)
                {
                    failures.push(format!(
                        "{at}: machine arc direction expected {:?}, got {:?}",
                        expected.machine_clockwise, arc.machine_clockwise
                    ));
                }
                if expected
                    .clockwise
                    .is_some_and(|clockwise| clockwise != arc.clockwise)
                {
                    failures.push(format!(
                        "{at}: arc direction expected {:?}, got clockwise = {}",
                        expected.clockwise, arc.clockwise
                    ));
                }
            }
        }
    }
    if let Some(expected) = expectation.feed {
        if !movement.feed.is_some_and(|feed| close(feed, expected)) {
            failures.push(format!(
                "{at}: feed expected {expected}, got {:?}",
                movement.feed
            ));
        }
    }
    failures
}

fn fixtures() -> Vec<PathBuf> {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/conformance");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&folder)
        .expect("fixtures/conformance exists")
        .map(|entry| entry.expect("directory entry").path())
        .filter(|path| {
            path.extension()
                .and_then(|extension| extension.to_str())
                .is_some_and(|extension| {
                    extension.eq_ignore_ascii_case("mpf") || extension.eq_ignore_ascii_case("spf")
                })
        })
        .collect();
    paths.sort();
    paths
}

#[test]
fn conformance_fixtures_resolve_as_expected() {
    let paths = fixtures();
    assert!(
        paths.len() >= 10,
        "expected the conformance fixtures, found {}",
        paths.len()
    );
    let failures: Vec<String> = paths.iter().flat_map(|path| check_fixture(path)).collect();
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn the_harness_notices_a_wrong_expectation() {
    // A deliberately wrong expectation must be reported, or the fixtures would prove nothing.
    let folder = std::env::temp_dir().join(format!("sinumerik-conformance-{}", std::process::id()));
    std::fs::create_dir_all(&folder).unwrap();
    let path = folder.join("WRONG.MPF");
    std::fs::write(
        &path,
        "; toml: [offsets]\n; toml: G54 = { X = 100 }\nN10 G0 X10 ; => X11\nN20 G91 Y5 ; => Y5\nN30 G90 G54 X0 ; => none\nN40 X1 ; => MCS X1\nN50 G0 Y0\nN60 G2 X21 I10 J0 F100 ; => ARC X12 R10 CCW\nN70 MIRROR X0\nN80 G2 X-1 I10 J0 ; => ARC R10 CW MCSCW\n",
    )
    .unwrap();
    let failures = check_fixture(&path);
    std::fs::remove_dir_all(&folder).unwrap();
    assert_eq!(failures.len(), 8, "{failures:?}");
    assert!(failures[5].contains("arc centre X"), "{failures:?}");
    assert!(failures[6].contains("arc direction"), "{failures:?}");
    assert!(
        failures[7].contains("machine arc direction"),
        "{failures:?}"
    );
    assert!(failures[0].contains("X expected 11"), "{failures:?}");
}
