//! Literals: the value of a number token (with an exact fast path for the decimals CAM programs are
//! made of), and the findings about broken numbers and strings.

use crate::diagnostics::{Code, Fix, Span};
use crate::syntax::parser::cursor::Parser;

impl Parser<'_> {
    pub(super) fn report_unterminated_string(&mut self, span: Span) {
        let fix = Fix::replace(
            "Close the string at the end of the line",
            Span::new(span.end(), span.end()),
            "\"",
        );
        self.report_with_fix(
            Code::UnterminatedString,
            span,
            "this string has no closing `\"` on its line (strings cannot continue onto the next line)",
            fix,
        );
    }

    pub(super) fn report_bad_number(&mut self, span: Span) {
        let text = self.text(span).to_string();
        let message = if text.starts_with('\'') {
            format!(
                "`{text}` is not a valid literal: write hexadecimal as 'H1F' and binary as 'B101'"
            )
        } else {
            format!("`{text}` is not a valid number")
        };
        self.report(Code::InvalidNumber, span, message);
    }

    /// The value of the number token at `span`, or `None` after reporting S133 when it lies beyond the
    /// range of a double (`1EX400`, a number of ten thousand digits): such a number used to become
    /// infinity, which must never be shown as a position.
    pub(super) fn number_value(&mut self, span: Span) -> Option<f64> {
        let value = parse_number(self.text(span));
        if value.is_none() {
            self.report_number_out_of_range(span);
        }
        value
    }

    pub(super) fn report_number_out_of_range(&mut self, span: Span) {
        let text = self.text(span).to_string();
        self.report(
            Code::InvalidNumber,
            span,
            format!("`{text}` is too large for a number: the control computes with values up to about 1.8EX308"),
        );
    }
}

/// Parses a number token's text (`10`, `.5`, `1.5EX-3`). `None` when the text is not a number or its
/// value is not finite (beyond about 1.8e308), so that no caller can turn it into an infinite position.
pub fn parse_number(text: &str) -> Option<f64> {
    if let Some(value) = parse_simple_decimal(text.as_bytes()) {
        return Some(value);
    }
    // The exponent is written `EX` (`1.5EX-3`); the standard parser reads it as `1.5e-3`, correctly
    // rounded, and gives 0 for `0EX400` where multiplying by 10^400 gave NaN.
    let value: f64 = match text.bytes().position(|byte| byte == b'E' || byte == b'e') {
        None => text.parse().ok()?,
        Some(position) => {
            let exponent = text.get(position + 2..)?;
            format!("{}e{exponent}", &text[..position]).parse().ok()?
        }
    };
    value.is_finite().then_some(value)
}

/// Exact fast path for the numbers CAM programs are made of (`123.456`): when the digits form an
/// integer below 2^53 and at most 22 decimals follow, one IEEE division gives the correctly rounded
/// value, the same as the standard parser.
fn parse_simple_decimal(bytes: &[u8]) -> Option<f64> {
    if bytes.is_empty() || bytes.len() > MAX_SIMPLE_DECIMAL_LENGTH {
        return None;
    }
    let mut mantissa: u64 = 0;
    let mut decimals: Option<usize> = None;
    for &byte in bytes {
        match byte {
            b'0'..=b'9' => {
                mantissa = mantissa * 10 + u64::from(byte - b'0');
                if let Some(count) = decimals.as_mut() {
                    *count += 1;
                }
            }
            b'.' if decimals.is_none() => decimals = Some(0),
            _ => return None,
        }
    }
    decimal_from_parts(mantissa, decimals.unwrap_or(0))
}

/// Longest number text (digits and point) the exact fast path takes: 17 digits cannot overflow `u64`.
pub(super) const MAX_SIMPLE_DECIMAL_LENGTH: usize = 17;

/// `mantissa / 10^decimals`, exact when the mantissa is below 2^53 (both operands are exact doubles and
/// IEEE division rounds correctly); `None` otherwise.
pub(super) fn decimal_from_parts(mantissa: u64, decimals: usize) -> Option<f64> {
    const POWERS_OF_TEN: [f64; 23] = [
        1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
        1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
    ];
    if mantissa >= 1 << 53 {
        return None;
    }
    Some(mantissa as f64 / *POWERS_OF_TEN.get(decimals)?)
}
