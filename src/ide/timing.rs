//! The machining time of an open document (reference §15) for the hover and the status bar: the time
//! of each line over all its passes, the time elapsed before the line's first pass in execution
//! order, and the totals. Made once per revision from the document's run (its moves and dwells in
//! execution order), or, for a program that runs in program order, from reading it in order.

use crate::analysis::document::LineSource;
use crate::analysis::execution::ExecutedMove;
pub use crate::analysis::simulation::time::{MoveTime, TimeModel, TimeTotals};
use crate::analysis::{visit_moves_and_dwells, ProgramKind};
use crate::config::MachineConfig;
use crate::ide::execution::DocumentExecution;
use std::ops::Range;

/// The time of one line's moves over all passes.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LineTime {
    pub totals: TimeTotals,
    /// How many moves (and dwells) the line makes.
    pub moves: u32,
}

/// The time elapsed before a line's first pass starts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elapsed {
    /// Seconds of the moves before it whose time is known.
    pub seconds: f64,
    /// Moves before it whose time is unknown: then `seconds` is a lower bound.
    pub unknown_moves: u64,
}

#[derive(Debug, Clone, PartialEq, Default)]
pub struct DocumentTimes {
    lines: Vec<LineTime>,
    /// Per line, the time before its first pass; `None` for a line the run does not place (a line
    /// without moves in a program with flow, or one that never runs).
    starts: Vec<Option<Elapsed>>,
    totals: TimeTotals,
}

impl DocumentTimes {
    /// The times of the document held by `source`, whose run is `execution`.
    pub fn new(
        source: &dyn LineSource,
        execution: &DocumentExecution,
        config: &MachineConfig,
        kind: ProgramKind,
    ) -> DocumentTimes {
        let line_count = source.line_count();
        let mut times = DocumentTimes {
            lines: vec![LineTime::default(); line_count],
            starts: vec![None; line_count],
            totals: TimeTotals::default(),
        };
        let model = TimeModel::new(config);
        match execution {
            DocumentExecution::Executed { run, .. } => {
                for executed in run.moves.iter() {
                    times.add(
                        ExecutedMove::outer_line(executed),
                        model.time_of(&executed.movement),
                    );
                }
            }
            DocumentExecution::InOrder => {
                let mut text = String::new();
                source.for_each_line(0, &mut |_, line| {
                    text.push_str(line);
                    text.push('\n');
                    true
                });
                let mut next_line = 0;
                visit_moves_and_dwells(&text, config, kind, |movement| {
                    // Every line up to this one starts after what ran before it.
                    times.place_lines_up_to(&mut next_line, movement.line);
                    times.add(movement.line, model.time_of(movement));
                });
                times.place_lines_up_to(&mut next_line, line_count);
            }
        }
        times
    }

    /// In program order, the lines from `next` up to `line` (exclusive) that have no start yet begin
    /// at the time elapsed so far.
    fn place_lines_up_to(&mut self, next: &mut usize, line: usize) {
        let elapsed = self.elapsed();
        while *next < line.min(self.starts.len()) {
            self.starts[*next].get_or_insert(elapsed);
            *next += 1;
        }
    }

    fn elapsed(&self) -> Elapsed {
        Elapsed {
            seconds: self.totals.total_s,
            unknown_moves: self.totals.unknown_moves,
        }
    }

    fn add(&mut self, line: usize, time: MoveTime) {
        let elapsed = self.elapsed();
        if let Some(start) = self.starts.get_mut(line) {
            start.get_or_insert(elapsed);
        }
        if let Some(entry) = self.lines.get_mut(line) {
            entry.totals.add(time);
            entry.moves += 1;
        }
        self.totals.add(time);
    }

    /// The time of `line`'s moves over all passes.
    pub fn line(&self, line: usize) -> LineTime {
        self.lines.get(line).copied().unwrap_or_default()
    }

    /// The time elapsed before `line`'s first pass, if the run places the line.
    pub fn start(&self, line: usize) -> Option<Elapsed> {
        self.starts.get(line).copied().flatten()
    }

    /// The totals of the whole document.
    pub fn totals(&self) -> TimeTotals {
        self.totals
    }

    /// The totals of the moves of `lines`.
    pub fn totals_in(&self, lines: Range<usize>) -> TimeTotals {
        let mut totals = TimeTotals::default();
        for line in self.lines.get(lines).unwrap_or_default() {
            totals.total_s += line.totals.total_s;
            totals.feed_s += line.totals.feed_s;
            totals.rapid_s += line.totals.rapid_s;
            totals.dwell_s += line.totals.dwell_s;
            totals.unknown_moves += line.totals.unknown_moves;
        }
        totals
    }
}

/// A duration as the hover and the status bar write it: `9.425 s`, `2 min 3.5 s`, `1 h 2 min 3 s`.
pub fn format_duration(seconds: f64) -> String {
    if !seconds.is_finite() || seconds < 0.0 {
        return "?".to_string();
    }
    if seconds < 60.0 {
        return format!("{} s", crate::ide::numbers::short(seconds));
    }
    let whole = seconds.round() as u64;
    let (hours, minutes, rest) = (whole / 3600, whole / 60 % 60, whole % 60);
    if hours > 0 {
        format!("{hours} h {minutes} min {rest} s")
    } else {
        format!("{minutes} min {rest} s")
    }
}

/// The hover's lines about the time of `line`, as Markdown; `None` for a line without moves and
/// without a place in the run.
pub fn time_summary(times: &DocumentTimes, line: usize) -> Option<String> {
    let own = times.line(line);
    let start = times.start(line);
    if own.moves == 0 && start.is_none() {
        return None;
    }
    let mut parts = Vec::new();
    if own.moves > 0 {
        let known = format_duration(own.totals.total_s);
        let text = match own.totals.unknown_moves {
            0 => format!("**Time**: {known}"),
            unknown if u64::from(own.moves) == unknown => "**Time**: unknown".to_string(),
            unknown => format!("**Time**: at least {known} ({unknown} of its moves unknown)"),
        };
        parts.push(text);
    }
    if let Some(start) = start {
        let elapsed = format_duration(start.seconds);
        parts.push(match start.unknown_moves {
            0 => format!("starts after {elapsed}"),
            unknown => format!("starts after at least {elapsed} ({unknown} earlier moves unknown)"),
        });
    }
    Some(parts.join(", ") + ".")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::document::TextLines;
    use crate::analysis::execution::ExecutionOptions;
    use crate::analysis::library::NoLibrary;
    use crate::ide::execution::execute_document;

    fn times_of(text: &str) -> DocumentTimes {
        let lines = TextLines::new(text);
        let config = MachineConfig::mill();
        let execution = execute_document(
            &lines,
            &config,
            ProgramKind::Main,
            &NoLibrary,
            &ExecutionOptions::default(),
            None,
        );
        DocumentTimes::new(&lines, &execution, &config, ProgramKind::Main)
    }

    #[test]
    fn a_program_in_order_places_every_line() {
        let times = times_of("G90 G0 X0 Y0\nG1 X100 F500\nM3 S100\nG4 F2.5\nX0\n");
        assert_eq!(times.line(1).totals.total_s, 12.0);
        assert_eq!(times.line(3).totals.dwell_s, 2.5);
        let start = times.start(2).expect("placed");
        assert_eq!((start.seconds, start.unknown_moves), (12.0, 1));
        assert_eq!(times.start(4).expect("placed").seconds, 14.5);
        assert_eq!(times.totals().total_s, 26.5);
        assert_eq!(times.totals_in(3..5).total_s, 14.5);
        let summary = time_summary(&times, 1).expect("a summary");
        assert!(summary.contains("**Time**: 12 s"), "{summary}");
        assert!(
            summary.contains("starts after at least 0 s (1 earlier moves unknown)"),
            "{summary}"
        );
    }

    #[test]
    fn a_loop_counts_every_pass_and_starts_at_the_first() {
        let text = "G90 G0 X0\nG1 F600\nFOR R1=1 TO 3\nG1 X=R1*10\nG4 F1\nENDFOR\nM30\n";
        let times = times_of(text);
        // X10 (1 s), X20 (1 s), X30 (1 s) at 600 mm/min.
        assert_eq!(times.line(3).totals.total_s, 3.0);
        assert_eq!(times.line(3).moves, 3);
        assert_eq!(times.line(4).totals.dwell_s, 3.0);
        assert_eq!(times.start(4).expect("placed").seconds, 1.0);
        let summary = time_summary(&times, 3).expect("a summary");
        assert!(summary.contains("**Time**: 3 s"), "{summary}");
        assert!(summary.contains("starts after at least 0 s"), "{summary}");
    }

    #[test]
    fn durations_read_as_minutes_and_hours() {
        assert_eq!(format_duration(9.4248), "9.425 s");
        assert_eq!(format_duration(12.0), "12 s");
        assert_eq!(format_duration(123.4), "2 min 3 s");
        assert_eq!(format_duration(3723.0), "1 h 2 min 3 s");
        assert_eq!(format_duration(f64::NAN), "?");
    }
}
