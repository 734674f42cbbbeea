//! Tests of the corner geometry against the reference's worked examples (§14.3, T106-T110) and
//! constructions checked by hand.

use super::corner_geometry::{chamfer, round, Element, NoCorner};

fn close(actual: (f64, f64), expected: (f64, f64)) -> bool {
    (actual.0 - expected.0).abs() < 1e-4 && (actual.1 - expected.1).abs() < 1e-4
}

fn line(start: (f64, f64), end: (f64, f64)) -> Element {
    Element::Line { start, end }
}

#[test]
fn a_right_angle_left_turn_is_rounded_counter_clockwise() {
    let corner = round(
        &line((0.0, 0.0), (50.0, 0.0)),
        &line((50.0, 0.0), (50.0, 50.0)),
        5.0,
    )
    .unwrap();
    assert!(close(corner.first_end, (45.0, 0.0)) && close(corner.second_start, (50.0, 5.0)));
    let rounding = corner.rounding.unwrap();
    assert!(close(rounding.centre, (45.0, 5.0)));
    assert!(rounding.counter_clockwise && (rounding.sweep - 90.0).abs() < 1e-9);
    assert!(!corner.reduced);
}

#[test]
fn a_right_turn_is_rounded_clockwise() {
    // T108: 45° line into a 0° line, a right turn of 45°.
    let corner = round(
        &line((0.0, 0.0), (20.0, 20.0)),
        &line((20.0, 20.0), (60.0, 20.0)),
        5.0,
    )
    .unwrap();
    let rounding = corner.rounding.unwrap();
    assert!(!rounding.counter_clockwise);
    assert!(close(corner.first_end, (18.5355, 18.5355)));
    assert!(close(corner.second_start, (22.0711, 20.0)));
    assert!(close(rounding.centre, (22.0711, 15.0)));
    assert!((rounding.sweep - 45.0).abs() < 1e-6);
}

#[test]
fn a_line_into_an_arc_keeps_the_arc_circle() {
    // T110: the rounding touches the line and the arc around (70, 0) with radius 20.
    let arc = Element::Arc {
        start: (50.0, 0.0),
        end: (70.0, 20.0),
        centre: (70.0, 0.0),
        radius: 20.0,
        counter_clockwise: false,
        sweep: 90.0,
    };
    let corner = round(&line((0.0, 0.0), (50.0, 0.0)), &arc, 5.0).unwrap();
    assert!(close(corner.first_end, (45.5051, 0.0)));
    assert!(close(corner.second_start, (50.4041, 4.0)));
    let rounding = corner.rounding.unwrap();
    assert!(close(rounding.centre, (45.5051, 5.0)) && rounding.counter_clockwise);
    assert!((rounding.sweep - 78.4630).abs() < 1e-3);
}

#[test]
fn an_arc_into_a_line_and_two_arcs_are_rounded() {
    // The arc of T110 run backwards (counter-clockwise from (70, 20) to (50, 0)), then the line back
    // to its start: the same corner from the other side, a right turn, with the same tangent points.
    let arc = Element::Arc {
        start: (70.0, 20.0),
        end: (50.0, 0.0),
        centre: (70.0, 0.0),
        radius: 20.0,
        counter_clockwise: true,
        sweep: 90.0,
    };
    let corner = round(&arc, &line((50.0, 0.0), (0.0, 0.0)), 5.0).unwrap();
    assert!(close(corner.first_end, (50.4041, 4.0)));
    assert!(close(corner.second_start, (45.5051, 0.0)));
    assert!(!corner.rounding.unwrap().counter_clockwise);
    // Two clockwise arcs meeting at (70, 20) at a right angle (left turn).
    let first = Element::Arc {
        start: (50.0, 0.0),
        end: (70.0, 20.0),
        centre: (70.0, 0.0),
        radius: 20.0,
        counter_clockwise: false,
        sweep: 90.0,
    };
    let second = Element::Arc {
        start: (70.0, 20.0),
        end: (110.0, 20.0),
        centre: (90.0, 20.0),
        radius: 20.0,
        counter_clockwise: false,
        sweep: 180.0,
    };
    let corner = round(&first, &second, 3.0).unwrap();
    let rounding = corner.rounding.unwrap();
    assert!(close(rounding.centre, (67.1742, 22.8258)));
    assert!(rounding.counter_clockwise);
    // Both tangent points lie on their circles.
    let on = |point: (f64, f64), centre: (f64, f64)| {
        ((point.0 - centre.0).hypot(point.1 - centre.1) - 20.0).abs() < 1e-9
    };
    assert!(on(corner.first_end, (70.0, 0.0)) && on(corner.second_start, (90.0, 20.0)));
}

#[test]
fn a_rounding_that_does_not_fit_is_reduced_to_the_shorter_line() {
    let corner = round(
        &line((0.0, 0.0), (5.0, 0.0)),
        &line((5.0, 0.0), (5.0, 10.0)),
        50.0,
    )
    .unwrap();
    assert!(corner.reduced);
    assert!((corner.rounding.unwrap().radius - 5.0).abs() < 1e-6);
    assert!(close(corner.first_end, (0.0, 0.0)) && close(corner.second_start, (5.0, 5.0)));
}

#[test]
fn reversals_and_tangential_transitions_insert_nothing() {
    let forward = line((0.0, 0.0), (10.0, 0.0));
    assert_eq!(
        round(&forward, &line((10.0, 0.0), (0.0, 0.0)), 1.0),
        Err(NoCorner::Reversal)
    );
    assert_eq!(
        round(&forward, &line((10.0, 0.0), (20.0, 0.0)), 1.0),
        Err(NoCorner::Tangential)
    );
    assert_eq!(
        chamfer(&forward, &line((10.0, 0.0), (0.0, 0.0)), 1.0, false),
        Err(NoCorner::Reversal)
    );
}

#[test]
fn chamfers_have_equal_legs_or_the_programmed_length() {
    let first = line((50.0, 50.0), (100.0, 50.0));
    let second = line((100.0, 50.0), (100.0, 100.0));
    // T107: CHF=5 at a right angle gives legs of 3.5355 and a chamfer 5 long.
    let corner = chamfer(&first, &second, 5.0, true).unwrap();
    assert!(
        close(corner.first_end, (96.4645, 50.0)) && close(corner.second_start, (100.0, 53.5355))
    );
    let length = (corner.second_start.0 - corner.first_end.0)
        .hypot(corner.second_start.1 - corner.first_end.1);
    assert!((length - 5.0).abs() < 1e-9);
    let corner = chamfer(&first, &second, 5.0, false).unwrap();
    assert!(close(corner.first_end, (95.0, 50.0)) && close(corner.second_start, (100.0, 55.0)));
    assert!(corner.rounding.is_none());
}
