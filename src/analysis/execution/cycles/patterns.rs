//! The hole patterns HOLES1 (row), HOLES2 (circle) and CYCLE801 (grid) of reference §16.6: the
//! positions in the plane, in program units of the current coordinate system, in the order they are
//! visited, and the alarms the arguments decide.

use super::super::paths::Argument;
use super::drilling::parameter;
use crate::config::cycles::{GridOrder, RowOrder};

/// Holes of one pattern at most: a pattern beyond it is not followed (its call stays unknown).
pub(super) const MAX_HOLES: f64 = 100_000.0;

/// What a pattern call gives.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Pattern {
    /// The positions in visiting order, and whether that order is known (else the plane position
    /// after the pattern is not).
    Holes {
        positions: Vec<(f64, f64)>,
        order_known: bool,
    },
    /// NUM = 0: alarm 61103, no motion.
    NoHoles,
    /// HOLES2 whose holes would reach round the full circle: alarm 61106, no motion.
    CircleTooLong,
    /// An argument that decides the positions is not known, or the pattern is too large.
    Unknown,
}

/// An INT parameter as the control reads a REAL passed to it: rounded.
fn count(value: f64) -> Option<f64> {
    let value = value.abs().round();
    (value <= MAX_HOLES).then_some(value)
}

/// HOLES1 (SPCA, SPCO, STA1, FDIS, DBH, NUM): a row from the reference point at angle STA1, the first
/// hole FDIS from it, DBH between holes. `current` is the position in the plane before the call (in
/// the same units), for the order that starts at the end hole nearer to it.
pub(super) fn row(arguments: &[Argument], current: Option<(f64, f64)>, order: RowOrder) -> Pattern {
    let value = |index| parameter(arguments, index);
    let (Some(spca), Some(spco), Some(sta1), Some(fdis), Some(dbh), Some(num)) =
        (value(0), value(1), value(2), value(3), value(4), value(5))
    else {
        return Pattern::Unknown;
    };
    let Some(num) = count(num) else {
        return Pattern::Unknown;
    };
    if num == 0.0 {
        return Pattern::NoHoles;
    }
    let (fdis, dbh) = (fdis.abs(), dbh.abs());
    let (sin, cos) = sta1.to_radians().sin_cos();
    let mut positions: Vec<(f64, f64)> = (0..num as usize)
        .map(|index| {
            let distance = fdis + index as f64 * dbh;
            (spca + distance * cos, spco + distance * sin)
        })
        .collect();
    let nearer_last = |reference: (f64, f64)| {
        let distance = |point: &(f64, f64)| (point.0 - reference.0).hypot(point.1 - reference.1);
        match (positions.first(), positions.last()) {
            (Some(first), Some(last)) => distance(last) < distance(first),
            _ => false,
        }
    };
    let (reverse, order_known) = match order {
        RowOrder::First => (false, true),
        RowOrder::NearOrigin => (nearer_last((0.0, 0.0)), true),
        RowOrder::NearCurrent => match current {
            Some(current) => (nearer_last(current), true),
            None => (false, false),
        },
        RowOrder::Unknown => (false, false),
    };
    if reverse {
        positions.reverse();
    }
    Pattern::Holes {
        positions,
        order_known,
    }
}

/// HOLES2 (CPA, CPO, RAD, STA1, INDA, NUM): a circle round (CPA, CPO) of radius RAD, the first hole
/// at angle STA1, INDA between holes (0: the full circle divided evenly), in that order.
pub(super) fn circle(arguments: &[Argument]) -> Pattern {
    let value = |index| parameter(arguments, index);
    let (Some(cpa), Some(cpo), Some(rad), Some(sta1), Some(inda), Some(num)) =
        (value(0), value(1), value(2), value(3), value(4), value(5))
    else {
        return Pattern::Unknown;
    };
    let Some(num) = count(num) else {
        return Pattern::Unknown;
    };
    if num == 0.0 {
        return Pattern::NoHoles;
    }
    let rad = rad.abs();
    let inda = if inda == 0.0 { 360.0 / num } else { inda };
    if inda.abs() * (num - 1.0) >= 360.0 {
        return Pattern::CircleTooLong;
    }
    let positions = (0..num as usize)
        .map(|index| {
            let (sin, cos) = (sta1 + index as f64 * inda).to_radians().sin_cos();
            (cpa + rad * cos, cpo + rad * sin)
        })
        .collect();
    Pattern::Holes {
        positions,
        order_known: true,
    }
}

/// CYCLE801 (_SPCA, _SPCO, _STA, _DIS1, _DIS2, _NUM1, _NUM2): a grid from (SPCA, SPCO) turned by STA,
/// NUM1 columns DIS1 apart and NUM2 rows DIS2 apart. The order is a meander along the direction of
/// the smaller spacing, starting at the reference corner; with `GridOrder::Unknown` it is drawn so
/// but not taken as known. Also says whether NUM1 or NUM2 was 0 (alarm 62105, taken as 1).
pub(super) fn grid(arguments: &[Argument], order: GridOrder) -> (Pattern, bool) {
    let value = |index| parameter(arguments, index);
    let (Some(spca), Some(spco), Some(sta), Some(dis1), Some(dis2), Some(num1), Some(num2)) = (
        value(0),
        value(1),
        value(2),
        value(3),
        value(4),
        value(5),
        value(6),
    ) else {
        return (Pattern::Unknown, false);
    };
    let (Some(num1), Some(num2)) = (count(num1), count(num2)) else {
        return (Pattern::Unknown, false);
    };
    let empty = num1 == 0.0 || num2 == 0.0;
    let (num1, num2) = (num1.max(1.0) as usize, num2.max(1.0) as usize);
    if (num1 * num2) as f64 > MAX_HOLES {
        return (Pattern::Unknown, empty);
    }
    let (dis1, dis2) = (dis1.abs(), dis2.abs());
    let (sin, cos) = sta.to_radians().sin_cos();
    let at = |column: usize, row: usize| {
        let (a, b) = (column as f64 * dis1, row as f64 * dis2);
        (spca + a * cos - b * sin, spco + a * sin + b * cos)
    };
    let mut positions = Vec::with_capacity(num1 * num2);
    // The inner direction is the one with the smaller spacing; every other line runs backwards.
    let along_first = dis1 <= dis2;
    let (inner, outer) = if along_first {
        (num1, num2)
    } else {
        (num2, num1)
    };
    for line in 0..outer {
        for step in 0..inner {
            let step = if line % 2 == 0 {
                step
            } else {
                inner - 1 - step
            };
            positions.push(if along_first {
                at(step, line)
            } else {
                at(line, step)
            });
        }
    }
    let pattern = Pattern::Holes {
        positions,
        order_known: order == GridOrder::Meander,
    };
    (pattern, empty)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn given(values: &[f64]) -> Vec<Argument> {
        values
            .iter()
            .map(|value| Argument::Given(Some(*value)))
            .collect()
    }

    fn holes(pattern: Pattern) -> Vec<(f64, f64)> {
        match pattern {
            Pattern::Holes { positions, .. } => positions
                .into_iter()
                .map(|(a, b)| ((a * 1e4).round() / 1e4, (b * 1e4).round() / 1e4))
                .collect(),
            other => panic!("holes expected, got {other:?}"),
        }
    }

    #[test]
    fn a_row_starts_at_the_end_nearer_to_the_current_position() {
        let arguments = given(&[-100.0, 0.0, 0.0, 10.0, 15.0, 4.0]);
        let near_origin = holes(row(&arguments, Some((0.0, 0.0)), RowOrder::NearCurrent));
        assert_eq!(near_origin.first(), Some(&(-45.0, 0.0)));
        let far_left = holes(row(&arguments, Some((-200.0, 0.0)), RowOrder::NearCurrent));
        assert_eq!(far_left.first(), Some(&(-90.0, 0.0)));
        assert!(matches!(
            row(&arguments, None, RowOrder::NearCurrent),
            Pattern::Holes {
                order_known: false,
                ..
            }
        ));
    }

    #[test]
    fn a_full_circle_is_divided_evenly_and_a_too_long_one_is_an_alarm() {
        let full = holes(circle(&given(&[0.0, 0.0, 30.0, 45.0, 0.0, 3.0])));
        assert_eq!(full[1], (-28.9778, 7.7646));
        assert_eq!(
            circle(&given(&[0.0, 0.0, 30.0, 0.0, 120.0, 4.0])),
            Pattern::CircleTooLong
        );
        assert_eq!(
            circle(&given(&[0.0, 0.0, 30.0, 0.0, 90.0, 0.0])),
            Pattern::NoHoles
        );
    }

    #[test]
    fn a_grid_meanders_along_the_smaller_spacing() {
        let (pattern, empty) = grid(
            &given(&[0.0, 0.0, 0.0, 10.0, 5.0, 3.0, 2.0]),
            GridOrder::Meander,
        );
        assert!(!empty);
        assert_eq!(
            holes(pattern),
            vec![
                (0.0, 0.0),
                (0.0, 5.0),
                (10.0, 5.0),
                (10.0, 0.0),
                (20.0, 0.0),
                (20.0, 5.0)
            ]
        );
        let (_, empty) = grid(
            &given(&[0.0, 0.0, 0.0, 10.0, 5.0, 0.0, 2.0]),
            GridOrder::Meander,
        );
        assert!(empty);
    }
}
