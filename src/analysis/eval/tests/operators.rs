//! Operators and their precedence (reference §8.2), comparisons (§18.1), strings (§8.5).

use super::*;

#[test]
fn arithmetic_follows_the_parsed_precedence() {
    assert_eq!(number("2+3*4"), Some(14.0));
    assert_eq!(number("(2+3)*4"), Some(20.0));
    assert_eq!(number("10-4-3"), Some(3.0));
    assert_eq!(number("2*3/4"), Some(1.5));
    assert_eq!(number("-2*3"), Some(-6.0));
    assert_eq!(number("+2-3"), Some(-1.0));
    assert_eq!(number("7/2"), Some(3.5));
}

#[test]
fn div_truncates_and_mod_keeps_the_sign_of_the_dividend() {
    assert_eq!(number("7 DIV 2"), Some(3.0));
    assert_eq!(number("-7 DIV 2"), Some(-3.0));
    assert_eq!(number("7.5 DIV 2"), Some(3.0));
    assert_eq!(number("9 DIV 3"), Some(3.0));
    assert_eq!(number("7 MOD 4"), Some(3.0));
    assert_eq!(number("-7 MOD 4"), Some(-3.0));
    assert_eq!(number("8 MOD 4"), Some(0.0));
    assert_eq!(number("2+7 MOD 4"), Some(5.0));
}

#[test]
fn division_by_zero_is_an_error_with_the_operation_s_span() {
    assert_eq!(error("1/0"), EvalError::DivisionByZero(Span::new(3, 6)));
    assert!(matches!(error("7 DIV 0"), EvalError::DivisionByZero(_)));
    assert!(matches!(error("7 MOD 0"), EvalError::DivisionByZero(_)));
    assert!(matches!(error("1/(2-2)"), EvalError::DivisionByZero(_)));
    // An unknown divisor is unknown, not an error.
    assert_eq!(number("1/UNKNOWNVAR"), None);
}

#[test]
fn a_result_beyond_a_double_is_an_overflow() {
    assert_eq!(error("1EX308*10"), EvalError::Overflow(Span::new(3, 12)));
    assert!(matches!(error("-1EX308-1EX308"), EvalError::Overflow(_)));
    assert!(matches!(error("1EX308/1EX-10"), EvalError::Overflow(_)));
    assert_eq!(number("1EX308*0.5"), Some(0.5e308));
}

#[test]
fn unknown_values_stay_unknown() {
    assert_eq!(number("R1+1"), None);
    assert_eq!(number("$AA_IW[X]"), None);
    assert_eq!(number("UNKNOWNVAR*0"), None);
    assert_eq!(number("-UNKNOWNVAR"), None);
}

#[test]
fn equality_uses_the_relative_tolerance_of_the_control() {
    // T137: 0.1+0.2 is 0.30000000000000004 in IEEE, equal to 0.3 on the control.
    assert_eq!(number("0.1+0.2==0.3"), Some(1.0));
    assert_eq!(number("0.1+0.2<>0.3"), Some(0.0));
    assert_eq!(number("1==1.000001"), Some(0.0));
    // The tolerance is relative: against exactly 0 the comparison stays exact.
    let mut variables = Variables::default();
    let r6 = number("0.1+0.2-0.3").expect("known");
    assert!(r6 != 0.0);
    variables.set_r_parameter(6, Some(r6));
    assert_eq!(number_in("R6==0", &variables), Some(0.0));
    assert_eq!(number_in("R6<>0", &variables), Some(1.0));
    assert_eq!(number_in("R6>0", &variables), Some(1.0));
}

#[test]
fn less_and_greater_follow_md10280() {
    let mut variables = Variables::default();
    // Ten additions of 0.1, as the WHILE of T137 makes them.
    let sum = (0..10).fold(0.0, |sum: f64, _| sum + 0.1);
    assert!(sum < 1.0);
    variables.set_r_parameter(1, Some(sum));
    let tolerant = EvalOptions::default();
    let exact = EvalOptions {
        exact_less_greater: true,
    };
    let compare = |expression: &str, options: &EvalOptions| {
        eval_with(expression, &variables, options)
            .unwrap()
            .and_then(|value| value.number())
    };
    assert_eq!(compare("R1<1", &tolerant), Some(0.0));
    assert_eq!(compare("R1<1", &exact), Some(1.0));
    assert_eq!(compare("1>R1", &tolerant), Some(0.0));
    assert_eq!(compare("1>R1", &exact), Some(1.0));
    // `<=`, `>=`, `==` and `<>` keep the tolerance under both settings.
    for options in [&tolerant, &exact] {
        assert_eq!(compare("1<=R1", options), Some(1.0));
        assert_eq!(compare("R1>=1", options), Some(1.0));
        assert_eq!(compare("R1==1", options), Some(1.0));
        assert_eq!(compare("R1<>1", options), Some(0.0));
    }
    assert_eq!(number("1<2"), Some(1.0));
    assert_eq!(number("2<1"), Some(0.0));
    assert_eq!(number("2>1"), Some(1.0));
    assert_eq!(number("1>=2"), Some(0.0));
    assert_eq!(number("2<=1"), Some(0.0));
}

#[test]
fn comparisons_bind_weakest() {
    assert_eq!(number("1+1==2"), Some(1.0));
    assert_eq!(number("2==1+1"), Some(1.0));
}

#[test]
fn logical_operators_and_their_precedence() {
    assert_eq!(number("1 AND 0"), Some(0.0));
    assert_eq!(number("1 AND 2"), Some(1.0));
    assert_eq!(number("1 OR 0"), Some(1.0));
    assert_eq!(number("0 OR 0"), Some(0.0));
    assert_eq!(number("1 XOR 1"), Some(0.0));
    assert_eq!(number("1 XOR 0"), Some(1.0));
    assert_eq!(number("NOT 0"), Some(1.0));
    assert_eq!(number("NOT 5"), Some(0.0));
    // AND binds tighter than OR, NOT tighter than both.
    assert_eq!(number("1 OR 0 AND 0"), Some(1.0));
    assert_eq!(number("NOT 1 OR 1"), Some(1.0));
    assert_eq!(number("1 XOR 1 OR 1"), Some(1.0));
    assert_eq!(number("TRUE AND FALSE"), Some(0.0));
}

#[test]
fn a_known_operand_decides_and_or_when_the_other_is_unknown() {
    assert_eq!(number("0 AND UNKNOWNVAR"), Some(0.0));
    assert_eq!(number("UNKNOWNVAR AND 0"), Some(0.0));
    assert_eq!(number("1 OR UNKNOWNVAR"), Some(1.0));
    assert_eq!(number("1 AND UNKNOWNVAR"), None);
    assert_eq!(number("0 OR UNKNOWNVAR"), None);
    assert_eq!(number("1 XOR UNKNOWNVAR"), None);
    assert_eq!(number("0 AND \"A\""), None);
}

#[test]
fn bit_operators_work_on_integers() {
    assert_eq!(number("5 B_AND 3"), Some(1.0));
    assert_eq!(number("5 B_OR 3"), Some(7.0));
    assert_eq!(number("5 B_XOR 3"), Some(6.0));
    assert_eq!(number("B_NOT 5"), Some(-6.0));
    assert_eq!(number("B_NOT 0"), Some(-1.0));
    // B_AND binds tighter than B_XOR, which binds tighter than B_OR.
    assert_eq!(number("2 B_OR 1 B_AND 0"), Some(2.0));
    assert_eq!(number("1 B_XOR 3 B_AND 2"), Some(3.0));
    assert_eq!(number("6 B_OR 1 B_XOR 3"), Some(6.0));
    // Bit operators bind weaker than arithmetic.
    assert_eq!(number("2+2 B_AND 3"), Some(0.0));
    assert_eq!(number("1.5 B_AND 1"), None);
    assert_eq!(number("3EX9 B_AND 1"), None);
}

#[test]
fn constants() {
    assert_eq!(number("TRUE"), Some(1.0));
    assert_eq!(number("FALSE"), Some(0.0));
    assert_eq!(number("true"), Some(1.0));
    assert_eq!(number("$PI"), Some(std::f64::consts::PI));
}

#[test]
fn concatenation_converts_only_certain_numbers() {
    assert_eq!(text("\"X=\" << 5").as_deref(), Some("X=5"));
    assert_eq!(text("\"A\" << \"B\"").as_deref(), Some("AB"));
    assert_eq!(text("\"N\" << -3").as_deref(), Some("N-3"));
    // `<<` binds weaker than arithmetic: the sum is converted.
    assert_eq!(text("\"N\" << 1+1").as_deref(), Some("N2"));
    assert_eq!(text("1 << 2").as_deref(), Some("12"));
    // How the control writes a fractional REAL is not documented.
    assert_eq!(text("\"X=\" << 2.5"), None);
    assert_eq!(text("\"X=\" << UNKNOWNVAR"), None);
    // `<<` with a right operand only converts it (reference §8.5.1).
    assert_eq!(text("<<(7)").as_deref(), Some("7"));
    assert_eq!(text("<<(0.5)"), None);
    assert_eq!(text("\"\"").as_deref(), Some(""));
}

#[test]
fn strings_compare_equal_or_not() {
    assert_eq!(number("\"AB\"==\"AB\""), Some(1.0));
    assert_eq!(number("\"AB\"<>\"AB\""), Some(0.0));
    assert_eq!(number("\"AB\"==\"ab\""), Some(0.0));
    assert_eq!(number("\"AB\"<>\"AC\""), Some(1.0));
    assert_eq!(number("\"A\" << 1==\"A1\""), Some(1.0));
    // Ordering of texts, and texts against numbers, are not followed.
    assert_eq!(number("\"A\"<\"B\""), None);
    assert_eq!(number("\"1\"==1"), None);
    assert_eq!(number("\"A\"+1"), None);
    assert_eq!(number("-\"A\""), None);
    assert_eq!(number("NOT \"A\""), None);
}
