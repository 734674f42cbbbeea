//! Reads of R parameters and user variables, indexed or not (reference §8.1).

use super::*;

#[test]
fn r_parameters_by_number_index_and_system_variable() {
    let mut variables = Variables::default();
    variables.set_r_parameter(2, Some(5.0));
    variables.set_r_parameter(1, Some(1.0));
    assert_eq!(number_in("R2", &variables), Some(5.0));
    assert_eq!(number_in("R[2]", &variables), Some(5.0));
    assert_eq!(number_in("R[R1+1]", &variables), Some(5.0));
    assert_eq!(number_in("$R2", &variables), Some(5.0));
    assert_eq!(number_in("$R[2]", &variables), Some(5.0));
    assert_eq!(number_in("$R[1+1]*2", &variables), Some(10.0));
    assert_eq!(number_in("R[3]", &variables), None);
    assert_eq!(
        eval_in("R[-1]", &variables),
        Err(EvalError::IndexOutOfRange(Span::new(3, 8)))
    );
    assert!(matches!(
        eval_in("$R[R1-2]", &variables),
        Err(EvalError::IndexOutOfRange(_))
    ));
    assert_eq!(number_in("R[1.5]", &variables), None);
    assert_eq!(number_in("R[R9]", &variables), None);
    assert!(matches!(
        eval_in("R[1/0]", &variables),
        Err(EvalError::DivisionByZero(_))
    ));
}

fn arrays() -> Variables {
    let mut variables = Variables::default();
    variables.define("LIST", VarType::Real, &[4]).unwrap();
    variables.define("TABLE", VarType::Int, &[2, 3]).unwrap();
    variables.define("CUBE", VarType::Real, &[2, 3, 4]).unwrap();
    variables.define("NAME", VarType::Text, &[]).unwrap();
    variables
        .assign("LIST", &[3], Some(Value::Number(2.5)))
        .unwrap();
    variables
        .assign("TABLE", &[1, 2], Some(Value::Number(7.0)))
        .unwrap();
    variables
        .assign("CUBE", &[1, 2, 3], Some(Value::Number(9.0)))
        .unwrap();
    variables
        .assign("NAME", &[], Some(Value::text_from("PART")))
        .unwrap();
    variables.set_r_parameter(1, Some(1.0));
    variables
}

#[test]
fn array_elements_by_index_from_zero() {
    let variables = arrays();
    assert_eq!(number_in("LIST[3]", &variables), Some(2.5));
    assert_eq!(number_in("LIST[0]", &variables), Some(0.0));
    assert_eq!(number_in("list[R1+2]*2", &variables), Some(5.0));
    assert_eq!(number_in("TABLE[1,2]", &variables), Some(7.0));
    assert_eq!(number_in("TABLE[0,2]", &variables), Some(0.0));
    assert_eq!(number_in("CUBE[1,2,3]", &variables), Some(9.0));
    assert_eq!(number_in("CUBE[1,2,2]", &variables), Some(0.0));
    // An unknown index, a fractional one or the wrong count: unknown.
    assert_eq!(number_in("LIST[R9]", &variables), None);
    assert_eq!(number_in("LIST[0.5]", &variables), None);
    assert_eq!(number_in("TABLE[1]", &variables), None);
    // A scalar or an undefined name with indexes.
    assert_eq!(number_in("OTHER[1]", &variables), None);
}

#[test]
fn a_known_index_outside_the_array_is_an_error() {
    let variables = arrays();
    let out_of_range = |expression: &str| {
        assert_eq!(
            eval_in(expression, &variables),
            Err(EvalError::IndexOutOfRange(Span::new(
                3,
                3 + expression.find(']').unwrap() + 1
            ))),
            "{expression}"
        );
    };
    out_of_range("LIST[4]");
    out_of_range("LIST[-1]");
    out_of_range("TABLE[2,0]");
    out_of_range("TABLE[0,3]");
    out_of_range("CUBE[0,0,4]");
    // Known to be outside even while another index is unknown.
    out_of_range("TABLE[R9,3]");
}

#[test]
fn texts_of_variables() {
    let variables = arrays();
    assert_eq!(
        eval_in("NAME << \"_\" << 2", &variables),
        Ok(Some(Value::text_from("PART_2")))
    );
    assert_eq!(
        eval_in("NAME==\"PART\"", &variables),
        Ok(Some(Value::Number(1.0)))
    );
}
