//! Shrinking a failing input while it still fails: first whole lines (in halving chunks), then
//! characters, and for document cases first whole edits. Bounded by a number of attempts and a time,
//! so a slow failure still ends with the smallest input found so far.

use super::document::DocumentCase;
use std::time::{Duration, Instant};

/// Stops a minimisation after this many tries of candidates or this much time.
const MAX_ATTEMPTS: usize = 20_000;
const MAX_TIME: Duration = Duration::from_secs(60);

struct Budget {
    attempts: usize,
    started: Instant,
}

impl Budget {
    fn new() -> Budget {
        Budget {
            attempts: 0,
            started: Instant::now(),
        }
    }

    fn spend(&mut self) -> bool {
        self.attempts += 1;
        self.attempts <= MAX_ATTEMPTS && self.started.elapsed() < MAX_TIME
    }
}

/// Removes chunks of `items` (halving the chunk size) while `fails` stays true for what is left.
fn shrink_list<T: Clone>(
    items: &mut Vec<T>,
    budget: &mut Budget,
    fails: &mut dyn FnMut(&[T]) -> bool,
) {
    let mut chunk = items.len().div_ceil(2).max(1);
    loop {
        let mut start = 0;
        while start < items.len() {
            if !budget.spend() {
                return;
            }
            let end = (start + chunk).min(items.len());
            let mut candidate = items.clone();
            candidate.drain(start..end);
            if fails(&candidate) {
                *items = candidate;
            } else {
                start = end;
            }
        }
        if chunk == 1 {
            return;
        }
        chunk = chunk.div_ceil(2);
    }
}

/// The smallest text found that still fails: lines first (with their line ends), then characters.
pub fn minimise_text(text: &str, fails: &mut dyn FnMut(&str) -> bool) -> String {
    repeat_while_smaller(text.to_string(), &|text| text.len(), &mut |best, budget| {
        shrink_text_once(best, budget, fails)
    })
}

/// Runs `shrink_once` again while it makes the input smaller: each round may make an earlier step
/// possible again (a line that mattered only together with another).
fn repeat_while_smaller<T>(
    start: T,
    size: &dyn Fn(&T) -> usize,
    shrink_once: &mut dyn FnMut(&T, &mut Budget) -> T,
) -> T {
    let mut budget = Budget::new();
    let mut best = start;
    loop {
        let smaller = shrink_once(&best, &mut budget);
        if size(&smaller) >= size(&best) {
            return best;
        }
        best = smaller;
        if budget.attempts > MAX_ATTEMPTS {
            return best;
        }
    }
}

fn shrink_text_once(
    text: &str,
    budget: &mut Budget,
    fails: &mut dyn FnMut(&str) -> bool,
) -> String {
    let mut lines: Vec<String> = text
        .split_inclusive(['\n', '\r'])
        .map(str::to_string)
        .collect();
    shrink_list(&mut lines, budget, &mut |candidate| {
        fails(&candidate.concat())
    });
    let mut characters: Vec<char> = lines.concat().chars().collect();
    shrink_list(&mut characters, budget, &mut |candidate| {
        fails(&candidate.iter().collect::<String>())
    });
    characters.into_iter().collect()
}

/// The smallest document case found that still fails: edits, start lines, inserted lines, then the
/// characters of each remaining line.
pub fn minimise_document(
    case: &DocumentCase,
    fails: &mut dyn FnMut(&DocumentCase) -> bool,
) -> DocumentCase {
    repeat_while_smaller(
        case.clone(),
        &|case| case.to_bytes().len(),
        &mut |best, budget| shrink_document_once(best, budget, fails),
    )
}

fn shrink_document_once(
    case: &DocumentCase,
    budget: &mut Budget,
    fails: &mut dyn FnMut(&DocumentCase) -> bool,
) -> DocumentCase {
    let mut best = case.clone();
    let mut edits = best.edits.clone();
    shrink_list(&mut edits, budget, &mut |candidate| {
        fails(&DocumentCase {
            edits: candidate.to_vec(),
            ..best.clone()
        })
    });
    best.edits = edits;
    let mut lines = best.lines.clone();
    shrink_list(&mut lines, budget, &mut |candidate| {
        fails(&DocumentCase {
            lines: candidate.to_vec(),
            ..best.clone()
        })
    });
    best.lines = lines;
    for index in 0..best.edits.len() {
        let mut inserted = best.edits[index].inserted.clone();
        shrink_list(&mut inserted, budget, &mut |candidate| {
            let mut trial = best.clone();
            trial.edits[index].inserted = candidate.to_vec();
            fails(&trial)
        });
        best.edits[index].inserted = inserted;
    }
    for index in 0..best.lines.len() {
        let mut characters: Vec<char> = best.lines[index].chars().collect();
        shrink_list(&mut characters, budget, &mut |candidate| {
            let mut trial = best.clone();
            trial.lines[index] = candidate.iter().collect();
            fails(&trial)
        });
        best.lines[index] = characters.into_iter().collect();
    }
    for edit_index in 0..best.edits.len() {
        for index in 0..best.edits[edit_index].inserted.len() {
            let mut characters: Vec<char> =
                best.edits[edit_index].inserted[index].chars().collect();
            shrink_list(&mut characters, budget, &mut |candidate| {
                let mut trial = best.clone();
                trial.edits[edit_index].inserted[index] = candidate.iter().collect();
                fails(&trial)
            });
            best.edits[edit_index].inserted[index] = characters.into_iter().collect();
        }
    }
    best
}
