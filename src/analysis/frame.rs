//! The programmable frame (TRANS, ROT, SCALE, MIRROR and their additive forms) as an affine map from
//! programmed coordinates (X, Y, Z) to the coordinates of the parent frame (reference §7.2, §7.3):
//! `parent = matrix · point + translation`. Absolute instructions replace the frame; additive ones act in
//! the already transformed coordinates, `F := F ∘ A`.

/// An affine map of the three geometry axes X, Y, Z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    pub matrix: [[f64; 3]; 3],
    pub translation: [f64; 3],
}

impl Default for Frame {
    fn default() -> Frame {
        Frame::IDENTITY
    }
}

impl Frame {
    pub const IDENTITY: Frame = Frame {
        matrix: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        translation: [0.0; 3],
    };

    pub fn is_identity(&self) -> bool {
        *self == Frame::IDENTITY
    }

    /// A pure translation.
    pub fn translation(offset: [f64; 3]) -> Frame {
        Frame {
            translation: offset,
            ..Frame::IDENTITY
        }
    }

    /// A rotation by `degrees` in a plane given by its two axis indexes (0 = X, 1 = Y, 2 = Z), turning
    /// from the first axis toward the second.
    pub fn rotation_in_plane(first: usize, second: usize, degrees: f64) -> Frame {
        // Snap the rounding noise of multiples of 90° (cos 90° = 6e-17) so that a quarter turn keeps
        // its exact zeros and an unknown coordinate does not leak into an axis it does not affect.
        let snap = |value: f64| if value.abs() < 1e-15 { 0.0 } else { value };
        let (sin, cos) = degrees.to_radians().sin_cos();
        let (sin, cos) = (snap(sin), snap(cos));
        let mut frame = Frame::IDENTITY;
        frame.matrix[first][first] = cos;
        frame.matrix[first][second] = -sin;
        frame.matrix[second][first] = sin;
        frame.matrix[second][second] = cos;
        frame
    }

    /// Scale factors per axis.
    pub fn scale(factors: [f64; 3]) -> Frame {
        let mut frame = Frame::IDENTITY;
        for (axis, factor) in factors.iter().enumerate() {
            frame.matrix[axis][axis] = *factor;
        }
        frame
    }

    /// `self ∘ inner`: `inner` acts first, in the coordinates `self` already transforms.
    pub fn then_inner(&self, inner: &Frame) -> Frame {
        let mut matrix = [[0.0; 3]; 3];
        let mut translation = self.translation;
        for (row, outer_row) in self.matrix.iter().enumerate() {
            for (column, cell) in matrix[row].iter_mut().enumerate() {
                *cell = (0..3).map(|k| outer_row[k] * inner.matrix[k][column]).sum();
            }
            translation[row] += (0..3)
                .map(|k| outer_row[k] * inner.translation[k])
                .sum::<f64>();
        }
        Frame {
            matrix,
            translation,
        }
    }

    /// The inverse map (parent coordinates back to programmed ones); `None` when the frame is singular,
    /// e.g. after `SCALE X0`.
    pub fn inverse(&self) -> Option<Frame> {
        let m = &self.matrix;
        let cofactor = |row: usize, column: usize| {
            let (r1, r2) = ((row + 1) % 3, (row + 2) % 3);
            let (c1, c2) = ((column + 1) % 3, (column + 2) % 3);
            m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1]
        };
        let determinant: f64 = (0..3)
            .map(|column| m[0][column] * cofactor(0, column))
            .sum();
        if !determinant.is_finite() || determinant.abs() < 1e-12 {
            return None;
        }
        // Snap rounding noise so that exact zeros stay zeros (see `rotation_in_plane`).
        let snap = |value: f64| if value.abs() < 1e-15 { 0.0 } else { value };
        let mut matrix = [[0.0; 3]; 3];
        for (row, cells) in matrix.iter_mut().enumerate() {
            for (column, cell) in cells.iter_mut().enumerate() {
                *cell = snap(cofactor(column, row) / determinant);
            }
        }
        let mut translation = [0.0; 3];
        for (row, value) in translation.iter_mut().enumerate() {
            *value = -(0..3)
                .map(|k| matrix[row][k] * self.translation[k])
                .sum::<f64>();
        }
        Some(Frame {
            matrix,
            translation,
        })
    }

    /// The parent coordinate `axis` of a point whose coordinates may be partly unknown; unknown when a
    /// coordinate it depends on is.
    pub fn apply_axis(&self, axis: usize, point: [Option<f64>; 3]) -> Option<f64> {
        let mut value = self.translation[axis];
        for (column, coordinate) in point.iter().enumerate() {
            let weight = self.matrix[axis][column];
            if weight != 0.0 {
                value += weight * (*coordinate)?;
            }
        }
        Some(value)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn apply(frame: &Frame, point: [f64; 3]) -> [f64; 3] {
        let point = point.map(Some);
        [0, 1, 2].map(|axis| frame.apply_axis(axis, point).unwrap())
    }

    fn near(left: [f64; 3], right: [f64; 3]) -> bool {
        left.iter().zip(&right).all(|(a, b)| (a - b).abs() < 1e-9)
    }

    #[test]
    fn composition_follows_the_reference() {
        // T47: TRANS X10, AROT RPL=90, then X5 Y0 -> (10, 5).
        let frame =
            Frame::translation([10.0, 0.0, 0.0]).then_inner(&Frame::rotation_in_plane(0, 1, 90.0));
        assert!(near(apply(&frame, [5.0, 0.0, 0.0]), [10.0, 5.0, 0.0]));
        // T48: SCALE X2 Y2, ATRANS X5, then X1 -> X 12.
        let frame = Frame::scale([2.0, 2.0, 1.0]).then_inner(&Frame::translation([5.0, 0.0, 0.0]));
        assert!(near(apply(&frame, [1.0, 0.0, 0.0]), [12.0, 0.0, 0.0]));
        // T46: TRANS X10, ATRANS X5 -> X 15.
        let frame =
            Frame::translation([10.0, 0.0, 0.0]).then_inner(&Frame::translation([5.0, 0.0, 0.0]));
        assert!(near(apply(&frame, [0.0, 0.0, 0.0]), [15.0, 0.0, 0.0]));
    }

    #[test]
    fn the_inverse_undoes_the_frame() {
        let frame = Frame::translation([10.0, 5.0, 0.0])
            .then_inner(&Frame::rotation_in_plane(0, 1, 30.0))
            .then_inner(&Frame::scale([2.0, -1.0, 1.0]));
        let inverse = frame.inverse().unwrap();
        let point = [3.0, -4.0, 7.0];
        assert!(near(apply(&inverse, apply(&frame, point)), point));
        assert!(Frame::scale([0.0, 1.0, 1.0]).inverse().is_none());
        let quarter = Frame::rotation_in_plane(0, 1, 90.0).inverse().unwrap();
        assert_eq!(quarter.apply_axis(0, [None, Some(2.0), None]), Some(2.0));
    }

    #[test]
    fn unknown_coordinates_matter_only_where_they_are_used() {
        let frame = Frame::translation([10.0, 5.0, 0.0]);
        assert_eq!(frame.apply_axis(0, [Some(1.0), None, None]), Some(11.0));
        let rotated = Frame::rotation_in_plane(0, 1, 90.0);
        assert_eq!(
            rotated
                .apply_axis(1, [Some(1.0), None, None])
                .map(f64::round),
            Some(1.0)
        );
        assert_eq!(rotated.apply_axis(0, [Some(1.0), None, None]), None);
    }
}
