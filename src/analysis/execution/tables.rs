//! Curve table definitions (`CTABDEF(..)` … `CTABEND`): the motion blocks between them give the
//! intermediate points of the table and move no axis; at `CTABEND` the control restores the program
//! state it had before the definition (Siemens Programming Manual, Job planning, "Curve tables").
//! The variables the definition computes keep their values: only the motion state comes back.

use crate::analysis::engine::engine_state::Engine;
use crate::analysis::execution::interpreter::Interpreter;
use crate::analysis::execution::paths::Control;
use crate::syntax::ast::{Block, Statement};

/// What a block does to a curve table definition.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TableMark {
    /// `CTABDEF(..)`: a definition starts with this block.
    Start,
    /// `CTABEND`: the definition ends after this block.
    End,
}

/// Whether `block` starts or ends a curve table definition.
pub fn table_mark(block: &Block, line: &str) -> Option<TableMark> {
    block
        .interpreted_statements()
        .iter()
        .find_map(|statement| match statement {
            Statement::Instruction { name, .. } => {
                let word = line.get(name.start()..name.end())?;
                if word.eq_ignore_ascii_case("CTABDEF") {
                    Some(TableMark::Start)
                } else if word.eq_ignore_ascii_case("CTABEND") {
                    Some(TableMark::End)
                } else {
                    None
                }
            }
            _ => None,
        })
}

impl<'a, 's> Interpreter<'a, 's> {
    /// Before the block: a `CTABDEF` keeps the state the definition will restore (a definition that
    /// starts again inside one keeps the first state, as the control restores the state before the
    /// definition).
    pub(super) fn table_start(&self, control: &mut Control, engine: &Engine<'a>, mark: TableMark) {
        let level = control.level_mut();
        if mark == TableMark::Start && level.curve_table.is_none() {
            level.curve_table = Some(Box::new(engine.snapshot()));
        }
    }

    /// After the block: a `CTABEND` restores the state kept at `CTABDEF`, with the variables as the
    /// definition left them.
    pub(super) fn table_end(
        &self,
        control: &mut Control,
        engine: &mut Engine<'a>,
        mark: TableMark,
    ) {
        if mark != TableMark::End {
            return;
        }
        let Some(saved) = control.level_mut().curve_table.take() else {
            return;
        };
        let variables = std::mem::take(&mut engine.state.variables);
        *engine = self.engine_from(*saved);
        engine.state.variables = variables;
    }
}
