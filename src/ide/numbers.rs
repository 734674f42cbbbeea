//! How the product writes coordinates and other computed numbers for people: the hover's
//! explanations (three decimals, as the control's position display), the inlay hints and the hover's
//! summaries (as short as exact), and the preview's CSV and JSON (the value without floating-point
//! noise). One place, so that the same position reads the same in every output.

/// `58.000`, `-32.000`: three decimals, as the control's position display shows them.
pub fn fixed(value: f64) -> String {
    let text = format!("{value:.3}");
    // -0.000 reads as a different position from 0.000; it is not one.
    if text
        .trim_start_matches('-')
        .bytes()
        .all(|byte| byte == b'0' || byte == b'.')
    {
        text.trim_start_matches('-').to_string()
    } else {
        text
    }
}

/// A value in a sum: negative values in parentheses, `(-32.000)`.
pub fn term(value: f64) -> String {
    let text = fixed(value);
    if text.starts_with('-') {
        format!("({text})")
    } else {
        text
    }
}

/// `115`, `57.5`, `0.001`: up to three decimals without trailing zeros.
pub fn short(value: f64) -> String {
    short_to(value, 3)
}

/// Up to `decimals` decimals without trailing zeros and without a sign on zero: `short_to(2.50004,
/// 4)` is `2.5`, `short_to(-0.00001, 4)` is `0`.
pub fn short_to(value: f64, decimals: usize) -> String {
    let text = format!("{value:.decimals$}");
    let text = if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.')
    } else {
        text.as_str()
    };
    if text == "-0" {
        "0".to_string()
    } else {
        text.to_string()
    }
}

/// Whether two computed positions are the same for a reader (floating-point noise aside).
pub fn same(left: f64, right: f64) -> bool {
    (left - right).abs() <= 1e-6 * left.abs().max(right.abs()).max(1.0)
}

/// The value without floating-point noise (1e-9 mm), so that `58.0` does not print as
/// `57.99999999999999`; zero without its sign. The preview's JSON and CSV write this value with the
/// shortest text that reads back as it.
#[inline]
pub fn without_noise(value: f64) -> f64 {
    // Beyond about 1e299 the scaling below overflows to infinity (written as `null`); such values
    // have no digits after the point to round anyway.
    if !(value * 1e9).is_finite() {
        return value;
    }
    let rounded = (value * 1e9).round() / 1e9;
    if rounded == 0.0 {
        0.0
    } else {
        rounded
    }
}

/// A time in seconds to the microsecond, as the preview writes times.
pub fn microseconds(seconds: f64) -> f64 {
    (seconds * 1e6).round() / 1e6
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_print_as_the_control_shows_them() {
        assert_eq!(fixed(58.0), "58.000");
        assert_eq!(fixed(-0.0001), "0.000");
        assert_eq!(term(-32.0), "(-32.000)");
        assert_eq!(term(40.0), "40.000");
        assert_eq!(short(115.0), "115");
        assert_eq!(short(57.5), "57.5");
        assert_eq!(short(-0.0002), "0");
        assert_eq!(short(-12.25), "-12.25");
        assert_eq!(short(100.0), "100");
        assert_eq!(short_to(2.50004, 4), "2.5");
        assert_eq!(short_to(2.50006, 4), "2.5001");
        assert_eq!(short_to(-0.00001, 4), "0");
        assert_eq!(short_to(12.0, 0), "12");
        assert!(same(58.0, 57.999_999_999_99));
        assert!(!same(58.0, 58.01));
    }

    #[test]
    fn noise_is_taken_off_and_zero_loses_its_sign() {
        assert_eq!(without_noise(57.999_999_999_999_99), 58.0);
        assert_eq!(without_noise(0.1 + 0.2), 0.3);
        assert!(without_noise(-1e-12).is_sign_positive());
        assert_eq!(without_noise(1e300), 1e300);
        assert!(without_noise(f64::NAN).is_nan());
        assert_eq!(microseconds(9.42477796), 9.424778);
    }
}
