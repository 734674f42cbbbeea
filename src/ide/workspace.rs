//! The index over the documents of a workspace: each document's symbol table, its program name (the
//! file stem, `_N_NAME_SPF` read as `NAME`) and kind, and lookups across documents: subprograms by
//! name, global `DEF`/`DEFINE` from `.DEF` files, `EXTERN` declarations. The caller gives the texts;
//! nothing here reads a file.

use crate::analysis::document::LineSource;
use crate::config::MachineConfig;
use crate::ide::symbols::{MacroDefinition, ProcedureDefinition, SymbolTable, VariableDefinition};
use std::collections::BTreeMap;
use std::sync::Arc;

/// The caller's name for a document (a URI or a path); compared as written.
pub type DocumentId = Arc<str>;

/// What a file holds, by its extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    /// `.MPF`: a main program.
    MainProgram,
    /// `.SPF`: a subprogram or cycle.
    Subprogram,
    /// `.DEF`: definitions of global user data and macros.
    Definitions,
    /// Anything else (`.INI`, `.TXT`, ...).
    Other,
}

/// One indexed document.
#[derive(Debug, Clone)]
pub struct IndexedDocument {
    pub id: DocumentId,
    pub kind: FileKind,
    /// The program name the control calls it by, upper case.
    pub program_name: String,
    pub symbols: Arc<SymbolTable>,
}

/// The stem of a file name or path and its extension with the dot (`PART2` and `.SPF`); a name
/// without a dot after its first byte has an empty extension.
fn stem_and_extension(file_name: &str) -> (&str, &str) {
    let base = file_name.rsplit(['/', '\\']).next().unwrap_or(file_name);
    match base.rfind('.') {
        Some(dot) if dot > 0 => (&base[..dot], &base[dot..]),
        _ => (base, ""),
    }
}

/// The program name and kind of a file name or path: `PART2.SPF` and `_N_PART2_SPF` are `PART2`.
pub fn program_name_and_kind(file_name: &str) -> (String, FileKind) {
    let (stem, dotted_extension) = stem_and_extension(file_name);
    let extension = dotted_extension
        .strip_prefix('.')
        .unwrap_or(dotted_extension);
    let upper_stem = stem.to_ascii_uppercase();
    let (stem, extension) = match upper_stem.strip_prefix("_N_") {
        Some(rest)
            if extension.is_empty()
                || rest.ends_with("_SPF")
                || rest.ends_with("_MPF")
                || rest.ends_with("_DEF") =>
        {
            match rest.rfind('_') {
                Some(underscore) if underscore > 0 => (
                    rest[..underscore].to_string(),
                    rest[underscore + 1..].to_string(),
                ),
                _ => (rest.to_string(), extension.to_ascii_uppercase()),
            }
        }
        _ => (upper_stem.clone(), extension.to_ascii_uppercase()),
    };
    let kind = match extension.as_str() {
        "MPF" => FileKind::MainProgram,
        "SPF" => FileKind::Subprogram,
        "DEF" => FileKind::Definitions,
        _ => FileKind::Other,
    };
    (stem, kind)
}

/// How well the file `file_name` (a name or path) answers a call of its program name, the lower the
/// better, or `None` when it holds no program a call can run. Subprograms come before main programs
/// (the control searches `_SPF` before `_MPF`), and a name as written on a PC (`PART2.SPF`) before
/// the control's own form (`_N_PART2_SPF`).
pub fn call_rank(file_name: &str) -> Option<u8> {
    let (program, kind) = program_name_and_kind(file_name);
    let kind_rank = match kind {
        FileKind::Subprogram => 0,
        FileKind::MainProgram => 2,
        FileKind::Definitions | FileKind::Other => return None,
    };
    let base = file_name.rsplit(['/', '\\']).next().unwrap_or(file_name);
    let control_form = !base.to_ascii_uppercase().starts_with(&program);
    Some(kind_rank + u8::from(control_form))
}

/// Where a definition file of the program name `program` comes in the order the control reads the
/// macro files of a folder: `_N_SMAC_DEF`, `_N_MMAC_DEF`, `_N_UMAC_DEF` (system, machine
/// manufacturer, user), then the others.
pub fn macro_file_rank(program: &str) -> u8 {
    match program {
        "SMAC" => 0,
        "MMAC" => 1,
        "UMAC" => 2,
        _ => 3,
    }
}

/// The file name (without folder) that makes the file of `file_name` hold the program `program`, in
/// the same style: `PART2.SPF` becomes `PART3.SPF`, `part2.spf` becomes `part3.spf` and the control's
/// own `_N_PART2_SPF` becomes `_N_PART3_SPF`. The control finds a program by its file name, so a
/// renamed program needs its file renamed too.
pub fn file_name_for_program(file_name: &str, program: &str) -> String {
    let (stem, extension) = stem_and_extension(file_name);
    // Only the control's own form gives a program name other than the stem itself.
    let control_style = program_name_and_kind(file_name).0 != stem.to_ascii_uppercase();
    match stem.rfind('_') {
        // `_N_` + name + `_` + type, as the control writes it: only the name changes.
        Some(underscore) if control_style && underscore > 2 => format!(
            "{}{}{}{extension}",
            &stem[..3],
            in_case_of(&stem[3..underscore], program),
            &stem[underscore..]
        ),
        _ => format!("{}{extension}", in_case_of(stem, program)),
    }
}

/// `name` in lower case where `written` is (a name written in lower case keeps its case), else in
/// upper case, as the control shows names.
fn in_case_of(written: &str, name: &str) -> String {
    if written.bytes().any(|byte| byte.is_ascii_uppercase()) {
        name.to_ascii_uppercase()
    } else {
        name.to_ascii_lowercase()
    }
}

/// The symbol tables of many documents and the cross-document lookups.
#[derive(Debug, Clone, Default)]
pub struct WorkspaceIndex {
    documents: BTreeMap<DocumentId, IndexedDocument>,
    /// Whether the caller has given every program and definition file the programs use, so that a
    /// name found nowhere is really missing. Until then, nothing is reported as unknown.
    complete: bool,
}

impl WorkspaceIndex {
    pub fn new() -> WorkspaceIndex {
        WorkspaceIndex::default()
    }

    /// Adds or replaces a document, collecting its symbol table. `file_name` is its path or URI, from
    /// which the program name and kind are taken.
    pub fn update(
        &mut self,
        id: DocumentId,
        file_name: &str,
        source: &dyn LineSource,
        config: &MachineConfig,
    ) {
        let symbols = Arc::new(SymbolTable::build(source, config));
        self.insert(id, file_name, symbols);
    }

    /// Adds or replaces a document whose symbol table the caller has already built.
    pub fn insert(&mut self, id: DocumentId, file_name: &str, symbols: Arc<SymbolTable>) {
        let (program_name, kind) = program_name_and_kind(file_name);
        self.documents.insert(
            Arc::clone(&id),
            IndexedDocument {
                id,
                kind,
                program_name,
                symbols,
            },
        );
    }

    pub fn remove(&mut self, id: &str) {
        self.documents.remove(id);
    }

    /// Says whether every file the programs use is indexed (the server sets it once its background
    /// indexing has finished; the CLI when it has read the folders).
    pub fn set_complete(&mut self, complete: bool) {
        self.complete = complete;
    }

    pub fn is_complete(&self) -> bool {
        self.complete
    }

    pub fn document(&self, id: &str) -> Option<&IndexedDocument> {
        self.documents.get(id)
    }

    pub fn documents(&self) -> impl Iterator<Item = &IndexedDocument> {
        self.documents.values()
    }

    /// The documents that define the program `name` (upper case): by file name (programs, not
    /// definition files), or by a `PROC` header of that name.
    pub fn programs_named<'a>(
        &'a self,
        name: &'a str,
    ) -> impl Iterator<Item = &'a IndexedDocument> + 'a {
        self.documents.values().filter(move |document| {
            (document.kind != FileKind::Definitions && document.program_name == name)
                || document
                    .symbols
                    .procedure
                    .as_ref()
                    .is_some_and(|procedure| procedure.name == name)
        })
    }

    /// The `PROC` header of the program `name`, if an indexed document has one.
    pub fn procedure<'a>(
        &'a self,
        name: &'a str,
    ) -> Option<(&'a IndexedDocument, &'a ProcedureDefinition)> {
        self.programs_named(name).find_map(|document| {
            document
                .symbols
                .procedure
                .as_ref()
                .filter(|procedure| procedure.name == name)
                .map(|procedure| (document, procedure))
        })
    }

    /// Global variables (`DEF NCK|CHAN ...` or any `DEF` of a `.DEF` file) named `name`.
    pub fn global_variables<'a>(
        &'a self,
        name: &'a str,
    ) -> impl Iterator<Item = (&'a IndexedDocument, &'a VariableDefinition)> + 'a {
        self.documents.values().flat_map(move |document| {
            document
                .symbols
                .variables
                .iter()
                .filter(move |variable| {
                    variable.name == name
                        && (document.kind == FileKind::Definitions
                            || variable.global_attribute.is_some())
                })
                .map(move |variable| (document, variable))
        })
    }

    /// Macros of `.DEF` files named `name`.
    pub fn global_macros<'a>(
        &'a self,
        name: &'a str,
    ) -> impl Iterator<Item = (&'a IndexedDocument, &'a MacroDefinition)> + 'a {
        self.documents
            .values()
            .filter(|document| document.kind == FileKind::Definitions)
            .flat_map(move |document| {
                document
                    .symbols
                    .macros
                    .iter()
                    .filter(move |definition| definition.name == name)
                    .map(move |definition| (document, definition))
            })
    }

    /// Whether a main program of the workspace defines `name` with `DEF`: such program-global data
    /// may be visible in the subprograms it calls (depending on MD11120), so a subprogram's use of
    /// the name is not reported as undefined.
    pub fn main_program_defines(&self, name: &str) -> bool {
        self.documents.values().any(|document| {
            document.kind == FileKind::MainProgram
                && document
                    .symbols
                    .variables
                    .iter()
                    .any(|variable| variable.name == name)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_renamed_program_s_file_keeps_its_style_and_names_the_new_program() {
        for (file, expected) in [
            ("PART2.SPF", "PART3.SPF"),
            ("part2.spf", "part3.spf"),
            ("Part2.Spf", "PART3.Spf"),
            ("_N_PART2_SPF", "_N_PART3_SPF"),
            ("_N_CUST_800_SPF", "_N_PART3_SPF"),
            ("_N_PART2_SPF.txt", "_N_PART3_SPF.txt"),
            ("/a/b/MAIN.MPF", "PART3.MPF"),
            ("C:\\x\\_n_part2_spf", "_n_part3_spf"),
            ("PART2", "PART3"),
        ] {
            let renamed = file_name_for_program(file, "Part3");
            assert_eq!(renamed, expected, "{file}");
            // The new file holds the new program, of the same kind.
            assert_eq!(
                program_name_and_kind(&renamed),
                ("PART3".to_string(), program_name_and_kind(file).1),
                "{file}"
            );
        }
    }

    #[test]
    fn calls_prefer_subprograms_and_pc_file_names() {
        for (file, rank) in [
            ("PART2.SPF", Some(0)),
            ("/nc/part2.spf", Some(0)),
            ("_N_PART2_SPF", Some(1)),
            ("C:\\nc\\_n_part2_spf.txt", Some(1)),
            ("PART2.MPF", Some(2)),
            ("_N_PART2_MPF", Some(3)),
            ("_N_PART2.SPF", Some(0)),
            ("GUD.DEF", None),
            ("_N_SMAC_DEF", None),
            ("PART2.TXT", None),
        ] {
            assert_eq!(call_rank(file), rank, "{file}");
        }
        assert!(macro_file_rank("SMAC") < macro_file_rank("MMAC"));
        assert!(macro_file_rank("MMAC") < macro_file_rank("UMAC"));
        assert!(macro_file_rank("UMAC") < macro_file_rank("AAA"));
    }

    #[test]
    fn program_names_come_from_stems_and_control_file_names() {
        assert_eq!(
            program_name_and_kind("/a/b/part2.spf"),
            ("PART2".to_string(), FileKind::Subprogram)
        );
        assert_eq!(
            program_name_and_kind("C:\\x\\MAIN.MPF"),
            ("MAIN".to_string(), FileKind::MainProgram)
        );
        assert_eq!(
            program_name_and_kind("_N_CUST_800_SPF"),
            ("CUST_800".to_string(), FileKind::Subprogram)
        );
        assert_eq!(
            program_name_and_kind("GUD.DEF"),
            ("GUD".to_string(), FileKind::Definitions)
        );
        assert_eq!(program_name_and_kind("notes.txt").1, FileKind::Other);
    }
}
