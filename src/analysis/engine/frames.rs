//! The programmable frame (reference §7.2, §7.3): TRANS/ATRANS, ROT/AROT, SCALE/ASCALE,
//! MIRROR/AMIRROR and G58/G59, with and without a fine translation, and the turning direction of an
//! arc in the machine after the frame.

use crate::analysis::engine::engine_state::Engine;
use crate::analysis::engine::evaluation::axis_name;
use crate::config::AxisKind;
use crate::diagnostics::Diagnostic;
use crate::syntax::ast::*;
use crate::syntax::gcodes::GCode;

impl<'a> Engine<'a> {
    /// TRANS/ATRANS, ROT/AROT (RPL in the plane), SCALE/ASCALE, MIRROR/AMIRROR (reference §7.2, §7.3).
    /// What cannot be followed (a spatial rotation, unknown values, frame values of other axes, G58/G59,
    /// ROTS) makes the frame unknown.
    pub(super) fn apply_frame_instruction(
        &mut self,
        code: GCode,
        line: &str,
        block: &Block,
        statements: &[Statement],
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        use crate::analysis::frame::Frame;
        let name = code.name();
        let name = name.as_ref();
        if !matches!(
            name,
            "TRANS"
                | "ATRANS"
                | "ROT"
                | "AROT"
                | "SCALE"
                | "ASCALE"
                | "MIRROR"
                | "AMIRROR"
                | "ROTS"
                | "AROTS"
                | "G58"
                | "G59"
        ) {
            // Working-area limits (G25/G26) do not move the coordinate system.
            return;
        }
        let is_length = matches!(name, "TRANS" | "ATRANS" | "G58" | "G59");
        let mut values: [Option<Option<f64>>; 3] = [None; 3];
        // G58 and G59 replace the coarse and fine translation axially; without a fine translation
        // (MD18600 = 0) they are not followed.
        let mut followable = !matches!(name, "ROTS" | "AROTS")
            && (self.config.frame_fine_trans || !matches!(name, "G58" | "G59"));
        let mut rotation_in_plane = None;
        for statement in statements {
            let Statement::Address(word) = statement else {
                continue;
            };
            match word.kind {
                AddressKind::Axis => {
                    let axis = axis_name(line, word);
                    let Some(slot) = ["X", "Y", "Z"]
                        .iter()
                        .position(|name| axis.eq_ignore_ascii_case(name))
                    else {
                        // Frame components of other axes are not followed.
                        followable = false;
                        continue;
                    };
                    let mut value = self.word_value(line, block, word, diagnostics);
                    if is_length {
                        value = value
                            .zip(self.state.length_factor(self.config.metric))
                            .map(|(value, factor)| value * factor);
                        let transverse = self
                            .config
                            .axis(&axis)
                            .is_some_and(|axis| axis.kind == AxisKind::Transverse);
                        if transverse && self.state.diameter_mode() != Some((false, false)) {
                            // Whether a frame offset on a diameter axis is a diameter is not followed.
                            value = None;
                        }
                    }
                    values[slot] = Some(value);
                }
                AddressKind::Named(NamedAddress::RotationInPlane) => {
                    rotation_in_plane = Some(self.word_value(line, block, word, diagnostics));
                }
                _ => {}
            }
        }
        let any_unknown = values.iter().any(|value| matches!(value, Some(None)));
        let written = |slot: usize, default: f64| values[slot].flatten().unwrap_or(default);
        let element = if !followable || any_unknown {
            None
        } else {
            match name {
                "TRANS" | "ATRANS" | "G58" | "G59" => Some(Frame::translation([
                    written(0, 0.0),
                    written(1, 0.0),
                    written(2, 0.0),
                ])),
                "ROT" | "AROT" => {
                    if values.iter().any(Option::is_some) {
                        // A spatial rotation (ROT X.. Y.. Z..) is not followed.
                        None
                    } else {
                        match rotation_in_plane {
                            None => Some(Frame::IDENTITY),
                            Some(None) => None,
                            Some(Some(degrees)) => {
                                self.state.plane_axis_names().map(|(first, second)| {
                                    let slot = |name: &str| {
                                        ["X", "Y", "Z"]
                                            .iter()
                                            .position(|axis| *axis == name)
                                            .unwrap_or(0)
                                    };
                                    Frame::rotation_in_plane(slot(first), slot(second), degrees)
                                })
                            }
                        }
                    }
                }
                "SCALE" | "ASCALE" => Some(Frame::scale([
                    written(0, 1.0),
                    written(1, 1.0),
                    written(2, 1.0),
                ])),
                // The value of a mirrored axis is ignored: writing the axis mirrors it.
                _ => Some(Frame::scale([0, 1, 2].map(|slot| {
                    if values[slot].is_some() {
                        -1.0
                    } else {
                        1.0
                    }
                }))),
            }
        };
        if self.config.frame_fine_trans {
            let written = values.map(|value| value.is_some());
            self.compose_with_fine_translation(name, element, written);
            return;
        }
        let absolute = matches!(name, "TRANS" | "ROT" | "SCALE" | "MIRROR");
        self.state.frame = match (absolute, element) {
            (_, None) => None,
            (true, Some(element)) => Some(element),
            (false, Some(element)) => self.state.frame.map(|frame| frame.then_inner(&element)),
        };
    }
    /// Frame composition with a fine translation (MD18600 = 1, reference §7.2): TRANS writes the
    /// coarse part and keeps the fine one, ATRANS adds to the fine part, G58 and G59 replace the
    /// coarse and the fine part of the written axes. Whether ROT, SCALE and MIRROR clear a fine part is
    /// not documented: with one, the frame becomes unknown.
    pub(super) fn compose_with_fine_translation(
        &mut self,
        name: &str,
        element: Option<crate::analysis::frame::Frame>,
        written: [bool; 3],
    ) {
        use crate::analysis::frame::Frame;
        let known = self.state.frame.zip(self.state.fine_translation);
        let result = element.zip(known).and_then(|(element, (frame, fine))| {
            let add =
                |left: [f64; 3], right: [f64; 3]| [0, 1, 2].map(|axis| left[axis] + right[axis]);
            match name {
                "TRANS" => Some((Frame::translation(add(element.translation, fine)), fine)),
                "ATRANS" => {
                    let shift = [0, 1, 2].map(|row| {
                        (0..3)
                            .map(|column| frame.matrix[row][column] * element.translation[column])
                            .sum::<f64>()
                    });
                    Some((frame.then_inner(&element), add(fine, shift)))
                }
                "G58" | "G59" => {
                    let mut frame = frame;
                    let mut fine = fine;
                    for axis in (0..3).filter(|axis| written[*axis]) {
                        let value = element.translation[axis];
                        if name == "G58" {
                            frame.translation[axis] = value + fine[axis];
                        } else {
                            frame.translation[axis] += value - fine[axis];
                            fine[axis] = value;
                        }
                    }
                    Some((frame, fine))
                }
                "ROT" | "SCALE" | "MIRROR" => (fine == [0.0; 3]).then_some((element, fine)),
                _ => Some((frame.then_inner(&element), fine)),
            }
        });
        self.state.frame = result.map(|(frame, _)| frame);
        self.state.fine_translation = result.map(|(_, fine)| fine);
    }
    /// The turning direction in the machine of an arc programmed `clockwise` in the active plane: the
    /// frame's map of the plane reverses it when its determinant is negative (an odd number of
    /// mirrors). `None` when the frame or the plane is unknown, or the frame tilts the plane.
    pub(super) fn machine_clockwise(&self, clockwise: bool) -> Option<bool> {
        let frame = self.state.frame?;
        let (first, second) = match self.state.plane_index()? {
            0 => (0, 1),
            1 => (2, 0),
            _ => (1, 2),
        };
        let normal = 3 - first - second;
        let tilted = frame.matrix[normal][first] != 0.0
            || frame.matrix[normal][second] != 0.0
            || frame.matrix[first][normal] != 0.0
            || frame.matrix[second][normal] != 0.0;
        if tilted {
            return None;
        }
        let determinant = frame.matrix[first][first] * frame.matrix[second][second]
            - frame.matrix[first][second] * frame.matrix[second][first];
        Some(if determinant < 0.0 {
            !clockwise
        } else {
            clockwise
        })
    }
}
