//! Assignments through the engine, with variables defined beforehand (the definitions themselves are
//! the business of the DEF statement).

use crate::analysis::engine::engine_state::Engine;
use crate::analysis::eval::{Value, VarType, Variables};
use crate::config::MachineConfig;
use crate::diagnostics::{Code, Diagnostic, Severity};
use crate::syntax::{parse_line, SyntaxContext};

struct Run {
    variables: Variables,
    /// The X position after the last block.
    x: Option<f64>,
    findings: Vec<(usize, Diagnostic)>,
}

impl Run {
    fn codes(&self) -> Vec<(usize, &'static str)> {
        self.findings
            .iter()
            .map(|(line, finding)| (*line, finding.code.as_str()))
            .collect()
    }

    fn message(&self, code: Code) -> &str {
        self.findings
            .iter()
            .find(|(_, finding)| finding.code == code)
            .map(|(_, finding)| finding.message.as_str())
            .unwrap_or_else(|| panic!("no {code} among {:?}", self.findings))
    }
}

/// Runs `lines` on the mill after `setup` has defined variables.
fn run(setup: impl FnOnce(&mut Variables), lines: &[&str]) -> Run {
    let config = MachineConfig::mill();
    let context = SyntaxContext::new(&config);
    let mut engine = Engine::new(&config);
    setup(&mut engine.state.variables);
    let mut findings = Vec::new();
    for (index, line) in lines.iter().enumerate() {
        let (block, syntax) = parse_line(line, &context);
        assert!(
            syntax
                .iter()
                .all(|finding| finding.severity != Severity::Error),
            "`{line}`: {syntax:?}"
        );
        let mut semantic = Vec::new();
        engine.step(line, &block, &mut semantic);
        findings.extend(semantic.into_iter().map(|finding| (index, finding)));
    }
    let x = config
        .axes
        .iter()
        .position(|axis| axis.name == "X")
        .and_then(|index| engine.state.positions[index]);
    Run {
        variables: engine.state.variables.clone(),
        x,
        findings,
    }
}

fn arrays(variables: &mut Variables) {
    variables.define("LIST", VarType::Real, &[3]).unwrap();
    variables.define("TABLE", VarType::Int, &[2, 3]).unwrap();
    variables.define("CUBE", VarType::Real, &[2, 2, 2]).unwrap();
    variables.define("COUNT", VarType::Int, &[]).unwrap();
    variables.define("TEXT", VarType::Text, &[]).unwrap();
    variables.define("AXVAR", VarType::Axis, &[]).unwrap();
}

fn number(value: f64) -> Option<Value> {
    Some(Value::Number(value))
}

#[test]
fn r_parameters_by_computed_number() {
    let run = run(|_| {}, &["R1=2", "R[R1+1]=5", "$R[4]=6", "$R5=7", "r[0]=1"]);
    assert_eq!(run.variables.r_parameter(3), Some(5.0));
    assert_eq!(run.variables.r_parameter(4), Some(6.0));
    assert_eq!(run.variables.r_parameter(5), Some(7.0));
    assert_eq!(run.variables.r_parameter(0), Some(1.0));
    assert!(run.findings.is_empty(), "{:?}", run.findings);
}

#[test]
fn an_unknown_r_number_may_have_written_any_parameter() {
    let run = run(|_| {}, &["R1=1 R2=2", "R[R9]=3"]);
    assert_eq!(run.variables.r_parameter(1), None);
    assert_eq!(run.variables.r_parameter(2), None);
    let run = self::run(|_| {}, &["R1=1 R2=2", "R[1.5]=3"]);
    assert_eq!(run.variables.r_parameter(1), None);
}

#[test]
fn a_negative_r_number_is_out_of_range() {
    let run = run(|_| {}, &["R1=1", "R[-1]=3", "$R[R1-2]=4"]);
    assert_eq!(run.codes(), vec![(1, "A227"), (2, "A227")]);
    assert_eq!(run.variables.r_parameter(1), Some(1.0));
    assert!(run.message(Code::IndexOutOfRange).contains("not -1"));
    // A huge number keeps the message short.
    let run = self::run(|_| {}, &["R[-1EX300]=1"]);
    assert_eq!(
        run.message(Code::IndexOutOfRange),
        "R parameters are numbered from 0, not -1e300 (alarm 17020)"
    );
}

#[test]
fn array_elements_are_written_and_read() {
    let run = run(
        arrays,
        &[
            "LIST[1]=2.5",
            "TABLE[1,2]=3.6",
            "CUBE[1,0,1]=0.5",
            "G0 X=LIST[1]+TABLE[1,2]+CUBE[1,0,1]",
        ],
    );
    assert!(run.findings.is_empty(), "{:?}", run.findings);
    assert_eq!(run.variables.value("LIST", &[1]), number(2.5));
    assert_eq!(run.variables.value("TABLE", &[1, 2]), number(4.0));
    assert_eq!(run.variables.value("TABLE", &[0, 2]), number(0.0));
    assert_eq!(run.variables.value("CUBE", &[1, 0, 1]), number(0.5));
    assert_eq!(run.x, Some(7.0));
}

#[test]
fn an_index_out_of_bounds_is_reported_and_writes_nothing() {
    let run = run(arrays, &["LIST[3]=1", "TABLE[0,3]=1", "LIST[-1]=1"]);
    assert_eq!(run.codes(), vec![(0, "A227"), (1, "A227"), (2, "A227")]);
    let messages: Vec<&str> = run
        .findings
        .iter()
        .map(|(_, finding)| finding.message.as_str())
        .collect();
    assert_eq!(
        messages[0],
        "index 3 is out of range: `LIST` has 3 elements, 0 to 2 (alarm 17020)"
    );
    assert_eq!(
        messages[1],
        "index 3 is out of range: dimension 2 of `TABLE` has 3 elements, 0 to 2 (alarm 17020)"
    );
    assert!(messages[2].contains("not -1"), "{}", messages[2]);
    assert_eq!(run.findings[0].1.span.start(), 0);
    assert_eq!(run.findings[0].1.span.end(), "LIST[3]".len());
    for index in 0..3 {
        assert_eq!(run.variables.value("LIST", &[index]), number(0.0));
    }
}

#[test]
fn reading_outside_an_array_is_reported() {
    let run = run(arrays, &["G0 X=LIST[5]"]);
    assert_eq!(run.codes(), vec![(0, "A227")]);
    assert_eq!(
        run.message(Code::IndexOutOfRange),
        "`LIST[5]`: the index is out of range (alarm 17020)"
    );
    assert_eq!(run.x, None);
}

#[test]
fn an_unknown_index_makes_the_whole_array_unknown() {
    let run = run(arrays, &["LIST[0]=1", "LIST[R9]=2"]);
    assert_eq!(run.variables.value("LIST", &[0]), None);
    assert_eq!(run.variables.value("LIST", &[2]), None);
    assert_eq!(run.variables.dimensions("LIST"), Some(&[3][..]));
}

#[test]
fn after_a_label_the_written_element_is_unknown_and_the_others_stay() {
    let run = run(arrays, &["LIST[0]=1", "BACK: LIST[1]=2"]);
    assert_eq!(run.variables.value("LIST", &[0]), number(1.0));
    assert_eq!(run.variables.value("LIST", &[1]), None);
    assert_eq!(run.variables.value("LIST", &[2]), number(0.0));
}

#[test]
fn typed_variables_convert_what_is_assigned() {
    let run = run(
        arrays,
        &["COUNT=2.5", "TEXT=\"N\" << COUNT", "AXVAR=Y", "R1=COUNT"],
    );
    assert_eq!(run.variables.variable("COUNT"), Some(3.0));
    assert_eq!(
        run.variables.value("TEXT", &[]),
        Some(Value::text_from("N3"))
    );
    assert_eq!(
        run.variables.value("AXVAR", &[]),
        Some(Value::text_from("Y"))
    );
    assert_eq!(run.variables.r_parameter(1), Some(3.0));
    // A name that is not a configured axis is not known to be one.
    let run = self::run(arrays, &["AXVAR=Y", "AXVAR=NOAXIS"]);
    assert_eq!(run.variables.value("AXVAR", &[]), None);
}

#[test]
fn evaluation_errors_are_reported_with_their_codes() {
    let run = run(
        |_| {},
        &[
            "R1=SQRT(-1)",
            "R1=POT(2,3)",
            "G0 X=1EX308*10",
            "R1=1/0",
            "R1=SUBSTR(\"A\")",
        ],
    );
    assert_eq!(
        run.codes(),
        vec![
            (0, "A225"),
            (1, "A226"),
            (2, "A225"),
            (3, "A205"),
            (4, "A226")
        ]
    );
    let messages: Vec<&str> = run
        .findings
        .iter()
        .map(|(_, finding)| finding.message.as_str())
        .collect();
    assert_eq!(messages[0], "SQRT of a negative number (alarm 14051)");
    assert_eq!(messages[1], "POT takes 1 argument (alarm 14020)");
    assert!(messages[2].starts_with("arithmetic overflow"));
    assert_eq!(messages[4], "SUBSTR takes 2 or 3 arguments (alarm 14020)");
    assert_eq!(run.variables.r_parameter(1), None);
    assert_eq!(run.x, None);
}

#[test]
fn errors_in_indexes_are_reported() {
    let run = run(arrays, &["LIST[1/0]=1", "R[SQRT(-1)]=1"]);
    assert_eq!(run.codes(), vec![(0, "A205"), (1, "A225")]);
    assert_eq!(run.variables.value("LIST", &[0]), None);
}
