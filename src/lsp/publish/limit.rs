//! The optional limit on the diagnostics published for one document (the `maxDiagnostics` setting).
//! VS Code keeps at most 1,000 problems per file and drops the rest itself, errors first; a server
//! that sends 40,000 findings of a large CAM program to it pays for writing and sending megabytes
//! on every edit for nothing the user sees. Under a limit the server keeps the same ones VS Code
//! would keep (errors, then warnings, information and hints, each in document order), and adds one
//! note saying how many were left out. The choice depends on the findings alone, so it does not
//! change from version to version unless the findings do. Without a limit every finding goes out.

use crate::diagnostics::{LineDiagnostic, Severity};
use crate::lsp::publish::wire::WireDiagnostic;
use std::borrow::Cow;
use tower_lsp_server::ls_types::Range;

/// The findings shown under `limit`, in document order, and how many were left out.
pub fn within_limit(
    diagnostics: &[LineDiagnostic],
    limit: Option<usize>,
) -> (Cow<'_, [LineDiagnostic]>, usize) {
    let Some(limit) = limit.filter(|&limit| limit < diagnostics.len()) else {
        return (Cow::Borrowed(diagnostics), 0);
    };
    // How many of each severity there are, most severe first; then the least severe one that still
    // fits, and how many of it fit.
    let rank = |severity: Severity| match severity {
        Severity::Error => 0,
        Severity::Warning => 1,
        Severity::Information => 2,
        Severity::Hint => 3,
    };
    let mut counts = [0usize; 4];
    for item in diagnostics {
        counts[rank(item.diagnostic.severity)] += 1;
    }
    let mut left = limit;
    let mut last_rank = 0;
    let mut of_last_rank = 0;
    for (index, &count) in counts.iter().enumerate() {
        last_rank = index;
        of_last_rank = count.min(left);
        left -= of_last_rank;
        if left == 0 {
            break;
        }
    }
    let mut taken_of_last_rank = 0;
    let shown = diagnostics
        .iter()
        .filter(|item| {
            let rank = rank(item.diagnostic.severity);
            if rank < last_rank {
                return true;
            }
            if rank == last_rank && taken_of_last_rank < of_last_rank {
                taken_of_last_rank += 1;
                return true;
            }
            false
        })
        .cloned()
        .collect();
    (Cow::Owned(shown), diagnostics.len() - limit)
}

/// The note published with a limited set, as a diagnostic at the document's start.
pub fn note(left_out: usize, limit: usize) -> String {
    format!(
        "{left_out} more findings are not shown here: the setting maxDiagnostics shows {limit} per \
         document, errors first. `sinumerik-lsp check` lists them all."
    )
}

/// The note as the client receives it.
pub fn note_diagnostic(message: &str) -> WireDiagnostic<'_> {
    WireDiagnostic {
        range: Range::default(),
        severity: 3,
        code: None,
        source: "sinumerik",
        message,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostics::{Code, Diagnostic, Span};

    fn finding(line: usize, severity: Severity) -> LineDiagnostic {
        let mut diagnostic = Diagnostic::new(Code::ALL[0], Span::new(0, 1), format!("{line}"));
        diagnostic.severity = severity;
        LineDiagnostic { line, diagnostic }
    }

    fn lines(shown: &[LineDiagnostic]) -> Vec<usize> {
        shown.iter().map(|item| item.line).collect()
    }

    #[test]
    fn errors_come_first_then_warnings_then_the_rest_each_in_document_order() {
        let severities = [
            Severity::Hint,
            Severity::Warning,
            Severity::Error,
            Severity::Information,
            Severity::Warning,
            Severity::Error,
            Severity::Hint,
        ];
        let all: Vec<LineDiagnostic> = severities
            .iter()
            .enumerate()
            .map(|(line, &severity)| finding(line, severity))
            .collect();
        let cases: [(usize, Vec<usize>); 6] = [
            (0, vec![]),
            (1, vec![2]),
            (2, vec![2, 5]),
            (3, vec![1, 2, 5]),
            (5, vec![1, 2, 3, 4, 5]),
            (6, vec![0, 1, 2, 3, 4, 5]),
        ];
        for (limit, expected) in cases {
            let (shown, left_out) = within_limit(&all, Some(limit));
            assert_eq!(lines(&shown), expected, "limit {limit}");
            assert_eq!(left_out, all.len() - limit, "limit {limit}");
        }
    }

    #[test]
    fn without_a_limit_or_under_it_everything_is_shown_as_it_is() {
        let all = vec![finding(0, Severity::Hint), finding(3, Severity::Error)];
        for limit in [None, Some(2), Some(100)] {
            let (shown, left_out) = within_limit(&all, limit);
            assert!(matches!(shown, Cow::Borrowed(_)));
            assert_eq!(shown.as_ref(), all.as_slice());
            assert_eq!(left_out, 0);
        }
    }

    #[test]
    fn the_note_is_an_array_of_one_information_diagnostic_saying_how_many_are_left_out() {
        let message = note(30_387, 1000);
        let mut encoded = Vec::new();
        note_diagnostic(&message).write(&mut encoded);
        let note: serde_json::Value = serde_json::from_slice(&encoded).unwrap();
        assert_eq!(note["severity"], 3);
        assert_eq!(note["range"]["start"]["line"], 0);
        assert_eq!(note.get("code"), None);
        let message = note["message"].as_str().unwrap();
        assert!(message.starts_with("30387 more findings"), "{message}");
        assert!(message.contains("shows 1000"), "{message}");
    }
}
