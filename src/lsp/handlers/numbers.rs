//! How the editor features print numbers: three decimals in explanations, as short as exact in hints.

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
    let text = fixed(value);
    let text = if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    };
    if text == "-0" {
        "0".to_string()
    } else {
        text
    }
}

/// Whether two computed positions are the same for a reader (floating-point noise aside).
pub fn same(left: f64, right: f64) -> bool {
    (left - right).abs() <= 1e-6 * left.abs().max(right.abs()).max(1.0)
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
        assert!(same(58.0, 57.999_999_999_99));
        assert!(!same(58.0, 58.01));
    }
}
