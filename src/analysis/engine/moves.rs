//! The description of a move: `Move` and `ArcMove`, and how the engine describes the block it last
//! applied (positions as the program shows them, machine coordinates, the circle, the dwell).

use crate::analysis::engine::corner_requests::ContourRequest;
use crate::analysis::engine::engine_state::Engine;
use crate::analysis::engine::timing::Timing;
use crate::config::AxisKind;
use crate::diagnostics::Diagnostic;
use crate::syntax::ast::Block;
use crate::syntax::gcodes::GCode;
use std::borrow::Cow;
use std::sync::Arc;

/// A block that moves axes.
#[derive(Debug, Clone, PartialEq)]
pub struct Move {
    /// 0-based line of the block.
    pub line: usize,
    /// The block number as written (`N20`), if any.
    pub block_number: Option<String>,
    /// The motion G function in effect (`G0`, `G1`, `G2`, ...).
    pub motion: Cow<'static, str>,
    /// Axis values before the block, as the program shows them (a diameter under DIAMON); unknown
    /// axes are left out.
    pub start: Vec<(Arc<str>, f64)>,
    /// Axis values after the block, as the program shows them; unknown axes are left out.
    pub end: Vec<(Arc<str>, f64)>,
    /// Machine coordinates (radius on transverse axes) when they are known, i.e. when no offset or
    /// frame whose value is unknown is active.
    pub machine: Option<Vec<(Arc<str>, f64)>>,
    /// The modal feed in the basic unit system, if known.
    pub feed: Option<f64>,
    /// Axes whose value is unknown or depends on the program's flow (jumps, loops).
    pub uncertain: Vec<Arc<str>>,
    /// The circle of a G2/G3 block, when start, end and centre are known.
    pub arc: Option<ArcMove>,
    /// The working plane of the block: the names of its first and second axis (G17: X, Y; G18: Z, X;
    /// G19: Y, Z), `None` when it is unknown.
    pub plane: Option<(&'static str, &'static str)>,
    /// Whether the values of transverse axes in `start`, `end` and `arc` are diameters.
    pub transverse_as_diameter: bool,
    /// The standard cycle whose built-in model made the move (`"CYCLE81"`, `"HOLES1"`), `None` for
    /// a move the program's own block makes.
    pub cycle: Option<Arc<str>>,
    /// What the block asks of the corner at its end (RND, CHF, CHR, RNDM, FRC, FRCM; reference §14),
    /// for the corner stage of the simulation; `None` for most moves.
    pub contour: Option<Box<ContourRequest>>,
    /// For a chamfer or rounding the corner stage inserted: `"RND"`, `"CHF"` or `"CHR"`.
    pub inserted: Option<&'static str>,
    /// What the machining time of the move depends on besides its geometry (`engine/spindle.rs`).
    pub timing: Timing,
}

/// The circle a G2/G3 block follows.
#[derive(Debug, Clone, PartialEq)]
pub struct ArcMove {
    /// The centre in the two plane axes, as the program shows them (like `Move::end`).
    pub centre: Vec<(Arc<str>, f64)>,
    /// The radius in the basic unit system.
    pub radius: f64,
    pub clockwise: bool,
    /// The direction the machine turns, after the programmable frame: a mirror in the plane turns a
    /// clockwise arc counter-clockwise (reference §7.2, T49). `None` when the frame is unknown.
    pub machine_clockwise: Option<bool>,
    /// The swept angle in degrees.
    pub sweep: f64,
}

impl<'a> Engine<'a> {
    /// Applies `block` (the parsed form of `line`, line number `line_index`) and returns its move, if
    /// it moves axes. Semantic findings go to `diagnostics`.
    pub fn apply(
        &mut self,
        line_index: usize,
        line: &str,
        block: &Block,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> Option<Move> {
        self.step(line, block, diagnostics)
            .then(|| self.describe_last_move(line_index, line, block))
    }
    /// Machine coordinates of the touched axes whose value is known (transverse axes as radii).
    pub(super) fn machine_positions(&self) -> Vec<(Arc<str>, f64)> {
        self.axis_names
            .iter()
            .enumerate()
            .filter(|(index, _)| self.state.touched[*index])
            .filter_map(|(index, name)| Some((name.clone(), self.state.machine[index]?)))
            .collect()
    }
    /// The move of the block last applied with [`Engine::step`], which returned true for it.
    pub fn describe_last_move(&self, line_index: usize, line: &str, block: &Block) -> Move {
        let motion = self.state.groups[1]
            .map(GCode::name)
            .unwrap_or(Cow::Borrowed(""));
        let start_positions = &self.start_positions;
        let arc = self.last_arc;
        let shows_diameter = self.state.shows_diameter();
        // How the program shows a value; unknown for a transverse axis while the diameter mode is.
        let display = |index: usize, value: f64| -> Option<f64> {
            let transverse = self.config.axes[index].kind == AxisKind::Transverse;
            crate::analysis::state::shown_value(transverse, shows_diameter, value)
        };
        let mut start = Vec::new();
        let mut end = Vec::new();
        let mut uncertain = Vec::new();
        for (index, name) in self.axis_names.iter().enumerate() {
            if !self.state.touched[index] {
                continue;
            }
            if let Some(value) = start_positions[index].and_then(|value| display(index, value)) {
                start.push((name.clone(), value));
            }
            match self.state.positions[index].and_then(|value| display(index, value)) {
                Some(value) => {
                    end.push((name.clone(), value));
                    if self.flow_uncertain {
                        uncertain.push(name.clone());
                    }
                }
                None => uncertain.push(name.clone()),
            }
        }
        let machine = self.state.machine_known().then(|| self.machine_positions());
        let block_number = block
            .number
            .map(|number| line[number.span.start()..number.span.end()].to_string());
        let arc = arc.map(|circle| {
            let (first, second) = self.plane_axes();
            let mut centre = Vec::new();
            for (index, value) in [(first, circle.centre.0), (second, circle.centre.1)] {
                if let Some(shown) = index.and_then(|index| display(index, value)) {
                    centre.push((self.axis_names[index.unwrap_or_default()].clone(), shown));
                }
            }
            ArcMove {
                centre,
                radius: circle.radius,
                clockwise: circle.clockwise,
                machine_clockwise: self.machine_clockwise(circle.clockwise),
                sweep: circle.sweep,
            }
        });
        Move {
            line: line_index,
            block_number,
            motion,
            start,
            end,
            machine,
            feed: self.state.feed,
            uncertain,
            arc,
            transverse_as_diameter: shows_diameter == Some(true),
            plane: self.state.plane_axis_names(),
            cycle: None,
            contour: self.last_contour.clone(),
            inserted: None,
            timing: self.timing(),
        }
    }
    /// The dwell of the block last applied with [`Engine::step`], if it was a `G4` block: a move of
    /// no axis (`start` and `end` empty, motion `G4`) whose `timing.dwell` holds the time. Consumers
    /// of the path never see it unless they ask for it (`ExecutionOptions::dwell_moves`).
    pub fn describe_last_dwell(
        &self,
        line_index: usize,
        line: &str,
        block: &Block,
    ) -> Option<Move> {
        let dwell = self.last_dwell?;
        let block_number = block
            .number
            .map(|number| line[number.span.start()..number.span.end()].to_string());
        Some(Move {
            line: line_index,
            block_number,
            motion: Cow::Borrowed("G4"),
            start: Vec::new(),
            end: Vec::new(),
            machine: None,
            feed: self.state.feed,
            uncertain: Vec::new(),
            arc: None,
            plane: self.state.plane_axis_names(),
            transverse_as_diameter: self.state.shows_diameter() == Some(true),
            timing: Timing {
                dwell: Some(dwell),
                ..self.timing()
            },
            cycle: None,
            contour: None,
            inserted: None,
        })
    }
}
