//! Tests of what the parser keeps of section repetition (`REPEAT`, `REPEATB`) and of the branches of
//! `CASE` for running a program. Broken forms must give the findings they gave before the parser kept
//! these parts, which the tests spell out.

use crate::config::MachineConfig;
use crate::diagnostics::{Code, Diagnostic, Span};
use crate::syntax::ast::*;
use crate::syntax::context::SyntaxContext;
use crate::syntax::parser::findings::MAX_DIAGNOSTICS_PER_LINE;
use crate::syntax::parser::line_parser::parse_line;

fn parse(line: &str) -> (Block, Vec<Diagnostic>) {
    parse_line(line, &SyntaxContext::new(&MachineConfig::mill()))
}

fn text(line: &str, span: Span) -> &str {
    &line[span.start()..span.end()]
}

/// Each finding as its code and the text it marks.
fn findings<'a>(line: &'a str, diagnostics: &[Diagnostic]) -> Vec<(Code, &'a str)> {
    diagnostics
        .iter()
        .map(|diagnostic| (diagnostic.code, text(line, diagnostic.span)))
        .collect()
}

/// A section repetition as texts: start, end, whether the end is ENDLABEL, count and whole statement.
type SectionRepeatTexts<'a> = (&'a str, Option<&'a str>, bool, Option<&'a str>, &'a str);

fn section_repeat<'a>(
    line: &'a str,
    block: &Block,
    statement: &Statement,
) -> SectionRepeatTexts<'a> {
    let Statement::SectionRepeat {
        start,
        end,
        end_is_endlabel,
        count,
        span,
    } = statement
    else {
        panic!("{line}: expected a section repetition, got {statement:?}");
    };
    (
        text(line, *start),
        end.map(|end| text(line, end)),
        *end_is_endlabel,
        count.map(|count| text(line, block.expr(count).span)),
        text(line, *span),
    )
}

#[test]
fn section_repetitions_keep_their_labels_and_count() {
    let cases: &[(&str, SectionRepeatTexts)] = &[
        (
            "REPEAT LAB1 P=3",
            ("LAB1", None, false, Some("3"), "REPEAT LAB1 P=3"),
        ),
        (
            "REPEAT LAB1 LAB2 P=2",
            (
                "LAB1",
                Some("LAB2"),
                false,
                Some("2"),
                "REPEAT LAB1 LAB2 P=2",
            ),
        ),
        (
            "REPEAT LAB1 ENDLABEL P=2",
            (
                "LAB1",
                Some("ENDLABEL"),
                true,
                Some("2"),
                "REPEAT LAB1 ENDLABEL P=2",
            ),
        ),
        (
            "repeat lab1 endlabel p = 2",
            (
                "lab1",
                Some("endlabel"),
                true,
                Some("2"),
                "repeat lab1 endlabel p = 2",
            ),
        ),
        ("REPEAT LAB1", ("LAB1", None, false, None, "REPEAT LAB1")),
        (
            "REPEAT LAB1 P=R1+1",
            ("LAB1", None, false, Some("R1+1"), "REPEAT LAB1 P=R1+1"),
        ),
        (
            "REPEAT LAB1 LAB2 LAB3 P=2",
            (
                "LAB1",
                Some("LAB2"),
                false,
                Some("2"),
                "REPEAT LAB1 LAB2 LAB3 P=2",
            ),
        ),
        (
            "REPEAT LAB1 P3",
            ("LAB1", None, false, Some("3"), "REPEAT LAB1 P3"),
        ),
    ];
    for (line, expected) in cases {
        let (block, diagnostics) = parse(line);
        assert!(diagnostics.is_empty(), "{line}: {diagnostics:?}");
        let [statement] = block.statements.as_slice() else {
            panic!("{line}: {:?}", block.statements);
        };
        assert_eq!(section_repeat(line, &block, statement), *expected, "{line}");
    }
    // A count written without `=` is a number of the arena like any other.
    let (block, _) = parse("REPEAT LAB1 P3");
    let Statement::SectionRepeat {
        count: Some(count), ..
    } = block.statements[0]
    else {
        panic!("{:?}", block.statements)
    };
    assert_eq!(block.expr(count).kind, ExprKind::Number(3.0));
}

#[test]
fn a_block_repetition_keeps_its_label_and_count() {
    let cases: &[(&str, Option<&str>, Option<&str>, &str)] = &[
        (
            "REPEATB LAB1 P=2",
            Some("LAB1"),
            Some("2"),
            "REPEATB LAB1 P=2",
        ),
        ("REPEATB LAB1", Some("LAB1"), None, "REPEATB LAB1"),
        ("REPEATB P=2", None, Some("2"), "REPEATB P=2"),
        ("REPEATB", None, None, "REPEATB"),
    ];
    for (line, label, count, whole) in cases {
        let (block, diagnostics) = parse(line);
        assert!(diagnostics.is_empty(), "{line}: {diagnostics:?}");
        let [Statement::BlockRepeat {
            label: found_label,
            count: found_count,
            span,
        }] = block.statements.as_slice()
        else {
            panic!("{line}: {:?}", block.statements);
        };
        assert_eq!(found_label.map(|span| text(line, span)), *label, "{line}");
        assert_eq!(
            found_count.map(|id| text(line, block.expr(id).span)),
            *count,
            "{line}"
        );
        assert_eq!(text(line, *span), *whole, "{line}");
    }
    // Only one label: a second name is a call of its own, and the `P` after it belongs to that call.
    let line = "REPEATB LBL1 LBL2 P=2";
    let (block, _) = parse(line);
    assert!(
        matches!(
            block.statements.as_slice(),
            [
                Statement::BlockRepeat { count: None, .. },
                Statement::Call { .. },
                Statement::Address(_)
            ]
        ),
        "{:?}",
        block.statements
    );
}

#[test]
fn repeat_without_a_label_is_the_loop() {
    let (block, diagnostics) = parse("REPEAT");
    assert!(diagnostics.is_empty());
    assert!(matches!(
        block.statements.as_slice(),
        [Statement::Structure {
            keyword: StructureKeyword::Repeat,
            ..
        }]
    ));
    // `P=2` after the loop keyword is an address word of its own, as it always was.
    let (block, diagnostics) = parse("REPEAT P=2");
    assert!(diagnostics.is_empty());
    assert!(
        matches!(
            block.statements.as_slice(),
            [
                Statement::Structure {
                    keyword: StructureKeyword::Repeat,
                    ..
                },
                Statement::Address(AddressWord {
                    kind: AddressKind::Repetitions,
                    ..
                })
            ]
        ),
        "{:?}",
        block.statements
    );
}

#[test]
fn broken_repetitions_give_the_findings_they_always_gave() {
    let cases: &[(&str, &[(Code, &str)])] = &[
        ("REPEAT LBL1 P=", &[(Code::MissingValue, "P=")]),
        ("REPEAT LBL1 P=2 P=3", &[(Code::AddressTwice, "P=3")]),
        (
            "REPEAT LBL1 P=(1+",
            &[
                (Code::ExpectedExpression, ""),
                (Code::UnbalancedParentheses, "("),
            ],
        ),
        (
            "TRANS X10 REPEAT LBL1 P=2",
            &[
                (Code::InstructionNotAlone, "REPEAT LBL1"),
                (Code::InstructionNotAlone, "P=2"),
            ],
        ),
        (
            "TRANS X10 REPEATB LBL1 P=2",
            &[
                (Code::InstructionNotAlone, "REPEATB LBL1"),
                (Code::InstructionNotAlone, "P=2"),
            ],
        ),
        (
            "REPEAT LBL1 P=AC(2)",
            &[(Code::ModifierNotAllowed, "AC(2)")],
        ),
    ];
    for (line, expected) in cases {
        let (_, diagnostics) = parse(line);
        assert_eq!(findings(line, &diagnostics), *expected, "{line}");
    }
    let line = "REPEAT LBL1 P=2 P=3";
    let (block, diagnostics) = parse(line);
    assert!(
        diagnostics[0].message.contains("(`P=2`;"),
        "{}",
        diagnostics[0].message
    );
    assert_eq!(
        section_repeat(line, &block, &block.statements[0]).3,
        Some("2")
    );
    assert!(matches!(block.statements[1], Statement::Address(_)));

    let line = "REPEAT LBL1 P=";
    let (block, _) = parse(line);
    assert_eq!(
        section_repeat(line, &block, &block.statements[0]),
        ("LBL1", None, false, None, "REPEAT LBL1 P=")
    );
    // A `P` with a modifier is not a count: it stays the address word it was.
    let line = "REPEAT LBL1 P=AC(2)";
    let (block, _) = parse(line);
    assert_eq!(
        section_repeat(line, &block, &block.statements[0]),
        ("LBL1", None, false, None, "REPEAT LBL1")
    );
    assert!(matches!(block.statements[1], Statement::Address(_)));
}

#[test]
fn a_repetition_ends_before_the_comment() {
    let line = "N20 REPEAT LBL1 P=3 ; three more times";
    let (block, diagnostics) = parse(line);
    assert!(diagnostics.is_empty());
    assert_eq!(
        section_repeat(line, &block, &block.statements[0]).4,
        "REPEAT LBL1 P=3"
    );
}

#[test]
fn each_case_branch_stands_before_its_jump() {
    for line in [
        "CASE R1 OF 1 GOTOF LAB1 2 GOTOF LAB2 DEFAULT GOTOF LAB3",
        "CASE (R1) OF 1 GOTOF LAB1 2 GOTOF LAB2 DEFAULT GOTOF LAB3",
    ] {
        let (block, diagnostics) = parse(line);
        assert!(diagnostics.is_empty(), "{line}: {diagnostics:?}");
        let mut described = Vec::new();
        for statement in &block.statements {
            described.push(match statement {
                Statement::Structure {
                    keyword: StructureKeyword::Case,
                    condition: Some(condition),
                    ..
                } => format!("case {}", text(line, block.expr(*condition).span)),
                Statement::CaseBranch { value, span } => format!(
                    "branch {} at {}",
                    value.map_or("DEFAULT", |value| text(line, block.expr(value).span)),
                    text(line, *span)
                ),
                Statement::Jump {
                    target: JumpTarget::Label(label),
                    ..
                } => format!("jump {}", text(line, *label)),
                other => panic!("{line}: {other:?}"),
            });
        }
        let condition = if line.contains("(R1)") { "(R1)" } else { "R1" };
        assert_eq!(
            described,
            [
                format!("case {condition}"),
                "branch 1 at 1".to_string(),
                "jump LAB1".to_string(),
                "branch 2 at 2".to_string(),
                "jump LAB2".to_string(),
                "branch DEFAULT at DEFAULT".to_string(),
                "jump LAB3".to_string(),
            ],
            "{line}"
        );
    }
    let line = "CASE R1 OF -1 GOTOB LAB1 1+1 GOTOF N400";
    let (block, _) = parse(line);
    let values: Vec<&str> = block
        .statements
        .iter()
        .filter_map(|statement| match statement {
            Statement::CaseBranch {
                value: Some(value), ..
            } => Some(text(line, block.expr(*value).span)),
            _ => None,
        })
        .collect();
    assert_eq!(values, ["-1", "1+1"]);
}

#[test]
fn broken_case_blocks_give_the_findings_they_always_gave() {
    let cases: &[(&str, &[(Code, &str)])] = &[
        ("CASE R1 OF 1 GOTOF LBL3 2", &[]),
        ("CASE R1 OF", &[]),
        ("CASE", &[(Code::ExpectedExpression, "CASE")]),
        (
            "CASE R1 OF 1 LBL3 2 GOTOF LBL4",
            &[(Code::UnexpectedToken, "LBL3")],
        ),
        ("CASE R1 OF 1 GOTOF", &[(Code::ExpectedExpression, "GOTOF")]),
        (
            "TRANS X10 CASE R1 OF 1 GOTOF LBL3",
            &[
                (Code::InstructionNotAlone, "CASE R1"),
                (Code::InstructionNotAlone, "GOTOF LBL3"),
            ],
        ),
    ];
    for (line, expected) in cases {
        let (_, diagnostics) = parse(line);
        assert_eq!(findings(line, &diagnostics), *expected, "{line}");
    }
    // A value without a jump is no branch.
    let (block, _) = parse("CASE R1 OF 1 LBL3 2 GOTOF LBL4");
    let branches = block
        .statements
        .iter()
        .filter(|statement| matches!(statement, Statement::CaseBranch { .. }))
        .count();
    assert_eq!(branches, 1);
    let (block, _) = parse("CASE R1 OF 1 GOTOF LBL3 2");
    assert!(matches!(
        block.statements.as_slice(),
        [
            Statement::Structure { .. },
            Statement::CaseBranch { .. },
            Statement::Jump { .. }
        ]
    ));
}

#[test]
fn hostile_repetitions_and_case_blocks_stay_bounded() {
    let many_labels = format!("REPEAT {} P=2", "LBL ".repeat(20_000));
    let many_branches = format!("CASE R1 OF {}", "1 GOTOF L1 ".repeat(20_000));
    let many_counts = format!("REPEATB LBL {}", "P=2 ".repeat(20_000));
    for line in [many_labels, many_branches, many_counts] {
        let (block, diagnostics) = parse(&line);
        assert!(diagnostics.len() <= MAX_DIAGNOSTICS_PER_LINE);
        assert!(!block.statements.is_empty());
    }
}

#[test]
fn a_conditional_jump_keeps_its_condition() {
    let line = "IF R1<3 GOTOB LOOP1";
    let (block, diagnostics) = parse_line(line, &SyntaxContext::default());
    assert!(diagnostics.is_empty(), "{diagnostics:?}");
    let [Statement::Jump {
        kind: JumpKind::Gotob,
        condition: Some(condition),
        ..
    }] = block.statements.as_slice()
    else {
        panic!("expected one conditional jump, got {:?}", block.statements);
    };
    let span = block.expr(*condition).span;
    assert_eq!(&line[span.start()..span.end()], "R1<3");
    let (block, _) = parse_line("GOTOF END", &SyntaxContext::default());
    assert!(matches!(
        block.statements.as_slice(),
        [Statement::Jump {
            condition: None,
            ..
        }]
    ));
}
