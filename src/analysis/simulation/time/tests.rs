use super::*;
use crate::analysis::program_kind::ProgramKind;
use crate::analysis::whole_program::visit_moves_and_dwells;
use crate::config::timing::TimeModelKind;
use crate::diagnostics::Code;

/// The time of each move and dwell of `text` in program order: (1-based line, seconds), and the
/// codes of the findings.
fn times_with_findings(
    text: &str,
    config: &MachineConfig,
) -> (Vec<(usize, Option<f64>)>, Vec<Code>) {
    let model = TimeModel::new(config);
    let mut times = Vec::new();
    let findings = visit_moves_and_dwells(text, config, ProgramKind::Main, |movement| {
        times.push((movement.line + 1, model.time_of(movement).seconds));
    });
    let codes = findings.iter().map(|item| item.diagnostic.code).collect();
    (times, codes)
}

fn times(text: &str, config: &MachineConfig) -> Vec<(usize, Option<f64>)> {
    times_with_findings(text, config).0
}

/// The time of the move (or dwell) on 1-based `line`.
fn at(times: &[(usize, Option<f64>)], line: usize) -> Option<f64> {
    let found: Vec<_> = times.iter().filter(|(at, _)| *at == line).collect();
    assert_eq!(found.len(), 1, "one move on line {line}: {times:?}");
    found[0].1
}

fn close(actual: Option<f64>, expected: f64) {
    let actual = actual.expect("a known time");
    assert!(
        (actual - expected).abs() < 5e-4,
        "expected {expected} s, found {actual} s"
    );
}

#[test]
fn g94_lines_arcs_and_dwell_in_seconds_t116() {
    let text =
        "N10 G17 G90 G94 G1 X0 Y0 F500\nN20 X100\nN30 G3 X120 Y20 I0 J20 F200\nN40 G4 F2.5\n";
    let times = times(text, &MachineConfig::mill());
    // The first move starts where the program does not say.
    assert_eq!(at(&times, 1), None);
    close(at(&times, 2), 12.0);
    close(at(&times, 3), 9.4248);
    close(at(&times, 4), 2.5);
}

#[test]
fn feed_per_revolution_and_dwell_in_revolutions_t117() {
    let text = "N10 G17 G90 G0 X0 Y0\nN20 M3 S1000 G97\nN30 G95 G1 X50 F0.2\nN40 G4 S30\n";
    let times = times(text, &MachineConfig::mill());
    close(at(&times, 3), 15.0);
    close(at(&times, 4), 1.8);
}

#[test]
fn inverse_time_rotary_axes_and_the_feed_programmed_again_t118() {
    let text = "N10 G90 G0 X0 Y0 A0\nN20 G93 G1 X100 F2\nN30 G94 G1 A90 F3600\nN40 G93 G1 X0\n";
    let (times, codes) = times_with_findings(text, &MachineConfig::mill());
    close(at(&times, 2), 30.0);
    close(at(&times, 3), 1.5);
    assert_eq!(at(&times, 4), None);
    assert_eq!(
        codes
            .iter()
            .filter(|code| **code == Code::FeedNotReprogrammed)
            .count(),
        1,
        "{codes:?}"
    );
}

#[test]
fn inverse_time_ignores_the_length_and_inch_units() {
    let text = "G90 G0 X0 Y0\nG700 G93 G1 X1 F4\nX3 F4\n";
    let times = times(text, &MachineConfig::mill());
    close(at(&times, 2), 15.0);
    close(at(&times, 3), 15.0);
}

#[test]
fn a_feed_switch_with_a_new_feed_is_no_finding() {
    let text = "G90 G0 X0\nG95 G1 X10 F0.1 S100\nG94 X20 F100\n";
    let (times, codes) = times_with_findings(text, &MachineConfig::mill());
    assert!(!codes.contains(&Code::FeedNotReprogrammed), "{codes:?}");
    close(at(&times, 2), 60.0);
    close(at(&times, 3), 6.0);
}

#[test]
fn constant_cutting_speed_integrates_exactly_with_and_without_the_limit_t119() {
    let text = "N10 G18 G90 DIAMON G0 X100 Z0\nN20 G96 S100 LIMS=1000 F0.1 M3\nN30 G1 X20\n";
    close(at(&times(text, &MachineConfig::turn()), 3), 45.8985);
    let text = text.replace("LIMS=1000", "LIMS=2000");
    close(at(&times(&text, &MachineConfig::turn()), 3), 45.2389);
}

#[test]
fn a_line_across_the_axis_adds_both_sides() {
    // From radius 10 to -10 at the limit everywhere below radius 15.9: 20 mm at 0.1 mm/rev, 1000 rpm.
    let text = "G18 G90 DIAMOF G0 X10 Z0\nG96 S100 LIMS=1000 F0.1\nG1 X-10\n";
    close(at(&times(text, &MachineConfig::turn()), 3), 12.0);
}

#[test]
fn constant_cutting_speed_on_an_arc_is_integrated_numerically() {
    // A quarter circle from radius 50 to radius 30 about (Z-20, X50), clockwise in (Z, X).
    let text = "G18 G90 DIAMOF G0 X50 Z0\nG96 S100 LIMS=3000 F0.1\nG2 X30 Z-20 I0 K-20\n";
    let seconds = at(&times(text, &MachineConfig::turn()), 3);
    // Independently: midpoint sums along the circle.
    let steps = 200_000;
    let mut minutes = 0.0;
    let length = 20.0 * std::f64::consts::FRAC_PI_2;
    for step in 0..steps {
        let angle = (step as f64 + 0.5) / steps as f64 * std::f64::consts::FRAC_PI_2;
        // G2 in G18 from (Z0, X50) about (Z-20, X50): X = 50 - 20·sin(angle).
        let radius: f64 = 50.0 - 20.0 * angle.sin();
        let speed = (1000.0 * 100.0 / (std::f64::consts::PI * 2.0 * radius)).min(3000.0);
        minutes += length / steps as f64 / (0.1 * speed);
    }
    close(seconds, minutes * 60.0);
}

#[test]
fn g97_keeps_the_speed_g96_reached_last() {
    // At diameter 31.831 mm, 100 m/min give 1000 rpm.
    let text = "G18 G90 DIAMON G0 X31.830989 Z0\nG96 S100 LIMS=5000 F0.1\nG97\nG95 G1 Z-10 F0.1\n";
    close(at(&times(text, &MachineConfig::turn()), 4), 6.0);
}

#[test]
fn unknown_feed_speed_limit_or_start_make_the_time_unknown() {
    let mill = MachineConfig::mill();
    // The feed is an unknown variable.
    let unknown_feed = times("G90 G0 X0\nG1 X10 F=$AA_IW[X]\n", &mill);
    assert_eq!(at(&unknown_feed, 2), None);
    // Feed per revolution without a spindle speed.
    let no_speed = times("G90 G0 X0\nG95 G1 X10 F0.1\n", &mill);
    assert_eq!(at(&no_speed, 2), None);
    // G96 without LIMS nor a configured limit: the speed near the axis is not known.
    let no_limit = times(
        "G18 G90 G0 X100 Z0\nG96 S100 F0.1\nG1 X20\n",
        &MachineConfig::turn(),
    );
    assert_eq!(at(&no_limit, 3), None);
    // With the limit configured it is.
    let mut turn = MachineConfig::turn();
    turn.timing.max_spindle_speed = Some(1000.0);
    let configured = times("G18 G90 DIAMON G0 X100 Z0\nG96 S100 F0.1\nG1 X20\n", &turn);
    close(at(&configured, 3), 45.8985);
    // A dwell in revolutions without a spindle speed.
    let dwell = times("G4 S10\n", &mill);
    assert_eq!(at(&dwell, 1), None);
    // An incremental move of an axis whose position is unknown.
    let unknown_end = times("G90 G0 X10\nG91 Y5\n", &mill);
    assert_eq!(at(&unknown_end, 2), None);
    // After an unknown call the spindle speed is unknown.
    let call = times(
        "G90 G0 X0\nS1000 G95\nUNKNOWN_SUB\nG0 X0\nG1 X10 F0.1\n",
        &mill,
    );
    assert_eq!(at(&call, 5), None);
}

#[test]
fn rapid_traverse_by_the_slowest_axis_and_the_trapezoid_t120() {
    let mut config = MachineConfig::mill();
    config.timing.max_velocity = vec![("X".into(), 20000.0), ("Y".into(), 10000.0)];
    config.timing.max_acceleration = vec![("X".into(), 2.0), ("Y".into(), 2.0)];
    let text = "N10 G17 G90 G0 X0 Y0\nN20 X200 Y50\nN30 X205\n";
    let base = times(text, &config);
    close(at(&base, 2), 0.6);
    close(at(&base, 3), 0.015);
    config.timing.model = TimeModelKind::Trapezoid;
    let trapezoid = times(text, &config);
    close(at(&trapezoid, 2), 0.7667);
    close(at(&trapezoid, 3), 0.1);
    // Without an acceleration for Y the trapezoid cannot time a move of Y.
    config.timing.max_acceleration = vec![("X".into(), 2.0)];
    let partial = times(text, &config);
    assert_eq!(at(&partial, 2), None);
    close(at(&partial, 3), 0.1);
}

#[test]
fn rapid_traverse_defaults_to_10000_per_axis() {
    let times = times("G90 G0 X0 Y0\nX100 Y50\n", &MachineConfig::mill());
    close(at(&times, 2), 0.6);
}

#[test]
fn totals_count_unknown_moves_apart() {
    let mut totals = TimeTotals::default();
    totals.add(MoveTime {
        kind: TimeKind::Feed,
        seconds: Some(2.0),
    });
    totals.add(MoveTime {
        kind: TimeKind::Rapid,
        seconds: Some(0.5),
    });
    totals.add(MoveTime {
        kind: TimeKind::Dwell,
        seconds: Some(1.0),
    });
    totals.add(MoveTime {
        kind: TimeKind::Feed,
        seconds: None,
    });
    assert_eq!(totals.total_s, 3.5);
    assert_eq!(
        (totals.feed_s, totals.rapid_s, totals.dwell_s),
        (2.0, 0.5, 1.0)
    );
    assert_eq!(totals.unknown_moves, 1);
}

#[test]
fn the_antiderivative_is_continuous_at_the_limit() {
    let (cutting, limit) = (100.0, 1000.0);
    let capped = 1000.0 * cutting / (2.0 * std::f64::consts::PI * limit);
    let below = cutting_speed::antiderivative(capped - 1e-9, cutting, limit);
    let above = cutting_speed::antiderivative(capped + 1e-9, cutting, limit);
    assert!((below - above).abs() < 1e-9, "{below} {above}");
    assert_eq!(
        cutting_speed::antiderivative(-5.0, cutting, limit),
        -cutting_speed::antiderivative(5.0, cutting, limit)
    );
}
