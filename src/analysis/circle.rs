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
