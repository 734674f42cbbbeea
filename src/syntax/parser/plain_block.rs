//! The fast path for plain blocks: an optional `N` number, then words made of one letter and a constant
//! (`G1`, `X-1.5`, `F2500`), then an optional comment. CAM output consists almost entirely of such blocks,
//! so reading them straight from the bytes, without the lexer and the general statement parser, is what
//! makes a full parse of a large program fast.
//!
//! The fast path must give exactly what the general parser gives. It therefore handles only the plain
//! shapes and gives up (returns `false`) at the first byte that could mean anything else; the caller then
//! parses the line the general way. `tests/plain_block_equivalence.rs` compares both paths.

use crate::diagnostics::Span;
use crate::syntax::ast::{AddressKind, AddressWord, BlockNumber, Statement, Value, ValueExpr};
use crate::syntax::gcodes::GCode;
use crate::syntax::parser::cursor::Parser;
use crate::syntax::parser::literals::{
    decimal_from_parts, parse_number, MAX_SIMPLE_DECIMAL_LENGTH,
};

fn is_blank(byte: u8) -> bool {
    byte == b' ' || byte == b'\t'
}

impl Parser<'_> {
    /// Parses the line if it is a plain block. Returns `false` as soon as it is not; the block and the
    /// diagnostics are then incomplete and must be cleared by the caller.
    pub(super) fn parse_plain_block(&mut self) -> bool {
        let bytes = self.line.as_bytes();
        let length = bytes.len();
        let mut index = 0;
        let mut first_word = true;
        // The block checks can only find something when a G function is present or a letter repeats;
        // tracking both here lets the common block skip them.
        let mut has_g_function = false;
        let mut letters_seen: u32 = 0;
        let mut letter_repeated = false;
        self.check_block_length();
        loop {
            while index < length && is_blank(bytes[index]) {
                index += 1;
            }
            if index == length {
                break;
            }
            let byte = bytes[index];
            if byte == b';' {
                self.block.comment = Some(Span::new(index, length));
                break;
            }
            if !byte.is_ascii_alphabetic() {
                return false;
            }
            let letter = byte.to_ascii_uppercase();
            let letter_start = index;
            index += 1;
            // Two letters in a row make a name (`XR1`), which the general parser handles.
            if index < length && (bytes[index].is_ascii_alphabetic() || bytes[index] == b'_') {
                return false;
            }
            while index < length && is_blank(bytes[index]) {
                index += 1;
            }
            let value_start = index;
            let negative = match bytes.get(index) {
                Some(b'-') => {
                    index += 1;
                    true
                }
                Some(b'+') => {
                    index += 1;
                    false
                }
                _ => false,
            };
            let has_sign = index != value_start;
            let number_start = index;
            // The digits are also accumulated here, so a short number needs no second pass; wrapping
            // arithmetic is harmless because longer numbers take `parse_number` below. The digits
            // before and after the point are read by two loops, so that a digit is not asked whether
            // a point came before it.
            let mut mantissa: u64 = 0;
            index = accumulate_digits(bytes, index, &mut mantissa);
            let mut digit_count = index - number_start;
            let has_point = index < length && bytes[index] == b'.';
            let mut decimals = 0;
            if has_point {
                let fraction_start = index + 1;
                index = accumulate_digits(bytes, fraction_start, &mut mantissa);
                decimals = index - fraction_start;
                digit_count += decimals;
            }
            if digit_count == 0 {
                return false;
            }
            let number_end = index;
            // A second point, an `EX` exponent or an underscore continue the token in ways the general
            // lexer decides.
            match bytes.get(index) {
                Some(b'.') | Some(b'_') => return false,
                Some(b'E') | Some(b'e')
                    if matches!(bytes.get(index + 1), Some(b'X') | Some(b'x')) =>
                {
                    return false
                }
                _ => {}
            }
            let number_text = &self.line[number_start..number_end];
            let word_span = Span::new(letter_start, number_end);
            match letter {
                b'N' => {
                    if !first_word || has_sign || has_point {
                        return false;
                    }
                    let Some(value) = parse_plain_integer(number_text) else {
                        return false;
                    };
                    self.block.number = Some(BlockNumber {
                        value,
                        main: false,
                        span: word_span,
                    });
                }
                b'G' => {
                    if has_sign || has_point {
                        return false;
                    }
                    let Some(number) = parse_plain_integer(number_text) else {
                        return false;
                    };
                    let Some(code) = u32::try_from(number).ok().and_then(GCode::from_number) else {
                        return false;
                    };
                    has_g_function = true;
                    self.block.statements.push(Statement::GCode {
                        code,
                        span: word_span,
                    });
                }
                b'R' | b'O' | b'L' => return false,
                _ => {
                    if letter != b'M' && letter != b'H' {
                        let bit = 1u32 << (letter - b'A');
                        letter_repeated |= letters_seen & bit != 0;
                        letters_seen |= bit;
                    }
                    let kind = self.classify_letter(letter, None);
                    let short = number_end - number_start <= MAX_SIMPLE_DECIMAL_LENGTH;
                    // A number beyond the range of a double is reported by the general parser.
                    let Some(magnitude) = short
                        .then(|| decimal_from_parts(mantissa, decimals))
                        .flatten()
                        .or_else(|| parse_number(number_text))
                    else {
                        return false;
                    };
                    let value = if negative { -magnitude } else { magnitude };
                    let expr = ValueExpr::Constant {
                        value,
                        span: Span::new(value_start, number_end),
                    };
                    if kind == AddressKind::Axis {
                        self.check_axis_configured(letter, None, word_span);
                    }
                    self.block.statements.push(Statement::Address(AddressWord {
                        kind,
                        name: Span::new(letter_start, letter_start + 1),
                        extension: None,
                        value: Value {
                            modifier: None,
                            expr,
                            has_equals: false,
                        },
                        span: word_span,
                    }));
                }
            }
            first_word = false;
        }
        if has_g_function || letter_repeated {
            self.check_block();
        }
        true
    }
}

/// Digits only, without overflow; what `integer_at` accepts in the general parser.
fn parse_plain_integer(text: &str) -> Option<u64> {
    let mut value: u64 = 0;
    for byte in text.bytes() {
        if !byte.is_ascii_digit() {
            return None;
        }
        value = value.checked_mul(10)?.checked_add(u64::from(byte - b'0'))?;
    }
    Some(value)
}

/// Reads the decimal digits of `bytes` from `index` on into `mantissa` (wrapping: a long number is
/// parsed again in full); returns the index after the last digit.
#[inline]
fn accumulate_digits(bytes: &[u8], mut index: usize, mantissa: &mut u64) -> usize {
    while let Some(&byte) = bytes.get(index).filter(|byte| byte.is_ascii_digit()) {
        *mantissa = mantissa
            .wrapping_mul(10)
            .wrapping_add(u64::from(byte - b'0'));
        index += 1;
    }
    index
}
