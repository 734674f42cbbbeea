//! Macros of the definition files the library provides (the control's `_N_SMAC_DEF`, `_N_MMAC_DEF`,
//! `_N_UMAC_DEF`, or `SMAC.DEF`, ... on a PC; reference §8.10). They are read once per run, known to
//! the parser of every program the run reads (so that `G300` or `RETRACT` reads as a macro use, not
//! as an unknown G function or a call) and expanded by the engine like the program's own macros. A
//! program's own `DEFINE` of the same name replaces a file's definition from the block that defines
//! it on, as the engine records every definition it passes.

use crate::analysis::engine::macros::macro_definition;
use crate::analysis::library::ProgramLibrary;
use crate::config::MachineConfig;
use crate::syntax::ast::Block;
use crate::syntax::{lines, macro_names, LineParser, SyntaxContext};

/// The macros of the library's definition files, in reading order: upper-case name and body text.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LibraryMacros {
    pub definitions: Vec<(String, String)>,
}

impl LibraryMacros {
    /// Reads the definitions of every macro file `library` provides. A name defined again in a later
    /// file takes the later body: the files come system, machine manufacturer, user, so the user's
    /// definition is the one that stays.
    pub fn read(library: &dyn ProgramLibrary, config: &MachineConfig) -> LibraryMacros {
        let mut definitions: Vec<(String, String)> = Vec::new();
        let mut parser = LineParser::new();
        let mut block = Block::default();
        let mut findings = Vec::new();
        for file in library.macro_files() {
            let text = file.text.as_ref();
            let mut context = SyntaxContext::new(config);
            for name in macro_names(text) {
                context.add_macro(name);
            }
            for (start, end) in lines::line_ranges(text) {
                let line = &text[start..end];
                findings.clear();
                parser.parse(line, &context, &mut block, &mut findings);
                for statement in &block.statements {
                    if let Some((name, body)) = macro_definition(line, statement) {
                        definitions.retain(|(known, _)| *known != name);
                        definitions.push((name, body));
                    }
                }
            }
        }
        LibraryMacros { definitions }
    }

    /// The macro names, upper case.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.definitions.iter().map(|(name, _)| name.as_str())
    }

    pub fn is_empty(&self) -> bool {
        self.definitions.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::library::MemoryLibrary;

    #[test]
    fn later_files_replace_earlier_definitions() {
        let mut library = MemoryLibrary::default();
        library.insert_macro_file(
            "_N_SMAC_DEF",
            "DEFINE G300 AS G90 G0 Z=R210\nDEFINE A1 AS X1\n",
        );
        library.insert_macro_file("_N_UMAC_DEF", "; user\nDEFINE a1 AS X2 ; mine\n");
        let macros = LibraryMacros::read(&library, &MachineConfig::mill());
        assert_eq!(
            macros.definitions,
            vec![
                ("G300".to_string(), "G90 G0 Z=R210".to_string()),
                ("A1".to_string(), "X2".to_string()),
            ]
        );
    }
}
