//! Hostile input: parsing never fails, deep nesting is cut off with one S170, huge lines cost linear time,
//! and every span of every block and diagnostic lies inside its line on character boundaries.
//!
//! Each test builds one kind of input that a broken or malicious file could contain and checks a concrete
//! outcome: the diagnostic codes and how often they appear, the shape of the block, and the spans. The
//! tests run in debug and in release builds, because the lexer and the recursive descent use far more
//! stack per level in debug builds.

use sinumerik_lsp::analysis::{diagnose_program, ProgramKind};
use sinumerik_lsp::config::MachineConfig;
use sinumerik_lsp::diagnostics::{Code, Diagnostic, LineDiagnostic, Span};
use sinumerik_lsp::io::source_file::{decode_source, decode_windows_1252, SourceEncoding};
use sinumerik_lsp::syntax::ast::{
    AddressKind, Expr, ExprKind, JumpTarget, Statement, StructureKeyword, ValueExpr,
};
use sinumerik_lsp::syntax::parser::MAX_EXPRESSION_DEPTH;
use sinumerik_lsp::syntax::{check_program, lines, Block, LineParser, SyntaxContext};
use std::process::Command;

/// The span checks the fuzzer applies, shared so that both check the same spans.
#[path = "../examples/fuzz/spans.rs"]
mod fuzz_spans;
use std::time::{Duration, Instant};

/// The size of the "5 MB" lines of the issue.
const FIVE_MB: usize = 5 * 1024 * 1024;

/// How many times a construct is nested in the deep-nesting tests.
const DEEP: usize = 100_000;

/// A loose upper bound for the diagnostics of one hostile line. The parser may cap its findings much
/// lower; what must not happen is one diagnostic per token of a line with millions of tokens.
const MAX_DIAGNOSTICS_PER_LINE: usize = 1_000;

// ----- helpers -------------------------------------------------------------------------------------

/// Parses one line with the default machine (the general parser after the fast path, as the product
/// does) and checks every span of the result before returning it.
fn parse(line: &str) -> (Block, Vec<Diagnostic>) {
    let context = SyntaxContext::default();
    let mut block = Block::default();
    let mut diagnostics = Vec::new();
    LineParser::new().parse(line, &context, &mut block, &mut diagnostics);
    assert_block_spans_valid(line, &block);
    assert_diagnostic_spans_valid(line, &diagnostics);
    (block, diagnostics)
}

/// Like [`parse`], but always through the general parser (lexer and recursive descent).
fn parse_general(line: &str) -> (Block, Vec<Diagnostic>) {
    let context = SyntaxContext::default();
    let mut block = Block::default();
    let mut diagnostics = Vec::new();
    LineParser::new().parse_without_fast_path(line, &context, &mut block, &mut diagnostics);
    assert_block_spans_valid(line, &block);
    assert_diagnostic_spans_valid(line, &diagnostics);
    (block, diagnostics)
}

/// Checks a whole program with the default machine and checks that every diagnostic lies inside its line.
fn check(text: &str) -> Vec<LineDiagnostic> {
    let diagnostics = check_program(text, &MachineConfig::default());
    let line_texts: Vec<&str> = lines::line_ranges(text)
        .map(|(start, end)| &text[start..end])
        .collect();
    for item in &diagnostics {
        let line = line_texts.get(item.line).copied().unwrap_or_else(|| {
            panic!(
                "diagnostic {:?} is on line {}, but the text has {} lines",
                item.diagnostic.code,
                item.line,
                line_texts.len()
            )
        });
        assert_diagnostic_spans_valid(line, std::slice::from_ref(&item.diagnostic));
    }
    diagnostics
}

fn assert_diagnostic_spans_valid(line: &str, diagnostics: &[Diagnostic]) {
    if let Err(problem) = fuzz_spans::check_diagnostic_spans(line, diagnostics) {
        panic!("{problem} in {:?}", abbreviate(line));
    }
}

/// Every span a block holds: its markers, its statements with their parts, and its expression nodes.
fn assert_block_spans_valid(line: &str, block: &Block) {
    if let Err(problem) = fuzz_spans::check_block_spans(line, block) {
        panic!("{problem} in {:?}", abbreviate(line));
    }
}

fn count(diagnostics: &[Diagnostic], code: Code) -> usize {
    diagnostics
        .iter()
        .filter(|diagnostic| diagnostic.code == code)
        .count()
}

/// The codes of `diagnostics` in order, for assertion messages and exact comparisons.
fn codes(diagnostics: &[Diagnostic]) -> Vec<&'static str> {
    diagnostics
        .iter()
        .map(|diagnostic| diagnostic.code.as_str())
        .collect()
}

/// How many diagnostics of each code, sorted by code, for compact assertion messages.
fn code_histogram(diagnostics: &[Diagnostic]) -> Vec<(&'static str, usize)> {
    let mut histogram: Vec<(&'static str, usize)> = Vec::new();
    for diagnostic in diagnostics {
        let code = diagnostic.code.as_str();
        match histogram.iter_mut().find(|(known, _)| *known == code) {
            Some((_, count)) => *count += 1,
            None => histogram.push((code, 1)),
        }
    }
    histogram.sort();
    histogram
}

/// `chunk` repeated as often as it fits into `size` bytes.
fn repeat_to(chunk: &str, size: usize) -> String {
    chunk.repeat(size / chunk.len())
}

/// The start and the length of a long line, for assertion messages that must not print megabytes.
fn abbreviate(line: &str) -> String {
    if line.len() <= 80 {
        return line.to_string();
    }
    let mut end = 60;
    while !line.is_char_boundary(end) {
        end -= 1;
    }
    format!("{}... ({} bytes)", &line[..end], line.len())
}

/// A deterministic xorshift generator, so that the random tests give the same lines on every run.
struct XorShift(u64);

impl XorShift {
    fn next(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        self.0 = x;
        x
    }

    fn below(&mut self, bound: usize) -> usize {
        (self.next() % bound as u64) as usize
    }
}

/// The fastest of a few runs of `work`, which is less disturbed by other tests running at the same time.
fn fastest_of(runs: usize, mut work: impl FnMut()) -> Duration {
    (0..runs)
        .map(|_| {
            let start = Instant::now();
            work();
            start.elapsed()
        })
        .min()
        .unwrap_or_default()
}

/// Runs `work` in a child process that runs only the test `test_name`. A stack overflow aborts the whole
/// test binary; in a child process it fails just this test, with the child's output in the message.
fn in_child_process(test_name: &str, work: impl FnOnce()) {
    const CHILD: &str = "HOSTILE_INPUT_CHILD";
    if std::env::var_os(CHILD).is_some_and(|name| name == test_name) {
        work();
        return;
    }
    let output = Command::new(std::env::current_exe().expect("the path of the test binary"))
        .args(["--exact", test_name, "--nocapture", "--test-threads=1"])
        .env(CHILD, test_name)
        .env("RUST_BACKTRACE", "0")
        .output()
        .expect("the test binary starts again");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success(),
        "`{test_name}` failed in its child process ({}):\n{}",
        output.status,
        stderr.trim()
    );
}

// ----- 1. long lines of ordinary words -------------------------------------------------------------

#[test]
fn five_megabyte_line_of_plain_words_gives_every_word() {
    let chunk = "X1.5 Y2 Z-3 ";
    let line = repeat_to(chunk, FIVE_MB);
    let repetitions = line.len() / chunk.len();
    let (block, diagnostics) = parse(&line);
    assert_eq!(block.statements.len(), 3 * repetitions);
    assert!(block.statements.iter().all(
        |statement| matches!(statement, Statement::Address(word) if word.kind == AddressKind::Axis)
    ));
    let last = block.statements.last().map(Statement::span);
    assert_eq!(
        last.map(|span| &line[span.start()..span.end()]),
        Some("Z-3")
    );
    // The repeated-address check compares only the first 64 words: X, Y and Z, then 61 repetitions.
    assert_eq!(
        code_histogram(&diagnostics),
        vec![("S143", 61), ("S163", 1)],
        "diagnostics of the 5 MB line of plain words"
    );
}

#[test]
fn five_megabyte_line_of_plain_words_gives_the_same_result_through_the_general_parser() {
    let line = repeat_to("X1.5 Y2 Z-3 ", FIVE_MB);
    let fast = parse(&line);
    let general = parse_general(&line);
    assert!(
        fast.0 == general.0,
        "the general parser builds a different block for the 5 MB line"
    );
    assert_eq!(fast.1, general.1);
}

#[test]
fn five_megabyte_line_of_one_address_reports_s143_a_bounded_number_of_times() {
    let line = repeat_to("X1 ", FIVE_MB);
    let (block, diagnostics) = parse(&line);
    assert_eq!(block.statements.len(), line.len() / 3);
    // Only the first 64 words are compared: the first X is the original, the next 63 repeat it.
    assert_eq!(count(&diagnostics, Code::AddressTwice), 63);
    assert_eq!(count(&diagnostics, Code::BlockTooLong), 1);
    assert_eq!(diagnostics.len(), 64);
    let (_, general) = parse_general(&line);
    assert_eq!(diagnostics, general);
}

#[test]
fn five_megabyte_line_of_mixed_statements_is_parsed_in_linear_time() {
    // Assignments, calls, modifiers and brackets: everything goes through the lexer and the general parser.
    let chunk = "R1=R2+SIN(3)*(4-R[2]) X=AC(1) F100 AA_B[1]=2 MSG(\"OK\") ";
    let big = repeat_to(chunk, FIVE_MB);
    let quarter = repeat_to(chunk, FIVE_MB / 4);
    let (block, diagnostics) = parse(&big);
    assert_eq!(block.statements.len(), 5 * (big.len() / chunk.len()));
    // X and F repeat in every chunk, but only the first 64 statements are compared (S143).
    assert_eq!(
        code_histogram(&diagnostics),
        vec![("S143", 24), ("S163", 1)]
    );
    // Debug builds are slow enough that one run of each size is already a stable measurement.
    let runs = if cfg!(debug_assertions) { 1 } else { 3 };
    let context = SyntaxContext::default();
    let mut parser = LineParser::new();
    let mut output = (Block::default(), Vec::new());
    let mut time = |line: &str| {
        fastest_of(runs, || {
            parser.parse_without_fast_path(line, &context, &mut output.0, &mut output.1)
        })
    };
    let quarter_time = time(&quarter);
    let big_time = time(&big);
    // Linear time gives a ratio near 4 and quadratic time one near 16; the margin absorbs noise.
    assert!(
        big_time < quarter_time * 9 + Duration::from_millis(50),
        "1.25 MB took {quarter_time:?} and 5 MB took {big_time:?}: that is not linear"
    );
}

#[test]
fn a_line_of_evaluation_errors_is_analysed_in_linear_time() {
    // Every statement is an error of the evaluation (A226, A225, A227), each reported with its message.
    let chunk = "R1=POT(1,2) R2=SQRT(-1) R[-1]=1 R3=ATAN2(BOUND(1)) ";
    let big = repeat_to(chunk, FIVE_MB / 8);
    let quarter = repeat_to(chunk, FIVE_MB / 32);
    let config = MachineConfig::default();
    let diagnostics = diagnose_program(&big, &config, ProgramKind::Main);
    let statements = big.len() / chunk.len();
    assert_eq!(
        diagnostics
            .iter()
            .filter(|item| item.diagnostic.code == Code::FunctionArgumentCount)
            .count(),
        2 * statements
    );
    let runs = if cfg!(debug_assertions) { 1 } else { 3 };
    let time = |text: &str| {
        fastest_of(runs, || {
            diagnose_program(text, &config, ProgramKind::Main);
        })
    };
    let quarter_time = time(&quarter);
    let big_time = time(&big);
    // Linear time gives a ratio near 4 and quadratic time one near 16; the margin absorbs noise.
    assert!(
        big_time < quarter_time * 9 + Duration::from_millis(50),
        "{} bytes took {quarter_time:?} and {} bytes took {big_time:?}: that is not linear",
        quarter.len(),
        big.len()
    );
}

// ----- 2. deep nesting -----------------------------------------------------------------------------
//
// Each test runs in a child process, so that a stack overflow fails the one test instead of aborting
// the whole test binary. Every line is longer than 512 characters, so S163 (block too long) is expected.

#[test]
fn hundred_thousand_balanced_parentheses_report_s170_once() {
    in_child_process(
        "hundred_thousand_balanced_parentheses_report_s170_once",
        || {
            let line = format!("X={}1{}", "(".repeat(DEEP), ")".repeat(DEEP));
            let (block, diagnostics) = parse(&line);
            assert_eq!(code_histogram(&diagnostics), vec![("S163", 1), ("S170", 1)]);
            // The report points at the first parenthesis beyond the limit; the levels above are checked,
            // so no closing parenthesis is left over (no S130).
            let too_deep = diagnostics
                .iter()
                .find(|diagnostic| diagnostic.code == Code::TooDeeplyNested)
                .unwrap();
            assert_eq!(
                too_deep.span.start(),
                "X=".len() + MAX_EXPRESSION_DEPTH as usize
            );
            assert_eq!(block.statements.len(), 1);
            assert_eq!(block.statements[0].span(), Span::new(0, line.len()));
        },
    );
}

#[test]
fn hundred_thousand_unclosed_parentheses_report_s170_and_s130_once_each() {
    in_child_process(
        "hundred_thousand_unclosed_parentheses_report_s170_and_s130_once_each",
        || {
            let line = format!("X={}", "(".repeat(DEEP));
            let (block, diagnostics) = parse(&line);
            assert_eq!(
                code_histogram(&diagnostics),
                vec![("S130", 1), ("S163", 1), ("S170", 1)]
            );
            assert_eq!(block.statements.len(), 1);
        },
    );
}

#[test]
fn hundred_thousand_unclosed_parentheses_without_an_address_report_s130_once() {
    in_child_process(
        "hundred_thousand_unclosed_parentheses_without_an_address_report_s130_once",
        || {
            let line = "(".repeat(DEEP);
            let (_, diagnostics) = parse(&line);
            assert_eq!(code_histogram(&diagnostics), vec![("S130", 1), ("S163", 1)]);
            let unclosed = diagnostics
                .iter()
                .find(|diagnostic| diagnostic.code == Code::UnbalancedParentheses)
                .unwrap();
            assert_eq!(unclosed.span, Span::new(0, 1));
        },
    );
}

#[test]
fn hundred_thousand_nested_brackets_report_s170_once() {
    in_child_process("hundred_thousand_nested_brackets_report_s170_once", || {
        let line = format!("{}1{}=1", "R[".repeat(DEEP), "]".repeat(DEEP));
        let (block, diagnostics) = parse(&line);
        assert_eq!(code_histogram(&diagnostics), vec![("S163", 1), ("S170", 1)]);
        assert!(matches!(
            block.statements.as_slice(),
            [Statement::Assignment { value: Some(_), .. }]
        ));
    });
}

#[test]
fn hundred_thousand_unary_minus_signs_report_s170_once() {
    in_child_process(
        "hundred_thousand_unary_minus_signs_report_s170_once",
        || {
            let line = format!("X={}1", "-".repeat(DEEP));
            let (block, diagnostics) = parse(&line);
            assert_eq!(code_histogram(&diagnostics), vec![("S163", 1), ("S170", 1)]);
            assert_eq!(block.statements.len(), 1);
            assert_eq!(block.statements[0].span(), Span::new(0, line.len()));
        },
    );
}

#[test]
fn hundred_thousand_nots_in_an_if_condition_report_s170_once() {
    in_child_process(
        "hundred_thousand_nots_in_an_if_condition_report_s170_once",
        || {
            let first_line = format!("IF {}1", "NOT ".repeat(DEEP));
            let program = format!("{first_line}\nX1\nENDIF\n");
            let diagnostics = check(&program);
            let on_first_line: Vec<Diagnostic> = diagnostics
                .iter()
                .filter(|item| item.line == 0)
                .map(|item| item.diagnostic.clone())
                .collect();
            assert_eq!(diagnostics.len(), on_first_line.len());
            assert_eq!(
                code_histogram(&on_first_line),
                vec![("S163", 1), ("S170", 1)]
            );
            let (block, _) = parse(&first_line);
            assert!(matches!(
                block.statements.as_slice(),
                [Statement::Structure {
                    keyword: StructureKeyword::If,
                    condition: Some(_),
                    ..
                }]
            ));
        },
    );
}

#[test]
fn hundred_thousand_nots_before_a_jump_keep_the_jump() {
    // The condition is cut off at the depth limit, but `GOTOF` ends it: the jump must still be seen, or
    // the IF is taken for an IF block that is never closed (S190 from the structure check).
    in_child_process("hundred_thousand_nots_before_a_jump_keep_the_jump", || {
        let line = format!("IF {}1 GOTOF END", "NOT ".repeat(DEEP));
        let diagnostics = check(&line);
        let plain: Vec<Diagnostic> = diagnostics
            .iter()
            .map(|item| item.diagnostic.clone())
            .collect();
        assert_eq!(code_histogram(&plain), vec![("S163", 1), ("S170", 1)]);
        let (block, _) = parse(&line);
        assert!(
            matches!(
                block.statements.as_slice(),
                [Statement::Jump {
                    target: JumpTarget::Label(_),
                    ..
                }]
            ),
            "the block holds no jump to the label END"
        );
    });
}

#[test]
fn hundred_thousand_nested_function_calls_report_s170_once() {
    in_child_process(
        "hundred_thousand_nested_function_calls_report_s170_once",
        || {
            let line = format!("X={}1{}", "SIN(".repeat(DEEP), ")".repeat(DEEP));
            let (block, diagnostics) = parse(&line);
            assert_eq!(code_histogram(&diagnostics), vec![("S163", 1), ("S170", 1)]);
            assert_eq!(block.statements.len(), 1);
            assert_eq!(block.statements[0].span(), Span::new(0, line.len()));
        },
    );
}

#[test]
fn hundred_thousand_levels_of_every_operator_precedence_report_s170_once() {
    // Each operator binds tighter than the one before, so every level of brackets also nests one binary
    // operator per precedence level: the most stack per nesting level the expression parser can use.
    in_child_process(
        "hundred_thousand_levels_of_every_operator_precedence_report_s170_once",
        || {
            let ladder = "1==1<<1 OR 1 XOR 1 AND 1 B_OR 1 B_XOR 1 B_AND 1+1*(";
            let line = format!("IF {}1{}", ladder.repeat(DEEP), ")".repeat(DEEP));
            let (block, diagnostics) = parse(&line);
            assert_eq!(code_histogram(&diagnostics), vec![("S163", 1), ("S170", 1)]);
            assert!(matches!(
                block.statements.as_slice(),
                [Statement::Structure {
                    keyword: StructureKeyword::If,
                    condition: Some(_),
                    ..
                }]
            ));
        },
    );
}

#[test]
fn nesting_at_the_limit_is_accepted_and_one_more_level_is_reported() {
    let depth = MAX_EXPRESSION_DEPTH as usize;
    // The value itself counts as one level, so at most MAX_EXPRESSION_DEPTH - 1 parentheses are accepted.
    let at_limit = format!("X={}1{}", "(".repeat(depth - 1), ")".repeat(depth - 1));
    let (_, diagnostics) = parse(&at_limit);
    assert_eq!(codes(&diagnostics), Vec::<&str>::new());
    let beyond = format!("X={}1{}", "(".repeat(depth), ")".repeat(depth));
    let (_, diagnostics) = parse(&beyond);
    assert_eq!(codes(&diagnostics), vec!["S170"]);
}

#[test]
fn hundred_thousand_for_keywords_do_not_overflow_the_stack() {
    // `FOR` parses its start assignment as a statement, which may be another `FOR`: a recursion through
    // statements, which the expression depth limit does not cover.
    in_child_process(
        "hundred_thousand_for_keywords_do_not_overflow_the_stack",
        || {
            let line = "FOR ".repeat(DEEP);
            let (block, diagnostics) = parse(&line);
            assert!(!block.statements.is_empty());
            assert!(
                diagnostics.len() <= MAX_DIAGNOSTICS_PER_LINE,
                "{:?}",
                code_histogram(&diagnostics)
            );
        },
    );
}

// ----- 3. long tokens ------------------------------------------------------------------------------

#[test]
fn five_megabyte_comment_is_one_comment() {
    let comment = format!("; {}", "A".repeat(FIVE_MB));
    for line in [comment.clone(), format!("R1=1 {comment}")] {
        let (block, diagnostics) = parse(&line);
        let comment_start = line.len() - comment.len();
        assert_eq!(block.comment, Some(Span::new(comment_start, line.len())));
        assert_eq!(codes(&diagnostics), vec!["S163"], "{}", abbreviate(&line));
    }
}

#[test]
fn five_megabyte_string_is_one_string() {
    let line = format!("MSG(\"{}\")", "A".repeat(FIVE_MB));
    let (block, diagnostics) = parse(&line);
    assert_eq!(codes(&diagnostics), vec!["S163"]);
    let strings: Vec<Span> = block
        .exprs
        .iter()
        .filter(|expr| expr.kind == ExprKind::String)
        .map(|expr| expr.span)
        .collect();
    assert_eq!(strings, vec![Span::new(4, line.len() - 1)]);
}

#[test]
fn five_megabyte_unterminated_string_reports_s132_once() {
    let line = format!("MSG(\"{}", "A".repeat(FIVE_MB));
    let (_, diagnostics) = parse(&line);
    assert_eq!(count(&diagnostics, Code::UnterminatedString), 1);
    assert_eq!(count(&diagnostics, Code::BlockTooLong), 1);
    assert_eq!(diagnostics.len(), 2, "{:?}", codes(&diagnostics));
    let unterminated = diagnostics
        .iter()
        .find(|diagnostic| diagnostic.code == Code::UnterminatedString)
        .unwrap();
    assert_eq!(unterminated.span, Span::new(4, line.len()));
}

#[test]
fn five_megabyte_identifier_is_one_name() {
    let name = "AB".repeat(FIVE_MB / 2);
    let (block, diagnostics) = parse(&name);
    assert_eq!(block.statements.len(), 1);
    assert_eq!(block.statements[0].span(), Span::new(0, name.len()));
    assert_eq!(codes(&diagnostics), vec!["S163"]);

    let assignment = format!("{name}=1");
    let (block, _) = parse(&assignment);
    assert!(matches!(
        block.statements.as_slice(),
        [Statement::Assignment { target_span, .. }] if *target_span == Span::new(0, name.len())
    ));
}

#[test]
fn five_megabyte_and_ten_thousand_digit_numbers_are_s133_and_unknown() {
    // Such a number lies beyond the range of a double: it used to become infinity silently. It is one
    // number token, reported once (S133), and its value is an error node, so no position is made of it.
    for digits in [10_000, FIVE_MB] {
        let number = "7".repeat(digits);
        for line in [format!("X{number}"), format!("X={number}")] {
            let (block, diagnostics) = parse(&line);
            let value = match block.statements.as_slice() {
                [Statement::Address(word)] => word.value.expr,
                _ => panic!("{} is not one address word", abbreviate(&line)),
            };
            let error_span = match value {
                ValueExpr::Expr(id) => match block.expr(id) {
                    Expr {
                        kind: ExprKind::Error,
                        span,
                    } => Some(*span),
                    _ => None,
                },
                _ => None,
            };
            assert_eq!(
                error_span.map(|span| span.end() - span.start()),
                Some(digits),
                "{}",
                abbreviate(&line)
            );
            let mut expected = vec!["S133"];
            if line.len() > 512 {
                expected.insert(0, "S163");
            }
            assert_eq!(codes(&diagnostics), expected, "{}", abbreviate(&line));
        }
        // Block numbers, G numbers and R parameter numbers must be whole numbers that fit: S133.
        for line in [
            format!("N{number} X1"),
            format!("G{number}"),
            format!("R{number}=1"),
        ] {
            let (_, diagnostics) = parse(&line);
            assert_eq!(
                count(&diagnostics, Code::InvalidNumber),
                1,
                "{}: {:?}",
                abbreviate(&line),
                codes(&diagnostics)
            );
            assert_eq!(diagnostics.len(), 1 + usize::from(line.len() > 512));
        }
    }
}

#[test]
fn numbers_beyond_the_range_of_a_double_are_s133_and_never_a_position() {
    let config = MachineConfig::default();
    for (line, s133) in [
        ("G0 X1EX400", 1),
        ("G0 X=-1EX99999999999", 1),
        ("G0 X=AC(1EX400)", 1),
        ("G0 X='HFFFFFFFFFFFFFFFFFFFF'", 1),
        ("G0 X=2*1EX308", 0),
        ("G0 X1EX308\nG91 X1EX308", 0),
    ] {
        let program = line;
        let diagnostics = check(program);
        assert_eq!(
            diagnostics
                .iter()
                .filter(|item| item.diagnostic.code == Code::InvalidNumber)
                .count(),
            s133,
            "{line}: {:?}",
            diagnostics
                .iter()
                .map(|item| item.diagnostic.code)
                .collect::<Vec<_>>()
        );
        // The last move's X is unknown: left out of the end point and named as uncertain.
        let analysis = sinumerik_lsp::analysis::analyze(program, &config);
        let last = analysis.moves.last().expect("the program moves");
        assert!(
            last.end.iter().all(|(name, _)| &**name != "X")
                && last.uncertain.iter().any(|name| &**name == "X"),
            "{line}: {last:?}"
        );
        for movement in &analysis.moves {
            assert!(movement.end.iter().all(|(_, value)| value.is_finite()));
        }
    }
    // Just inside the range the value is kept, and a zero with a huge exponent is zero (it was NaN).
    for (line, expected) in [
        ("G0 X1EX308", 1e308),
        ("G0 X0EX400", 0.0),
        ("G0 X1EX-400", 0.0),
    ] {
        let analysis = sinumerik_lsp::analysis::analyze(line, &config);
        assert_eq!(analysis.moves[0].end[0].1, expected, "{line}");
        assert!(check(line).is_empty(), "{line}");
    }
}

#[test]
fn one_megabyte_label_is_one_label() {
    let name = "A".repeat(1024 * 1024);
    let line = format!("{name}:");
    let (block, diagnostics) = parse(&line);
    assert_eq!(block.label, Some(Span::new(0, name.len())));
    assert!(block.statements.is_empty());
    // The name is longer than 31 characters (S162) and the block longer than 512 (S163).
    assert_eq!(code_histogram(&diagnostics), vec![("S162", 1), ("S163", 1)]);
}

#[test]
fn five_megabytes_of_blanks_and_control_bytes_are_an_empty_block() {
    let blanks: String = (0u8..=0x1F)
        .chain([0x7F, b' '])
        .filter(|byte| !matches!(byte, b'\n' | b'\r'))
        .map(char::from)
        .collect();
    let line = repeat_to(&blanks, FIVE_MB);
    let (block, diagnostics) = parse(&line);
    assert!(block.statements.is_empty());
    assert_eq!(codes(&diagnostics), vec!["S163"]);
}

#[test]
fn messages_do_not_quote_megabytes_of_the_line() {
    // A message that quotes a whole 1 MB name is no help in an editor or a terminal; a long token should
    // be shortened in the message (the span still marks all of it).
    const MAX_MESSAGE_LENGTH: usize = 1_000;
    let name = "A".repeat(1024 * 1024);
    let digits = "7".repeat(1024 * 1024);
    let lines = [
        format!("{name}:"),
        format!("DEF INT {name}"),
        format!("N{digits} X1"),
        format!("G{digits}"),
        format!("R{digits}=1"),
        format!("X={digits}.{digits}.1"),
        format!("X1 Y{name}=1"),
    ];
    let mut failures = Vec::new();
    for line in &lines {
        let (_, diagnostics) = parse(line);
        for diagnostic in diagnostics {
            if diagnostic.message.len() > MAX_MESSAGE_LENGTH {
                failures.push(format!(
                    "{} for {}: a message of {} bytes",
                    diagnostic.code.as_str(),
                    abbreviate(line),
                    diagnostic.message.len()
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

// ----- 4. bytes that are not NC text ---------------------------------------------------------------

#[test]
fn control_bytes_inside_a_line_are_blanks() {
    for byte in (0u8..=0x1F).chain([0x7F]) {
        if byte == b'\n' || byte == b'\r' {
            continue;
        }
        let c = char::from(byte);
        let line = format!("G1{c}X1{c}Y2{c}Z=3{c}; note{c}end");
        let (block, diagnostics) = parse(&line);
        assert_eq!(
            codes(&diagnostics),
            Vec::<&str>::new(),
            "control byte {byte:#04x}"
        );
        assert_eq!(block.statements.len(), 4, "control byte {byte:#04x}");
        let comment_start = line.find(';').unwrap();
        assert_eq!(
            block.comment,
            Some(Span::new(comment_start, line.len())),
            "control byte {byte:#04x}"
        );
    }
}

#[test]
fn carriage_return_and_line_feed_inside_a_program_end_the_line() {
    for terminator in ["\n", "\r", "\r\n"] {
        let program = format!("X1{terminator}X");
        let diagnostics = check(&program);
        assert_eq!(diagnostics.len(), 1, "{terminator:?}");
        assert_eq!(diagnostics[0].line, 1, "{terminator:?}");
        assert_eq!(diagnostics[0].diagnostic.code, Code::MissingValue);
    }
}

#[test]
fn invalid_utf8_is_decoded_and_reported_on_character_boundaries() {
    // 0xC4 is `Ä` in Windows-1252 and two bytes in UTF-8; 0x81 becomes the C1 control U+0081.
    let bytes = b"N10 G1 X1 \xC4 Y2 \x81\n; \xFC\xE4\xDF\nZ=\xFF\n";
    let decoded = decode_source(bytes);
    assert_eq!(decoded.encoding, SourceEncoding::Windows1252);
    let diagnostics = check(&decoded.text);
    let on_line = |line: usize| -> Vec<&LineDiagnostic> {
        diagnostics
            .iter()
            .filter(|item| item.line == line)
            .collect()
    };
    let first_line = decoded.text.lines().next().unwrap();
    let unexpected: Vec<&str> = on_line(0)
        .iter()
        .filter(|item| item.diagnostic.code == Code::UnexpectedCharacter)
        .map(|item| &first_line[item.diagnostic.span.start()..item.diagnostic.span.end()])
        .collect();
    assert_eq!(unexpected, vec!["Ä", "\u{81}"]);
    assert!(on_line(1).is_empty(), "a comment may hold any character");
    let third: Vec<Code> = on_line(2).iter().map(|item| item.diagnostic.code).collect();
    assert!(
        third.contains(&Code::UnexpectedCharacter) || third.contains(&Code::ExpectedExpression),
        "`Z=ÿ` must be reported: {third:?}"
    );

    // A byte order mark makes the decoder keep UTF-8 and put U+FFFD (three bytes) for the bad byte.
    let decoded = decode_source(b"\xEF\xBB\xBFX1 \xC4 Y2\n");
    assert_eq!(decoded.encoding, SourceEncoding::Utf8Lossy);
    let diagnostics = check(&decoded.text);
    assert_eq!(diagnostics.len(), 1);
    let span = diagnostics[0].diagnostic.span;
    assert_eq!(&decoded.text[span.start()..span.end()], "\u{FFFD}");
}

#[test]
fn random_lines_of_nc_characters_parse_with_valid_spans() {
    let alphabet = b"XYZGNRACIF0123456789.=-+*/()[]\";:$_ \t'";
    let context = SyntaxContext::default();
    let mut parser = LineParser::new();
    let mut fast = (Block::default(), Vec::new());
    let mut general = (Block::default(), Vec::new());
    let mut random = XorShift(0x9E37_79B9_7F4A_7C15);
    let mut with_diagnostics = 0;
    for _ in 0..1_000 {
        let length = random.below(200);
        let line: String = (0..length)
            .map(|_| char::from(alphabet[random.below(alphabet.len())]))
            .collect();
        parser.parse(&line, &context, &mut fast.0, &mut fast.1);
        assert_block_spans_valid(&line, &fast.0);
        assert_diagnostic_spans_valid(&line, &fast.1);
        // The fast path for plain blocks must agree with the general parser on any line.
        parser.parse_without_fast_path(&line, &context, &mut general.0, &mut general.1);
        assert!(fast.0 == general.0, "blocks differ for {line:?}");
        assert_eq!(fast.1, general.1, "diagnostics differ for {line:?}");
        assert!(
            fast.1.len() <= line.len() + 1,
            "{} diagnostics for {line:?}",
            fast.1.len()
        );
        with_diagnostics += usize::from(!fast.1.is_empty());
    }
    // Random text is mostly wrong: the checker must have had something to say about most lines.
    assert!(
        with_diagnostics > 500,
        "only {with_diagnostics} lines had diagnostics"
    );
}

#[test]
fn random_bytes_decoded_as_windows_1252_check_with_valid_spans() {
    let mut random = XorShift(0x2545_F491_4F6C_DD1D);
    let mut bytes = Vec::new();
    for _ in 0..1_000 {
        let length = random.below(200);
        bytes.extend((0..length).map(|_| random.next() as u8));
        bytes.push(b'\n');
    }
    let text = decode_windows_1252(&bytes);
    assert_eq!(text.chars().count(), bytes.len());
    // Random bytes contain line ends of their own; the checker must still stay inside every line.
    let line_count = lines::line_ranges(&text).count();
    assert!(line_count >= 1_000);
    let diagnostics = check(&text);
    assert!(diagnostics.iter().all(|item| item.line < line_count));
    assert!(!diagnostics.is_empty());
    // Also through the decoder the CLI uses: random bytes are not UTF-8, so it falls back to Windows-1252.
    let decoded = decode_source(&bytes);
    assert_eq!(decoded.encoding, SourceEncoding::Windows1252);
    assert_eq!(decoded.text, text);
}

// ----- 5. line ends --------------------------------------------------------------------------------

#[test]
fn million_lines_ended_by_carriage_returns_are_numbered_correctly() {
    const LINES: usize = 1_000_000;
    let mut program = String::with_capacity(LINES * 8);
    for index in 0..LINES {
        // Every thousandth line, and the last one, lacks its value (S150).
        if index % 1_000 == 0 || index == LINES - 1 {
            program.push_str("G1 X\r");
        } else {
            program.push_str("G1 X1\r");
        }
    }
    assert_eq!(lines::line_ranges(&program).count(), LINES);
    let diagnostics = check(&program);
    let expected: Vec<usize> = (0..LINES)
        .filter(|index| index % 1_000 == 0 || *index == LINES - 1)
        .collect();
    let reported: Vec<usize> = diagnostics.iter().map(|item| item.line).collect();
    assert_eq!(reported.len(), expected.len());
    assert!(
        reported == expected,
        "the reported lines are not the expected ones"
    );
    assert!(diagnostics
        .iter()
        .all(|item| item.diagnostic.code == Code::MissingValue
            && item.diagnostic.span == Span::new(3, 4)));
}

#[test]
fn mixed_line_ends_are_numbered_like_an_editor_does() {
    // Lines: 0 `X`, 1 `Y1`, 2 `X`, 3 `Z1`, 4 empty, 5 `X`, 6 empty (LF then CR), 7 `X`.
    let program = "X\nY1\r\nX\rZ1\r\n\r\nX\n\rX";
    let diagnostics = check(program);
    let lines_with_s150: Vec<usize> = diagnostics
        .iter()
        .filter(|item| item.diagnostic.code == Code::MissingValue)
        .map(|item| item.line)
        .collect();
    assert_eq!(lines_with_s150, vec![0, 2, 5, 7]);
    assert_eq!(diagnostics.len(), 4);
    assert_eq!(lines::line_ranges(program).count(), 8);
}

// ----- junk lines: one diagnostic per token must not happen ---------------------------------------
//
// A 5 MB line of one repeated mistake has hundreds of thousands of tokens. Each test checks that the
// line gives at most MAX_DIAGNOSTICS_PER_LINE diagnostics and still names the mistake.

/// Parses `prefix` and then `chunk` repeated up to 5 MB, and checks that the diagnostics are bounded and
/// include `code`.
fn assert_junk_bounded(prefix: &str, chunk: &str, code: Code) {
    let line = prefix.to_string() + &repeat_to(chunk, FIVE_MB);
    let (_, diagnostics) = parse(&line);
    assert!(
        diagnostics.len() <= MAX_DIAGNOSTICS_PER_LINE,
        "5 MB of {chunk:?} gave {} diagnostics: {:?}",
        diagnostics.len(),
        code_histogram(&diagnostics)
    );
    assert!(count(&diagnostics, code) >= 1, "{:?}", codes(&diagnostics));
}

#[test]
fn five_megabytes_of_unexpected_characters_give_bounded_diagnostics() {
    assert_junk_bounded("", "@", Code::UnexpectedCharacter);
}

#[test]
fn five_megabytes_of_closing_parentheses_give_bounded_diagnostics() {
    assert_junk_bounded("", ")", Code::UnbalancedParentheses);
}

#[test]
fn five_megabytes_of_closing_brackets_give_bounded_diagnostics() {
    assert_junk_bounded("", "]", Code::UnbalancedBrackets);
}

#[test]
fn five_megabytes_of_operators_give_bounded_diagnostics() {
    assert_junk_bounded("", "+", Code::UnexpectedToken);
}

#[test]
fn five_megabytes_of_addresses_without_value_give_bounded_diagnostics() {
    assert_junk_bounded("", "X ", Code::MissingValue);
}

#[test]
fn five_megabytes_of_g_functions_of_one_group_give_bounded_diagnostics() {
    assert_junk_bounded("", "G17 G18 ", Code::SameGroupTwice);
}

#[test]
fn five_megabytes_of_syntax_defining_g_functions_give_bounded_diagnostics() {
    assert_junk_bounded("", "G0 G1 ", Code::SyntaxDefiningConflict);
}

#[test]
fn five_megabytes_of_dwells_with_axes_give_bounded_diagnostics() {
    assert_junk_bounded("G4 F1 ", "X1 ", Code::InstructionNotAlone);
}

#[test]
fn five_megabytes_of_words_after_a_frame_instruction_give_bounded_diagnostics() {
    assert_junk_bounded("TRANS X1 ", "M3 ", Code::InstructionNotAlone);
}

#[test]
fn five_megabytes_of_closing_parentheses_in_a_program_give_bounded_diagnostics() {
    // The whole checker, with the structure check and the severities, keeps the bound as well.
    let program = format!("X1\n{}\nY1\n", ")".repeat(FIVE_MB));
    let diagnostics = check(&program);
    assert!(diagnostics.iter().all(|item| item.line == 1));
    assert!(
        diagnostics.len() <= MAX_DIAGNOSTICS_PER_LINE,
        "{} diagnostics",
        diagnostics.len()
    );
    assert!(diagnostics
        .iter()
        .any(|item| item.diagnostic.code == Code::UnbalancedParentheses));
}

#[test]
fn five_megabytes_of_endifs_in_a_program_give_bounded_diagnostics() {
    // Each ENDIF without IF is a structure finding (S190), which the structure check adds after the
    // parser, so a bound inside the parser alone does not cover it.
    let program = format!("X1\n{}\nY1\n", "ENDIF ".repeat(FIVE_MB / 6));
    let diagnostics = check(&program);
    assert!(
        diagnostics.len() <= MAX_DIAGNOSTICS_PER_LINE,
        "{} diagnostics",
        diagnostics.len()
    );
    assert!(diagnostics
        .iter()
        .any(|item| item.diagnostic.code == Code::StructureMismatch));
}

#[test]
fn five_megabytes_of_unclosed_loops_in_a_program_give_bounded_diagnostics() {
    // Each LOOP stays open to the end of the program, where the structure check reports it (S190).
    let program = format!("X1\n{}\nY1\n", "LOOP ".repeat(FIVE_MB / 5));
    let diagnostics = check(&program);
    assert!(
        diagnostics.len() <= MAX_DIAGNOSTICS_PER_LINE,
        "{} diagnostics",
        diagnostics.len()
    );
    assert!(diagnostics
        .iter()
        .any(|item| item.line == 1 && item.diagnostic.code == Code::StructureMismatch));
}

#[test]
fn five_megabytes_of_unknown_g_functions_give_bounded_diagnostics() {
    assert_junk_bounded("", "G9999 ", Code::UnknownGCode);
}
