//! Axis words: how one word of a configured axis programs its position (absolute or incremental,
//! inch or metric, diameter or radius, in machine coordinates), and the plane's axes by index.

use crate::analysis::engine::block_words::BlockFunctions;
use crate::analysis::engine::engine_state::Engine;
use crate::analysis::engine::evaluation::AxisName;
use crate::analysis::four_decimals::FourDecimals;
use crate::config::AxisKind;
use crate::diagnostics::{Code, Diagnostic};
use crate::syntax::ast::*;

impl<'a> Engine<'a> {
    /// Applies one axis word of the configured axis `index`; returns false when the axis became
    /// unknown.
    pub(super) fn apply_axis_word(
        &mut self,
        index: usize,
        line: &str,
        block: &Block,
        word: &AddressWord,
        functions: &BlockFunctions,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> bool {
        let name = AxisName(line, word);
        self.state.touched[index] = true;
        self.written[index] = 1;
        let kind = self.config.axes[index].kind;
        let modifier = word.value.modifier.map(|(modifier, _)| modifier);
        let absolute = match modifier {
            Some(Modifier::Ic | Modifier::Dic | Modifier::Ric | Modifier::Cic) => Some(false),
            Some(_) => Some(true),
            None => self.state.is_incremental().map(|incremental| !incremental),
        };
        if let (Some((modifier, modifier_span)), Some(incremental)) =
            (word.value.modifier, self.state.is_incremental())
        {
            let redundant = match modifier {
                Modifier::Ac => !incremental,
                Modifier::Ic => incremental,
                _ => false,
            };
            if redundant {
                let active = if incremental { "G91" } else { "G90" };
                diagnostics.push(Diagnostic::new(
                    Code::RedundantModifier,
                    modifier_span,
                    format!(
                        "{} is redundant here: {active} already reads `{name}` this way",
                        modifier.as_str()
                    ),
                ));
            }
        }
        let value = self.word_value(line, block, word, diagnostics);
        // Unknown value, or a mode inherited from an unseen caller: the position is unknown.
        let (Some(mut value), Some(absolute)) = (value, absolute) else {
            self.state.program(index, None);
            return false;
        };
        if matches!(kind, AxisKind::Linear | AxisKind::Transverse) {
            match self.state.length_factor(self.config.metric) {
                Some(factor) => value *= factor,
                None => {
                    self.state.program(index, None);
                    return false;
                }
            }
        }
        if kind == AxisKind::Transverse {
            let is_diameter = match modifier {
                Some(Modifier::Dac | Modifier::Dic) => Some(true),
                Some(Modifier::Rac | Modifier::Ric) => Some(false),
                _ => self
                    .state
                    .diameter_mode()
                    .map(|(absolute_diameter, incremental_diameter)| {
                        if absolute {
                            absolute_diameter
                        } else {
                            incremental_diameter
                        }
                    }),
            };
            match is_diameter {
                Some(true) => value /= 2.0,
                Some(false) => {}
                None => {
                    self.state.program(index, None);
                    return false;
                }
            }
        }
        if functions.machine_coordinates || functions.reference_point {
            // G53/G153/SUPA values are machine positions, stored in workpiece coordinates after the
            // block (reference §3.8); G74/G75 approach machine-defined points. An increment in machine
            // coordinates is not followed.
            let known = functions.machine_coordinates && absolute;
            self.state.machine[index] = known.then_some(value);
            self.state.program(index, None);
            self.written[index] = 2;
            return known;
        }
        // Under SD42440 = 1 an increment adds to the last programmed value, so that it also traverses
        // a frame change since; under 0 it adds to the set-point in the new frames (reference §3.6).
        let reference = if self.config.frame_offset_incr_prog {
            self.state.programmed[index]
        } else {
            self.state.positions[index]
        };
        if !absolute && self.config.frame_offset_incr_prog {
            let programmed = self.state.programmed[index];
            let difference = match (programmed, self.state.positions[index]) {
                (Some(programmed), Some(current)) => ((programmed - current).abs() > 1e-9)
                    .then(|| FourDecimals(programmed - current).to_string()),
                (Some(_), None) => Some("an unknown amount".to_string()),
                _ => None,
            };
            if let Some(difference) = difference {
                diagnostics.push(Diagnostic::new(
                    Code::IncrementAfterOffsetChange,
                    word.span,
                    format!("`{name}` moves incrementally after a frame or offset change: the change ({difference} in workpiece coordinates) is traversed in addition to the increment (SD42440 = 1)"),
                ));
            }
        }
        let target = if absolute {
            Some(value)
        } else {
            match reference {
                // A modulo axis counts 0 to 360 degrees: an increment wraps (reference §3.5).
                Some(previous) if kind == AxisKind::Modulo => {
                    Some((previous + value).rem_euclid(360.0))
                }
                Some(previous) => Some(previous + value),
                None => {
                    // Turning a modulo axis on by an increment from wherever it stands is usual
                    // practice (`C=IC(720)`), not a likely mistake: information only.
                    let code = if kind == AxisKind::Modulo {
                        Code::ModuloIncrementOnUnknownPosition
                    } else {
                        Code::IncrementOnUnknownPosition
                    };
                    diagnostics.push(Diagnostic::new(
                        code,
                        word.span,
                        format!("`{name}` moves incrementally, but its position is not known here, so the end point is unknown"),
                    ));
                    None
                }
            }
        };
        self.state.program(index, target);
        target.is_some()
    }
    /// The block programs axis `index` to `value` in workpiece coordinates.
    pub(super) fn program_axis(&mut self, index: usize, value: Option<f64>) {
        self.state.program(index, value);
        self.written[index] = 1;
    }
    /// The words of configured axes among `statements`, with the configuration index of each.
    pub(super) fn configured_axis_words<'s>(
        &'s self,
        line: &'s str,
        statements: &'s [Statement],
    ) -> impl Iterator<Item = (usize, &'s AddressWord)> + 's {
        statements
            .iter()
            .filter_map(move |statement| match statement {
                Statement::Address(word) if word.kind == AddressKind::Axis => self
                    .axes
                    .index(self.config, line, word)
                    .map(|index| (index, word)),
                _ => None,
            })
    }

    /// The configuration index of an axis, by name in any case.
    pub(super) fn axis_index(&self, name: &str) -> Option<usize> {
        self.config
            .axes
            .iter()
            .position(|axis| axis.name.eq_ignore_ascii_case(name))
    }
    /// The configuration indexes of the plane's first and second axis (G17: X, Y; G18: Z, X; G19: Y, Z).
    pub(super) fn plane_axes(&self) -> (Option<usize>, Option<usize>) {
        match self.state.plane_index() {
            Some(plane) => self.plane_axis_cache[plane],
            // The plane is inherited from an unseen caller.
            None => (None, None),
        }
    }
    pub(super) fn plane_axis_indexes(&self) -> Vec<usize> {
        match self.plane_axes() {
            (None, None) => {
                // The plane is unknown: any geometry axis may be in it.
                (0..self.config.axes.len())
                    .filter(|&index| {
                        matches!(
                            self.config.axes[index].name.to_ascii_uppercase().as_str(),
                            "X" | "Y" | "Z"
                        )
                    })
                    .collect()
            }
            (first, second) => first.into_iter().chain(second).collect(),
        }
    }
}
