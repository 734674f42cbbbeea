//! Checks the interpreter against the fixtures in `fixtures/execution`: each block may say where the
//! axes are after each of its executions (`; => X10 | X20 | X30`, one part per pass in execution
//! order), that it never moves (`; => none`), and which execution findings it reports (`!! E401`).
//! A folder is one case of several files: its `main.mpf` (or `main.spf`) runs, and the other files are
//! the programs it can call, by file name. See `fixtures/execution/README.md`.

use sinumerik_lsp::analysis::execution::{
    execute_collecting, EntryState, ExecutedMove, ExecutionOptions,
};
use sinumerik_lsp::analysis::library::MemoryLibrary;
use sinumerik_lsp::analysis::ProgramKind;
use sinumerik_lsp::config::{parse_config_text, MachineConfig};
use sinumerik_lsp::ide::workspace::{macro_file_rank, program_name_and_kind, FileKind};
use sinumerik_lsp::syntax::lines;
use std::path::{Path, PathBuf};

/// What one pass of a block must give: axis values (`None` = unknown) and flags.
#[derive(Debug, Default, Clone)]
struct PassExpectation {
    positions: Vec<(String, Option<(f64, usize)>)>,
    /// `@CYCLE81`: the move is made by that cycle's built-in model; `@none`: by the block itself.
    cycle: Option<String>,
    /// `G0`, `G1`: the motion of the move.
    motion: Option<String>,
    /// `F100`: the feed of the move (`F?`: unknown).
    feed: Option<Option<(f64, usize)>>,
    /// `COND`: the move lies on a way whose condition is not decided.
    conditional: bool,
    /// `ASSUMED X Y`: these axes rest on the assumed entry state (and no others).
    assumed: Option<Vec<String>>,
    /// `RND`, `CHF` or `CHR`: the move is an element the corner stage inserted (else it is none).
    inserted: Option<String>,
    /// `START=X45/Y0`: the move starts at these values.
    start: Vec<(String, (f64, usize))>,
    /// `CENTRE=X45/Y5`: the centre of the move's circle.
    centre: Vec<(String, (f64, usize))>,
    /// `FEED=100`: the move's feed.
    element_feed: Option<(f64, usize)>,
}

/// `X45/Y5.5` as axis values.
fn axis_values(text: &str) -> Vec<(String, (f64, usize))> {
    text.split('/')
        .map(|part| {
            let split = part
                .find(|c: char| !c.is_ascii_alphabetic())
                .unwrap_or(part.len());
            (part[..split].to_string(), written_number(&part[split..]))
        })
        .collect()
}

#[derive(Debug, Default)]
struct LineExpectation {
    passes: Option<Vec<PassExpectation>>,
    /// `last =>`: only the last of the block's moves is checked (against the one part).
    last_only: bool,
    /// From `; holes:` lines below the block: the holes its drilling cycles make, as a set.
    holes: Option<Vec<PassExpectation>>,
    no_move: bool,
    codes: Vec<String>,
}

fn written_number(text: &str) -> (f64, usize) {
    let number: f64 = text
        .parse()
        .unwrap_or_else(|_| panic!("`{text}` is not a number"));
    let decimals = text
        .split_once('.')
        .map_or(0, |(_, fraction)| fraction.len());
    (number, decimals)
}

fn parse_pass(text: &str) -> PassExpectation {
    let mut pass = PassExpectation::default();
    let mut in_assumed = false;
    for word in text.split_whitespace() {
        if word == "COND" {
            pass.conditional = true;
            in_assumed = false;
            continue;
        }
        if matches!(word, "RND" | "CHF" | "CHR") {
            pass.inserted = Some(word.to_string());
            continue;
        }
        if let Some(values) = word.strip_prefix("START=") {
            pass.start = axis_values(values);
            continue;
        }
        if let Some(values) = word.strip_prefix("CENTRE=") {
            pass.centre = axis_values(values);
            continue;
        }
        if let Some(value) = word.strip_prefix("FEED=") {
            pass.element_feed = Some(written_number(value));
            continue;
        }
        if word == "ASSUMED" {
            pass.assumed = Some(Vec::new());
            in_assumed = true;
            continue;
        }
        if in_assumed {
            pass.assumed.as_mut().unwrap().push(word.to_string());
            continue;
        }
        if let Some(cycle) = word.strip_prefix('@') {
            pass.cycle = Some(cycle.to_string());
            continue;
        }
        if word.len() > 1
            && word.starts_with('G')
            && word[1..].bytes().all(|byte| byte.is_ascii_digit())
        {
            pass.motion = Some(word.to_string());
            continue;
        }
        if let Some(feed) = word.strip_prefix('F') {
            pass.feed = Some((feed != "?").then(|| written_number(feed)));
            continue;
        }
        let split = word
            .find(|c: char| !c.is_ascii_alphabetic())
            .unwrap_or(word.len());
        let (name, value) = word.split_at(split);
        let value = value.strip_prefix('=').unwrap_or(value);
        if value == "?" {
            pass.positions.push((name.to_string(), None));
        } else {
            pass.positions
                .push((name.to_string(), Some(written_number(value))));
        }
    }
    pass
}

fn parse_line_expectation(comment: &str) -> LineExpectation {
    let mut expectation = LineExpectation::default();
    let (moves_part, codes_part) = match comment.find("!!") {
        Some(position) => (&comment[..position], &comment[position + 2..]),
        None => (comment, ""),
    };
    expectation.codes = codes_part.split_whitespace().map(str::to_string).collect();
    if let Some(position) = moves_part.find("=>") {
        expectation.last_only = moves_part[..position].trim() == "last";
        let rest = moves_part[position + 2..].trim();
        if rest == "none" {
            expectation.no_move = true;
        } else {
            expectation.passes = Some(rest.split('|').map(parse_pass).collect());
        }
    }
    expectation
}

fn matches_written(actual: f64, expected: f64, decimals: usize) -> bool {
    let tolerance = if decimals == 0 {
        1e-6
    } else {
        0.5 * 10f64.powi(-(decimals as i32)) + 1e-9
    };
    (actual - expected).abs() <= tolerance
}

/// The machine, options and library a case is run with.
struct Case {
    main: PathBuf,
    others: Vec<PathBuf>,
}

fn cases() -> Vec<Case> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/execution");
    let mut entries: Vec<PathBuf> = std::fs::read_dir(&root)
        .expect("fixtures/execution exists")
        .map(|entry| entry.expect("readable entry").path())
        .collect();
    entries.sort();
    let mut cases = Vec::new();
    for entry in entries {
        if entry.is_dir() {
            let mut files: Vec<PathBuf> = std::fs::read_dir(&entry)
                .expect("readable case folder")
                .map(|file| file.expect("readable entry").path())
                .collect();
            files.sort();
            let main = files
                .iter()
                .position(|file| {
                    file.file_stem()
                        .is_some_and(|stem| stem.eq_ignore_ascii_case("main"))
                })
                .unwrap_or_else(|| panic!("{} has no main program", entry.display()));
            let main = files.remove(main);
            cases.push(Case {
                main,
                others: files,
            });
        } else if entry
            .extension()
            .is_some_and(|extension| extension == "mpf" || extension == "spf")
        {
            cases.push(Case {
                main: entry,
                others: Vec::new(),
            });
        }
    }
    cases
}

fn options_of(text: &str) -> ExecutionOptions {
    let mut options = ExecutionOptions::default();
    for line in text.lines() {
        let Some(settings) = line.strip_prefix("; options: ") else {
            continue;
        };
        for setting in settings.split_whitespace() {
            let (key, value) = setting.split_once('=').expect("key=value");
            match key {
                "max_blocks" => options.max_blocks = value.parse().unwrap(),
                "max_loop_passes" => options.max_loop_passes = value.parse().unwrap(),
                "entry" => {
                    options.entry = match value {
                        "reset" => EntryState::Reset,
                        _ => EntryState::Unknown,
                    }
                }
                "m30_ends_subprogram" => options.m30_ends_subprogram = value == "true",
                "gotos" => {
                    options.gotos_restarts = match value {
                        "true" => Some(true),
                        "false" => Some(false),
                        _ => None,
                    }
                }
                _ => panic!("unknown option {key}"),
            }
        }
    }
    options
}

fn config_of(text: &str, path: &Path) -> MachineConfig {
    let toml: String = text
        .lines()
        .filter_map(|line| line.strip_prefix("; toml: "))
        .flat_map(|line| [line, "\n"])
        .collect();
    if !toml.is_empty() {
        parse_config_text(&toml, path).unwrap_or_else(|error| panic!("{error}"))
    } else if text.starts_with("; config: turn") {
        MachineConfig::turn()
    } else {
        MachineConfig::mill()
    }
}

fn check_case(case: &Case) -> Vec<String> {
    let text = std::fs::read_to_string(&case.main).expect("readable fixture");
    let config = config_of(&text, &case.main);
    let options = options_of(&text);
    let mut library = MemoryLibrary::default();
    // Macro definition files (`_N_UMAC_DEF`, `SMAC.DEF`, ...) in the order the control reads them.
    let mut definitions: Vec<(u8, &PathBuf)> = Vec::new();
    for other in &case.others {
        let file_name = other.file_name().unwrap().to_string_lossy().to_string();
        let (program, file_kind) = program_name_and_kind(&file_name);
        if file_kind == FileKind::Definitions {
            definitions.push((macro_file_rank(&program), other));
            continue;
        }
        let name = other.file_stem().unwrap().to_string_lossy().to_string();
        let other_text = std::fs::read_to_string(other).expect("readable fixture");
        library.insert(&name, &other.display().to_string(), &other_text);
    }
    definitions.sort_by_key(|(rank, _)| *rank);
    for (_, file) in definitions {
        let file_text = std::fs::read_to_string(file).expect("readable fixture");
        library.insert_macro_file(&file.display().to_string(), &file_text);
    }
    let kind = ProgramKind::from_extension(case.main.extension().and_then(|e| e.to_str()));
    let (execution, moves) = execute_collecting(&text, &config, kind, &library, &options);
    let mut failures = Vec::new();
    // The analysed program's own lines, then each called file's lines.
    let mut files = vec![(case.main.clone(), None::<String>)];
    files.extend(
        case.others
            .iter()
            .map(|other| (other.clone(), Some(other.display().to_string()))),
    );
    for (path, key) in files {
        let file_text = std::fs::read_to_string(&path).expect("readable fixture");
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let all_lines: Vec<&str> = lines::line_ranges(&file_text)
            .map(|(start, end)| &file_text[start..end])
            .collect();
        for (line_index, line) in all_lines.iter().copied().enumerate() {
            let mut expectation = match line.find(';') {
                Some(position)
                    if line[position..].contains("=>") || line[position..].contains("!!") =>
                {
                    parse_line_expectation(&line[position + 1..])
                }
                _ => LineExpectation::default(),
            };
            if !line.trim().starts_with("; holes:") {
                expectation.holes = holes_below(&all_lines, line_index);
            }
            if key.is_none() {
                let reported: Vec<String> = execution
                    .findings
                    .iter()
                    .filter(|item| item.line == line_index)
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
            }
            let of_line: Vec<&ExecutedMove> = moves
                .iter()
                .filter(|executed| {
                    executed.movement.line == line_index
                        && executed.path.as_deref() == key.as_deref()
                })
                .collect();
            if expectation.no_move && !of_line.is_empty() {
                failures.push(format!(
                    "{name}:{}: expected no move, found {}",
                    line_index + 1,
                    of_line.len()
                ));
            }
            if let Some(holes) = &expectation.holes {
                failures.extend(compare_holes(
                    &format!("{name}:{}", line_index + 1),
                    holes,
                    &of_line,
                ));
            }
            let Some(passes) = &expectation.passes else {
                continue;
            };
            if expectation.last_only {
                match (passes.as_slice(), of_line.last()) {
                    ([expected], Some(last)) => failures.extend(compare_pass(
                        &format!("{name}:{} last move", line_index + 1),
                        expected,
                        last,
                    )),
                    _ => failures.push(format!(
                        "{name}:{}: `last =>` needs one part and a move",
                        line_index + 1
                    )),
                }
                continue;
            }
            if passes.len() != of_line.len() {
                failures.push(format!(
                    "{name}:{}: expected {} moves, found {}: {:?}",
                    line_index + 1,
                    passes.len(),
                    of_line.len(),
                    of_line
                        .iter()
                        .map(|executed| &executed.movement.end)
                        .collect::<Vec<_>>()
                ));
                continue;
            }
            for (number, (expected, executed)) in passes.iter().zip(&of_line).enumerate() {
                let at = format!("{name}:{} pass {}", line_index + 1, number + 1);
                failures.extend(compare_pass(&at, expected, executed));
            }
            // A block that runs more than once numbers its moves 1, 2, 3, ...; once, not at all (a
            // block that triggers a cycle makes several moves in one execution, with one number).
            // Inserted roundings and chamfers carry the pass of the block's own move.
            let counted: Vec<_> = of_line
                .iter()
                .filter(|executed| executed.movement.inserted.is_none())
                .collect();
            let numbers: Vec<u32> = counted.iter().map(|executed| executed.pass).collect();
            let once = numbers.iter().all(|number| *number == 0);
            let by_cycles = counted
                .iter()
                .any(|executed| executed.movement.cycle.is_some());
            let numbered = if numbers.len() > 1 && !(once && by_cycles) {
                numbers.first() == Some(&1)
                    && numbers
                        .windows(2)
                        .all(|pair| pair[0] < pair[1] || (by_cycles && pair[0] == pair[1]))
            } else {
                true
            };
            if !numbered {
                failures.push(format!(
                    "{name}:{}: the passes of a block that runs {} times are numbered {numbers:?}",
                    line_index + 1,
                    of_line.len()
                ));
            }
        }
    }
    failures
}

/// The `; holes: X30 Y10, X45 Y10` lines right below line `index` (comment lines of their own),
/// joined: the holes the block's drilling cycles make.
fn holes_below(lines: &[&str], index: usize) -> Option<Vec<PassExpectation>> {
    let mut holes: Option<Vec<PassExpectation>> = None;
    for line in lines.iter().skip(index + 1) {
        let Some(list) = line.trim().strip_prefix("; holes:") else {
            break;
        };
        holes.get_or_insert_with(Vec::new).extend(
            list.split(',')
                .filter(|hole| !hole.trim().is_empty())
                .map(parse_pass),
        );
    }
    holes
}

/// Compares the holes of a block's moves with the expected set: a hole is where a run of moves of
/// one drilling cycle (`CYCLE8…`) starts, its first move's end in the plane.
fn compare_holes(at: &str, expected: &[PassExpectation], moves: &[&ExecutedMove]) -> Vec<String> {
    let mut actual: Vec<&ExecutedMove> = Vec::new();
    let mut previous: Option<&str> = None;
    for executed in moves {
        let cycle = executed
            .movement
            .cycle
            .as_deref()
            .filter(|name| name.starts_with("CYCLE8") && *name != "CYCLE801");
        if cycle.is_some() && previous.is_none() {
            actual.push(executed);
        }
        previous = cycle;
    }
    if actual.len() != expected.len() {
        return vec![format!(
            "{at}: expected {} holes, found {}: {:?}",
            expected.len(),
            actual.len(),
            actual
                .iter()
                .map(|executed| &executed.movement.end)
                .collect::<Vec<_>>()
        )];
    }
    let mut unmatched: Vec<&ExecutedMove> = actual;
    let mut failures = Vec::new();
    for hole in expected {
        match unmatched
            .iter()
            .position(|executed| compare_pass(at, hole, executed).is_empty())
        {
            Some(found) => {
                unmatched.remove(found);
            }
            None => failures.push(format!(
                "{at}: no hole at {:?}; left: {:?}",
                hole.positions,
                unmatched
                    .iter()
                    .map(|executed| &executed.movement.end)
                    .collect::<Vec<_>>()
            )),
        }
    }
    failures
}

fn compare_pass(at: &str, expected: &PassExpectation, executed: &ExecutedMove) -> Vec<String> {
    let mut failures = Vec::new();
    let movement = &executed.movement;
    if let Some(cycle) = &expected.cycle {
        let actual = movement.cycle.as_deref().unwrap_or("none");
        if actual != cycle {
            failures.push(format!("{at}: expected cycle {cycle}, got {actual}"));
        }
    }
    if let Some(motion) = &expected.motion {
        if movement.motion.as_ref() != motion {
            failures.push(format!("{at}: expected {motion}, got {}", movement.motion));
        }
    }
    if let Some(feed) = &expected.feed {
        let agrees = match (feed, movement.feed) {
            (Some((value, decimals)), Some(actual)) => matches_written(actual, *value, *decimals),
            (None, None) => true,
            _ => false,
        };
        if !agrees {
            failures.push(format!(
                "{at}: expected feed {feed:?}, got {:?}",
                movement.feed
            ));
        }
    }
    for (axis, value) in &expected.positions {
        let actual = movement
            .end
            .iter()
            .find(|(name, _)| name.as_ref() == axis.as_str())
            .map(|(_, value)| *value);
        let agrees = match (value, actual) {
            (Some((value, decimals)), Some(actual)) => matches_written(actual, *value, *decimals),
            (None, None) => movement.uncertain.iter().any(|name| name.as_ref() == axis),
            _ => false,
        };
        if !agrees {
            failures.push(format!(
                "{at}: {axis} expected {value:?}, got {actual:?} (uncertain {:?})",
                movement.uncertain
            ));
        }
    }
    if expected.inserted.as_deref() != movement.inserted {
        failures.push(format!(
            "{at}: expected inserted {:?}, got {:?}",
            expected.inserted, movement.inserted
        ));
    }
    let values_agree = |expected: &[(String, (f64, usize))],
                        actual: &[(std::sync::Arc<str>, f64)]| {
        expected.iter().all(|(axis, (value, decimals))| {
            actual
                .iter()
                .find(|(name, _)| name.as_ref() == axis.as_str())
                .is_some_and(|(_, actual)| matches_written(*actual, *value, *decimals))
        })
    };
    if !values_agree(&expected.start, &movement.start) {
        failures.push(format!(
            "{at}: expected start {:?}, got {:?}",
            expected.start, movement.start
        ));
    }
    if !expected.centre.is_empty() {
        let centre = movement.arc.as_ref().map(|arc| arc.centre.as_slice());
        if !centre.is_some_and(|centre| values_agree(&expected.centre, centre)) {
            failures.push(format!(
                "{at}: expected centre {:?}, got {centre:?}",
                expected.centre
            ));
        }
    }
    if let Some((feed, decimals)) = expected.element_feed {
        if !movement
            .feed
            .is_some_and(|actual| matches_written(actual, feed, decimals))
        {
            failures.push(format!(
                "{at}: expected feed {feed}, got {:?}",
                movement.feed
            ));
        }
    }
    if expected.conditional != executed.conditional {
        failures.push(format!(
            "{at}: expected conditional = {}, got {}",
            expected.conditional, executed.conditional
        ));
    }
    if let Some(assumed) = &expected.assumed {
        let actual: Vec<String> = executed
            .assumed
            .iter()
            .map(|name| name.to_string())
            .collect();
        if &actual != assumed {
            failures.push(format!(
                "{at}: expected assumed {assumed:?}, got {actual:?}"
            ));
        }
    }
    failures
}

#[test]
fn execution_fixtures_run_as_annotated() {
    let cases = cases();
    assert!(cases.len() >= 10, "the execution fixtures are missing");
    let failures: Vec<String> = cases.iter().flat_map(check_case).collect();
    assert!(
        failures.is_empty(),
        "{} mismatches:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
