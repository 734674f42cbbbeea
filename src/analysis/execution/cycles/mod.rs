//! The standard drilling cycles and hole patterns as motion (reference §16), for calls of cycles the
//! program library has no file for (a file it has runs as the control runs it). A cycle becomes NC
//! blocks (`G0 G90 Z=1`, `G1 Z=-5`, `G4 F2`, ...) that go through the caller's
//! [`Engine`](crate::analysis::engine::engine_state::Engine), so units, frames, the diameter mode and the feed apply to
//! them as to the program's own blocks. Their moves carry the line (and stack and pass) of the
//! block that triggers the cycle, and the cycle's name.

pub(super) mod cycle_state;
mod drilling;
mod patterns;

use super::interpreter::Interpreter;
use super::paths::{Argument, Control, ModalCall};
use crate::analysis::engine::engine_state::Engine;
use crate::diagnostics::{Code, Span};
use crate::syntax::ast::{Block, CallKind, Statement};
use crate::syntax::{parse_line, SyntaxContext};
use cycle_state::is_drilling;
use drilling::{Feed, Plan, Step};
use patterns::Pattern;
use std::sync::Arc;

/// The hole patterns modelled here.
const PATTERNS: [&str; 3] = ["HOLES1", "HOLES2", "CYCLE801"];

/// The tool axis of G17, G18 and G19 (reference §16.1).
const TOOL_AXES: [&str; 3] = ["Z", "Y", "X"];

/// Blocks one pattern call may make at most (holes times the blocks of the modal cycle): a larger
/// pattern is not followed, so that one block cannot run the analysis for long. The blocks count
/// towards the run's budget of executed blocks as well.
const MAX_PATTERN_BLOCKS: usize = 1_000_000;

/// A call of a modelled cycle that no program of the library provides.
pub(super) struct BuiltinCall {
    name: String,
    arguments: Vec<Argument>,
    span: Span,
}

/// The block that makes a cycle run: its line in the current program level and its block number.
struct Trigger {
    pc: usize,
    number: Option<String>,
}

impl Trigger {
    fn new(pc: usize, line: &str, block: &Block) -> Trigger {
        let number = block
            .number
            .and_then(|number| line.get(number.span.start()..number.span.end()))
            .filter(|text| text.starts_with(['N', 'n']))
            .map(str::to_string);
        Trigger { pc, number }
    }
}

impl<'a, 's> Interpreter<'a, 's> {
    /// The call of `block` the built-in models run: a modelled cycle that is not a macro and that
    /// the library has no program for. A hole pattern qualifies only when the modal call, if any,
    /// is a built-in drilling cycle too (the interpreter cannot run a called program per hole from
    /// inside a pattern, so that pattern stays an unknown call).
    pub(super) fn builtin_call(
        &mut self,
        control: &Control,
        engine: &Engine<'a>,
        block: &Block,
        line: &str,
    ) -> Option<BuiltinCall> {
        let (name, args, span) = block
            .interpreted_statements()
            .iter()
            .find_map(|statement| match statement {
                Statement::Call {
                    kind: CallKind::Named,
                    name: Some(name),
                    args,
                    span,
                } => Some((
                    line.get(name.start()..name.end())?
                        .trim()
                        .to_ascii_uppercase(),
                    args,
                    *span,
                )),
                _ => None,
            })?;
        let pattern = PATTERNS.contains(&name.as_str());
        if !(pattern || is_drilling(&name)) || engine.is_macro(&name) {
            return None;
        }
        if self.find_unit(&name).is_some() {
            return None;
        }
        if pattern {
            if let Some(modal) = &control.level().modal_call {
                let modal_name = modal.name.clone();
                if !is_drilling(&modal_name) || self.find_unit(&modal_name).is_some() {
                    return None;
                }
            }
        }
        Some(BuiltinCall {
            name,
            arguments: super::calls::evaluate_arguments(engine, block, line, args),
            span,
        })
    }

    /// Runs the built-in model of `call`, made by the block at `pc` (already applied).
    pub(super) fn run_builtin(
        &mut self,
        control: &mut Control,
        engine: &mut Engine<'a>,
        pc: usize,
        line: &str,
        block: &Block,
        call: BuiltinCall,
    ) {
        let trigger = Trigger::new(pc, line, block);
        if is_drilling(&call.name) {
            let modal = ModalCall {
                name: call.name,
                arguments: call.arguments,
            };
            self.run_drilling(control, engine, &trigger, &modal, call.span);
        } else {
            self.run_pattern(control, engine, &trigger, call);
        }
    }

    /// Runs the modally called drilling cycle `modal` after the block at `pc`, which moved.
    pub(super) fn run_modal_cycle(
        &mut self,
        control: &mut Control,
        engine: &mut Engine<'a>,
        pc: usize,
        line: &str,
        block: &Block,
        modal: &ModalCall,
    ) {
        let trigger = Trigger::new(pc, line, block);
        self.run_drilling(control, engine, &trigger, modal, Span::default());
    }

    fn run_drilling(
        &mut self,
        control: &mut Control,
        engine: &mut Engine<'a>,
        trigger: &Trigger,
        cycle: &ModalCall,
        span: Span,
    ) {
        let Some(plane) = engine.state.plane_index() else {
            // Without the plane the tool axis is not known: the cycle may have moved any axis.
            engine.state.forget_positions();
            return;
        };
        let tool = TOOL_AXES[plane];
        let outcome = drilling::plan(&cycle.name, &cycle.arguments);
        if let Some((dp, from_relative)) = outcome.depth_disagrees {
            self.report(
                control,
                trigger.pc,
                Code::CycleDepthDisagrees,
                span,
                format!(
                    "{}: DP {} and DPR give different final depths; DPR wins, the cycle drills to {}",
                    cycle.name,
                    number(dp).unwrap_or_default(),
                    number(from_relative).unwrap_or_default()
                ),
            );
        }
        let (steps, feed_after_unknown) = match outcome.plan {
            Plan::Steps {
                steps,
                feed_after_unknown,
            } => (steps, feed_after_unknown),
            Plan::ReferencePlaneWrong => {
                self.report(
                    control,
                    trigger.pc,
                    Code::CycleReferencePlane,
                    span,
                    format!(
                        "{}: the retraction plane and the final depth lie on the same side of the reference plane (alarm 61101): the cycle makes no motion",
                        cycle.name
                    ),
                );
                return;
            }
            Plan::Unknown => {
                forget_axes(engine, self.config, &[tool]);
                return;
            }
        };
        let Some((first, second)) = engine.state.plane_axis_names() else {
            return;
        };
        let Some(blocks) = drilling_blocks(&steps, [first, second, tool], trigger) else {
            forget_axes(engine, self.config, &[tool]);
            return;
        };
        if !self.has_axis(tool) {
            engine.state.forget_positions();
            return;
        }
        let saved = (engine.state.groups, engine.state.frame);
        let feed_before = engine.state.feed;
        self.cycles.current = Some(Arc::from(cycle.name.as_str()));
        for (text, feed) in blocks {
            if let Some(unknown_or_given) = feed {
                engine.state.feed = unknown_or_given;
            }
            self.run_text(control, engine, trigger.pc, &text);
        }
        self.cycles.current = None;
        if self.config.cycles.restore_modal {
            engine.restore_saved(&saved.0, saved.1);
        }
        match steps
            .iter()
            .any(|step| matches!(step, Step::Feed(_, Feed::Unknown)))
        {
            // Tapping moves at pitch times speed do not change the programmed feed.
            true if !feed_after_unknown => engine.state.feed = feed_before,
            _ if feed_after_unknown => engine.state.feed = None,
            _ => {}
        }
    }

    fn run_pattern(
        &mut self,
        control: &mut Control,
        engine: &mut Engine<'a>,
        trigger: &Trigger,
        call: BuiltinCall,
    ) {
        let Some(plane) = engine.state.plane_index() else {
            engine.state.forget_positions();
            return;
        };
        let Some((first, second)) = engine.state.plane_axis_names() else {
            return;
        };
        let options = self.config.cycles;
        let (pattern, empty_grid) = match call.name.as_str() {
            "HOLES1" => {
                let current = self.plane_position(engine, first, second);
                (
                    patterns::row(&call.arguments, current, options.holes1_order),
                    false,
                )
            }
            "HOLES2" => (patterns::circle(&call.arguments), false),
            _ => patterns::grid(&call.arguments, options.cycle801_order),
        };
        let (positions, order_known) = match pattern {
            Pattern::Holes {
                positions,
                order_known,
            } => (positions, order_known),
            Pattern::NoHoles => {
                let message = format!(
                    "{}: the number of holes is 0 (alarm 61103): the cycle is aborted",
                    call.name
                );
                self.report(
                    control,
                    trigger.pc,
                    Code::PatternWithoutHoles,
                    call.span,
                    message,
                );
                return;
            }
            Pattern::CircleTooLong => {
                let message = "HOLES2: the angle between the holes times the number of gaps reaches 360 degrees (alarm 61106): the cycle is aborted".to_string();
                self.report(
                    control,
                    trigger.pc,
                    Code::CircleOfHolesTooLong,
                    call.span,
                    message,
                );
                return;
            }
            Pattern::Unknown => {
                forget_axes(engine, self.config, &[first, second, TOOL_AXES[plane]]);
                return;
            }
        };
        if empty_grid {
            let message =
                "CYCLE801: 0 rows or columns (alarm 62105): the control stops (M0) and takes 1"
                    .to_string();
            self.report(
                control,
                trigger.pc,
                Code::GridWithoutRowsOrColumns,
                call.span,
                message,
            );
        }
        let modal = control.level().modal_call.clone();
        let per_hole = 1 + modal.as_ref().map_or(0, |modal| {
            match drilling::plan(&modal.name, &modal.arguments).plan {
                Plan::Steps { steps, .. } => 2 * steps.len(),
                _ => 0,
            }
        });
        if positions.len().saturating_mul(per_hole) > MAX_PATTERN_BLOCKS {
            forget_axes(engine, self.config, &[first, second, TOOL_AXES[plane]]);
            return;
        }
        if modal.is_none() && call.name != "CYCLE801" {
            let message = format!(
                "{}: no drilling cycle is called modally (alarm 62100): the control stops (M0) and, after NC start, approaches the positions without drilling",
                call.name
            );
            self.report(
                control,
                trigger.pc,
                Code::PatternWithoutModalCall,
                call.span,
                message,
            );
        }
        let saved = (engine.state.groups, engine.state.frame);
        let name: Arc<str> = Arc::from(call.name.as_str());
        for (a, b) in positions {
            let (Some(a), Some(b)) = (number(a), number(b)) else {
                forget_axes(engine, self.config, &[first, second]);
                break;
            };
            let text = format!("{}G0 G90 {first}={a} {second}={b}", block_number(trigger));
            self.cycles.current = Some(Arc::clone(&name));
            let moved = self.run_text(control, engine, trigger.pc, &text);
            self.cycles.current = None;
            if let (true, Some(modal)) = (moved, &modal) {
                self.run_drilling(control, engine, trigger, modal, Span::default());
            }
        }
        // CYCLE801 has SAVE (its ATRANS and AROT, which this model does not need, are undone);
        // the others as configured.
        if options.restore_modal || call.name == "CYCLE801" {
            engine.restore_saved(&saved.0, saved.1);
        }
        if !order_known {
            forget_axes(engine, self.config, &[first, second]);
        }
    }

    /// Applies one block of a cycle, made by the block at `pc`, and records its move. Whether it
    /// moved.
    fn run_text(
        &mut self,
        control: &mut Control,
        engine: &mut Engine<'a>,
        pc: usize,
        text: &str,
    ) -> bool {
        let config = self.config;
        let context = self
            .cycles
            .context
            .get_or_insert_with(|| SyntaxContext::new(config));
        let (block, _) = parse_line(text, context);
        self.executed += 1;
        // The cycle's own blocks raise no finding of the program's (a feed that is not known shows
        // as a move without feed).
        let mut ignored = Vec::new();
        let moved = engine.step(text, &block, &mut ignored);
        if moved && !self.counting && !control.widening() {
            let unit_index = control.level().unit;
            self.record_move(control, engine, unit_index, pc, text, &block);
        } else if self.options.dwell_moves && !self.counting && !control.widening() {
            // A cycle's dwell (`G4 F=2` at the final depth) counts in the machining time.
            let unit_index = control.level().unit;
            self.record_dwell(control, engine, unit_index, pc, text, &block);
        }
        moved
    }

    /// The position in the plane before a pattern, in the program's units, when known.
    fn plane_position(&self, engine: &Engine<'a>, first: &str, second: &str) -> Option<(f64, f64)> {
        let factor = engine.state.length_factor(self.config.metric)?;
        let value = |name: &str| {
            let index = self.axis_index(name)?;
            if self.config.axes[index].kind == crate::config::AxisKind::Transverse {
                // A diameter or radius: not compared with the pattern's values.
                return None;
            }
            Some(engine.state.positions[index]? / factor)
        };
        Some((value(first)?, value(second)?))
    }

    fn axis_index(&self, name: &str) -> Option<usize> {
        self.config
            .axes
            .iter()
            .position(|axis| axis.name.eq_ignore_ascii_case(name))
    }

    fn has_axis(&self, name: &str) -> bool {
        self.axis_index(name).is_some()
    }
}

/// The axes `names` become unknown: a cycle moved them in a way the analysis does not follow.
fn forget_axes(engine: &mut Engine, config: &crate::config::MachineConfig, names: &[&str]) {
    for name in names {
        if let Some(index) = config
            .axes
            .iter()
            .position(|axis| axis.name.eq_ignore_ascii_case(name))
        {
            let state = &mut engine.state;
            state.positions[index] = None;
            state.programmed[index] = None;
            state.machine[index] = None;
            state.touched[index] = true;
        }
    }
}

/// A value as a block writes it; `None` for one a block cannot hold.
fn number(value: f64) -> Option<String> {
    (value.is_finite() && value.abs() < 1e12).then(|| {
        // `{}` writes the shortest text that reads back as the same value, never an exponent.
        let text = format!("{value}");
        if text == "-0" {
            "0".to_string()
        } else {
            text
        }
    })
}

fn block_number(trigger: &Trigger) -> String {
    trigger
        .number
        .as_ref()
        .map_or(String::new(), |number| format!("{number} "))
}

/// The blocks of a drilling cycle's steps, with the feed to set before each (`Some(None)`: unknown).
/// `axes` are the first and second plane axis and the tool axis. `None` when a value cannot be
/// written.
fn drilling_blocks(
    steps: &[Step],
    axes: [&str; 3],
    trigger: &Trigger,
) -> Option<Vec<(String, Option<Option<f64>>)>> {
    let [first, second, tool] = axes;
    let prefix = block_number(trigger);
    let mut blocks = Vec::with_capacity(steps.len() + 1);
    for step in steps {
        match *step {
            Step::Rapid(position) => {
                blocks.push((format!("{prefix}G0 G90 {tool}={}", number(position)?), None))
            }
            Step::Feed(position, feed) => {
                let position = number(position)?;
                match feed {
                    Feed::Modal => blocks.push((format!("{prefix}G1 G90 {tool}={position}"), None)),
                    Feed::Programmed(value) => blocks.push((
                        format!("{prefix}G1 G90 {tool}={position} F={}", number(value)?),
                        None,
                    )),
                    Feed::Unknown => {
                        blocks.push((format!("{prefix}G1 G90 {tool}={position}"), Some(None)))
                    }
                }
            }
            Step::Dwell(time) if time >= 0.0 => {
                blocks.push((format!("{prefix}G4 F={}", number(time)?), None))
            }
            Step::Dwell(revolutions) => {
                blocks.push((format!("{prefix}G4 S={}", number(-revolutions)?), None))
            }
            Step::Stop => blocks.push((format!("{prefix}M5 M0"), None)),
            Step::RapidBy([a, b, c]) => {
                blocks.push((
                    format!(
                        "{prefix}G0 G91 {first}={} {second}={} {tool}={}",
                        number(a)?,
                        number(b)?,
                        number(c)?
                    ),
                    None,
                ));
                blocks.push((format!("{prefix}G90"), None));
            }
        }
    }
    Some(blocks)
}
