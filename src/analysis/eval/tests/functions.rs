//! The predefined functions (reference §8.2), angles in degrees.

use super::*;

#[test]
fn trigonometry_in_degrees() {
    assert_near("SIN(30)", 0.5);
    assert_near("COS(60)", 0.5);
    assert_near("TAN(45)", 1.0);
    assert_near("ASIN(0.5)", 30.0);
    assert_near("ACOS(0.5)", 60.0);
    assert_near("ATAN2(1,1)", 45.0);
    assert_near("ATAN2(0,-1)", 180.0);
    assert_near("ATAN2(-1,0)", -90.0);
    assert_eq!(number("ATAN2(0,0)"), None);
    assert_eq!(number("TAN(90)"), None);
    assert_eq!(number("TAN(-270)"), None);
    assert_near("TAN(180)", 0.0);
}

#[test]
fn arguments_outside_the_domain_are_errors() {
    assert_eq!(
        error("SQRT(-1)"),
        EvalError::Domain(Span::new(3, 11), "SQRT of a negative number")
    );
    assert!(matches!(error("ACOS(2)"), EvalError::Domain(_, _)));
    assert!(matches!(error("ASIN(-1.5)"), EvalError::Domain(_, _)));
    assert!(matches!(error("LN(0)"), EvalError::Domain(_, _)));
    assert!(matches!(error("LN(-1)"), EvalError::Domain(_, _)));
    assert_eq!(number("SQRT(UNKNOWNVAR)"), None);
    assert_eq!(number("ACOS(1)"), Some(0.0));
}

#[test]
fn roots_powers_and_logarithms() {
    assert_eq!(number("SQRT(16)"), Some(4.0));
    assert_eq!(number("SQRT(0)"), Some(0.0));
    assert_eq!(number("POT(3)"), Some(9.0));
    assert_eq!(number("POT(-3)"), Some(9.0));
    assert_near("LN(EXP(2))", 2.0);
    assert_eq!(number("EXP(0)"), Some(1.0));
    assert!(matches!(error("EXP(1000)"), EvalError::Overflow(_)));
    assert!(matches!(error("POT(1EX200)"), EvalError::Overflow(_)));
}

#[test]
fn a_wrong_number_of_arguments_is_an_error_of_the_call() {
    assert_eq!(
        error("POT(2,3)"),
        EvalError::ArgumentCount(Span::new(3, 11), 1)
    );
    assert_eq!(error("SIN()"), EvalError::ArgumentCount(Span::new(3, 8), 1));
    assert!(matches!(error("ATAN2(1)"), EvalError::ArgumentCount(_, 2)));
    assert!(matches!(
        error("BOUND(1,2)"),
        EvalError::ArgumentCount(_, 3)
    ));
    assert!(matches!(
        error("SUBSTR(\"ABC\")"),
        EvalError::ArgumentCount(_, 2)
    ));
    assert!(matches!(
        error("SUBSTR(\"ABC\",1,1,1)"),
        EvalError::ArgumentCount(_, 3)
    ));
    // Even with unknown arguments the count is wrong.
    assert!(matches!(
        error("POT(UNKNOWNVAR,1)"),
        EvalError::ArgumentCount(_, 1)
    ));
}

#[test]
fn errors_in_arguments_are_found() {
    assert!(matches!(error("SIN(1/0)"), EvalError::DivisionByZero(_)));
    assert!(matches!(error("ABS(SQRT(-4))"), EvalError::Domain(_, _)));
}

#[test]
fn rounding() {
    assert_eq!(number("ABS(-2.5)"), Some(2.5));
    assert_eq!(number("TRUNC(-2.7)"), Some(-2.0));
    assert_eq!(number("TRUNC(2.7)"), Some(2.0));
    assert_eq!(number("ROUND(2.5)"), Some(3.0));
    assert_eq!(number("ROUND(-2.5)"), Some(-3.0));
    assert_eq!(number("ROUND(2.4999)"), Some(2.0));
    assert_eq!(number("ROUNDUP(3.1)"), Some(4.0));
    assert_eq!(number("ROUNDUP(3.6)"), Some(4.0));
    assert_eq!(number("ROUNDUP(-3.1)"), Some(-3.0));
    assert_eq!(number("ROUNDUP(-3.6)"), Some(-3.0));
    assert_eq!(number("ROUNDUP(3)"), Some(3.0));
}

#[test]
fn bounds_and_extremes() {
    assert_eq!(number("BOUND(0,10,15)"), Some(10.0));
    assert_eq!(number("BOUND(0,10,-1)"), Some(0.0));
    assert_eq!(number("BOUND(0,10,5)"), Some(5.0));
    assert_eq!(number("BOUND(10,0,5)"), None);
    assert_eq!(number("MINVAL(3,-2)"), Some(-2.0));
    assert_eq!(number("MAXVAL(3,-2)"), Some(3.0));
    assert_eq!(number("MINVAL(3,UNKNOWNVAR)"), None);
}

#[test]
fn type_conversions() {
    assert_eq!(number("ITOR(3)"), Some(3.0));
    assert_eq!(number("RTOI(2.5)"), Some(3.0));
    assert_eq!(number("RTOI(-2.5)"), Some(-3.0));
    assert_eq!(number("RTOI(2.49)"), Some(2.0));
    assert_eq!(number("RTOI(3EX9)"), None);
}

#[test]
fn string_functions() {
    assert_eq!(number("STRLEN(\"ABC\")"), Some(3.0));
    assert_eq!(number("STRLEN(\"\")"), Some(0.0));
    assert_eq!(number("STRLEN(5)"), None);
    assert_eq!(text("SUBSTR(\"ACK: 10 TO 99\",5,2)").as_deref(), Some("10"));
    assert_eq!(text("SUBSTR(\"ABCDE\",2)").as_deref(), Some("CDE"));
    assert_eq!(text("SUBSTR(\"ABCDE\",0,0)").as_deref(), Some(""));
    assert_eq!(text("SUBSTR(\"ABC\",2,5)"), None);
    assert_eq!(text("SUBSTR(\"ABC\",4)"), None);
    assert_eq!(text("SUBSTR(\"ABC\",-1,1)"), None);
    assert_eq!(number("INDEX(\"ABCABC\",\"B\")"), Some(1.0));
    assert_eq!(number("RINDEX(\"ABCABC\",\"B\")"), Some(4.0));
    assert_eq!(number("INDEX(\"ABC\",\"Z\")"), Some(-1.0));
    assert_eq!(number("INDEX(\"ABC\",67)"), Some(2.0));
    assert_eq!(number("INDEX(\"ABC\",\"BC\")"), None);
    assert_eq!(number("MINDEX(\"ABCDE\",\"DC\")"), Some(2.0));
    assert_eq!(number("MINDEX(\"ABCDE\",\"XY\")"), Some(-1.0));
    assert_eq!(number("MATCH(\"ABCDE\",\"CD\")"), Some(2.0));
    assert_eq!(number("MATCH(\"ABC\",\"X\")"), Some(-1.0));
    assert_eq!(text("TOUPPER(\"abC1\")").as_deref(), Some("ABC1"));
    assert_eq!(text("TOLOWER(\"AbC\")").as_deref(), Some("abc"));
    assert_eq!(text("TOUPPER(\"ä\")"), None);
}

#[test]
fn texts_read_as_numbers() {
    assert_eq!(number("NUMBER(\"12.5\")"), Some(12.5));
    assert_eq!(number("NUMBER(\"-1.5EX2\")"), Some(-150.0));
    assert_eq!(number("NUMBER(\"ABC\")"), None);
    assert_eq!(number("ISNUMBER(\"12.5\")"), Some(1.0));
    assert_eq!(number("ISNUMBER(\"ABC\")"), Some(0.0));
    assert_eq!(number("ISNUMBER(\" 1\")"), None);
    assert_eq!(number("NUMBER(\"1\" << 2)+1"), Some(13.0));
}

#[test]
fn functions_not_computed_are_unknown() {
    assert_eq!(number("AXNAME(\"X\")"), None);
    assert_eq!(number("ISVAR(\"R1\")"), None);
    assert!(!is_evaluated_function("AXNAME"));
    assert!(!is_evaluated_function("sin"));
    assert!(is_evaluated_function("SIN"));
    assert!(is_evaluated_function("SUBSTR"));
    assert_eq!(function_arguments("SUBSTR"), Some((2, 3)));
    assert_eq!(function_arguments("CTRANS"), None);
}
