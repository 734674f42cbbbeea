//! The drilling cycles CYCLE81 to CYCLE89 and CYCLE840 as a list of steps on the tool axis
//! (reference §16.2 to §16.4, parameter lists §8.7): the depth rules of DP and DPR, the alarm 61101
//! of planes on the wrong side, and the sequence of each cycle. Only numbers are computed here; the
//! steps become NC blocks in `mod.rs`.

use super::super::paths::Argument;

/// The feed of a feed move of a cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Feed {
    /// The feed active in the calling program (the cycle programs none).
    Modal,
    /// A feed the cycle programs (in the program's units).
    Programmed(f64),
    /// A feed the analysis does not know (tapping at pitch times speed, a parameter not known).
    Unknown,
}

/// One step of a drilling cycle; positions on the tool axis are absolute.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Step {
    /// `G0` on the tool axis.
    Rapid(f64),
    /// `G1` on the tool axis.
    Feed(f64, Feed),
    /// `G4`: seconds when positive or zero, revolutions (its magnitude) when negative.
    Dwell(f64),
    /// Spindle stop and program stop (`M5 M0`): the operator continues with NC start.
    Stop,
    /// `G0` by these increments of the first and second plane axis and the tool axis (the lift-off
    /// of CYCLE86).
    RapidBy([f64; 3]),
}

/// What the cycle does with its arguments.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Plan {
    /// The steps in order, and whether the modal feed after the cycle is unknown (the cycle
    /// programmed a feed of its own, which a `SAVE` does not restore, reference §20 #42).
    Steps {
        steps: Vec<Step>,
        feed_after_unknown: bool,
    },
    /// Alarm 61101: the reference plane is defined incorrectly; the cycle makes no motion.
    ReferencePlaneWrong,
    /// A parameter that decides the motion is not known: the tool axis is unknown afterwards.
    Unknown,
}

/// The plan of a cycle and whether DP and DPR were both given and disagree (DPR wins).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Outcome {
    pub plan: Plan,
    pub depth_disagrees: Option<(f64, f64)>,
}

/// The value of parameter `index`: 0 when omitted (reference §17.1), `None` when not known.
pub(super) fn parameter(arguments: &[Argument], index: usize) -> Option<f64> {
    match arguments.get(index) {
        None | Some(Argument::Omitted) => Some(0.0),
        Some(Argument::Given(value)) => *value,
    }
}

/// The cycles modelled here.
pub(super) const DRILLING_CYCLES: [&str; 10] = [
    "CYCLE81", "CYCLE82", "CYCLE83", "CYCLE84", "CYCLE840", "CYCLE85", "CYCLE86", "CYCLE87",
    "CYCLE88", "CYCLE89",
];

/// The plan of drilling cycle `name` with `arguments` (RTP, RFP, SDIS, DP, DPR, ... in the order of
/// reference §8.7).
pub(super) fn plan(name: &str, arguments: &[Argument]) -> Outcome {
    let value = |index| parameter(arguments, index);
    let unknown = Outcome {
        plan: Plan::Unknown,
        depth_disagrees: None,
    };
    let (Some(rtp), Some(rfp), Some(sdis), Some(dp), Some(dpr)) =
        (value(0), value(1), value(2), value(3), value(4))
    else {
        return unknown;
    };
    let (dp, depth_disagrees) = match final_depth(rtp, rfp, dp, dpr) {
        Some(depth) => depth,
        None => {
            return Outcome {
                plan: Plan::ReferencePlaneWrong,
                depth_disagrees: None,
            }
        }
    };
    if rfp == dp {
        // The cycle makes no motion (reference §16.2).
        return Outcome {
            plan: Plan::Steps {
                steps: Vec::new(),
                feed_after_unknown: false,
            },
            depth_disagrees,
        };
    }
    // The safety plane lies SDIS before the reference plane, on the side away from the depth.
    let safety = rfp + sdis.abs() * (rfp - dp).signum();
    // A dwell whose time is not known is left out: it changes no position.
    let dwell = |index| value(index).filter(|time| *time != 0.0).map(Step::Dwell);
    // In to the depth, the dwell DTB, out to the safety plane at a feed, up to the retraction plane:
    // the sequence of tapping, reaming and boring with a dwell, which differ in their feeds only.
    let in_dwell_out = |feed_in, feed_out| -> Vec<Step> {
        [
            Some(Step::Rapid(safety)),
            Some(Step::Feed(dp, feed_in)),
            dwell(5),
            Some(Step::Feed(safety, feed_out)),
            Some(Step::Rapid(rtp)),
        ]
        .into_iter()
        .flatten()
        .collect()
    };
    let mut feed_after_unknown = false;
    let steps: Vec<Step> = match name {
        "CYCLE81" => vec![
            Step::Rapid(safety),
            Step::Feed(dp, Feed::Modal),
            Step::Rapid(rtp),
        ],
        "CYCLE82" => [
            Some(Step::Rapid(safety)),
            Some(Step::Feed(dp, Feed::Modal)),
            dwell(5),
            Some(Step::Rapid(rtp)),
        ]
        .into_iter()
        .flatten()
        .collect(),
        "CYCLE83" => match deep_hole(arguments, rfp, safety, dp) {
            Some(mut steps) => {
                steps.extend(dwell(8));
                steps.push(Step::Rapid(rtp));
                steps
            }
            None => return unknown,
        },
        // Rigid tapping (G331/G332): the feed is the pitch times the spindle speed, not known here;
        // the retraction goes back to the safety plane.
        "CYCLE84" => in_dwell_out(Feed::Unknown, Feed::Unknown),
        // Tapping with a compensating chuck (G63) at the programmed feed, out with the spindle
        // reversed.
        "CYCLE840" => in_dwell_out(Feed::Modal, Feed::Modal),
        // Reaming: in at FFR, out to the safety plane at RFF.
        "CYCLE85" => {
            let mut feed = |index| match value(index) {
                Some(feed) if feed > 0.0 => {
                    feed_after_unknown = true;
                    Feed::Programmed(feed)
                }
                Some(_) => Feed::Modal,
                None => {
                    feed_after_unknown = true;
                    Feed::Unknown
                }
            };
            let (feed_in, feed_out) = (feed(6), feed(7));
            in_dwell_out(feed_in, feed_out)
        }
        // Boring with an oriented spindle stop: lift off by RPA, RPO, RPAP, retract, and move back
        // to the hole's axis at the retraction plane.
        "CYCLE86" => {
            let (Some(rpa), Some(rpo), Some(rpap)) = (value(7), value(8), value(9)) else {
                return unknown;
            };
            [
                Some(Step::Rapid(safety)),
                Some(Step::Feed(dp, Feed::Modal)),
                dwell(5),
                Some(Step::RapidBy([rpa, rpo, rpap])),
                Some(Step::Rapid(rtp)),
                Some(Step::RapidBy([-rpa, -rpo, 0.0])),
            ]
            .into_iter()
            .flatten()
            .collect()
        }
        // Boring with a spindle stop and a program stop at the bottom; the retraction follows the
        // NC start.
        "CYCLE87" => vec![
            Step::Rapid(safety),
            Step::Feed(dp, Feed::Modal),
            Step::Stop,
            Step::Rapid(rtp),
        ],
        "CYCLE88" => [
            Some(Step::Rapid(safety)),
            Some(Step::Feed(dp, Feed::Modal)),
            dwell(5),
            Some(Step::Stop),
            Some(Step::Rapid(rtp)),
        ]
        .into_iter()
        .flatten()
        .collect(),
        // Boring with a dwell, out at the feed.
        "CYCLE89" => in_dwell_out(Feed::Modal, Feed::Modal),
        _ => return unknown,
    };
    Outcome {
        plan: Plan::Steps {
            steps,
            feed_after_unknown,
        },
        depth_disagrees,
    }
}

/// The final depth after the depth rules of reference §16.2, with (DP, DP from DPR) when both were
/// given and disagree; `None` for alarm 61101.
fn final_depth(rtp: f64, rfp: f64, dp: f64, dpr: f64) -> Option<(f64, Option<(f64, f64)>)> {
    let dpr = dpr.abs();
    let mut disagrees = None;
    let dp = if dpr != 0.0 {
        if rtp == rfp {
            // The direction of DPR comes from the retraction plane, which is the reference plane.
            return None;
        }
        let from_relative = rfp - (rtp - rfp).signum() * dpr;
        if dp != 0.0 && (dp - from_relative).abs() > 1e-9 * dp.abs().max(1.0) {
            disagrees = Some((dp, from_relative));
        }
        from_relative
    } else {
        dp
    };
    let retraction = rtp - rfp;
    if rfp != dp && retraction != 0.0 && retraction.signum() != (rfp - dp).signum() {
        return None;
    }
    Some((dp, disagrees))
}

/// Pecks of the deep-hole cycle at most (a degression that would need more is cut short: the last
/// infeeds are made equal).
const MAX_PECKS: usize = 1000;

/// The infeeds of CYCLE83 (reference §16.4): an approximation. The first depth is FDPR relative to
/// the reference plane or FDEP absolute (the whole depth when neither is given); each further
/// infeed is smaller by DAM, not below DAM; VARI = 1 (chip removal) returns to the safety plane,
/// dwells DTS and goes back in rapid to an anticipation distance (`_DIS1`, else 0.6 mm up to 30 mm
/// of depth, depth / 50 up to 7 mm beyond) above the last depth; VARI = 0 (chip breaking) retracts
/// by `_VRT` (else 1 mm). `None` when a parameter that decides the motion is not known.
fn deep_hole(arguments: &[Argument], rfp: f64, safety: f64, dp: f64) -> Option<Vec<Step>> {
    let value = |index| parameter(arguments, index);
    let (fdep, fdpr, dam, vari, vrt, dis1) = (
        value(5)?,
        value(6)?,
        value(7)?,
        value(11)?,
        value(14)?,
        value(16)?,
    );
    let direction = (dp - rfp).signum();
    let total = (dp - rfp).abs();
    let first = if fdpr != 0.0 {
        rfp + direction * fdpr.abs()
    } else if fdep != 0.0 {
        fdep
    } else {
        dp
    };
    let first_infeed = (first - rfp) * direction;
    let first_infeed = if first_infeed > 0.0 && first_infeed < total {
        first_infeed
    } else {
        total
    };
    let dam = dam.abs();
    let smallest = (total / MAX_PECKS as f64).max(dam);
    let mut depths = vec![first_infeed];
    let mut infeed = first_infeed;
    let mut reached = first_infeed;
    while reached < total && depths.len() < MAX_PECKS {
        infeed = (infeed - dam).max(smallest);
        reached = (reached + infeed).min(total);
        depths.push(reached);
    }
    if reached < total {
        depths.push(total);
    }
    let removal = (vari.abs() as i64) % 10 == 1;
    let retraction = if vrt > 0.0 { vrt } else { 1.0 };
    let anticipation = if dis1 > 0.0 {
        dis1
    } else if total <= 30.0 {
        0.6
    } else {
        (total / 50.0).min(7.0)
    };
    let at = |depth: f64| rfp + direction * depth;
    let mut steps = vec![Step::Rapid(safety)];
    let mut previous: Option<f64> = None;
    for depth in depths {
        if let Some(last) = previous {
            if removal {
                steps.push(Step::Rapid(safety));
                if let Some(time) = value(9).filter(|time| *time != 0.0) {
                    steps.push(Step::Dwell(time));
                }
                steps.push(Step::Rapid(at((last - anticipation).max(0.0))));
            } else {
                steps.push(Step::Rapid(at((last - retraction).max(0.0))));
            }
        }
        steps.push(Step::Feed(at(depth), Feed::Modal));
        previous = Some(depth);
    }
    Some(steps)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn given(values: &[Option<f64>]) -> Vec<Argument> {
        values
            .iter()
            .map(|value| match value {
                Some(value) => Argument::Given(Some(*value)),
                None => Argument::Omitted,
            })
            .collect()
    }

    #[test]
    fn dpr_wins_over_dp_and_the_disagreement_is_told() {
        let outcome = plan(
            "CYCLE81",
            &given(&[Some(10.0), Some(0.0), Some(1.0), Some(-8.0), Some(5.0)]),
        );
        assert_eq!(outcome.depth_disagrees, Some((-8.0, -5.0)));
        let Plan::Steps { steps, .. } = outcome.plan else {
            panic!("a plan with steps")
        };
        assert_eq!(
            steps,
            vec![
                Step::Rapid(1.0),
                Step::Feed(-5.0, Feed::Modal),
                Step::Rapid(10.0)
            ]
        );
    }

    #[test]
    fn planes_on_the_wrong_side_are_alarm_61101() {
        let outcome = plan(
            "CYCLE81",
            &given(&[Some(-10.0), Some(0.0), Some(1.0), Some(-5.0)]),
        );
        assert_eq!(outcome.plan, Plan::ReferencePlaneWrong);
    }

    #[test]
    fn deep_hole_pecks_reach_the_final_depth_and_end_at_the_retraction_plane() {
        // RTP 10, RFP 0, SDIS 1, DP -20, FDEP -8, DAM 2, VARI 1.
        let arguments = given(&[
            Some(10.0),
            Some(0.0),
            Some(1.0),
            Some(-20.0),
            None,
            Some(-8.0),
            None,
            Some(2.0),
            None,
            None,
            None,
            Some(1.0),
        ]);
        let Plan::Steps { steps, .. } = plan("CYCLE83", &arguments).plan else {
            panic!("a plan with steps")
        };
        let feeds: Vec<f64> = steps
            .iter()
            .filter_map(|step| match step {
                Step::Feed(depth, _) => Some(*depth),
                _ => None,
            })
            .collect();
        // Infeeds 8, 6, 4, 2: depths -8, -14, -18, -20.
        assert_eq!(feeds, vec![-8.0, -14.0, -18.0, -20.0]);
        assert_eq!(steps.first(), Some(&Step::Rapid(1.0)));
        assert_eq!(steps.last(), Some(&Step::Rapid(10.0)));
    }
}
