//! The order in which the control finds a called program among the files of a workspace: the
//! caller's folder, the folders above it, the cycle folders in their configured order, then the rest;
//! within a folder a subprogram before a main program and a PC file name before the control's own.
//! The server's program library looks calls up through it (`lsp/workspace/library.rs`).

use crate::ide::workspace::WorkspaceIndex;
use crate::ide::workspace::{call_rank, macro_file_rank, FileKind, IndexedDocument};
use std::path::{Path, PathBuf};

/// The folder of the file at `path` and the folders above it, nearest first.
pub fn folders_above(path: Option<&Path>) -> Vec<PathBuf> {
    path.and_then(Path::parent)
        .map(|folder| folder.ancestors().map(Path::to_path_buf).collect())
        .unwrap_or_default()
}

/// The order in which a document looks for the programs it calls.
pub struct LookupOrder<'a> {
    /// The document's folder and the folders above it, nearest first.
    pub folders: &'a [PathBuf],
    /// The cycle folders, in the order of the setting.
    pub cycles: &'a [PathBuf],
}

impl LookupOrder<'_> {
    /// Where a document comes: its folder's place among the caller's folders, then among the cycle
    /// folders (which hold their subfolders' files too), then everything else (documents that are no
    /// file among them).
    fn folder_rank(&self, id: &str) -> usize {
        let path = Path::new(id);
        if !path.is_absolute() {
            return usize::MAX;
        }
        if let Some(place) = path
            .parent()
            .and_then(|folder| self.folders.iter().position(|known| known == folder))
        {
            return place;
        }
        self.cycles
            .iter()
            .position(|cycles| path.starts_with(cycles))
            .map_or(usize::MAX, |place| self.folders.len() + place)
    }

    /// The document a call of `name` (upper case) runs; `is_open` says whether a document is open
    /// in the editor, which wins over a file elsewhere that would rank the same.
    pub fn best_program<'i>(
        &self,
        index: &'i WorkspaceIndex,
        name: &str,
        is_open: impl Fn(&str) -> bool,
    ) -> Option<&'i IndexedDocument> {
        index
            .documents()
            .filter(|document| {
                document.program_name == name
                    && matches!(document.kind, FileKind::Subprogram | FileKind::MainProgram)
            })
            .filter_map(|document| {
                let rank = call_rank(&document.id)?;
                let key = (self.folder_rank(&document.id), rank, !is_open(&document.id));
                Some((key, document))
            })
            // The index iterates by id: among equals the first id wins, on every run alike.
            .min_by(|(left, _), (right, _)| left.cmp(right))
            .map(|(_, document)| document)
    }

    /// The definition files that define macros, in reading order.
    pub fn macro_files<'i>(&self, index: &'i WorkspaceIndex) -> Vec<&'i IndexedDocument> {
        let mut files: Vec<&IndexedDocument> = index
            .documents()
            .filter(|document| {
                document.kind == FileKind::Definitions && !document.symbols.macros.is_empty()
            })
            .collect();
        // Stable: equal ranks keep the index's order by id.
        files.sort_by_key(|document| {
            (
                self.folder_rank(&document.id),
                macro_file_rank(&document.program_name),
            )
        });
        files
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::MachineConfig;
    use crate::ide::symbols::SymbolTable;
    use crate::ide::workspace::DocumentId;
    use std::sync::Arc;

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
    fn the_folders_above_a_document_start_with_its_own() {
        let folders = folders_above(Some(&path("ws/a/MAIN.MPF")));
        assert_eq!(folders[0], path("ws/a"));
        assert_eq!(folders[1], path("ws"));
        assert_eq!(folders.last().unwrap().parent(), None);
        assert!(folders_above(None).is_empty());
    }
}
