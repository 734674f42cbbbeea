//! Tests of what the parser keeps of declarations for running a program: the declarators of `DEF`
//! and the parameters of `PROC`. Broken forms must give the findings they gave before the parser kept
//! these parts, which the tests spell out.

use crate::config::MachineConfig;
use crate::diagnostics::{Code, Diagnostic, Span};
use crate::syntax::ast::*;
use crate::syntax::context::SyntaxContext;
use crate::syntax::parser::expressions::MAX_EXPRESSION_DEPTH;
use crate::syntax::parser::line_parser::parse_line;

fn parse(line: &str) -> (Block, Vec<Diagnostic>) {
    parse_line(line, &SyntaxContext::new(&MachineConfig::mill()))
}

fn text(line: &str, span: Span) -> &str {
    &line[span.start()..span.end()]
}

fn expr_text<'a>(line: &'a str, block: &Block, id: ExprId) -> &'a str {
    text(line, block.expr(id).span)
}

/// Each finding as its code and the text it marks.
fn findings<'a>(line: &'a str, diagnostics: &[Diagnostic]) -> Vec<(Code, &'a str)> {
    diagnostics
        .iter()
        .map(|diagnostic| (diagnostic.code, text(line, diagnostic.span)))
        .collect()
}

/// The only statement of a line that must parse without findings.
fn only_statement(line: &str) -> (Block, Statement) {
    let (block, diagnostics) = parse(line);
    assert!(diagnostics.is_empty(), "{line}: {diagnostics:?}");
    let [statement] = block.statements.as_slice() else {
        panic!("{line}: expected one statement, got {:?}", block.statements);
    };
    let statement = statement.clone();
    (block, statement)
}

/// The type and declarators of the `DEF` of a line.
fn definition(block: &Block) -> (Option<DataType>, &[Span], &[Declarator]) {
    match block.statements.last() {
        Some(Statement::Definition {
            data_type,
            names,
            declarators,
            ..
        }) => (*data_type, names, declarators),
        other => panic!("expected a definition, got {other:?}"),
    }
}

fn texts<'a>(line: &'a str, block: &Block, ids: &[ExprId]) -> Vec<&'a str> {
    ids.iter().map(|id| expr_text(line, block, *id)).collect()
}

fn optional_texts<'a>(line: &'a str, block: &Block, ids: &[Option<ExprId>]) -> Vec<&'a str> {
    ids.iter()
        .map(|id| id.map_or("", |id| expr_text(line, block, id)))
        .collect()
}

#[test]
fn a_definition_keeps_its_type_names_and_initial_values() {
    let line = "DEF REAL DEPTH=2.5";
    let (block, _) = only_statement(line);
    let (data_type, names, declarators) = definition(&block);
    assert_eq!(data_type, Some(DataType::Real));
    assert_eq!(names.len(), 1);
    let [declarator] = declarators else {
        panic!("{declarators:?}")
    };
    assert_eq!(declarator.name, names[0]);
    assert_eq!(text(line, declarator.name), "DEPTH");
    assert!(declarator.dimensions.is_empty());
    let Some(Initializer::Value(value)) = declarator.initial else {
        panic!("{declarator:?}")
    };
    assert_eq!(block.expr(value).kind, ExprKind::Number(2.5));

    let line = "DEF INT AA=1, BB=2, CC";
    let (block, _) = only_statement(line);
    let (data_type, _, declarators) = definition(&block);
    assert_eq!(data_type, Some(DataType::Int));
    let described: Vec<(&str, Option<&str>)> = declarators
        .iter()
        .map(|declarator| {
            let value = match declarator.initial {
                Some(Initializer::Value(id)) => Some(expr_text(line, &block, id)),
                None => None,
                ref other => panic!("{other:?}"),
            };
            (text(line, declarator.name), value)
        })
        .collect();
    assert_eq!(
        described,
        [("AA", Some("1")), ("BB", Some("2")), ("CC", None)]
    );
}

#[test]
fn every_type_name_is_kept() {
    for (line, expected) in [
        ("DEF INT AA", DataType::Int),
        ("DEF REAL AA", DataType::Real),
        ("DEF BOOL AA=TRUE", DataType::Bool),
        ("DEF CHAR AA", DataType::Char),
        ("DEF STRING[20] AA", DataType::String),
        ("DEF AXIS AA", DataType::Axis),
        ("DEF FRAME AA", DataType::Frame),
        ("def real aa=1.5", DataType::Real),
        ("DEF NCK REAL AA", DataType::Real),
        (
            "DEF CHAN SYNR APR 7 APW 7 LLI 0 ULI 10 INT AA=5",
            DataType::Int,
        ),
    ] {
        let (block, _) = only_statement(line);
        let (data_type, names, declarators) = definition(&block);
        assert_eq!(data_type, Some(expected), "{line}");
        assert_eq!(names.len(), 1, "{line}");
        assert_eq!(declarators.len(), 1, "{line}");
        assert!(
            text(line, declarators[0].name).eq_ignore_ascii_case("AA"),
            "{line}"
        );
    }
}

#[test]
fn arrays_keep_their_sizes_and_initial_lists() {
    let line = "DEF REAL TAB[3]=(1,2,3)";
    let (block, _) = only_statement(line);
    let declarator = &definition(&block).2[0];
    assert_eq!(texts(line, &block, &declarator.dimensions), ["3"]);
    let Some(Initializer::List(items)) = &declarator.initial else {
        panic!("{declarator:?}")
    };
    assert_eq!(optional_texts(line, &block, items), ["1", "2", "3"]);

    let line = "DEF INT MM[2,2]=SET(1,2,3,4)";
    let (block, _) = only_statement(line);
    let declarator = &definition(&block).2[0];
    assert_eq!(texts(line, &block, &declarator.dimensions), ["2", "2"]);
    let Some(Initializer::Set(items)) = &declarator.initial else {
        panic!("{declarator:?}")
    };
    assert_eq!(optional_texts(line, &block, items), ["1", "2", "3", "4"]);

    let line = "DEF REAL VV[10]=REP(0)";
    let (block, _) = only_statement(line);
    let declarator = &definition(&block).2[0];
    let Some(Initializer::Repeat { value, count: None }) = declarator.initial else {
        panic!("{declarator:?}")
    };
    assert_eq!(expr_text(line, &block, value), "0");

    let line = "DEF REAL WW[10]=REP(1.5, 4)";
    let (block, _) = only_statement(line);
    let declarator = &definition(&block).2[0];
    let Some(Initializer::Repeat {
        value,
        count: Some(count),
    }) = declarator.initial
    else {
        panic!("{declarator:?}")
    };
    assert_eq!(expr_text(line, &block, value), "1.5");
    assert_eq!(expr_text(line, &block, count), "4");

    let line = "DEF REAL CUBE[2,3,R1+1], LIST[3]=(1,,3)";
    let (block, _) = only_statement(line);
    let declarators = definition(&block).2;
    assert_eq!(
        texts(line, &block, &declarators[0].dimensions),
        ["2", "3", "R1+1"]
    );
    assert_eq!(declarators[0].initial, None);
    let Some(Initializer::List(items)) = &declarators[1].initial else {
        panic!("{declarators:?}")
    };
    assert_eq!(optional_texts(line, &block, items), ["1", "", "3"]);

    // Blanks anywhere, as the formatter may leave them.
    let line = "DEF REAL BB = 3 , CC [ 2 ] = ( 4 , 5 )";
    let (block, _) = only_statement(line);
    let declarators = definition(&block).2;
    assert_eq!(text(line, declarators[1].name), "CC");
    assert_eq!(texts(line, &block, &declarators[1].dimensions), ["2"]);
    let Some(Initializer::List(items)) = &declarators[1].initial else {
        panic!("{declarators:?}")
    };
    assert_eq!(optional_texts(line, &block, items), ["4", "5"]);
}

#[test]
fn a_scalar_takes_a_bracketed_value_as_an_expression() {
    let line = "DEF REAL SUM=(1+2)*3";
    let (block, _) = only_statement(line);
    let Some(Initializer::Value(value)) = definition(&block).2[0].initial else {
        panic!("{:?}", block.statements)
    };
    assert_eq!(expr_text(line, &block, value), "(1+2)*3");
    assert!(matches!(
        block.expr(value).kind,
        ExprKind::Binary(BinaryOp::Multiply, _, _)
    ));
}

#[test]
fn strings_axes_and_frames_are_expressions_of_the_block() {
    let line = "DEF STRING[20] TXT=\"ABC\"";
    let (block, _) = only_statement(line);
    let (data_type, _, declarators) = definition(&block);
    assert_eq!(data_type, Some(DataType::String));
    assert_eq!(text(line, declarators[0].name), "TXT");
    let Some(Initializer::Value(value)) = declarators[0].initial else {
        panic!("{declarators:?}")
    };
    assert_eq!(block.expr(value).kind, ExprKind::String);
    assert_eq!(expr_text(line, &block, value), "\"ABC\"");

    let line = "DEF AXIS AX1=X";
    let (block, _) = only_statement(line);
    let Some(Initializer::Value(value)) = definition(&block).2[0].initial else {
        panic!("{:?}", block.statements)
    };
    assert!(matches!(block.expr(value).kind, ExprKind::Name { .. }));
    assert_eq!(expr_text(line, &block, value), "X");

    let line = "DEF FRAME FR1=CTRANS(X,10,Y,20)";
    let (block, _) = only_statement(line);
    let Some(Initializer::Value(value)) = definition(&block).2[0].initial else {
        panic!("{:?}", block.statements)
    };
    let ExprKind::Call { name, args } = &block.expr(value).kind else {
        panic!("{:?}", block.expr(value))
    };
    assert_eq!(text(line, *name), "CTRANS");
    assert_eq!(args.len(), 4);
}

#[test]
fn a_name_written_with_digits_after_its_letter_is_one_declarator() {
    let line = "DEF REAL V1AR=2";
    let (block, diagnostics) = parse(line);
    assert_eq!(findings(line, &diagnostics), [(Code::LabelStyle, "V1AR")]);
    let (_, names, declarators) = definition(&block);
    // `names` keeps the span it always had; the declarator has the whole name.
    assert_eq!(text(line, names[0]), "V");
    assert_eq!(text(line, declarators[0].name), "V1AR");
    let Some(Initializer::Value(value)) = declarators[0].initial else {
        panic!("{declarators:?}")
    };
    assert_eq!(expr_text(line, &block, value), "2");
}

#[test]
fn broken_definitions_give_the_findings_they_always_gave() {
    let cases: &[(&str, &[(Code, &str)])] = &[
        (
            "DEF REAL A[",
            &[(Code::InvalidLabel, "A"), (Code::UnbalancedBrackets, "DEF")],
        ),
        ("DEF REAL BAD=", &[]),
        ("DEF REAL BAD=(1,2", &[(Code::UnbalancedBrackets, "DEF")]),
        ("DEF INT BAD[2]=SET(", &[(Code::UnbalancedBrackets, "DEF")]),
        ("DEF INT BAD=REP(", &[(Code::UnbalancedBrackets, "DEF")]),
        ("DEF INT BAD=REP()", &[]),
        ("DEF REAL TAB[3]=(1,2,3))", &[]),
        ("DEF REAL CC=SIN(30", &[(Code::UnbalancedBrackets, "DEF")]),
        ("DEF INT AA=1, BB=", &[]),
        ("DEF INT AA=1,", &[]),
        ("DEF REAL", &[(Code::ExpectedExpression, "DEF")]),
        ("DEF", &[(Code::ExpectedExpression, "DEF")]),
    ];
    for (line, expected) in cases {
        let (block, diagnostics) = parse(line);
        assert_eq!(findings(line, &diagnostics), *expected, "{line}");
        let (_, names, declarators) = definition(&block);
        assert_eq!(names.len(), declarators.len(), "{line}");
    }

    let (block, _) = parse("DEF REAL A[");
    let declarator = &definition(&block).2[0];
    assert!(declarator.dimensions.is_empty() && declarator.initial.is_none());
    for line in ["DEF REAL BAD=", "DEF INT BAD=REP(", "DEF INT BAD=REP()"] {
        let (block, _) = parse(line);
        assert_eq!(definition(&block).2[0].initial, None, "{line}");
    }
    let (block, _) = parse("DEF INT BAD[2]=SET(");
    assert_eq!(
        definition(&block).2[0].initial,
        Some(Initializer::Set(Vec::new()))
    );
    let (block, _) = parse("DEF REAL");
    assert_eq!(definition(&block).0, Some(DataType::Real));
    let (block, _) = parse("DEF");
    assert_eq!(definition(&block).0, None);
}

#[test]
fn an_initial_value_is_read_with_the_depth_limit() {
    // Deeper than the limit, and short enough for a block (S163 would be reported otherwise).
    let depth = MAX_EXPRESSION_DEPTH as usize + 72;
    let line = format!("DEF REAL DEEP={}1{}", "(".repeat(depth), ")".repeat(depth));
    let (block, diagnostics) = parse(&line);
    // The definition's own reading finds nothing wrong; the expression parser's S170 is not repeated.
    assert!(diagnostics.is_empty(), "{diagnostics:?}");
    assert!(matches!(
        definition(&block).2[0].initial,
        Some(Initializer::Value(_))
    ));
    assert!(block.exprs.iter().any(|expr| expr.kind == ExprKind::Error));
    assert!(block.exprs.len() <= MAX_EXPRESSION_DEPTH as usize + 2);
}

/// The parameters of the `PROC` of a line, its parameter names and whether it has SAVE.
fn procedure(block: &Block) -> (&[Span], &[ProcParameter], bool) {
    match block.statements.last() {
        Some(Statement::ProcedureHeader {
            parameters,
            params,
            save,
            ..
        }) => (parameters, params, *save),
        other => panic!("expected a PROC header, got {other:?}"),
    }
}

/// A parameter as texts: name, type, `VAR`, dimensions and default.
type ParamTexts<'a> = (&'a str, Option<DataType>, bool, usize, Option<&'a str>);

#[test]
fn a_procedure_header_keeps_its_parameters() {
    let line = "PROC SUBX(REAL PA=5, INT PB, VAR REAL PC, VAR REAL ARR[], VAR INT AR2[,], STRING[10] PS=\"A\", AXIS PAX) SAVE DISPLOF";
    let (block, _) = only_statement(line);
    let (parameters, params, save) = procedure(&block);
    assert!(save);
    let described: Vec<ParamTexts> = params
        .iter()
        .map(|param| {
            (
                text(line, param.name),
                param.data_type,
                param.by_reference,
                param.dimensions,
                param.default.map(|id| expr_text(line, &block, id)),
            )
        })
        .collect();
    assert_eq!(
        described,
        [
            ("PA", Some(DataType::Real), false, 0, Some("5")),
            ("PB", Some(DataType::Int), false, 0, None),
            ("PC", Some(DataType::Real), true, 0, None),
            ("ARR", Some(DataType::Real), true, 1, None),
            ("AR2", Some(DataType::Int), true, 2, None),
            ("PS", Some(DataType::String), false, 0, Some("\"A\"")),
            ("PAX", Some(DataType::Axis), false, 0, None),
        ]
    );
    let names: Vec<Span> = params.iter().map(|param| param.name).collect();
    assert_eq!(parameters, names.as_slice());
}

#[test]
fn save_is_read_after_the_parameter_list_or_the_name() {
    for (line, expected) in [
        ("PROC SUBA SAVE", true),
        ("PROC CYCLE801(REAL A) SAVE DISPLOF", true),
        ("PROC CYCLE82 (REAL RTP) DISPLOF SAVE", true),
        ("proc sube(real x1=-1, var frame ff) save", true),
        ("PROC SUBB(REAL A) DISPLOF", false),
        ("PROC SUBC", false),
        ("PROC SAVER(REAL SAVE)", false),
    ] {
        let (block, _) = only_statement(line);
        assert_eq!(procedure(&block).2, expected, "{line}");
    }
    let line = "proc sube(real x1=-1, var frame ff) save";
    let (block, _) = only_statement(line);
    let (parameters, params, _) = procedure(&block);
    assert_eq!(params.len(), 2);
    // A name of a letter and digits lexes in pieces: the parameter has it whole, while the names the
    // editor features read leave it out, as they always did.
    assert_eq!(text(line, params[0].name), "x1");
    assert_eq!(parameters.len(), 1);
    assert_eq!(
        params[0].default.map(|id| expr_text(line, &block, id)),
        Some("-1")
    );
    assert_eq!(
        (params[1].data_type, params[1].by_reference),
        (Some(DataType::Frame), true)
    );
    let (block, _) = only_statement("PROC SUB(VAR REAL T3[,,], REAL T[3])");
    let dimensions: Vec<usize> = procedure(&block)
        .1
        .iter()
        .map(|param| param.dimensions)
        .collect();
    assert_eq!(dimensions, [3, 1]);
}

#[test]
fn broken_procedure_headers_give_the_findings_they_always_gave() {
    let cases: &[(&str, &[(Code, &str)])] = &[
        (
            "PROC SUBB(REAL A=, INT B[2, VAR) SAVE SBLOF",
            &[(Code::UnbalancedParentheses, "(")],
        ),
        ("PROC SUBC(", &[(Code::UnbalancedParentheses, "(")]),
        ("PROC", &[(Code::ExpectedExpression, "PROC")]),
        (
            "PROC SUB(REAL PA=(1+2",
            &[(Code::UnbalancedParentheses, "(")],
        ),
        (
            "PROC SUB(REAL PA=SIN(1)",
            &[(Code::UnbalancedParentheses, "(")],
        ),
        ("PROC SUB(REAL A, INT, , REAL)", &[]),
    ];
    for (line, expected) in cases {
        let (_, diagnostics) = parse(line);
        assert_eq!(findings(line, &diagnostics), *expected, "{line}");
    }
    let line = "PROC SUBB(REAL A=, INT B[2, VAR) SAVE SBLOF";
    let (block, _) = parse(line);
    let (_, params, save) = procedure(&block);
    // The unclosed list runs to the end of the line, attributes included.
    assert!(!save);
    assert_eq!(text(line, params[0].name), "A");
    assert_eq!(params[0].default, None);
    let line = "PROC SUB(REAL PA=SIN(1)";
    let (block, _) = parse(line);
    let params = procedure(&block).1;
    assert_eq!(
        params[0].default.map(|id| expr_text(line, &block, id)),
        Some("SIN(1)")
    );
    let line = "PROC SUB(REAL A, INT, , REAL)";
    let (block, _) = parse(line);
    let names: Vec<&str> = procedure(&block)
        .1
        .iter()
        .map(|param| text(line, param.name))
        .collect();
    assert_eq!(names, ["A"]);
    let (block, _) = parse("PROC");
    assert!(procedure(&block).1.is_empty());
}
