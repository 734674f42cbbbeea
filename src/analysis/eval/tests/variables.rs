//! Typed variables, arrays, program levels and joins (reference §8.1, §17.1, §17.6).

use super::*;

fn num(value: f64) -> Option<Value> {
    Some(Value::Number(value))
}

#[test]
fn variables_start_at_the_zero_of_their_type() {
    let mut variables = Variables::default();
    for (name, var_type) in [
        ("I", VarType::Int),
        ("R", VarType::Real),
        ("B", VarType::Bool),
        ("C", VarType::Char),
    ] {
        variables.define(name, var_type, &[]).unwrap();
        assert_eq!(variables.value(name, &[]), num(0.0), "{name}");
        assert_eq!(variables.var_type(name), Some(var_type));
    }
    variables.define("S", VarType::Text, &[]).unwrap();
    assert_eq!(variables.value("S", &[]), Some(Value::text_from("")));
    // The start value of an AXIS variable is not documented, and frames are not followed.
    variables.define("AX", VarType::Axis, &[]).unwrap();
    variables.define("FR", VarType::Frame, &[]).unwrap();
    assert_eq!(variables.value("AX", &[]), None);
    assert_eq!(variables.value("FR", &[]), None);
    assert_eq!(variables.dimensions("I"), Some(&[][..]));
    assert_eq!(variables.dimensions("NONE"), None);
}

#[test]
fn int_rounds_half_away_from_zero_and_must_fit() {
    let mut variables = Variables::default();
    variables.define("I", VarType::Int, &[]).unwrap();
    let mut assign = |value: f64| {
        let result = variables.assign("I", &[], num(value));
        (result, variables.variable("I"))
    };
    assert_eq!(assign(2.5), (Ok(()), Some(3.0)));
    assert_eq!(assign(-2.5), (Ok(()), Some(-3.0)));
    assert_eq!(assign(2.4999), (Ok(()), Some(2.0)));
    assert_eq!(assign(2147483647.0), (Ok(()), Some(2147483647.0)));
    assert_eq!(assign(-2147483648.0), (Ok(()), Some(-2147483648.0)));
    assert_eq!(
        assign(2147483647.5),
        (Err(AssignError::ValueOutOfRange(VarType::Int)), None)
    );
    assert_eq!(
        assign(3e9),
        (Err(AssignError::ValueOutOfRange(VarType::Int)), None)
    );
    // set_variable converts the same way.
    variables.set_variable("I", Some(-0.5));
    assert_eq!(variables.variable("I"), Some(-1.0));
}

#[test]
fn bool_char_real_and_text_conversions() {
    let mut variables = Variables::default();
    variables.define("B", VarType::Bool, &[]).unwrap();
    variables.define("C", VarType::Char, &[]).unwrap();
    variables.define("R", VarType::Real, &[]).unwrap();
    variables.define("S", VarType::Text, &[]).unwrap();
    variables.define("AX", VarType::Axis, &[]).unwrap();
    variables.define("FR", VarType::Frame, &[]).unwrap();
    variables.assign("B", &[], num(5.0)).unwrap();
    assert_eq!(variables.variable("B"), Some(1.0));
    variables.assign("B", &[], num(0.0)).unwrap();
    assert_eq!(variables.variable("B"), Some(0.0));
    variables.assign("C", &[], num(65.0)).unwrap();
    assert_eq!(variables.variable("C"), Some(65.0));
    assert_eq!(
        variables.assign("C", &[], num(300.0)),
        Err(AssignError::ValueOutOfRange(VarType::Char))
    );
    assert_eq!(variables.variable("C"), None);
    variables.assign("R", &[], num(2.5)).unwrap();
    assert_eq!(variables.variable("R"), Some(2.5));
    // A text in a number, a number in a text: the conversion is not followed.
    variables
        .assign("R", &[], Some(Value::text_from("1")))
        .unwrap();
    assert_eq!(variables.variable("R"), None);
    variables.assign("S", &[], num(1.0)).unwrap();
    assert_eq!(variables.value("S", &[]), None);
    variables
        .assign("S", &[], Some(Value::text_from("AB")))
        .unwrap();
    assert_eq!(variables.value("S", &[]), Some(Value::text_from("AB")));
    variables
        .assign("AX", &[], Some(Value::text_from("X")))
        .unwrap();
    assert_eq!(variables.value("AX", &[]), Some(Value::text_from("X")));
    variables.assign("FR", &[], num(1.0)).unwrap();
    assert_eq!(variables.value("FR", &[]), None);
}

#[test]
fn names_without_definition_hold_what_is_written() {
    let mut variables = Variables::default();
    variables.set_variable("GUD1", Some(2.5));
    assert_eq!(variables.variable("GUD1"), Some(2.5));
    variables
        .assign("GUD2", &[], Some(Value::text_from("T")))
        .unwrap();
    assert_eq!(variables.value("GUD2", &[]), Some(Value::text_from("T")));
    assert_eq!(variables.var_type("GUD1"), None);
    assert_eq!(
        variables.assign("GUD3", &[1], num(1.0)),
        Err(AssignError::NotDefined)
    );
    // A later definition takes over a name only assigned so far.
    variables.define("GUD1", VarType::Int, &[]).unwrap();
    assert_eq!(variables.variable("GUD1"), Some(0.0));
    assert_eq!(
        variables.define("GUD1", VarType::Int, &[]),
        Err(DefineError::AlreadyDefined)
    );
}

#[test]
fn definitions_are_checked() {
    let mut variables = Variables::default();
    assert_eq!(
        variables.define("A", VarType::Real, &[2, 2, 2, 2]),
        Err(DefineError::TooManyDimensions)
    );
    assert_eq!(
        variables.define("A", VarType::Real, &[2, 0]),
        Err(DefineError::EmptyDimension)
    );
    assert_eq!(variables.dimensions("A"), None);
    variables.define("A", VarType::Real, &[2, 3, 4]).unwrap();
    assert_eq!(variables.dimensions("A"), Some(&[2, 3, 4][..]));
}

#[test]
fn one_dimensional_arrays() {
    let mut variables = Variables::default();
    variables.define("A", VarType::Int, &[3]).unwrap();
    assert_eq!(variables.value("A", &[2]), num(0.0));
    variables.assign("A", &[2], num(4.6)).unwrap();
    assert_eq!(variables.value("A", &[2]), num(5.0));
    assert_eq!(variables.value("A", &[1]), num(0.0));
    assert_eq!(
        variables.assign("A", &[3], num(1.0)),
        Err(AssignError::Index(IndexError::OutOfRange {
            dimension: 0,
            index: 3,
            size: 3
        }))
    );
    assert_eq!(variables.value("A", &[3]), None);
    assert_eq!(
        variables.read("A", &[3]),
        Err(IndexError::OutOfRange {
            dimension: 0,
            index: 3,
            size: 3
        })
    );
    // The whole array has no single value.
    assert_eq!(variables.value("A", &[]), None);
    assert_eq!(variables.variable("A"), None);
    assert_eq!(
        variables.assign("A", &[], num(1.0)),
        Err(AssignError::Index(IndexError::Count { expected: 1 }))
    );
}

#[test]
fn two_and_three_dimensional_arrays_are_row_major() {
    let mut variables = Variables::default();
    variables.define("T", VarType::Real, &[2, 3]).unwrap();
    variables.assign("T", &[1, 2], num(7.0)).unwrap();
    variables.assign("T", &[0, 1], num(3.0)).unwrap();
    assert_eq!(variables.value("T", &[1, 2]), num(7.0));
    assert_eq!(variables.value("T", &[0, 1]), num(3.0));
    assert_eq!(variables.value("T", &[0, 2]), num(0.0));
    assert_eq!(variables.value("T", &[1, 1]), num(0.0));
    assert_eq!(
        variables.assign("T", &[2, 0], num(1.0)),
        Err(AssignError::Index(IndexError::OutOfRange {
            dimension: 0,
            index: 2,
            size: 2
        }))
    );
    assert_eq!(
        variables.assign("T", &[0, 3], num(1.0)),
        Err(AssignError::Index(IndexError::OutOfRange {
            dimension: 1,
            index: 3,
            size: 3
        }))
    );
    variables.define("C", VarType::Real, &[2, 3, 4]).unwrap();
    variables.assign("C", &[1, 2, 3], num(9.0)).unwrap();
    variables.assign("C", &[0, 0, 1], num(1.0)).unwrap();
    assert_eq!(variables.value("C", &[1, 2, 3]), num(9.0));
    assert_eq!(variables.value("C", &[0, 0, 1]), num(1.0));
    for other in [[1, 2, 2], [0, 2, 3], [1, 1, 3], [0, 1, 0]] {
        assert_eq!(variables.value("C", &other), num(0.0), "{other:?}");
    }
    assert_eq!(
        variables.assign("C", &[1, 3, 0], num(1.0)),
        Err(AssignError::Index(IndexError::OutOfRange {
            dimension: 1,
            index: 3,
            size: 3
        }))
    );
    assert_eq!(
        variables.assign("C", &[1, 2], num(1.0)),
        Err(AssignError::Index(IndexError::Count { expected: 3 }))
    );
}

#[test]
fn text_arrays_start_empty() {
    let mut variables = Variables::default();
    variables.define("S", VarType::Text, &[2]).unwrap();
    assert_eq!(variables.value("S", &[1]), Some(Value::text_from("")));
    variables
        .assign("S", &[1], Some(Value::text_from("AB")))
        .unwrap();
    assert_eq!(variables.value("S", &[1]), Some(Value::text_from("AB")));
    variables.assign("S", &[1], num(1.0)).unwrap();
    assert_eq!(variables.value("S", &[1]), None);
    variables.define("AXES", VarType::Axis, &[3]).unwrap();
    assert_eq!(variables.value("AXES", &[0]), None);
    variables
        .assign("AXES", &[0], Some(Value::text_from("X")))
        .unwrap();
    assert_eq!(variables.value("AXES", &[0]), Some(Value::text_from("X")));
    assert_eq!(variables.value("AXES", &[1]), None);
}

#[test]
fn large_arrays_keep_their_shape_but_not_their_values() {
    let mut variables = Variables::default();
    let size = MAX_FOLLOWED_ELEMENTS + 1;
    variables.define("BIG", VarType::Real, &[size]).unwrap();
    assert_eq!(variables.value("BIG", &[0]), None);
    variables.assign("BIG", &[5], num(1.0)).unwrap();
    assert_eq!(variables.value("BIG", &[5]), None);
    assert!(matches!(
        variables.assign("BIG", &[size], num(1.0)),
        Err(AssignError::Index(IndexError::OutOfRange { .. }))
    ));
    // A size whose element count overflows is not followed either, and its indexes still checked.
    variables
        .define("HUGE", VarType::Real, &[usize::MAX, 2])
        .unwrap();
    assert_eq!(variables.value("HUGE", &[7, 1]), None);
    assert!(matches!(
        variables.read("HUGE", &[0, 2]),
        Err(IndexError::OutOfRange { .. })
    ));
    // Frames are never followed.
    variables.define("F", VarType::Frame, &[2]).unwrap();
    variables.assign("F", &[0], num(1.0)).unwrap();
    assert_eq!(variables.value("F", &[0]), None);
}

#[test]
fn a_copy_is_independent_of_writes_to_the_original() {
    let mut variables = Variables::default();
    variables.define("A", VarType::Real, &[3]).unwrap();
    let copy = variables.clone();
    assert_eq!(copy, variables);
    variables.assign("A", &[1], num(2.0)).unwrap();
    assert_eq!(copy.value("A", &[1]), num(0.0));
    assert_eq!(variables.value("A", &[1]), num(2.0));
    assert_ne!(copy, variables);
    // The same values in another form are equal: all unknown by forgetting, or element by element.
    let mut forgotten = variables.clone();
    forgotten.forget_variable("A");
    let mut written = variables.clone();
    for index in 0..3 {
        written.assign("A", &[index], None).unwrap();
    }
    assert_eq!(forgotten, written);
}

#[test]
fn forgetting_keeps_definitions() {
    let mut variables = Variables::default();
    variables.set_r_parameter(1, Some(1.0));
    variables.define("I", VarType::Int, &[]).unwrap();
    variables.define("A", VarType::Int, &[2]).unwrap();
    variables.set_variable("G", Some(3.0));
    variables.forget_variable("I");
    assert_eq!(variables.variable("I"), None);
    assert_eq!(variables.value("A", &[0]), num(0.0));
    variables.forget_all();
    assert_eq!(variables.r_parameter(1), None);
    assert_eq!(variables.variable("G"), None);
    assert_eq!(variables.value("A", &[0]), None);
    assert_eq!(variables.var_type("I"), Some(VarType::Int));
    // The definitions still convert and check.
    variables.assign("I", &[], num(1.5)).unwrap();
    assert_eq!(variables.variable("I"), Some(2.0));
    variables.assign("A", &[1], num(4.0)).unwrap();
    assert_eq!(variables.value("A", &[1]), num(4.0));
    assert_eq!(variables.value("A", &[0]), None);
    assert!(variables.assign("A", &[2], num(4.0)).is_err());
    variables.set_r_parameter(2, Some(2.0));
    variables.forget_r_parameters();
    assert_eq!(variables.r_parameter(2), None);
}

#[test]
fn join_keeps_only_what_both_ways_agree_on() {
    let mut first = Variables::default();
    first.define("A", VarType::Real, &[3]).unwrap();
    first.define("S", VarType::Text, &[]).unwrap();
    first.define("CLEARED", VarType::Int, &[]).unwrap();
    let mut second = first.clone();
    first.set_r_parameter(1, Some(1.0));
    second.set_r_parameter(1, Some(1.0));
    first.set_r_parameter(2, Some(2.0));
    second.set_r_parameter(2, Some(3.0));
    first.set_r_parameter(3, Some(3.0));
    second.set_variable("CLEARED", None);
    first.assign("A", &[0], num(5.0)).unwrap();
    second.assign("A", &[0], num(5.0)).unwrap();
    first.assign("A", &[1], num(6.0)).unwrap();
    second.assign("A", &[1], num(7.0)).unwrap();
    second
        .assign("S", &[], Some(Value::text_from("X")))
        .unwrap();
    second.define("ONLY_SECOND", VarType::Int, &[]).unwrap();
    first.join(&second);
    assert_eq!(first.r_parameter(1), Some(1.0));
    assert_eq!(first.r_parameter(2), None);
    assert_eq!(first.r_parameter(3), None);
    assert_eq!(first.value("A", &[0]), num(5.0));
    assert_eq!(first.value("A", &[1]), None);
    assert_eq!(first.value("A", &[2]), num(0.0));
    assert_eq!(first.value("S", &[]), None);
    assert_eq!(first.variable("CLEARED"), None);
    assert_eq!(first.var_type("ONLY_SECOND"), Some(VarType::Int));
    assert_eq!(first.variable("ONLY_SECOND"), None);
    // Joining with an equal state changes nothing.
    let before = first.clone();
    first.join(&before);
    assert_eq!(first, before);
}

#[test]
fn join_forgets_variables_of_different_shapes() {
    let mut first = Variables::default();
    let mut second = Variables::default();
    first.define("A", VarType::Real, &[2]).unwrap();
    second.define("A", VarType::Real, &[3]).unwrap();
    first.define("B", VarType::Real, &[]).unwrap();
    second.define("B", VarType::Int, &[]).unwrap();
    first.join(&second);
    assert_eq!(first.value("A", &[0]), None);
    assert_eq!(first.dimensions("A"), Some(&[2][..]));
    assert_eq!(first.variable("B"), None);
}

#[test]
fn a_subprogram_level_has_its_own_variables() {
    let mut variables = Variables::default();
    variables.define("A", VarType::Int, &[]).unwrap();
    variables.assign("A", &[], num(5.0)).unwrap();
    variables.define("B", VarType::Int, &[]).unwrap();
    variables.assign("B", &[], num(6.0)).unwrap();
    variables.set_variable("GLOBAL", Some(1.0));
    variables.set_r_parameter(1, Some(2.0));
    let locals = variables.take_locals();
    assert!(!locals.is_empty());
    // The callee sees R parameters and global names, not the caller's variables.
    assert_eq!(variables.variable("A"), None);
    assert_eq!(variables.var_type("A"), None);
    assert_eq!(variables.variable("GLOBAL"), Some(1.0));
    assert_eq!(variables.r_parameter(1), Some(2.0));
    // The callee defines its own A and writes globals.
    variables.define("A", VarType::Real, &[]).unwrap();
    variables.assign("A", &[], num(7.5)).unwrap();
    variables.set_r_parameter(1, Some(3.0));
    variables.set_variable("GLOBAL", Some(4.0));
    // It writes B without defining it: with program-global user data that is the caller's B.
    variables.set_variable("B", Some(9.0));
    variables.restore_locals(locals);
    assert_eq!(variables.variable("A"), Some(5.0));
    assert_eq!(variables.var_type("A"), Some(VarType::Int));
    assert_eq!(variables.variable("B"), None);
    assert_eq!(variables.var_type("B"), Some(VarType::Int));
    assert_eq!(variables.r_parameter(1), Some(3.0));
    assert_eq!(variables.variable("GLOBAL"), Some(4.0));
}
