//! S180, an axis the configured machine does not have, reported once per axis and file. A lathe
//! program read with the mill's axes, or a machine with an axis the configuration leaves out, uses
//! that axis in hundreds of blocks: one finding per block would bury every other finding. The parser
//! reports every occurrence (a block is read on its own); [`summarize`] keeps the first finding of
//! each axis and says there how many blocks of the file use the axis. `check` and the server both
//! apply it to the findings of a whole file, so that they report the same.

use crate::diagnostics::{Code, LineDiagnostic};
use std::collections::HashMap;

/// The message of one occurrence, as the parser reports it: `name` is the axis word's name, `axes`
/// the configured axes (`axes X, Y, Z`).
pub fn occurrence_message(name: &str, axes: &str) -> String {
    format!("`{name}` is not an axis of the configured machine ({axes}); positions on it cannot be resolved")
}

/// The axis a finding of S180 is about, read from its message (see [`occurrence_message`]).
pub fn axis_of(message: &str) -> Option<&str> {
    let rest = message.strip_prefix('`')?;
    let end = rest.find('`')?;
    Some(&rest[..end])
}

/// Whether `findings` hold a finding of S180.
pub fn any(findings: &[LineDiagnostic]) -> bool {
    findings
        .iter()
        .any(|item| item.diagnostic.code == Code::AxisNotConfigured)
}

/// Keeps, of the S180 findings of one file (sorted by line), the first of each axis, and says in its
/// message how many blocks use the axis and how to configure it.
pub fn summarize(findings: &mut Vec<LineDiagnostic>) {
    // Per axis: the index of its first finding and the number of lines that use it.
    let mut axes: HashMap<String, (usize, usize, usize)> = HashMap::new();
    for (index, item) in findings.iter().enumerate() {
        if item.diagnostic.code != Code::AxisNotConfigured {
            continue;
        }
        let Some(name) = axis_of(&item.diagnostic.message) else {
            continue;
        };
        let entry = axes
            .entry(name.to_string())
            .or_insert((index, 0, usize::MAX));
        if entry.2 != item.line {
            entry.1 += 1;
            entry.2 = item.line;
        }
    }
    if axes.is_empty() {
        return;
    }
    let mut first = vec![None; findings.len()];
    for (name, (index, blocks, _)) in &axes {
        first[*index] = Some((name.as_str(), *blocks));
    }
    let mut summarized = Vec::with_capacity(findings.len());
    for (item, first) in findings.drain(..).zip(first) {
        if item.diagnostic.code != Code::AxisNotConfigured
            || axis_of(&item.diagnostic.message).is_none()
        {
            summarized.push(item);
            continue;
        }
        let Some((name, blocks)) = first else {
            continue;
        };
        let mut item = item;
        item.diagnostic.message = summary_message(&item.diagnostic.message, name, blocks);
        summarized.push(item);
    }
    *findings = summarized;
}

/// The message of an axis's first finding: the occurrence's, with the count and the remedy.
fn summary_message(occurrence: &str, name: &str, blocks: usize) -> String {
    let head = occurrence
        .split_once(';')
        .map_or(occurrence, |(head, _)| head);
    let uses = if blocks == 1 {
        "1 block of this file uses it".to_string()
    } else {
        format!("{blocks} blocks of this file use it, reported here only")
    };
    format!(
        "{head} ({uses}); positions on it cannot be resolved. If the machine has {name}, list it with its kind in the `[axes]` table of sinumerik.toml, together with the other axes (docs/configuration.md)"
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostics::{Diagnostic, Span};

    fn finding(line: usize, name: &str) -> LineDiagnostic {
        LineDiagnostic {
            line,
            diagnostic: Diagnostic::new(
                Code::AxisNotConfigured,
                Span::new(0, 1),
                occurrence_message(name, "axes X, Z, C"),
            ),
        }
    }

    #[test]
    fn one_finding_per_axis_at_the_first_block_with_the_count_of_blocks() {
        let other = LineDiagnostic {
            line: 2,
            diagnostic: Diagnostic::new(Code::MissingValue, Span::new(0, 1), "x"),
        };
        let mut findings = vec![
            finding(1, "Y"),
            other.clone(),
            finding(3, "B"),
            finding(3, "Y"),
            finding(3, "Y"),
            finding(7, "Y"),
        ];
        summarize(&mut findings);
        assert_eq!(findings.len(), 3, "{findings:#?}");
        assert_eq!(findings[0].line, 1);
        assert!(
            findings[0]
                .diagnostic
                .message
                .contains("(3 blocks of this file use it"),
            "{}",
            findings[0].diagnostic.message
        );
        assert!(findings[0].diagnostic.message.contains("`[axes]`"));
        assert_eq!(findings[1], other);
        assert_eq!(findings[2].line, 3);
        assert!(findings[2].diagnostic.message.contains("(1 block of"));
        assert_eq!(axis_of(&findings[2].diagnostic.message), Some("B"));
    }
}
