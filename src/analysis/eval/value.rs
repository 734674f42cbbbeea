//! The values an NC expression can have, and the control's rules for comparing and converting them.

use std::sync::Arc;

/// A known value. Numbers carry INT, REAL, BOOL (0 or 1) and CHAR (the character code) alike, as the
/// control computes all of them in doubles; texts carry STRING values and axis names (AXIS). A known
/// number is always finite.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    Number(f64),
    Text(Arc<str>),
}

impl Value {
    /// The truth value of BOOL results (comparisons, AND, NOT ...).
    pub fn from_bool(value: bool) -> Value {
        Value::Number(if value { 1.0 } else { 0.0 })
    }

    pub fn text_from(text: &str) -> Value {
        Value::Text(Arc::from(text))
    }

    pub fn number(&self) -> Option<f64> {
        match self {
            Value::Number(value) => Some(*value),
            Value::Text(_) => None,
        }
    }

    pub fn text(&self) -> Option<&str> {
        match self {
            Value::Number(_) => None,
            Value::Text(text) => Some(text),
        }
    }

    /// The text `<<` makes of this value, when it is certain. A whole number is written with its digits
    /// and no decimals; how the control writes a fractional REAL is not documented (reference §8.5.1),
    /// so that text is unknown rather than a guess.
    pub fn to_text(&self) -> Option<Arc<str>> {
        match self {
            Value::Text(text) => Some(text.clone()),
            Value::Number(value) => {
                // Beyond 2^53 a double holds no fractional part and its digits are not certain either
                // (the control may switch to an exponent), so such numbers stay unknown too.
                let whole = value.fract() == 0.0 && value.abs() < 9_007_199_254_740_992.0;
                whole.then(|| Arc::from((*value as i64).to_string()))
            }
        }
    }
}

/// Relative equality of REAL values (reference §18.1, MD10280 bit 0): `|a-b| <= 1e-12 * max(|a|, |b|)`.
/// There is no absolute part, so a comparison with exactly 0 stays exact (`5.55e-17 == 0` is FALSE).
pub fn real_equal(left: f64, right: f64) -> bool {
    (left - right).abs() <= 1e-12 * left.abs().max(right.abs())
}

/// `left < right` as the control compares: not less when the two are equal within the tolerance,
/// unless MD10280 bit 0 makes `<` and `>` plain IEEE comparisons (`exact`).
pub fn real_less(left: f64, right: f64, exact: bool) -> bool {
    if exact {
        left < right
    } else {
        left < right && !real_equal(left, right)
    }
}

/// `left <= right`: less or equal within the tolerance, whatever MD10280 says (it exempts only `<` and
/// `>`).
pub fn real_less_equal(left: f64, right: f64) -> bool {
    left < right || real_equal(left, right)
}

/// The smallest and largest INT values (reference §8.1 prints -2147483646 as the lower end, which is
/// most likely a misprint of the 32-bit limit).
pub const INT_RANGE: std::ops::RangeInclusive<f64> = (i32::MIN as f64)..=(i32::MAX as f64);

/// Rounds half away from zero, as the control converts REAL to INT (ROUND, RTOI, assignment to INT).
pub fn round_half_away(value: f64) -> f64 {
    value.round()
}

/// The value as a 32-bit integer when it is a whole number in the INT range: the operands of the bit
/// operators.
pub fn as_int(value: f64) -> Option<i32> {
    (value.fract() == 0.0 && INT_RANGE.contains(&value)).then_some(value as i32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equality_is_relative_without_an_absolute_part() {
        let sum = std::hint::black_box(0.1) + 0.2;
        assert!(real_equal(sum, 0.3));
        assert_ne!(sum, 0.3, "the case needs the tolerance");
        assert!(!real_equal(0.1 + 0.2 - 0.3, 0.0));
        assert!(real_equal(0.0, 0.0));
        assert!(real_equal(1e300, 1e300 * (1.0 + 1e-13)));
        assert!(!real_equal(1.0, 1.0 + 1e-11));
    }

    #[test]
    fn less_respects_the_tolerance_unless_exact() {
        let almost_one = 0.9999999999999999;
        assert!(!real_less(almost_one, 1.0, false));
        assert!(real_less(almost_one, 1.0, true));
        assert!(real_less_equal(1.0, almost_one));
        assert!(!real_less_equal(1.0 + 1e-9, 1.0));
    }

    #[test]
    fn only_whole_numbers_become_text() {
        assert_eq!(Value::Number(42.0).to_text().as_deref(), Some("42"));
        assert_eq!(Value::Number(-7.0).to_text().as_deref(), Some("-7"));
        assert_eq!(Value::Number(-0.0).to_text().as_deref(), Some("0"));
        assert_eq!(Value::Number(2.5).to_text(), None);
        assert_eq!(Value::Number(1e20).to_text(), None);
        assert_eq!(Value::text_from("AB").to_text().as_deref(), Some("AB"));
    }

    #[test]
    fn int_conversion_needs_a_whole_number_in_range() {
        assert_eq!(as_int(5.0), Some(5));
        assert_eq!(as_int(-2147483648.0), Some(i32::MIN));
        assert_eq!(as_int(2147483648.0), None);
        assert_eq!(as_int(1.5), None);
        assert_eq!(round_half_away(2.5), 3.0);
        assert_eq!(round_half_away(-2.5), -3.0);
        assert_eq!(round_half_away(2.4999), 2.0);
    }
}
