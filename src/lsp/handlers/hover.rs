//! The hover: on an axis word, how its value resolves; on a G function, what it does, its group and
//! the function of that group in effect before the block; on other words the documentation of
//! `ide::documentation` (keywords, cycles, system variables, a called `PROC` with its doc comment);
//! and everywhere in a block the modal state in effect and the block's end point. The values come
//! from the analysis's `BlockReport` only.

use crate::analysis::document::{
    BlockReport, LineSource, ResolutionMode, StateSummary, WordResolution,
};
use crate::config::{AxisKind, MachineConfig};
use crate::diagnostics::Span;
use crate::ide::documentation::Documentation;
use crate::ide::language_docs::{gcode_summary, group_name};
use crate::lsp::convert::{character_to_byte, span_to_range, PositionEncoding};
use crate::lsp::documents::Analysed;
use crate::lsp::handlers::hover_resolution::{explain_resolution, is_incremental};
use crate::lsp::handlers::numbers::{same, short};
use crate::lsp::handlers::words::{word_at, words, Word, WordValue};
use crate::syntax::ast::Modifier;
use crate::syntax::gcodes::GCode;
use std::fmt::Write;
use tower_lsp_server::ls_types::{Hover, HoverContents, MarkupContent, MarkupKind, Position};

/// Up to this many lines the hover makes the machining times of a revision itself (a few
/// milliseconds); a larger document shows them once the status bar or the toolpath made them.
const HOVER_TIMES_LINES: usize = 20_000;

/// The hover at `position` of the analysed text, `None` on a line without words. On a word that is
/// neither an axis word nor a G function, `documentation` (called with the line's text, its index
/// and the byte offset) gives the word's documentation, shown above the block's state.
pub fn hover(
    analysed: &Analysed,
    library: &dyn crate::analysis::library::ProgramLibrary,
    position: Position,
    encoding: PositionEncoding,
    documentation: impl FnOnce(&str, usize, usize) -> Option<Documentation>,
) -> Option<Hover> {
    let lines = analysed.lines();
    let line_idx = position.line as usize;
    if line_idx >= lines.line_count() {
        return None;
    }
    let line = lines.line(line_idx);
    let line_words = words(&line);
    if line_words.is_empty() {
        return None;
    }
    let offset = character_to_byte(&line, position.character, encoding);
    let config = analysed.analysis.config();
    let report = analysed.analysis.block_report(&lines, line_idx);
    let word = word_at(&line_words, offset);
    let special = word.and_then(|word| match axis_of(word, config) {
        Some(axis) => Some((
            axis_hover(word, &axis, &line, &line_words, &report, config),
            Some(word.span.clone()),
        )),
        None => gcode_of(word).map(|code| (gcode_hover(code, &report), Some(word.span.clone()))),
    });
    // The run of the program adds what program order cannot show: passes, calls, assumptions. A
    // program that runs in order (the large CAM programs) is not run for a hover.
    let needs_run = report.before.flow_uncertain
        || report.after.flow_uncertain
        || analysed.analysis.kind() == crate::analysis::ProgramKind::Subprogram
        || calls_a_program(&line, config);
    let run_summary = needs_run
        .then(|| {
            let execution = analysed.execution(library);
            crate::ide::execution::execution_summary(&execution, line_idx)
        })
        .flatten();
    let (markdown, span) = match special {
        Some(found) => found,
        None => match documentation(&line, line_idx, offset) {
            Some(doc) => (
                format!(
                    "**{}**\n\n{}\n\n---\n\n{}",
                    doc.title,
                    doc.text,
                    block_hover(&report, config)
                ),
                Some(doc.span.start()..doc.span.end()),
            ),
            None => (block_hover(&report, config), None),
        },
    };
    let markdown = match run_summary {
        Some(summary) => format!("{summary}\n\n---\n\n{markdown}"),
        None => markdown,
    };
    // The machining time of the block over its passes and the time before its first pass, when the
    // status bar or the toolpath made this revision's times: a hover does not read a large program
    // again after every edit.
    let times = if lines.line_count() <= HOVER_TIMES_LINES {
        Some(analysed.times(library))
    } else {
        analysed.cached_times(library)
    };
    let time = times.and_then(|times| crate::ide::timing::time_summary(&times, line_idx));
    let markdown = match time {
        Some(time) => format!("{markdown}\n\n---\n\n{time}"),
        None => markdown,
    };
    Some(Hover {
        contents: HoverContents::Markup(MarkupContent {
            kind: MarkupKind::Markdown,
            value: markdown,
        }),
        range: span
            .map(|span| span_to_range(line_idx, &line, Span::new(span.start, span.end), encoding)),
    })
}

/// The configured axis a word writes, if it is an axis word.
pub fn axis_of(word: &Word<'_>, config: &MachineConfig) -> Option<String> {
    if matches!(word.value, WordValue::None) {
        return None;
    }
    let name = word.upper_name();
    config.axis(&name).map(|axis| axis.name.clone())
}

fn gcode_of(word: &Word<'_>) -> Option<GCode> {
    match word.value {
        WordValue::Number(Some(number)) if word.name.eq_ignore_ascii_case("G") => {
            (number >= 0.0 && number.fract() == 0.0 && number < 10_000.0)
                .then(|| GCode::from_number(number as u32))
                .flatten()
        }
        WordValue::None => GCode::from_name(word.name),
        _ => None,
    }
}

fn axis_hover(
    word: &Word<'_>,
    axis: &str,
    line: &str,
    line_words: &[Word<'_>],
    report: &BlockReport,
    config: &MachineConfig,
) -> String {
    let from_core = report.words.iter().find(|resolution| {
        resolution.span.start() <= word.span.start
            && word.span.start < resolution.span.end().max(resolution.span.start() + 1)
    });
    let resolution = match from_core {
        Some(resolution) => resolution.clone(),
        None => resolution_from_movement(word, axis, line_words, report, config),
    };
    let mut text = match modifier_without_brackets(line, word) {
        Some(modifier) if resolution.end.is_none() => format!(
            "{axis} = **unknown**: `{modifier}` needs its value in parentheses, `{axis}={modifier}(...)` (S101); as written, the control reads `{modifier}` as the name of a variable"
        ),
        _ => explain_resolution(&resolution, &report.after, config),
    };
    if report.before.flow_uncertain {
        text.push_str("\n\n⚠ A label, jump or loop comes before this block: the control may run another path than program order, so these values may not be the control's.");
    }
    text
}

/// The position modifier written without its parentheses in an axis word (`X=AC 5`), which the
/// control reads as a variable named `AC`: the hover points at the missing parentheses rather than
/// at an unknown variable.
fn modifier_without_brackets<'a>(line: &'a str, word: &Word<'_>) -> Option<&'a str> {
    let text = line.get(word.span.start..)?;
    let after_equals = &text[text.find('=')? + 1..];
    if text[..text.find('=')?].trim().len() != word.name.len() {
        return None;
    }
    let after_equals = after_equals.trim_start();
    let name_length = after_equals
        .bytes()
        .take_while(|byte| byte.is_ascii_alphabetic())
        .count();
    let name = &after_equals[..name_length];
    let next = after_equals[name_length..].trim_start().chars().next();
    let is_modifier = [
        "AC", "IC", "DC", "ACP", "ACN", "DAC", "DIC", "RAC", "RIC", "CAC", "CIC", "CDC", "CACP",
        "CACN",
    ]
    .iter()
    .any(|modifier| modifier.eq_ignore_ascii_case(name));
    (is_modifier && next != Some('(')).then_some(name)
}

/// How a word resolves, worked out from the block's move when the analysis gave no per-word
/// report: the arithmetic shown is checked against the analysis's end point, never assumed.
fn resolution_from_movement(
    word: &Word<'_>,
    axis: &str,
    line_words: &[Word<'_>],
    report: &BlockReport,
    config: &MachineConfig,
) -> WordResolution {
    let lookup = |values: &[(std::sync::Arc<str>, f64)]| {
        values
            .iter()
            .find(|(name, _)| &**name == axis)
            .map(|(_, value)| *value)
    };
    let movement = report.movement.as_ref();
    let machine_block = line_words.iter().any(|other| {
        let name = other.upper_name();
        name == "SUPA" || (name == "G" && matches!(other.value, WordValue::Number(Some(number)) if number == 53.0 || number == 153.0))
    });
    let mode = if machine_block {
        ResolutionMode::Machine
    } else if let Some((name, _)) = word.modifier() {
        Modifier::from_name(name).map_or(ResolutionMode::Unknown, ResolutionMode::Override)
    } else {
        // The block's own G functions apply to its words: the state in effect is the one after it.
        match report.after.distance.as_deref() {
            Some("G90") => ResolutionMode::Absolute,
            Some("G91") => ResolutionMode::Incremental,
            _ => ResolutionMode::Unknown,
        }
    };
    let axis_kind = config.axis(axis).map(|axis| axis.kind);
    let unit_factor = if axis_kind.is_some_and(AxisKind::is_rotary) {
        Some(1.0)
    } else {
        match report.after.units.as_deref() {
            Some("G70" | "G700") => Some(if config.metric { 25.4 } else { 1.0 }),
            Some("G71" | "G710") => Some(if config.metric { 1.0 } else { 1.0 / 25.4 }),
            _ => None,
        }
    };
    let end = movement.and_then(|movement| lookup(&movement.end));
    let start = movement.and_then(|movement| lookup(&movement.start));
    let unknown_reason = end.is_none().then(|| {
        if is_incremental(mode) && start.is_none() {
            return "the move is incremental and the axis position before the block is not known"
                .to_string();
        }
        "the analysis cannot follow this value here (see the block's findings)".to_string()
    });
    WordResolution {
        span: Span::new(word.span.start, word.span.end),
        axis: axis.to_string(),
        programmed: word.literal(),
        mode,
        unit_factor,
        read_as_diameter: axis_kind == Some(AxisKind::Transverse)
            && movement.is_some_and(|movement| movement.transverse_as_diameter),
        shown_as_diameter: axis_kind == Some(AxisKind::Transverse)
            && movement.is_some_and(|movement| movement.transverse_as_diameter),
        // Built from the move alone; `explain_resolution` spells out a sum only when it checks
        // against the analysis's end point.
        explained: true,
        start,
        end,
        machine: movement
            .and_then(|movement| movement.machine.as_deref())
            .and_then(lookup),
        unknown_reason,
    }
}

/// The value of a group in effect before the block, when the analysis follows that group.
fn group_value(group: u8, before: &StateSummary) -> Option<Option<&str>> {
    let value = match group {
        1 => &before.motion,
        6 => &before.plane,
        8 => &before.settable_offset,
        13 => &before.units,
        14 => &before.distance,
        29 => &before.diameter,
        _ => return None,
    };
    Some(value.as_deref())
}

fn gcode_hover(code: GCode, report: &BlockReport) -> String {
    let name = code.name();
    let group = code.group();
    let mut text = format!("**{name}**");
    if let Some(description) = gcode_summary(&name) {
        let _ = write!(text, " — {description}");
    } else if matches!(code, GCode::WorkOffset(_)) {
        text.push_str(" — Settable work offset from the machine's offset table.");
    }
    let modality = if code.is_modal() {
        "modal: stays active until another function of the group"
    } else {
        "non-modal: acts in this block only"
    };
    let _ = write!(
        text,
        "\n\nGroup {group} ({}), {modality}.",
        group_name(group)
    );
    match group_value(group, &report.before) {
        Some(Some(value)) => {
            let _ = write!(text, " Before this block: **{value}**.");
        }
        Some(None) => {
            text.push_str(" Before this block: **unknown** (inherited from the caller, or lost).")
        }
        None => {}
    }
    text
}

fn or_unknown(value: &Option<String>) -> &str {
    value.as_deref().unwrap_or("unknown")
}

fn axes_text(values: &[(std::sync::Arc<str>, f64)], unknown: &[std::sync::Arc<str>]) -> String {
    let mut parts: Vec<String> = values
        .iter()
        .map(|(name, value)| format!("{name}{}", short(*value)))
        .collect();
    parts.extend(
        unknown
            .iter()
            .filter(|name| !values.iter().any(|(known, _)| known == *name))
            .map(|name| format!("{name}?")),
    );
    parts.join(" ")
}

/// The modal state in effect before the block and the block's end point.
fn block_hover(report: &BlockReport, config: &MachineConfig) -> String {
    let before = &report.before;
    let mut text = String::from("**Modal state before this block**\n\n");
    let pole = match &before.pole {
        Some(None) => "none (the workpiece zero)".to_string(),
        Some(Some((first, second))) => format!("{} {}", short(*first), short(*second)),
        None => "unknown".to_string(),
    };
    let frame = match before.frame_is_identity {
        Some(true) => "none",
        Some(false) => "active",
        None => "unknown",
    };
    let feed = before
        .feed
        .map_or_else(|| "not programmed or unknown".to_string(), short);
    let _ = write!(
        text,
        "- motion {} · plane {} · units {} · {}\n- diameter mode {} · work offset {}\n- pole {pole} · programmable frame {frame} · feed {feed}",
        or_unknown(&before.motion),
        or_unknown(&before.plane),
        or_unknown(&before.units),
        or_unknown(&before.distance),
        or_unknown(&before.diameter),
        or_unknown(&before.settable_offset),
    );
    match &report.movement {
        Some(movement) => {
            let _ = write!(
                text,
                "\n\n**End point** ({}): {}",
                movement.motion,
                axes_text(&movement.end, &movement.uncertain)
            );
            if let Some(machine) = &movement.machine {
                if machine_differs(
                    machine,
                    &movement.end,
                    movement.transverse_as_diameter,
                    config,
                ) {
                    let _ = write!(text, "\n\nMachine coordinates (after the programmable frame, radius on transverse axes): {}", axes_text(machine, &[]));
                }
            }
        }
        None => text.push_str("\n\nThis block does not move an axis."),
    }
    if before.flow_uncertain {
        text.push_str("\n\n⚠ A label, jump or loop comes before this block: the values may not be the control's.");
    }
    text
}

/// Whether the machine coordinates differ from the program's end point (a frame moves the point).
pub fn machine_differs(
    machine: &[(std::sync::Arc<str>, f64)],
    end: &[(std::sync::Arc<str>, f64)],
    transverse_as_diameter: bool,
    config: &MachineConfig,
) -> bool {
    machine.iter().any(|(name, machine_value)| {
        let transverse = config
            .axis(name)
            .is_some_and(|axis| axis.kind == AxisKind::Transverse);
        let shown = if transverse && transverse_as_diameter {
            machine_value * 2.0
        } else {
            *machine_value
        };
        end.iter()
            .find(|(end_name, _)| end_name == name)
            .is_some_and(|(_, end_value)| !same(shown, *end_value))
    })
}

/// Whether the block calls a program: its hover then shows what the call ran (the program's run).
fn calls_a_program(line: &str, config: &MachineConfig) -> bool {
    let context = crate::syntax::SyntaxContext::new(config);
    let mut block = crate::syntax::Block::default();
    let mut findings = Vec::new();
    crate::syntax::LineParser::new().parse(line, &context, &mut block, &mut findings);
    block.interpreted_statements().iter().any(|statement| {
        matches!(
            statement,
            crate::syntax::ast::Statement::Call {
                kind: crate::syntax::ast::CallKind::Named | crate::syntax::ast::CallKind::Indirect,
                ..
            }
        )
    })
}
