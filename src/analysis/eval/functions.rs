//! The predefined functions the evaluator computes (reference §8.2): arithmetic with angles in
//! degrees, rounding, type conversions and strings. A result that is not certain is `None`.

use super::value::{as_int, round_half_away, Value, INT_RANGE};
use std::sync::Arc;

/// The functions the evaluator computes with the number of arguments each takes (least, most).
const FUNCTIONS: &[(&str, usize, usize)] = &[
    ("SIN", 1, 1),
    ("COS", 1, 1),
    ("TAN", 1, 1),
    ("ASIN", 1, 1),
    ("ACOS", 1, 1),
    ("ATAN2", 2, 2),
    ("SQRT", 1, 1),
    ("POT", 1, 1),
    ("LN", 1, 1),
    ("EXP", 1, 1),
    ("ABS", 1, 1),
    ("TRUNC", 1, 1),
    ("ROUND", 1, 1),
    ("ROUNDUP", 1, 1),
    ("BOUND", 3, 3),
    ("MINVAL", 2, 2),
    ("MAXVAL", 2, 2),
    ("MIN", 2, 2),
    ("MAX", 2, 2),
    ("ITOR", 1, 1),
    ("RTOI", 1, 1),
    ("STRLEN", 1, 1),
    ("SUBSTR", 2, 3),
    ("INDEX", 2, 2),
    ("RINDEX", 2, 2),
    ("MINDEX", 2, 2),
    ("MATCH", 2, 2),
    ("TOUPPER", 1, 1),
    ("TOLOWER", 1, 1),
    ("NUMBER", 1, 1),
    ("ISNUMBER", 1, 1),
];

/// Whether the evaluator computes the function `upper_name`; a call of any other function is unknown,
/// which a caller may want to say.
pub fn is_evaluated_function(upper_name: &str) -> bool {
    function_arguments(upper_name).is_some()
}

/// How many arguments an evaluated function takes: the least and the most.
pub fn function_arguments(upper_name: &str) -> Option<(usize, usize)> {
    FUNCTIONS
        .iter()
        .find(|(name, _, _)| *name == upper_name)
        .map(|(_, least, most)| (*least, *most))
}

/// An error of the program found in a function's arguments (alarm 14051).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum FunctionError {
    /// The arguments are outside the function's domain; the text says how.
    Domain(&'static str),
}

/// Computes `upper_name` of `args` (their count already checked). Unknown arguments give an unknown
/// result; a number may be non-finite, which the caller reports as an overflow.
pub(super) fn apply(
    upper_name: &str,
    args: &[Option<Value>],
) -> Result<Option<Value>, FunctionError> {
    let number = |index: usize| args.get(index)?.as_ref()?.number();
    let text = |index: usize| -> Option<&str> { args.get(index)?.as_ref()?.text() };
    let numeric = |result: Option<f64>| Ok(result.map(Value::Number));
    match upper_name {
        "SIN" => numeric(number(0).map(|angle| angle.to_radians().sin())),
        "COS" => numeric(number(0).map(|angle| angle.to_radians().cos())),
        "TAN" => numeric(number(0).and_then(tan_degrees)),
        "ASIN" | "ACOS" => {
            let Some(value) = number(0) else {
                return Ok(None);
            };
            if !(-1.0..=1.0).contains(&value) {
                return Err(FunctionError::Domain(if upper_name == "ASIN" {
                    "ASIN of a value outside -1 to 1"
                } else {
                    "ACOS of a value outside -1 to 1"
                }));
            }
            let radians = if upper_name == "ASIN" {
                value.asin()
            } else {
                value.acos()
            };
            numeric(Some(radians.to_degrees()))
        }
        "ATAN2" => numeric(number(0).zip(number(1)).and_then(|(y, x)| {
            // The angle of the zero vector is not defined, and what the control answers is not known.
            (y != 0.0 || x != 0.0).then(|| y.atan2(x).to_degrees())
        })),
        "SQRT" => match number(0) {
            Some(value) if value < 0.0 => Err(FunctionError::Domain("SQRT of a negative number")),
            value => numeric(value.map(f64::sqrt)),
        },
        "POT" => numeric(number(0).map(|value| value * value)),
        "LN" => match number(0) {
            Some(value) if value <= 0.0 => {
                Err(FunctionError::Domain("LN of zero or a negative number"))
            }
            value => numeric(value.map(f64::ln)),
        },
        "EXP" => numeric(number(0).map(f64::exp)),
        "ABS" => numeric(number(0).map(f64::abs)),
        "TRUNC" => numeric(number(0).map(f64::trunc)),
        "ROUND" => numeric(number(0).map(round_half_away)),
        // The next larger whole number for positive values, the next smaller in magnitude for negative
        // ones: ROUNDUP(-3.6) is -3.
        "ROUNDUP" => numeric(number(0).map(f64::ceil)),
        "BOUND" => numeric(match (number(0), number(1), number(2)) {
            (Some(least), Some(most), Some(value)) if least <= most => {
                Some(value.clamp(least, most))
            }
            _ => None,
        }),
        "MINVAL" | "MIN" => numeric(number(0).zip(number(1)).map(|(a, b)| a.min(b))),
        "MAXVAL" | "MAX" => numeric(number(0).zip(number(1)).map(|(a, b)| a.max(b))),
        "ITOR" => numeric(number(0)),
        "RTOI" => numeric(
            number(0)
                .map(round_half_away)
                .filter(|value| INT_RANGE.contains(value)),
        ),
        "STRLEN" => numeric(text(0).map(|text| text.chars().count() as f64)),
        "SUBSTR" => Ok(substring(
            text(0),
            number(1),
            args.get(2).map(|_| number(2)),
        )),
        "INDEX" | "RINDEX" => {
            let (Some(text), Some(wanted)) = (
                text(0),
                args.get(1).and_then(Option::as_ref).and_then(character),
            ) else {
                return Ok(None);
            };
            let found = if upper_name == "INDEX" {
                text.find(wanted)
            } else {
                text.rfind(wanted)
            };
            numeric(Some(position(text, found)))
        }
        "MINDEX" => match (text(0), text(1)) {
            (Some(text), Some(wanted)) if !wanted.is_empty() => {
                numeric(Some(position(text, text.find(|c| wanted.contains(c)))))
            }
            _ => Ok(None),
        },
        "MATCH" => match (text(0), text(1)) {
            (Some(text), Some(wanted)) if !wanted.is_empty() => {
                numeric(Some(position(text, text.find(wanted))))
            }
            _ => Ok(None),
        },
        // Letters beyond ASCII may be mapped by the control or not: such texts stay unknown.
        "TOUPPER" => Ok(text(0)
            .filter(|text| text.is_ascii())
            .map(|text| Value::Text(Arc::from(text.to_ascii_uppercase())))),
        "TOLOWER" => Ok(text(0)
            .filter(|text| text.is_ascii())
            .map(|text| Value::Text(Arc::from(text.to_ascii_lowercase())))),
        "NUMBER" => numeric(text(0).and_then(|text| match read_number(text) {
            NumberText::Number(value) => Some(value),
            NumberText::NotANumber | NumberText::Uncertain => None,
        })),
        "ISNUMBER" => Ok(text(0).and_then(|text| match read_number(text) {
            NumberText::Number(_) => Some(Value::from_bool(true)),
            NumberText::NotANumber => Some(Value::from_bool(false)),
            NumberText::Uncertain => None,
        })),
        _ => Ok(None),
    }
}

/// TAN in degrees; at odd multiples of 90 degrees the tangent does not exist, and the huge number a
/// double gives there is nothing the control would compute.
fn tan_degrees(angle: f64) -> Option<f64> {
    let pole = (angle - 90.0) % 180.0 == 0.0;
    (!pole).then(|| angle.to_radians().tan())
}

/// SUBSTR(text, start[, count]): `count` characters from `start` (0-based), or the rest. A range that
/// leaves the text is unknown, as the control's answer to it is not documented.
fn substring(text: Option<&str>, start: Option<f64>, count: Option<Option<f64>>) -> Option<Value> {
    let text = text?;
    let start = whole_count(start?)?;
    let length = text.chars().count();
    let count = match count {
        Some(count) => whole_count(count?)?,
        None => length.checked_sub(start)?,
    };
    if start.checked_add(count)? > length {
        return None;
    }
    let part: String = text.chars().skip(start).take(count).collect();
    Some(Value::Text(Arc::from(part)))
}

fn whole_count(value: f64) -> Option<usize> {
    (value >= 0.0 && value.fract() == 0.0 && value <= u32::MAX as f64).then_some(value as usize)
}

/// The character a CHAR argument stands for: a text of one character, or an ASCII code (codes above
/// 127 depend on the control's character set).
fn character(value: &Value) -> Option<char> {
    match value {
        Value::Text(text) => {
            let mut characters = text.chars();
            let first = characters.next()?;
            characters.next().is_none().then_some(first)
        }
        Value::Number(code) => as_int(*code)
            .and_then(|code| u8::try_from(code).ok())
            .filter(u8::is_ascii)
            .map(char::from),
    }
}

/// The 0-based character position of a byte offset found in `text`, -1 when nothing was found.
fn position(text: &str, found: Option<usize>) -> f64 {
    match found {
        Some(byte) => text[..byte].chars().count() as f64,
        None => -1.0,
    }
}

/// What NUMBER and ISNUMBER make of a text.
#[derive(Debug, Clone, Copy, PartialEq)]
enum NumberText {
    Number(f64),
    /// Certainly no number: the text holds no digit.
    NotANumber,
    /// The control's rules for this text are not known (blanks, other letters, hexadecimal ...).
    Uncertain,
}

/// Reads a text written as an NC number: a sign, digits with at most one point, and an exponent
/// written `EX` (reference §1.5).
fn read_number(text: &str) -> NumberText {
    if !text.bytes().any(|byte| byte.is_ascii_digit()) {
        return NumberText::NotANumber;
    }
    let upper = text.to_ascii_uppercase();
    let (mantissa, exponent) = match upper.split_once("EX") {
        Some((mantissa, exponent)) => (mantissa, Some(exponent)),
        None => (upper.as_str(), None),
    };
    let unsigned = mantissa.strip_prefix(['+', '-']).unwrap_or(mantissa);
    let digits = unsigned.bytes().filter(u8::is_ascii_digit).count();
    let points = unsigned.bytes().filter(|byte| *byte == b'.').count();
    let mantissa_ok = digits > 0 && points <= 1 && digits + points == unsigned.len();
    let exponent_ok = exponent.is_none_or(|exponent| {
        let digits = exponent.strip_prefix(['+', '-']).unwrap_or(exponent);
        !digits.is_empty() && digits.bytes().all(|byte| byte.is_ascii_digit())
    });
    if !(mantissa_ok && exponent_ok) {
        return NumberText::Uncertain;
    }
    let written = match exponent {
        Some(exponent) => format!("{mantissa}e{exponent}"),
        None => mantissa.to_string(),
    };
    match written.parse::<f64>() {
        Ok(value) if value.is_finite() => NumberText::Number(value),
        _ => NumberText::Uncertain,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_read_as_written_in_a_program() {
        assert_eq!(read_number("12.5"), NumberText::Number(12.5));
        assert_eq!(read_number("-3"), NumberText::Number(-3.0));
        assert_eq!(read_number(".5"), NumberText::Number(0.5));
        assert_eq!(read_number("1.5EX3"), NumberText::Number(1500.0));
        assert_eq!(read_number("2ex-1"), NumberText::Number(0.2));
        assert_eq!(read_number("ABC"), NumberText::NotANumber);
        assert_eq!(read_number(""), NumberText::NotANumber);
        assert_eq!(read_number(" 12"), NumberText::Uncertain);
        assert_eq!(read_number("1.2.3"), NumberText::Uncertain);
        assert_eq!(read_number("12AB"), NumberText::Uncertain);
        assert_eq!(read_number("1EX"), NumberText::Uncertain);
    }

    #[test]
    fn every_listed_function_is_computed() {
        // A function in the table that `apply` does not know would always be unknown.
        for (name, least, _) in FUNCTIONS {
            let args = vec![Some(Value::Number(0.5)); *least];
            let text_args = vec![Some(Value::text_from("12")); *least];
            let numeric = apply(name, &args).ok().flatten();
            let textual = apply(name, &text_args).ok().flatten();
            let mixed = [Some(Value::text_from("12")), Some(Value::Number(0.0))]
                .get(..*least)
                .and_then(|args| apply(name, args).ok().flatten());
            assert!(
                numeric.is_some() || textual.is_some() || mixed.is_some(),
                "{name} gave no value"
            );
        }
    }
}
