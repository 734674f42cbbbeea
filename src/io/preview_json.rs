//! The JSON form of the preview (the command line's `preview --format json` and the server's
//! `sinumerik.endpointPreview`), written move by move: a program of a million blocks must neither build
//! a tree of a million JSON values nor keep its moves in memory. Numbers go through serde_json, so they
//! print exactly as any other JSON the product writes (`58.0`, shortest round trip).

use crate::analysis::execution::ExecutedMove;
use crate::analysis::simulation::time::{TimeModel, TimeTotals};
use crate::analysis::Move;
use crate::diagnostics::{LineDiagnostic, Span};
use crate::ide::numbers::without_noise;
use std::io::{self, Write};
use std::sync::Arc;

/// Writes the opening of the document: the file, the units and the start of the `moves` array.
pub fn write_header(out: &mut dyn Write, file: &str, metric: bool) -> io::Result<()> {
    write_header_with(out, file, metric, &[])
}

/// Writes the opening of the document with what was assumed about the entry state of a subprogram
/// (`"assumed": {"units": "G71", ...}`, left out when nothing was assumed).
pub fn write_header_with(
    out: &mut dyn Write,
    file: &str,
    metric: bool,
    assumed: &[(&'static str, String)],
) -> io::Result<()> {
    out.write_all(b"{\"file\":")?;
    serde_json::to_writer(&mut *out, file)?;
    let units = if metric { "mm" } else { "inch" };
    write!(out, ",\"units\":\"{units}\",")?;
    if !assumed.is_empty() {
        out.write_all(b"\"assumed\":{")?;
        for (index, (name, value)) in assumed.iter().enumerate() {
            if index > 0 {
                out.write_all(b",")?;
            }
            write!(out, "\"{name}\":")?;
            serde_json::to_writer(&mut *out, value)?;
        }
        out.write_all(b"},")?;
    }
    out.write_all(b"\n\"moves\": [")
}

/// Writes one move with its time in seconds (`null` when unknown); `first` says whether it opens
/// the array.
pub fn write_move(
    out: &mut dyn Write,
    movement: &Move,
    first: bool,
    time_s: Option<f64>,
) -> io::Result<()> {
    write_move_fields(out, movement, first)?;
    write_time(out, time_s)?;
    out.write_all(b"}")
}

/// Writes `,"time_s":` and the seconds, rounded to microseconds, or `null`.
fn write_time(out: &mut dyn Write, time_s: Option<f64>) -> io::Result<()> {
    out.write_all(b",\"time_s\":")?;
    write_seconds(out, time_s)
}

/// Seconds rounded to microseconds, written from their integer microseconds (a preview writes one
/// per move); `null` when unknown.
fn write_seconds(out: &mut dyn Write, seconds: Option<f64>) -> io::Result<()> {
    let micros = match seconds {
        Some(seconds) if seconds.is_finite() && (0.0..1e12).contains(&seconds) => {
            (seconds * 1e6).round() as u64
        }
        Some(seconds) if seconds.is_finite() => {
            return serde_json::to_writer(out, &seconds).map_err(io::Error::from)
        }
        _ => return out.write_all(b"null"),
    };
    let (whole, mut fraction) = (micros / 1_000_000, micros % 1_000_000);
    write_integer(out, whole)?;
    if fraction == 0 {
        return out.write_all(b".0");
    }
    let mut digits = [b'.', b'0', b'0', b'0', b'0', b'0', b'0'];
    for place in (1..7).rev() {
        digits[place] = b'0' + (fraction % 10) as u8;
        fraction /= 10;
    }
    let mut length = 7;
    while digits[length - 1] == b'0' {
        length -= 1;
    }
    out.write_all(&digits[..length])
}

/// Writes the top-level `"time"` of the preview: the sums over the moves and dwells, and how many
/// moves' times are unknown.
pub fn write_time_totals(
    out: &mut dyn Write,
    totals: &crate::analysis::simulation::time::TimeTotals,
) -> io::Result<()> {
    out.write_all(b"\n\"time\":{\"total_s\":")?;
    write_seconds(out, Some(totals.total_s))?;
    out.write_all(b",\"feed_s\":")?;
    write_seconds(out, Some(totals.feed_s))?;
    out.write_all(b",\"rapid_s\":")?;
    write_seconds(out, Some(totals.rapid_s))?;
    out.write_all(b",\"dwell_s\":")?;
    write_seconds(out, Some(totals.dwell_s))?;
    write!(out, ",\"unknown_moves\":{}}},", totals.unknown_moves)
}

/// Writes one executed move: the move's fields, then what execution adds (`pass`, `file`, `stack`,
/// `conditional`, `assumed`), each only where it applies.
pub fn write_executed_move(
    out: &mut dyn Write,
    executed: &ExecutedMove,
    first: bool,
    file: &str,
    time_s: Option<f64>,
) -> io::Result<()> {
    write_move_fields(out, &executed.movement, first)?;
    write_time(out, time_s)?;
    if executed.pass > 0 {
        write!(out, ",\"pass\":{}", executed.pass)?;
    }
    if let Some(path) = &executed.path {
        out.write_all(b",\"file\":")?;
        serde_json::to_writer(&mut *out, path.as_ref())?;
    }
    if !executed.stack.is_empty() {
        out.write_all(b",\"stack\":[")?;
        for (index, site) in executed.stack.iter().enumerate() {
            if index > 0 {
                out.write_all(b",")?;
            }
            out.write_all(b"{\"file\":")?;
            let path = site.path.as_deref().unwrap_or(file);
            serde_json::to_writer(&mut *out, path)?;
            write!(out, ",\"line\":{}}}", site.line + 1)?;
        }
        out.write_all(b"]")?;
    }
    if executed.conditional {
        out.write_all(b",\"conditional\":true")?;
    }
    if let Some(cycle) = &executed.movement.cycle {
        out.write_all(b",\"cycle\":")?;
        serde_json::to_writer(&mut *out, cycle.as_ref())?;
    }
    if !executed.assumed.is_empty() {
        out.write_all(b",\"assumed\":[")?;
        for (index, name) in executed.assumed.iter().enumerate() {
            if index > 0 {
                out.write_all(b",")?;
            }
            serde_json::to_writer(&mut *out, name.as_ref())?;
        }
        out.write_all(b"]")?;
    }
    out.write_all(b"}")
}

/// Writes the fields of one move, without the closing brace.
fn write_move_fields(out: &mut dyn Write, movement: &Move, first: bool) -> io::Result<()> {
    out.write_all(if first {
        b"\n  {\"line\":"
    } else {
        b",\n  {\"line\":"
    })?;
    write_integer(out, movement.line as u64 + 1)?;
    out.write_all(b",\"block\":")?;
    serde_json::to_writer(&mut *out, &movement.block_number)?;
    out.write_all(b",\"motion\":")?;
    serde_json::to_writer(&mut *out, movement.motion.as_ref())?;
    out.write_all(b",\"start\":")?;
    write_axes(out, &movement.start)?;
    out.write_all(b",\"end\":")?;
    write_axes(out, &movement.end)?;
    out.write_all(b",\"mcs\":")?;
    match &movement.machine {
        Some(values) => write_axes(out, values)?,
        None => out.write_all(b"null")?,
    }
    out.write_all(b",\"arc\":")?;
    match &movement.arc {
        Some(arc) => {
            out.write_all(b"{\"centre\":")?;
            write_axes(out, &arc.centre)?;
            out.write_all(b",\"radius\":")?;
            write_number(out, arc.radius)?;
            let direction = if arc.clockwise { "cw" } else { "ccw" };
            let machine_direction = match arc.machine_clockwise {
                Some(true) => "\"cw\"",
                Some(false) => "\"ccw\"",
                None => "null",
            };
            write!(
                out,
                ",\"direction\":\"{direction}\",\"mcs_direction\":{machine_direction},\"sweep\":"
            )?;
            write_number(out, arc.sweep)?;
            out.write_all(b"}")?;
        }
        None => out.write_all(b"null")?,
    }
    out.write_all(b",\"feed\":")?;
    match movement.feed {
        Some(feed) => write_number(out, feed)?,
        None => out.write_all(b"null")?,
    }
    out.write_all(b",\"uncertain\":[")?;
    for (index, name) in movement.uncertain.iter().enumerate() {
        if index > 0 {
            out.write_all(b",")?;
        }
        serde_json::to_writer(&mut *out, name.as_ref())?;
    }
    out.write_all(b"]")?;
    // A rounding or chamfer the corner stage inserted (reference §14); absent on other moves.
    if let Some(inserted) = movement.inserted {
        write!(out, ",\"inserted\":\"{inserted}\"")?;
    }
    Ok(())
}

/// Closes the `moves` array and writes the time totals and the diagnostics with 1-based lines and
/// character columns (`columns` converts a line's byte span).
pub fn write_footer(
    out: &mut dyn Write,
    totals: &crate::analysis::simulation::time::TimeTotals,
    diagnostics: &[LineDiagnostic],
    columns: &dyn Fn(&LineDiagnostic) -> (usize, usize),
) -> io::Result<()> {
    out.write_all(b"\n],")?;
    write_time_totals(out, totals)?;
    out.write_all(b"\n\"diagnostics\": [")?;
    for (index, item) in diagnostics.iter().enumerate() {
        out.write_all(if index == 0 { b"\n  " } else { b",\n  " })?;
        let (column, end_column) = columns(item);
        write!(
            out,
            "{{\"line\":{},\"column\":{column},\"end_column\":{end_column},\"severity\":\"{}\",\"code\":\"{}\",\"message\":",
            item.line + 1,
            item.diagnostic.severity.as_str(),
            item.diagnostic.code.as_str(),
        )?;
        serde_json::to_writer(&mut *out, &item.diagnostic.message)?;
        out.write_all(b"}")?;
    }
    out.write_all(b"\n]}\n")
}

fn write_axes(out: &mut dyn Write, values: &[(Arc<str>, f64)]) -> io::Result<()> {
    out.write_all(b"{")?;
    for (index, (name, value)) in values.iter().enumerate() {
        if index > 0 {
            out.write_all(b",")?;
        }
        serde_json::to_writer(&mut *out, name.as_ref())?;
        out.write_all(b":")?;
        write_number(out, *value)?;
    }
    out.write_all(b"}")
}

/// Writes a number as serde_json would. Most values of a program have at most three decimals; they
/// are written from their integer thousandths, which gives the same shortest text as the general
/// algorithm (checked below) at a fraction of its cost, the bulk of a preview's time.
fn write_number(out: &mut dyn Write, value: f64) -> io::Result<()> {
    let value = without_noise(value);
    let thousandths = value * 1000.0;
    if thousandths.abs() < 1e15 && thousandths == thousandths.trunc() {
        let count = thousandths as i64;
        // The text below parses back to `value` only if `value` is the double nearest to it.
        if count as f64 / 1000.0 == value {
            let magnitude = count.unsigned_abs();
            let (whole, fraction) = (magnitude / 1000, magnitude % 1000);
            // The digits are put together in a buffer: the formatting machinery of `write!` was a
            // tenth of a preview's time.
            let mut buffer = [0u8; 40];
            let mut length = 0;
            if count < 0 {
                buffer[0] = b'-';
                length = 1;
            }
            length += write_digits(&mut buffer[length..], whole);
            buffer[length] = b'.';
            length += 1;
            let digits = [fraction / 100, fraction / 10 % 10, fraction % 10];
            let shown = match fraction {
                0 => 1,
                _ if fraction % 100 == 0 => 1,
                _ if fraction % 10 == 0 => 2,
                _ => 3,
            };
            for digit in &digits[..shown] {
                buffer[length] = b'0' + *digit as u8;
                length += 1;
            }
            return out.write_all(&buffer[..length]);
        }
    }
    serde_json::to_writer(out, &value).map_err(io::Error::from)
}

/// Writes the decimal digits of `value` at the start of `buffer` (which holds at least 20 bytes)
/// and returns how many.
fn write_digits(buffer: &mut [u8], mut value: u64) -> usize {
    let mut reversed = [0u8; 20];
    let mut count = 0;
    loop {
        reversed[count] = b'0' + (value % 10) as u8;
        count += 1;
        value /= 10;
        if value == 0 {
            break;
        }
    }
    for (index, digit) in reversed[..count].iter().rev().enumerate() {
        buffer[index] = *digit;
    }
    count
}

/// Writes an unsigned integer without the formatting machinery.
fn write_integer(out: &mut dyn Write, value: u64) -> io::Result<()> {
    let mut buffer = [0u8; 20];
    let length = write_digits(&mut buffer, value);
    out.write_all(&buffer[..length])
}

/// The JSON document of `preview` for `moves` and `diagnostics` of the program `file`, as the language
/// server's `sinumerik.endpointPreview` returns it; `columns` gives the 1-based character columns of
/// a span in a 0-based line.
/// `timing` times each move and gives the totals of the lines shown.
pub fn write_preview_json(
    out: &mut dyn Write,
    file: &str,
    metric: bool,
    moves: &[Move],
    timing: (&TimeModel, &TimeTotals),
    diagnostics: &[LineDiagnostic],
    columns: &mut dyn FnMut(usize, Span) -> (usize, usize),
) -> io::Result<()> {
    write_header(out, file, metric)?;
    for (index, movement) in moves.iter().enumerate() {
        let time = timing.0.time_of(movement).seconds;
        write_move(out, movement, index == 0, time)?;
    }
    let columns = std::cell::RefCell::new(columns);
    write_footer(out, timing.1, diagnostics, &|item| {
        (columns.borrow_mut())(item.line, item.diagnostic.span)
    })
}

/// Like [`write_preview_json`] for executed moves, with what was assumed about the entry state.
// Each argument is one part of the document (header, moves, times, findings, column conversion).
#[allow(clippy::too_many_arguments)]
pub fn write_executed_preview_json(
    out: &mut dyn Write,
    file: &str,
    metric: bool,
    assumed: &[(&'static str, String)],
    moves: &[&ExecutedMove],
    timing: (&TimeModel, &TimeTotals),
    diagnostics: &[LineDiagnostic],
    columns: &mut dyn FnMut(usize, Span) -> (usize, usize),
) -> io::Result<()> {
    write_header_with(out, file, metric, assumed)?;
    for (index, movement) in moves.iter().enumerate() {
        let time = timing.0.time_of(&movement.movement).seconds;
        write_executed_move(out, movement, index == 0, file, time)?;
    }
    let columns = std::cell::RefCell::new(columns);
    write_footer(out, timing.1, diagnostics, &|item| {
        (columns.borrow_mut())(item.line, item.diagnostic.span)
    })
}

/// The 1-based character columns of a span in one line of text: the first character and the one
/// after the last. Offsets past the end count as the end, and an offset inside a multi-byte character
/// widens the span to that character, so a bad span never panics.
pub fn line_columns(line: &str, span: Span) -> (usize, usize) {
    let mut start = span.start().min(line.len());
    while !line.is_char_boundary(start) {
        start -= 1;
    }
    let mut end = span.end().max(span.start()).min(line.len());
    while !line.is_char_boundary(end) {
        end += 1;
    }
    let start_index = line[..start].chars().count();
    (
        start_index + 1,
        start_index + line[start..end].chars().count() + 1,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fast(value: f64) -> String {
        let mut out = Vec::new();
        write_number(&mut out, value).unwrap();
        String::from_utf8(out).unwrap()
    }

    fn seconds(value: Option<f64>) -> String {
        let mut out = Vec::new();
        write_seconds(&mut out, value).unwrap();
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn seconds_print_to_the_microsecond() {
        assert_eq!(seconds(Some(12.0)), "12.0");
        assert_eq!(seconds(Some(9.42477796)), "9.424778");
        assert_eq!(seconds(Some(0.015)), "0.015");
        assert_eq!(seconds(Some(0.0000004)), "0.0");
        assert_eq!(seconds(None), "null");
        assert_eq!(seconds(Some(f64::NAN)), "null");
        for value in [0.1, 1.5, 45.898544, 1234.000001] {
            let text = seconds(Some(value));
            let back: f64 = text.parse().unwrap();
            assert!((back - value).abs() < 1e-6, "{value} {text}");
        }
    }

    #[test]
    fn numbers_print_as_serde_json_prints_them() {
        let mut values = vec![
            0.0, -0.0, 1.0, -1.0, 58.0, 0.5, 0.05, 0.005, 0.001, 1e-7, 123456.789,
        ];
        values.extend([
            1e14,
            1e15,
            1e16,
            2.5e-3,
            -59.985,
            1.0 / 3.0,
            25.4,
            12.7 * 3.0,
        ]);
        let mut state = 12345u64;
        for _ in 0..100_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let thousandths = (state % 2_000_000_000) as f64 - 1e9;
            values.push(thousandths / 1000.0);
            values.push(thousandths / 7.0);
        }
        for value in values {
            let expected = serde_json::to_string(&without_noise(value)).unwrap();
            assert_eq!(fast(value), expected, "{value:e}");
        }
    }
}
