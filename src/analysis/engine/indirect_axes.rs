//! Axis words that name their axis in brackets: `AX[X]=10` (indirect axis programming), `POS[Z]=5`
//! and `POSA[Z]=5` (positioning axes, reference §3.5), and `MOV[X]=1`. The axis is the name written
//! (`AX[X]`), or the value of an `AXIS` variable or a string expression (`AX[A1]` after
//! `DEF AXIS A1=X`). A positioning axis reaches its end point like a path axis (POSA across block
//! boundaries), so the word moves that axis. When the name is not known, which axis moves is not
//! known: every axis becomes unknown, and no axis is shown as moved.

use crate::analysis::engine::block_words::BlockFunctions;
use crate::analysis::engine::engine_state::Engine;
use crate::analysis::eval::{evaluate_value, EvalOptions, Value};
use crate::diagnostics::Diagnostic;
use crate::syntax::ast::{AddressWord, Block, ExprKind, Extension};

/// What the bracketed axis word does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum WordEffect {
    /// Moves the axis to the word's value (AX, POS, POSA).
    Move,
    /// Travels without an end point the block gives (MOV): the axis becomes unknown.
    Travel,
    /// Positions a spindle (SPOS, SPOSA): no axis of the path.
    Spindle,
}

impl<'a> Engine<'a> {
    /// Applies a bracketed axis word; returns whether it moved a known axis.
    pub(super) fn apply_named_axis_word(
        &mut self,
        line: &str,
        block: &Block,
        word: &AddressWord,
        functions: &BlockFunctions,
        diagnostics: &mut Vec<Diagnostic>,
    ) -> bool {
        let name = line
            .get(word.name.start()..word.name.end())
            .unwrap_or_default()
            .to_ascii_uppercase();
        let effect = match name.as_str() {
            "AX" | "POS" | "POSA" => WordEffect::Move,
            "SPOS" | "SPOSA" => WordEffect::Spindle,
            _ => WordEffect::Travel,
        };
        if effect == WordEffect::Spindle {
            return false;
        }
        match (self.bracketed_axis(line, block, word), effect) {
            (Some(index), WordEffect::Move) => {
                self.apply_axis_word(index, line, block, word, functions, diagnostics);
                true
            }
            (Some(index), _) => {
                self.program_axis(index, None);
                false
            }
            (None, _) => {
                for index in 0..self.config.axes.len() {
                    self.program_axis(index, None);
                }
                false
            }
        }
    }

    /// The configured axis the brackets of `word` name, when the program determines it.
    fn bracketed_axis(&self, line: &str, block: &Block, word: &AddressWord) -> Option<usize> {
        let Some(Extension::Index { indexes, .. }) = &word.extension else {
            return None;
        };
        let [id] = indexes.as_slice() else {
            return None;
        };
        let expr = block.expr(*id);
        if let ExprKind::Name { indexes } = &expr.kind {
            let written = line.get(expr.span.start()..expr.span.end())?;
            let upper = written.to_ascii_uppercase();
            // A name that is not a variable is the axis itself (`AX[X]`).
            if indexes.is_empty() && self.state.variables.var_type(&upper).is_none() {
                return self.axis_index(&upper);
            }
        }
        // An AXIS variable, or an expression whose value is the axis name.
        let value = evaluate_value(
            block,
            line,
            *id,
            &self.state.variables,
            &EvalOptions::default(),
        );
        match value {
            Ok(Some(Value::Text(text))) => self.axis_index(text.trim()),
            _ => None,
        }
    }
}
