//! Tests of the server's program library: the lookup order over an index, and the texts kept until
//! their file changes.

use super::*;
use crate::config::MachineConfig;
use crate::ide::SymbolTable;
use crate::lsp::workspace::library_texts::LibraryTexts;
use std::cell::Cell;

/// An absolute path below a folder that need not exist (nothing here reads it).
fn path(relative: &str) -> PathBuf {
    std::env::temp_dir()
        .join("sinumerik-lsp-library-index")
        .join(relative)
}

fn id(relative: &str) -> DocumentId {
    Arc::from(path(relative).to_string_lossy().as_ref())
}

fn index_of(files: &[(&str, &str)]) -> WorkspaceIndex {
    let mut index = WorkspaceIndex::new();
    let config = MachineConfig::default();
    for (relative, text) in files {
        let id = id(relative);
        let symbols = Arc::new(SymbolTable::of_text(text, &config));
        index.insert(Arc::clone(&id), &id, symbols);
    }
    index
}

/// The id of the file a call of `name` from `caller` runs, relative to the test folder.
fn found(
    index: &WorkspaceIndex,
    caller: &str,
    cycles: &[&str],
    open: &[&str],
    name: &str,
) -> Option<String> {
    let folders = folders_above(Some(&path(caller)));
    let cycles: Vec<PathBuf> = cycles.iter().map(|folder| path(folder)).collect();
    let order = LookupOrder {
        folders: &folders,
        cycles: &cycles,
    };
    let open: Vec<DocumentId> = open.iter().map(|relative| id(relative)).collect();
    let base = path("");
    order
        .best_program(index, name, |id| open.iter().any(|open| &**open == id))
        .map(|document| {
            Path::new(document.id.as_ref())
                .strip_prefix(&base)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/")
        })
}

#[test]
fn the_caller_s_folder_comes_first_then_the_folders_above_then_the_cycles_then_the_rest() {
    let index = index_of(&[
        ("ws/a/b/MAIN.MPF", "M30\n"),
        ("ws/a/b/OWN.SPF", "M17\n"),
        ("ws/a/OWN.SPF", "M17\n"),
        ("ws/a/PARENT.SPF", "M17\n"),
        ("ws/PARENT.SPF", "M17\n"),
        ("ws/other/ELSEWHERE.SPF", "M17\n"),
        ("ws/other/CYCLE.SPF", "M17\n"),
        ("cycles1/deep/CYCLE.SPF", "M17\n"),
        ("cycles2/CYCLE.SPF", "M17\n"),
        ("cycles2/BOTH.SPF", "M17\n"),
        ("cycles1/BOTH.SPF", "M17\n"),
    ]);
    let cycles = ["cycles1", "cycles2"];
    let find = |name| found(&index, "ws/a/b/MAIN.MPF", &cycles, &[], name);
    assert_eq!(find("OWN").as_deref(), Some("ws/a/b/OWN.SPF"));
    assert_eq!(find("PARENT").as_deref(), Some("ws/a/PARENT.SPF"));
    assert_eq!(find("CYCLE").as_deref(), Some("cycles1/deep/CYCLE.SPF"));
    assert_eq!(find("BOTH").as_deref(), Some("cycles1/BOTH.SPF"));
    assert_eq!(find("ELSEWHERE").as_deref(), Some("ws/other/ELSEWHERE.SPF"));
    assert_eq!(find("MISSING"), None);

    let reversed = ["cycles2", "cycles1"];
    let find = |name| found(&index, "ws/a/b/MAIN.MPF", &reversed, &[], name);
    assert_eq!(find("BOTH").as_deref(), Some("cycles2/BOTH.SPF"));
    assert_eq!(find("CYCLE").as_deref(), Some("cycles2/CYCLE.SPF"));
    // Without cycle folders, the caller's folders still come first.
    let find = |name| found(&index, "ws/a/b/MAIN.MPF", &[], &[], name);
    assert_eq!(find("OWN").as_deref(), Some("ws/a/b/OWN.SPF"));
}

#[test]
fn subprograms_and_pc_names_win_in_a_folder_and_open_documents_among_equals() {
    let index = index_of(&[
        ("ws/MAIN.MPF", "M30\n"),
        ("ws/PART2.MPF", "M30\n"),
        ("ws/_N_PART2_SPF", "M17\n"),
        ("ws/_N_PART3_SPF", "M17\n"),
        ("ws/part3.spf", "M17\n"),
        ("ws/L123.SPF", "M17\n"),
        ("ws/L0123.SPF", "M17\n"),
        ("ws/MACROS.DEF", "DEFINE PART4 AS G0\n"),
        ("x/SAME.SPF", "M17\n"),
        ("y/SAME.SPF", "M17\n"),
    ]);
    let find = |name, open: &[&str]| found(&index, "ws/MAIN.MPF", &[], open, name);
    assert_eq!(find("PART2", &[]).as_deref(), Some("ws/_N_PART2_SPF"));
    assert_eq!(find("PART3", &[]).as_deref(), Some("ws/part3.spf"));
    assert_eq!(find("L123", &[]).as_deref(), Some("ws/L123.SPF"));
    assert_eq!(find("L0123", &[]).as_deref(), Some("ws/L0123.SPF"));
    assert_eq!(find("L00123", &[]), None);
    assert_eq!(find("PART4", &[]), None);
    assert_eq!(find("SAME", &[]).as_deref(), Some("x/SAME.SPF"));
    assert_eq!(find("SAME", &["y/SAME.SPF"]).as_deref(), Some("y/SAME.SPF"));
    // Being open does not outrank the caller's folder.
    assert_eq!(
        find("PART2", &["ws/PART2.MPF"]).as_deref(),
        Some("ws/_N_PART2_SPF")
    );
}

#[test]
fn macro_files_are_the_definition_files_with_macros_nearest_first() {
    let index = index_of(&[
        ("ws/a/MAIN.MPF", "M30\n"),
        ("ws/a/_N_UMAC_DEF", "DEFINE USER AS G0\n"),
        ("ws/a/_N_SMAC_DEF", "DEFINE SYSTEM AS G0\n"),
        ("ws/a/AAA.DEF", "DEFINE FIRST AS G0\n"),
        ("ws/a/GUD.DEF", "DEF NCK REAL LENGTH\n"),
        ("ws/TOP.DEF", "DEFINE TOP AS G0\n"),
        ("cycles/_N_CMAC_DEF", "DEFINE CYCLE AS G0\n"),
        ("other/ELSE.DEF", "DEFINE ELSE AS G0\n"),
        ("ws/a/SUB.SPF", "DEFINE LOCAL AS G0\n"),
    ]);
    let folders = folders_above(Some(&path("ws/a/MAIN.MPF")));
    let cycles = [path("cycles")];
    let order = LookupOrder {
        folders: &folders,
        cycles: &cycles,
    };
    let names: Vec<&str> = order
        .macro_files(&index)
        .iter()
        .map(|document| document.program_name.as_str())
        .collect();
    assert_eq!(names, ["SMAC", "UMAC", "AAA", "TOP", "CMAC", "ELSE"]);
}

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
fn the_folders_above_a_document_start_with_its_own() {
    let folders = folders_above(Some(&path("ws/a/MAIN.MPF")));
    assert_eq!(folders[0], path("ws/a"));
    assert_eq!(folders[1], path("ws"));
    assert_eq!(folders.last().unwrap().parent(), None);
    assert!(folders_above(None).is_empty());
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
