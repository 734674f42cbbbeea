//! Tests of the server's program library: the texts kept until their file changes, and what a
//! library keeps while the index stays the same.

use super::*;
use crate::lsp::workspace::library_texts::LibraryTexts;
use std::cell::Cell;

#[test]
fn texts_are_read_once_until_their_file_changes() {
    let texts = LibraryTexts::default();
    let reads = Cell::new(0);
    let part2: DocumentId = Arc::from("/nc/PART2.SPF");
    let read = |text: &str| {
        reads.set(reads.get() + 1);
        Some(Arc::<str>::from(text))
    };
    assert_eq!(texts.text(&part2, || read("old")).as_deref(), Some("old"));
    assert_eq!(texts.text(&part2, || read("new")).as_deref(), Some("old"));
    assert_eq!(reads.get(), 1);

    let generation = texts.generation();
    texts.index_changed();
    assert!(texts.generation() > generation);
    assert_eq!(texts.text(&part2, || read("new")).as_deref(), Some("old"));

    texts.file_changed("/nc/OTHER.SPF");
    assert_eq!(texts.text(&part2, || read("new")).as_deref(), Some("old"));
    texts.file_changed(&part2);
    assert_eq!(texts.text(&part2, || read("new")).as_deref(), Some("new"));
    assert_eq!(reads.get(), 2);

    // A file that cannot be read is remembered as such, also until it changes.
    let missing: DocumentId = Arc::from("/nc/MISSING.SPF");
    assert_eq!(texts.text(&missing, || None), None);
    assert_eq!(texts.text(&missing, || read("late")), None);
    texts.clear();
    assert_eq!(
        texts.text(&missing, || read("late")).as_deref(),
        Some("late")
    );
    assert_eq!(
        texts.text(&part2, || read("newest")).as_deref(),
        Some("newest")
    );
}

#[test]
fn a_text_read_while_its_file_changed_is_not_kept() {
    let texts = LibraryTexts::default();
    let part2: DocumentId = Arc::from("/nc/PART2.SPF");
    let text = texts.text(&part2, || {
        // The watcher reports the change while the old text is being read.
        texts.file_changed(&part2);
        Some(Arc::from("old"))
    });
    assert_eq!(text.as_deref(), Some("old"));
    assert_eq!(
        texts.text(&part2, || Some(Arc::from("new"))).as_deref(),
        Some("new")
    );
}

#[test]
fn a_library_keeps_what_it_found_while_the_index_stays_the_same() {
    let cache = Mutex::new(FoundCache::default());
    let lookups = Cell::new(0);
    let find = |generation: u64, current: u64, text: &str| {
        cached(
            &cache,
            generation,
            || current,
            |cache| cache.found.get("PART2").cloned(),
            |cache, found| {
                cache.found.insert("PART2".to_string(), found);
            },
            || {
                lookups.set(lookups.get() + 1);
                Some(Arc::new(LibraryProgram {
                    name: "PART2".to_string(),
                    path: Arc::from("/nc/PART2.SPF"),
                    text: Arc::from(text),
                }))
            },
        )
        .map(|program| program.text.to_string())
    };
    assert_eq!(find(1, 1, "first").as_deref(), Some("first"));
    assert_eq!(find(1, 1, "second").as_deref(), Some("first"));
    assert_eq!(lookups.get(), 1);
    // The index changed: the name is looked up again.
    assert_eq!(find(2, 2, "second").as_deref(), Some("second"));
    assert_eq!(lookups.get(), 2);
    // The index changed during the lookup: its result is not kept.
    assert_eq!(find(3, 4, "third").as_deref(), Some("third"));
    assert_eq!(find(3, 3, "fourth").as_deref(), Some("fourth"));
    assert_eq!(lookups.get(), 4);
    // A miss is kept like a find.
    let misses = Cell::new(0);
    let miss = || {
        cached(
            &cache,
            5,
            || 5,
            |cache| cache.found.get("NONE").cloned(),
            |cache, found| {
                cache.found.insert("NONE".to_string(), found);
            },
            || {
                misses.set(misses.get() + 1);
                None
            },
        )
    };
    assert!(miss().is_none() && miss().is_none());
    assert_eq!(misses.get(), 1);
}
