//! A number written with four decimals, exactly as `format!("{value:.4}")` writes it, without the
//! library's general float formatting.
//!
//! The findings about circles quote distances with four decimals, and in CAM programs such findings
//! come by the thousand: the library's exact formatting falls back to big-number arithmetic for them
//! and cost more than the rest of the analysis of their blocks. A double is `m · 2^e` exactly, so
//! `m · 10^4 · 2^e` rounded to an integer gives the four decimals with integer arithmetic alone.

use std::fmt;

/// Below this magnitude a double's mantissa times 10^4 fits into 128 bits with room for the shift;
/// larger numbers (and infinities, NaN) are left to the library.
const FAST_LIMIT: f64 = 1e15;

/// Shows the number as `{:.4}` does: rounded half to even on its exact binary value, a `-` for
/// negative numbers (negative zero and numbers that round to zero included).
#[derive(Debug, Clone, Copy)]
pub struct FourDecimals(pub f64);

impl fmt::Display for FourDecimals {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        let value = self.0;
        if !value.is_finite() || value.abs() >= FAST_LIMIT {
            return write!(formatter, "{value:.4}");
        }
        let units = ten_thousandths(value.abs());
        let sign = if value.is_sign_negative() { "-" } else { "" };
        write!(formatter, "{sign}{}.{:04}", units / 10_000, units % 10_000)
    }
}

/// `magnitude · 10^4` rounded half to even, for a finite `magnitude` from 0 up to [`FAST_LIMIT`].
fn ten_thousandths(magnitude: f64) -> u64 {
    let bits = magnitude.to_bits();
    let biased_exponent = ((bits >> 52) & 0x7ff) as i32;
    let fraction = bits & ((1 << 52) - 1);
    // The value is `mantissa · 2^exponent`; below the limit the exponent is negative.
    let (mantissa, exponent) = if biased_exponent == 0 {
        (fraction, -1074)
    } else {
        (fraction | (1 << 52), biased_exponent - 1075)
    };
    let scaled = u128::from(mantissa) * 10_000;
    let shift = exponent.unsigned_abs();
    // `scaled` is below 2^67: from a shift of 68 on it is less than half a unit and rounds to 0.
    if shift >= 68 {
        return 0;
    }
    let whole = scaled >> shift;
    let remainder = scaled & ((1u128 << shift) - 1);
    let half = 1u128 << (shift - 1);
    let rounded = if remainder > half || (remainder == half && whole & 1 == 1) {
        whole + 1
    } else {
        whole
    };
    // Below the limit the result is below 10^19.
    rounded as u64
}

#[cfg(test)]
mod tests {
    use super::*;

    fn assert_same(value: f64) {
        assert_eq!(
            FourDecimals(value).to_string(),
            format!("{value:.4}"),
            "{value:e}"
        );
    }

    #[test]
    fn edge_values_are_written_as_the_library_writes_them() {
        for value in [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.00005,
            -0.00005,
            0.00004999,
            -0.00001,
            0.99995,
            9.99995,
            123.45675,
            1e-300,
            -1e-300,
            f64::MIN_POSITIVE,
            5e-324,
            999_999_999_999_999.9,
            1e15,
            -1e15,
            1e300,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            f64::MAX,
        ] {
            assert_same(value);
        }
    }

    #[test]
    fn exact_ties_round_as_the_library_rounds_them() {
        // Odd multiples of 1/32 = 0.03125 lie exactly halfway between two ten-thousandths.
        for numerator in -100_000i64..100_000 {
            assert_same(numerator as f64 / 32.0);
            assert_same(numerator as f64 / 20_000.0);
        }
    }

    #[test]
    fn numbers_of_every_magnitude_are_written_as_the_library_writes_them() {
        // A fixed xorshift sequence of bit patterns: every sign, exponent and mantissa.
        let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..400_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            assert_same(f64::from_bits(state));
            // Numbers of the size of distances on a machine, in millimetres.
            let distance = (state >> 11) as f64 / (1u64 << 53) as f64 * 2000.0 - 1000.0;
            assert_same(distance);
        }
    }
}
