//! Circle geometry in the working plane: the centre from I/J/K or from CR, and the checks the control
//! makes before it accepts a circle (reference §3.2, §6.3, §6.4). Plain functions on plane coordinates
//! `(first axis, second axis)`: G17 (X, Y), G18 (Z, X), G19 (Y, Z); G3 turns counter-clockwise seen from
//! the positive third axis.

/// A resolved circle in plane coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Circle {
    pub centre: (f64, f64),
    pub radius: f64,
    pub clockwise: bool,
    /// The swept angle in degrees, 0 < sweep <= 360.
    pub sweep: f64,
}

/// Why the control rejects a circle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CircleError {
    /// The end point's distance from the centre differs from the start's by more than the tolerance
    /// (alarm 14040); the difference and the tolerance are given.
    EndNotOnCircle { difference: f64, tolerance: f64 },
    /// CR is smaller than half the chord beyond the tolerance: no circle exists.
    RadiusTooSmall { chord: f64, radius: f64 },
    /// CR with the end point equal to the start point (alarm 14040): CR cannot make a full circle.
    RadiusFullCircle,
    /// An opening angle AR outside 0 < AR < 360, or AR with the end point equal to the start point.
    OpeningAngleOutOfRange,
    /// CIP with its three points on one line, the intermediate point not between the others
    /// (alarm 14920).
    IntermediatePointOnLine,
}

/// A circle by its opening angle AR (degrees) from `start` to `end` (reference §6.2): the radius is
/// `chord / (2 sin(AR/2))`; the centre lies on the chord's bisector, to the left of the chord for a
/// counter-clockwise arc of at most 180°, to the other side beyond 180°.
pub fn from_opening_angle(
    start: (f64, f64),
    end: (f64, f64),
    degrees: f64,
    clockwise: bool,
) -> Result<Circle, CircleError> {
    let chord = (end.0 - start.0).hypot(end.1 - start.1);
    if !(degrees > 0.0 && degrees < 360.0) || chord <= 1e-9 {
        return Err(CircleError::OpeningAngleOutOfRange);
    }
    let half = (degrees / 2.0).to_radians();
    let radius = chord / (2.0 * half.sin());
    // Signed: negative beyond 180°, which puts the centre on the other side of the chord.
    let height = radius * half.cos();
    let middle = ((start.0 + end.0) / 2.0, (start.1 + end.1) / 2.0);
    let normal = (-(end.1 - start.1) / chord, (end.0 - start.0) / chord);
    let side = if clockwise { -1.0 } else { 1.0 };
    let centre = (
        middle.0 + side * height * normal.0,
        middle.1 + side * height * normal.1,
    );
    Ok(Circle {
        centre,
        radius,
        clockwise,
        sweep: degrees,
    })
}

/// A circle by its opening angle AR and its centre: the end point is the start turned about the
/// centre by AR, clockwise for G2 (reference §6.2).
pub fn from_opening_angle_and_centre(
    start: (f64, f64),
    centre: (f64, f64),
    degrees: f64,
    clockwise: bool,
) -> Result<((f64, f64), Circle), CircleError> {
    let radius = (start.0 - centre.0).hypot(start.1 - centre.1);
    if !(degrees > 0.0 && degrees < 360.0) || radius <= 1e-9 {
        return Err(CircleError::OpeningAngleOutOfRange);
    }
    let signed = if clockwise { -degrees } else { degrees };
    let (sin, cos) = signed.to_radians().sin_cos();
    let (dx, dy) = (start.0 - centre.0, start.1 - centre.1);
    let end = (
        centre.0 + dx * cos - dy * sin,
        centre.1 + dx * sin + dy * cos,
    );
    Ok((
        end,
        Circle {
            centre,
            radius,
            clockwise,
            sweep: degrees,
        },
    ))
}

/// The circle of CIP through `start`, the intermediate point `via` and `end` (reference §6.2); its
/// direction is the order of the three points. `Ok(None)` when the points lie on one line with the
/// intermediate point between the others: the control then moves along the straight line.
pub fn through_points(
    start: (f64, f64),
    via: (f64, f64),
    end: (f64, f64),
) -> Result<Option<Circle>, CircleError> {
    let first = (via.0 - start.0, via.1 - start.1);
    let second = (end.0 - start.0, end.1 - start.1);
    let cross = first.0 * second.1 - first.1 * second.0;
    let scale = first.0.hypot(first.1).max(second.0.hypot(second.1));
    if cross.abs() <= 1e-9 * scale * scale.max(1.0) {
        let along = first.0 * second.0 + first.1 * second.1;
        let length = second.0 * second.0 + second.1 * second.1;
        return if length > 1e-18 && along >= 0.0 && along <= length {
            Ok(None)
        } else {
            Err(CircleError::IntermediatePointOnLine)
        };
    }
    // The circumcentre, relative to the start point.
    let denominator = 2.0 * cross;
    let first_square = first.0 * first.0 + first.1 * first.1;
    let second_square = second.0 * second.0 + second.1 * second.1;
    let centre_x = (second.1 * first_square - first.1 * second_square) / denominator;
    let centre_y = (first.0 * second_square - second.0 * first_square) / denominator;
    let centre = (start.0 + centre_x, start.1 + centre_y);
    let clockwise = cross < 0.0;
    Ok(Some(Circle {
        centre,
        radius: centre_x.hypot(centre_y),
        clockwise,
        sweep: sweep_degrees(start, end, centre, clockwise),
    }))
}

/// The circle of CT: tangent at `start` to the direction `tangent` of the previous path element and
/// through `end` (reference §6.2); `None` when the end lies on the tangent (a straight line).
pub fn tangential(start: (f64, f64), tangent: (f64, f64), end: (f64, f64)) -> Option<Circle> {
    let length = tangent.0.hypot(tangent.1);
    if length <= 1e-12 {
        return None;
    }
    // The unit normal to the left of the tangent.
    let normal = (-tangent.1 / length, tangent.0 / length);
    let chord = (end.0 - start.0, end.1 - start.1);
    let across = chord.0 * normal.0 + chord.1 * normal.1;
    let chord_square = chord.0 * chord.0 + chord.1 * chord.1;
    if across.abs() <= 1e-9 * chord_square.sqrt().max(1.0) {
        return None;
    }
    // The centre is at signed distance s along the normal with |C - end| = |s|.
    let distance = chord_square / (2.0 * across);
    let centre = (start.0 + distance * normal.0, start.1 + distance * normal.1);
    let clockwise = distance < 0.0;
    Some(Circle {
        centre,
        radius: distance.abs(),
        clockwise,
        sweep: sweep_degrees(start, end, centre, clockwise),
    })
}

/// The direction of travel at the end of a circle, for a following CT.
pub fn end_tangent(circle: &Circle, end: (f64, f64)) -> (f64, f64) {
    let radial = (end.0 - circle.centre.0, end.1 - circle.centre.1);
    if circle.clockwise {
        (radial.1, -radial.0)
    } else {
        (-radial.1, radial.0)
    }
}

/// The tolerance of MD21000/MD21010 for a radius: `max(CONST, FACTOR × r)`.
pub fn tolerance(radius: f64, error_const: f64, error_factor: f64) -> f64 {
    error_const.max(error_factor * radius)
}

fn sweep_degrees(start: (f64, f64), end: (f64, f64), centre: (f64, f64), clockwise: bool) -> f64 {
    let start_angle = (start.1 - centre.1).atan2(start.0 - centre.0);
    let end_angle = (end.1 - centre.1).atan2(end.0 - centre.0);
    let mut sweep = if clockwise {
        start_angle - end_angle
    } else {
        end_angle - start_angle
    };
    while sweep <= 1e-12 {
        sweep += std::f64::consts::TAU;
    }
    while sweep > std::f64::consts::TAU + 1e-12 {
        sweep -= std::f64::consts::TAU;
    }
    sweep.to_degrees()
}

/// A circle through `start` and `end` around `centre` (I/J/K), with the control's end-point check.
pub fn from_centre(
    start: (f64, f64),
    end: (f64, f64),
    centre: (f64, f64),
    clockwise: bool,
    error_const: f64,
    error_factor: f64,
) -> Result<Circle, CircleError> {
    let start_radius = (start.0 - centre.0).hypot(start.1 - centre.1);
    let end_radius = (end.0 - centre.0).hypot(end.1 - centre.1);
    let allowed = tolerance(start_radius, error_const, error_factor);
    let difference = (start_radius - end_radius).abs();
    if difference > allowed {
        return Err(CircleError::EndNotOnCircle {
            difference,
            tolerance: allowed,
        });
    }
    let full_circle = (start.0 - end.0).hypot(start.1 - end.1) <= 1e-9;
    let sweep = if full_circle {
        360.0
    } else {
        sweep_degrees(start, end, centre, clockwise)
    };
    Ok(Circle {
        centre,
        radius: start_radius,
        clockwise,
        sweep,
    })
}

/// A circle from `start` to `end` with the signed radius `CR` (positive: at most 180°, negative: more).
/// A chord longer than the diameter by no more than the tolerance gives the half circle on the chord
/// (reference §6.3, T91).
pub fn from_radius(
    start: (f64, f64),
    end: (f64, f64),
    signed_radius: f64,
    clockwise: bool,
    error_const: f64,
    error_factor: f64,
) -> Result<Circle, CircleError> {
    let radius = signed_radius.abs();
    let chord = (end.0 - start.0).hypot(end.1 - start.1);
    if chord <= 1e-9 {
        return Err(CircleError::RadiusFullCircle);
    }
    let allowed = tolerance(radius, error_const, error_factor);
    if chord - 2.0 * radius > allowed {
        return Err(CircleError::RadiusTooSmall { chord, radius });
    }
    let half_chord = chord / 2.0;
    let height = (radius * radius - half_chord * half_chord).max(0.0).sqrt();
    let radius = radius.max(half_chord);
    let middle = ((start.0 + end.0) / 2.0, (start.1 + end.1) / 2.0);
    // The unit normal to the chord, to its left when walking from start to end.
    let normal = (-(end.1 - start.1) / chord, (end.0 - start.0) / chord);
    // Turning counter-clockwise, the short arc (at most 180°) has its centre to the left of the
    // chord; clockwise, to the right. A negative CR asks for the long arc: the other side.
    let left = clockwise != (signed_radius > 0.0);
    let side = if left { 1.0 } else { -1.0 };
    let centre = (
        middle.0 + side * height * normal.0,
        middle.1 + side * height * normal.1,
    );
    Ok(Circle {
        centre,
        radius,
        clockwise,
        sweep: sweep_degrees(start, end, centre, clockwise),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn near(left: f64, right: f64) -> bool {
        (left - right).abs() < 1e-6
    }

    #[test]
    fn centre_from_i_and_j() {
        // T07: G2 X20 Y0 I10 J0 from (0, 0).
        let circle = from_centre((0.0, 0.0), (20.0, 0.0), (10.0, 0.0), true, 0.01, 0.001).unwrap();
        assert!(near(circle.radius, 10.0));
        assert!(near(circle.sweep, 180.0));
        // T08: G3 X0 Y10 around (0, 0) from (10, 0): 90° counter-clockwise.
        let circle = from_centre((10.0, 0.0), (0.0, 10.0), (0.0, 0.0), false, 0.01, 0.001).unwrap();
        assert!(near(circle.sweep, 90.0));
    }

    #[test]
    fn radius_picks_the_arc_by_its_sign() {
        // T10: G3 X10 Y10 CR=10 from (0, 0): centre (0, 10), 90°.
        let circle = from_radius((0.0, 0.0), (10.0, 10.0), 10.0, false, 0.01, 0.001).unwrap();
        assert!(
            near(circle.centre.0, 0.0) && near(circle.centre.1, 10.0),
            "{circle:?}"
        );
        assert!(near(circle.sweep, 90.0));
        // T11: CR=-10: centre (10, 0), 270°.
        let circle = from_radius((0.0, 0.0), (10.0, 10.0), -10.0, false, 0.01, 0.001).unwrap();
        assert!(
            near(circle.centre.0, 10.0) && near(circle.centre.1, 0.0),
            "{circle:?}"
        );
        assert!(near(circle.sweep, 270.0));
        // T12: half circle.
        let circle = from_radius((0.0, 0.0), (20.0, 0.0), 10.0, true, 0.01, 0.001).unwrap();
        assert!(near(circle.centre.0, 10.0) && near(circle.centre.1, 0.0));
        assert!(near(circle.sweep, 180.0));
    }

    #[test]
    fn opening_angle_cip_and_ct() {
        // T19: G3 X20 Y0 AR=180 from (0, 0): centre (10, 0), r 10.
        let circle = from_opening_angle((0.0, 0.0), (20.0, 0.0), 180.0, false).unwrap();
        assert!(
            near(circle.centre.0, 10.0) && near(circle.centre.1, 0.0) && near(circle.radius, 10.0)
        );
        // AR=90 counter-clockwise to (10, 10): the centre of T10; AR=270: the centre of T11.
        let circle = from_opening_angle((0.0, 0.0), (10.0, 10.0), 90.0, false).unwrap();
        assert!(
            near(circle.centre.0, 0.0) && near(circle.centre.1, 10.0),
            "{circle:?}"
        );
        let circle = from_opening_angle((0.0, 0.0), (10.0, 10.0), 270.0, false).unwrap();
        assert!(
            near(circle.centre.0, 10.0) && near(circle.centre.1, 0.0),
            "{circle:?}"
        );
        assert_eq!(
            from_opening_angle((0.0, 0.0), (10.0, 10.0), 360.0, false),
            Err(CircleError::OpeningAngleOutOfRange)
        );
        // T20: G3 I-10 J0 AR=90 from (10, 0): end (0, 10).
        let (end, _) = from_opening_angle_and_centre((10.0, 0.0), (0.0, 0.0), 90.0, false).unwrap();
        assert!(near(end.0, 0.0) && near(end.1, 10.0), "{end:?}");
        let (end, _) = from_opening_angle_and_centre((10.0, 0.0), (0.0, 0.0), 90.0, true).unwrap();
        assert!(near(end.0, 0.0) && near(end.1, -10.0), "{end:?}");
        // T22: CIP from (30, 40) through (40, 45) to (50, 40): centre (40, 32.5), r 12.5, clockwise.
        let circle = through_points((30.0, 40.0), (40.0, 45.0), (50.0, 40.0))
            .unwrap()
            .unwrap();
        assert!(
            near(circle.centre.0, 40.0) && near(circle.centre.1, 32.5) && near(circle.radius, 12.5)
        );
        assert!(circle.clockwise);
        // T24: collinear with the intermediate point beyond the end; between: a straight line.
        assert_eq!(
            through_points((0.0, 0.0), (30.0, 0.0), (20.0, 0.0)),
            Err(CircleError::IntermediatePointOnLine)
        );
        assert_eq!(
            through_points((0.0, 0.0), (10.0, 0.0), (20.0, 0.0)),
            Ok(None)
        );
        // T25: CT from (10, 0) after a move along +X to (20, 10): centre (10, 10), counter-clockwise.
        let circle = tangential((10.0, 0.0), (1.0, 0.0), (20.0, 10.0)).unwrap();
        assert!(near(circle.centre.0, 10.0) && near(circle.centre.1, 10.0) && !circle.clockwise);
        assert!(near(circle.sweep, 90.0));
        let tangent = end_tangent(&circle, (20.0, 10.0));
        assert!(near(tangent.0, 0.0) && tangent.1 > 0.0, "{tangent:?}");
        assert_eq!(tangential((0.0, 0.0), (1.0, 0.0), (5.0, 0.0)), None);
    }

    #[test]
    fn the_control_rejects_what_it_rejects() {
        // T13: end point = start point with CR.
        assert_eq!(
            from_radius((5.0, 5.0), (5.0, 5.0), 10.0, true, 0.01, 0.001),
            Err(CircleError::RadiusFullCircle)
        );
        // T14: CR too small for the chord.
        assert!(matches!(
            from_radius((0.0, 0.0), (20.0, 0.0), 5.0, true, 0.01, 0.001),
            Err(CircleError::RadiusTooSmall { .. })
        ));
        // T91: a chord 0.004 longer than 2r is accepted as a half circle on the chord.
        let circle = from_radius((0.0, 0.0), (20.004, 0.0), 10.0, true, 0.01, 0.001).unwrap();
        assert!(near(circle.centre.0, 10.002) && near(circle.radius, 10.002));
        // T15 accepted, T16 rejected, T17 scaled with the radius.
        assert!(from_centre((0.0, 0.0), (10.0, 10.005), (10.0, 0.0), true, 0.01, 0.001).is_ok());
        assert!(from_centre((0.0, 0.0), (10.0, 10.05), (10.0, 0.0), true, 0.01, 0.001).is_err());
        assert!(from_centre((0.0, 0.0), (100.0, 100.05), (100.0, 0.0), true, 0.01, 0.001).is_ok());
        assert!(from_centre((0.0, 0.0), (100.0, 100.2), (100.0, 0.0), true, 0.01, 0.001).is_err());
    }
}
