//! `preview --format svg`: the toolpath in the working plane as an SVG picture. Rapid moves are dashed,
//! feed moves solid, arcs drawn as arcs, every segment titled with its line; the picture is scaled to
//! fit, and above a number of segments runs of moves are thinned out so that a program of a million
//! blocks still gives a small file.

use crate::analysis::Move;
use crate::config::{AxisKind, MachineConfig};
use std::fmt::Write as _;
use std::io::{self, Write};

/// One drawable piece of the toolpath in plane coordinates (horizontal, vertical).
struct Segment {
    line: usize,
    rapid: bool,
    from: (f64, f64),
    to: (f64, f64),
    /// Radius, whether counter-clockwise, sweep in degrees, centre.
    arc: Option<(f64, bool, f64, (f64, f64))>,
    /// Lines of the moves this segment stands for, when thinned.
    last_line: usize,
}

/// The value of `axis` in a list of axis values, as a radius on transverse axes shown as diameters.
fn plane_value(values: &[(std::sync::Arc<str>, f64)], axis: &str, halve: bool) -> Option<f64> {
    values
        .iter()
        .find(|(name, _)| name.as_ref() == axis)
        .map(|(_, value)| if halve { value / 2.0 } else { *value })
}

/// Coordinates beyond this (in mm or inch) are no toolpath a machine follows, and the picture's extent
/// computed from them could overflow to infinity (an SVG with `viewBox="-inf NaN inf inf"`, found with
/// hostile inputs): segments reaching beyond it are left out and counted in the title.
const MAX_DRAWN_COORDINATE: f64 = 1e15;

/// The segments of the picture, and how many were left out for coordinates beyond
/// [`MAX_DRAWN_COORDINATE`].
fn segments(config: &MachineConfig, moves: &[Move], plane: (&str, &str)) -> (Vec<Segment>, usize) {
    let transverse = |axis: &str| {
        config
            .axis(axis)
            .is_some_and(|axis| axis.kind == AxisKind::Transverse)
    };
    let mut out = Vec::new();
    let mut left_out = 0;
    for movement in moves {
        if movement.plane != Some((plane.0, plane.1)) && movement.plane.is_some() {
            continue;
        }
        let halve = |axis: &str| transverse(axis) && movement.transverse_as_diameter;
        let point = |values: &[(std::sync::Arc<str>, f64)]| {
            Some((
                plane_value(values, plane.0, halve(plane.0))?,
                plane_value(values, plane.1, halve(plane.1))?,
            ))
        };
        let (Some(from), Some(to)) = (point(&movement.start), point(&movement.end)) else {
            continue;
        };
        let arc = movement.arc.as_ref().and_then(|arc| {
            let centre = point(&arc.centre)?;
            Some((arc.radius, !arc.clockwise, arc.sweep, centre))
        });
        let drawable =
            |(x, y): (f64, f64)| x.abs() <= MAX_DRAWN_COORDINATE && y.abs() <= MAX_DRAWN_COORDINATE;
        let arc_drawable = arc.is_none_or(|(radius, _, _, centre)| {
            drawable(centre) && radius <= MAX_DRAWN_COORDINATE
        });
        if !(drawable(from) && drawable(to) && arc_drawable) {
            left_out += 1;
            continue;
        }
        out.push(Segment {
            line: movement.line,
            rapid: movement.motion == "G0",
            from,
            to,
            arc,
            last_line: movement.line,
        });
    }
    (out, left_out)
}

/// Joins runs of `stride` consecutive segments of the same kind into straight segments from the
/// first start to the last end.
fn thin(segments: Vec<Segment>, stride: usize) -> Vec<Segment> {
    let mut out: Vec<Segment> = Vec::new();
    let mut count_in_run = 0;
    for segment in segments {
        if let Some(last) = out.last_mut() {
            let continues = last.rapid == segment.rapid
                && (last.to.0 - segment.from.0).abs() < 1e-9
                && (last.to.1 - segment.from.1).abs() < 1e-9;
            if continues && count_in_run < stride {
                last.to = segment.to;
                last.arc = None;
                last.last_line = segment.line;
                count_in_run += 1;
                continue;
            }
        }
        count_in_run = 1;
        out.push(segment);
    }
    out
}

pub(crate) fn write_svg(
    stdout: &mut dyn Write,
    config: &MachineConfig,
    moves: &[Move],
    max_segments: usize,
) -> io::Result<()> {
    let plane = moves
        .iter()
        .find_map(|movement| movement.plane)
        .unwrap_or(("X", "Y"));
    let (mut pieces, left_out) = segments(config, moves, plane);
    if pieces.len() > max_segments.max(1) {
        let stride = pieces.len().div_ceil(max_segments.max(1));
        pieces = thin(pieces, stride);
    }
    let (mut min_x, mut min_y, mut max_x, mut max_y) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
    let mut include = |x: f64, y: f64| {
        min_x = min_x.min(x);
        max_x = max_x.max(x);
        min_y = min_y.min(y);
        max_y = max_y.max(y);
    };
    for piece in &pieces {
        include(piece.from.0, piece.from.1);
        include(piece.to.0, piece.to.1);
        if let Some((radius, _, _, centre)) = piece.arc {
            // The arc stays within its circle's bounding box.
            include(centre.0 - radius, centre.1 - radius);
            include(centre.0 + radius, centre.1 + radius);
        }
    }
    if pieces.is_empty() {
        (min_x, min_y, max_x, max_y) = (0.0, 0.0, 1.0, 1.0);
    }
    let margin = ((max_x - min_x).max(max_y - min_y) * 0.02).max(1e-3);
    let (left, bottom) = (min_x - margin, min_y - margin);
    let (width, height) = (max_x - min_x + 2.0 * margin, max_y - min_y + 2.0 * margin);
    let mut out = io::BufWriter::new(stdout);
    writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="{left} {} {width} {height}" width="800" height="{}">"#,
        -(bottom + height),
        (800.0 * height / width).round().clamp(1.0, 4000.0)
    )?;
    writeln!(
        out,
        "<title>toolpath in the {}/{} plane ({} segments{})</title>",
        plane.0,
        plane.1,
        pieces.len(),
        if left_out > 0 {
            format!(", {left_out} left out: coordinates beyond 1e15")
        } else {
            String::new()
        }
    )?;
    writeln!(
        out,
        r#"<style>path {{ fill: none; stroke-width: 1.5; vector-effect: non-scaling-stroke; }} .feed {{ stroke: #1565c0; }} .rapid {{ stroke: #c62828; stroke-dasharray: 6 4; }}</style>"#
    )?;
    // Plane coordinates have the vertical axis upwards; SVG's points down.
    writeln!(out, r#"<g transform="scale(1,-1)">"#)?;
    let mut data = String::new();
    for piece in &pieces {
        data.clear();
        let _ = write!(data, "M {} {}", piece.from.0, piece.from.1);
        match piece.arc {
            Some((radius, counter_clockwise, sweep, centre)) if sweep >= 359.999 => {
                // A full circle is two half arcs: one arc command cannot end where it starts.
                let flag = u8::from(counter_clockwise);
                let far = (2.0 * centre.0 - piece.from.0, 2.0 * centre.1 - piece.from.1);
                let _ = write!(
                    data,
                    " A {radius} {radius} 0 0 {flag} {} {} A {radius} {radius} 0 0 {flag} {} {}",
                    far.0, far.1, piece.to.0, piece.to.1
                );
            }
            Some((radius, counter_clockwise, sweep, _)) => {
                let _ = write!(
                    data,
                    " A {radius} {radius} 0 {} {} {} {}",
                    u8::from(sweep > 180.0),
                    u8::from(counter_clockwise),
                    piece.to.0,
                    piece.to.1
                );
            }
            None => {
                let _ = write!(data, " L {} {}", piece.to.0, piece.to.1);
            }
        }
        let title = if piece.last_line == piece.line {
            format!("line {}", piece.line + 1)
        } else {
            format!("lines {} to {}", piece.line + 1, piece.last_line + 1)
        };
        writeln!(
            out,
            r#"<path class="{}" d="{data}"><title>{title}</title></path>"#,
            if piece.rapid { "rapid" } else { "feed" }
        )?;
    }
    writeln!(out, "</g>\n</svg>")?;
    out.flush()
}
