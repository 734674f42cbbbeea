//! How an update changed the document's list of findings (`FindingsChange`), and the revisions that
//! number the states of the findings across every analysis of the process.

/// How one update changed the list of findings ([`DocumentAnalysis::diagnostics`]): the first `start`
/// are as they were; the old ones from `old_end` on are the new ones from `new_end` on, each
/// `line_delta` lines further; the old ones between were replaced by the new ones between. It lets
/// a consumer that keeps something per finding (the server's JSON) redo only the replaced part.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FindingsChange {
    pub start: usize,
    pub old_end: usize,
    pub new_end: usize,
    pub line_delta: isize,
}

impl FindingsChange {
    /// The change of a list of `count` findings that did not change.
    pub fn none(count: usize) -> FindingsChange {
        FindingsChange {
            start: count,
            old_end: count,
            new_end: count,
            line_delta: 0,
        }
    }
}

/// Numbers for the states of the findings, unique across every analysis of the process: a number
/// remembered from another analysis (one replaced after a change of configuration) never matches.
static NEXT_FINDINGS_REVISION: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);

#[derive(Debug, Clone, Copy)]
pub(super) struct FindingsHistory {
    pub(super) revision: u64,
    /// The revision before the last update, and how that update changed the findings (`None` when
    /// it is not known).
    pub(super) previous: u64,
    pub(super) change: Option<FindingsChange>,
}

impl FindingsHistory {
    pub(super) fn new() -> FindingsHistory {
        FindingsHistory {
            revision: next_findings_revision(),
            previous: 0,
            change: None,
        }
    }
}

pub(super) fn next_findings_revision() -> u64 {
    NEXT_FINDINGS_REVISION.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
}
