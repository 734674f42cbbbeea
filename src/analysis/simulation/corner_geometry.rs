//! The geometry of chamfers and roundings between two elements in the plane (reference §14.3):
//! straight lines and circles in any combination. Points are (first, second) coordinates of the
//! active plane; angles turn from the first axis toward the second (counter-clockwise).

type Point = (f64, f64);

/// Below this, lengths are zero and directions equal (the unit of the program: mm or inch).
const EPSILON: f64 = 1e-9;

/// A straight line or a circular arc of the path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Element {
    Line {
        start: Point,
        end: Point,
    },
    Arc {
        start: Point,
        end: Point,
        centre: Point,
        radius: f64,
        counter_clockwise: bool,
        /// The swept angle in degrees (more than 360 with TURN).
        sweep: f64,
    },
}

/// What is inserted at a corner: where the first element now ends, where the second now starts,
/// and the rounding's circle (`None` for a chamfer).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Corner {
    pub first_end: Point,
    pub second_start: Point,
    pub rounding: Option<Rounding>,
    /// Whether the programmed value had to be reduced to fit the elements.
    pub reduced: bool,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rounding {
    pub centre: Point,
    pub radius: f64,
    pub counter_clockwise: bool,
    /// The swept angle in degrees.
    pub sweep: f64,
}

/// Why nothing is inserted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NoCorner {
    /// The elements continue tangentially: there is no corner.
    Tangential,
    /// The path reverses at the corner (180°).
    Reversal,
    /// The elements are too short or too curved for any element (or degenerate).
    DoesNotFit,
}

fn sub(a: Point, b: Point) -> Point {
    (a.0 - b.0, a.1 - b.1)
}
fn add(a: Point, b: Point) -> Point {
    (a.0 + b.0, a.1 + b.1)
}
fn scale(a: Point, factor: f64) -> Point {
    (a.0 * factor, a.1 * factor)
}
fn dot(a: Point, b: Point) -> f64 {
    a.0 * b.0 + a.1 * b.1
}
fn cross(a: Point, b: Point) -> f64 {
    a.0 * b.1 - a.1 * b.0
}
fn length(a: Point) -> f64 {
    a.0.hypot(a.1)
}
fn left_normal(a: Point) -> Point {
    (-a.1, a.0)
}
fn unit(a: Point) -> Option<Point> {
    let norm = length(a);
    (norm > EPSILON).then(|| scale(a, 1.0 / norm))
}

/// The counter-clockwise angle from `from` to `to` around `centre`, in radians, in [0, 2π).
fn ccw_angle(centre: Point, from: Point, to: Point) -> f64 {
    let (a, b) = (sub(from, centre), sub(to, centre));
    let angle = cross(a, b).atan2(dot(a, b));
    if angle < 0.0 {
        angle + std::f64::consts::TAU
    } else {
        angle
    }
}

/// The angle travelled along an arc in its own direction from `from` to `to`, in radians.
fn travelled(centre: Point, counter_clockwise: bool, from: Point, to: Point) -> f64 {
    if counter_clockwise {
        ccw_angle(centre, from, to)
    } else {
        ccw_angle(centre, to, from)
    }
}

impl Element {
    pub fn start(&self) -> Point {
        match *self {
            Element::Line { start, .. } | Element::Arc { start, .. } => start,
        }
    }

    pub fn end(&self) -> Point {
        match *self {
            Element::Line { end, .. } | Element::Arc { end, .. } => end,
        }
    }

    /// The unit direction of travel at `point` (a point of the element).
    fn direction_at(&self, point: Point) -> Option<Point> {
        match *self {
            Element::Line { start, end } => unit(sub(end, start)),
            Element::Arc {
                centre,
                counter_clockwise,
                ..
            } => {
                let radial = unit(sub(point, centre))?;
                Some(if counter_clockwise {
                    left_normal(radial)
                } else {
                    scale(left_normal(radial), -1.0)
                })
            }
        }
    }

    /// The length of the element, for a line, or its swept angle in radians, for an arc.
    fn extent(&self) -> f64 {
        match *self {
            Element::Line { start, end } => length(sub(end, start)),
            Element::Arc { sweep, .. } => sweep.to_radians(),
        }
    }

    /// How far along the element `point` lies from `from` (a length or an angle in radians,
    /// like `extent`), `point` being on the element's line or circle.
    fn distance_along(&self, from: Point, point: Point, forward: bool) -> f64 {
        match *self {
            Element::Line { start, end } => {
                let direction = unit(sub(end, start)).unwrap_or((1.0, 0.0));
                let along = dot(sub(point, from), direction);
                if forward {
                    along
                } else {
                    -along
                }
            }
            Element::Arc {
                centre,
                counter_clockwise,
                ..
            } => {
                let angle = if forward {
                    travelled(centre, counter_clockwise, from, point)
                } else {
                    travelled(centre, counter_clockwise, point, from)
                };
                // A point a rounding error past `from` is at `from`, not a whole turn away.
                if angle > std::f64::consts::TAU - 1e-9 {
                    0.0
                } else {
                    angle
                }
            }
        }
    }

    /// The foot of `point` on the element's line or circle.
    fn foot(&self, point: Point) -> Option<Point> {
        match *self {
            Element::Line { start, end } => {
                let direction = unit(sub(end, start))?;
                Some(add(
                    start,
                    scale(direction, dot(sub(point, start), direction)),
                ))
            }
            Element::Arc { centre, radius, .. } => {
                Some(add(centre, scale(unit(sub(point, centre))?, radius)))
            }
        }
    }

    /// The element shifted by `offset` to its left (negative: to its right): a parallel line, or
    /// the concentric circle; `None` when the circle vanishes.
    fn offset(&self, offset: f64) -> Option<Offset> {
        match *self {
            Element::Line { start, end } => {
                let direction = unit(sub(end, start))?;
                Some(Offset::Line(
                    add(start, scale(left_normal(direction), offset)),
                    direction,
                ))
            }
            Element::Arc {
                centre,
                radius,
                counter_clockwise,
                ..
            } => {
                // The left of a counter-clockwise arc is its centre.
                let radius = if counter_clockwise {
                    radius - offset
                } else {
                    radius + offset
                };
                (radius > EPSILON).then_some(Offset::Circle(centre, radius))
            }
        }
    }

    /// The point at chord distance `chord` from the element's end (`from_end`) or start, on the
    /// element; `None` when the element is shorter.
    fn point_at_chord(&self, chord: f64, from_end: bool) -> Option<Point> {
        match *self {
            Element::Line { start, end } => {
                let direction = unit(sub(end, start))?;
                (chord <= self.extent() + EPSILON).then(|| {
                    if from_end {
                        sub(end, scale(direction, chord))
                    } else {
                        add(start, scale(direction, chord))
                    }
                })
            }
            Element::Arc {
                start,
                end,
                centre,
                radius,
                counter_clockwise,
                sweep,
            } => {
                if chord > 2.0 * radius {
                    return None;
                }
                let angle = 2.0 * (chord / (2.0 * radius)).asin();
                if angle > sweep.to_radians() + EPSILON {
                    return None;
                }
                // Back from the end against the direction of travel, or on from the start.
                let turn = match (counter_clockwise, from_end) {
                    (true, true) | (false, false) => -angle,
                    _ => angle,
                };
                let from = if from_end { end } else { start };
                let radial = sub(from, centre);
                let (sin, cos) = turn.sin_cos();
                Some(add(
                    centre,
                    (
                        radial.0 * cos - radial.1 * sin,
                        radial.0 * sin + radial.1 * cos,
                    ),
                ))
            }
        }
    }
}

enum Offset {
    Line(Point, Point),
    Circle(Point, f64),
}

/// The intersections of two offset elements.
fn intersections(a: &Offset, b: &Offset) -> Vec<Point> {
    match (a, b) {
        (Offset::Line(p, u), Offset::Line(q, v)) => {
            let denominator = cross(*u, *v);
            if denominator.abs() < EPSILON {
                return Vec::new();
            }
            let s = cross(sub(*q, *p), *v) / denominator;
            vec![add(*p, scale(*u, s))]
        }
        (Offset::Line(p, u), Offset::Circle(c, r)) | (Offset::Circle(c, r), Offset::Line(p, u)) => {
            let foot = add(*p, scale(*u, dot(sub(*c, *p), *u)));
            let distance = length(sub(foot, *c));
            if distance > *r + EPSILON {
                return Vec::new();
            }
            let half = (r * r - distance * distance).max(0.0).sqrt();
            vec![add(foot, scale(*u, half)), sub(foot, scale(*u, half))]
        }
        (Offset::Circle(c1, r1), Offset::Circle(c2, r2)) => {
            let between = sub(*c2, *c1);
            let d = length(between);
            if d < EPSILON || d > r1 + r2 + EPSILON || d < (r1 - r2).abs() - EPSILON {
                return Vec::new();
            }
            let a = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d);
            let h = (r1 * r1 - a * a).max(0.0).sqrt();
            let axis = scale(between, 1.0 / d);
            let base = add(*c1, scale(axis, a));
            let across = scale(left_normal(axis), h);
            vec![add(base, across), sub(base, across)]
        }
    }
}

/// The turning angle at the corner between `first` (ending there) and `second` (starting there),
/// in radians, with its sign (positive: a left turn).
fn turning(first: &Element, second: &Element) -> Option<(f64, Point, Point)> {
    let corner = first.end();
    let u1 = first.direction_at(corner)?;
    let u2 = second.direction_at(corner)?;
    Some((cross(u1, u2).atan2(dot(u1, u2)), u1, u2))
}

/// Checks the turn at the corner: the signed turning angle, or why nothing can be inserted.
fn corner_turn(first: &Element, second: &Element) -> Result<f64, NoCorner> {
    let (angle, _, _) = turning(first, second).ok_or(NoCorner::DoesNotFit)?;
    if angle.abs() < 1e-6 {
        Err(NoCorner::Tangential)
    } else if angle.abs() > std::f64::consts::PI - 1e-6 {
        Err(NoCorner::Reversal)
    } else {
        Ok(angle)
    }
}

/// The rounding of `radius` at the corner between `first` and `second`, or `None` when it does not
/// touch both elements within their extent.
fn rounding_of(first: &Element, second: &Element, radius: f64, left: bool) -> Option<Corner> {
    let side = if left { radius } else { -radius };
    let corner = first.end();
    let candidates = intersections(&first.offset(side)?, &second.offset(side)?);
    let centre = candidates
        .into_iter()
        .min_by(|a, b| length(sub(*a, corner)).total_cmp(&length(sub(*b, corner))))?;
    let first_end = first.foot(centre)?;
    let second_start = second.foot(centre)?;
    let tolerance = 1e-9;
    // The tangent points must lie on the elements: behind the corner on the first, ahead on the
    // second, within their extent.
    let back = first.distance_along(corner, first_end, false);
    let ahead = second.distance_along(corner, second_start, true);
    let fits =
        |distance: f64, extent: f64| distance >= -tolerance && distance <= extent + tolerance;
    if !fits(back, first.extent()) || !fits(ahead, second.extent()) {
        return None;
    }
    let sweep = if left {
        ccw_angle(centre, first_end, second_start)
    } else {
        ccw_angle(centre, second_start, first_end)
    };
    Some(Corner {
        first_end,
        second_start,
        rounding: Some(Rounding {
            centre,
            radius,
            counter_clockwise: left,
            sweep: sweep.to_degrees(),
        }),
        reduced: false,
    })
}

/// A rounding of `radius` between `first` and `second` (reference §14.3); when it does not fit, the
/// largest that does (found by halving the interval, a bounded number of steps).
pub fn round(first: &Element, second: &Element, radius: f64) -> Result<Corner, NoCorner> {
    let angle = corner_turn(first, second)?;
    let left = angle > 0.0;
    if let Some(corner) = rounding_of(first, second, radius, left) {
        return Ok(corner);
    }
    let (mut low, mut high) = (0.0, radius);
    let mut best = None;
    for _ in 0..60 {
        let middle = 0.5 * (low + high);
        match rounding_of(first, second, middle, left) {
            Some(corner) => {
                best = Some(corner);
                low = middle;
            }
            None => high = middle,
        }
    }
    best.filter(|corner| corner.rounding.is_some_and(|r| r.radius > EPSILON))
        .map(|corner| Corner {
            reduced: true,
            ..corner
        })
        .ok_or(NoCorner::DoesNotFit)
}

/// A chamfer between `first` and `second` (reference §14.3): `leg` along both elements (CHR), or
/// the chamfer's own `length` (CHF) turned into legs by the turning angle. At a circle the legs are
/// chords (the reference's recommendation). A chamfer that does not fit is reduced to the shorter
/// element.
pub fn chamfer(
    first: &Element,
    second: &Element,
    value: f64,
    is_length: bool,
) -> Result<Corner, NoCorner> {
    let angle = corner_turn(first, second)?;
    let leg = if is_length {
        value / (2.0 * (angle.abs() / 2.0).cos())
    } else {
        value
    };
    let corner_at = |leg: f64| {
        Some((
            first.point_at_chord(leg, true)?,
            second.point_at_chord(leg, false)?,
        ))
    };
    if let Some((first_end, second_start)) = corner_at(leg) {
        return Ok(Corner {
            first_end,
            second_start,
            rounding: None,
            reduced: false,
        });
    }
    let (mut low, mut high) = (0.0, leg);
    let mut best = None;
    for _ in 0..60 {
        let middle = 0.5 * (low + high);
        match corner_at(middle) {
            Some(points) => {
                best = Some(points);
                low = middle;
            }
            None => high = middle,
        }
    }
    match best {
        Some((first_end, second_start)) if low > EPSILON => Ok(Corner {
            first_end,
            second_start,
            rounding: None,
            reduced: true,
        }),
        _ => Err(NoCorner::DoesNotFit),
    }
}

/// The sweep in degrees left of an arc from `start` to its end, after the element was shortened.
pub fn remaining_sweep(element: &Element, from: Point, to: Point) -> Option<f64> {
    match *element {
        Element::Arc {
            centre,
            counter_clockwise,
            sweep,
            start,
            end,
            ..
        } => {
            // The part cut off at either end, in the arc's direction.
            let cut_start = travelled(centre, counter_clockwise, start, from);
            let cut_end = travelled(centre, counter_clockwise, to, end);
            let wrap = |cut: f64| {
                if cut > std::f64::consts::TAU - 1e-9 {
                    0.0
                } else {
                    cut
                }
            };
            Some((sweep - (wrap(cut_start) + wrap(cut_end)).to_degrees()).max(0.0))
        }
        Element::Line { .. } => None,
    }
}
