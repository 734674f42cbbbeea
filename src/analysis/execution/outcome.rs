//! What a run of a program gives: its executed moves (`ExecutedMove`, with the calls that led to
//! them), the whole run's result (`Execution`), and how a block ends a program level.

use crate::analysis::engine::moves::Move;
use crate::analysis::execution::first_pass::FirstPasses;
use crate::diagnostics::LineDiagnostic;
use crate::syntax::ast::{AddressKind, AddressWord, ValueExpr};
use std::sync::Arc;

/// Where a called program was called from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CallSite {
    /// The file of the calling program; `None` for the analysed program.
    pub path: Option<Arc<str>>,
    /// The 0-based line of the call in that file.
    pub line: usize,
}

/// One execution of a block that moves axes.
#[derive(Debug, Clone, PartialEq)]
pub struct ExecutedMove {
    /// The move; its `line` is the line in `path` (in the analysed program when `path` is `None`).
    pub movement: Move,
    /// The file of the called program that made the move; `None` for the analysed program.
    pub path: Option<Arc<str>>,
    /// The calls that led to the move, outermost first.
    pub stack: Arc<[CallSite]>,
    /// Which execution of its block this is (1, 2, ...), 0 when the block runs once only.
    pub pass: u32,
    /// The move lies on a way whose condition the analysis could not decide.
    pub conditional: bool,
    /// The axes whose value rests on the assumed entry state.
    pub assumed: Vec<Arc<str>>,
}

impl ExecutedMove {
    /// The line of the analysed program that caused the move: the outermost call, or its own line.
    pub fn outer_line(&self) -> usize {
        self.stack
            .first()
            .map_or(self.movement.line, |site| site.line)
    }
}

/// What running a program gave besides its moves.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Execution {
    /// Findings of the run, at lines of the analysed program (a finding inside a called program is
    /// reported at the call).
    pub findings: Vec<LineDiagnostic>,
    /// What was assumed about the entry state: (`"units"`, `"G71"`), (`"distance"`, `"G90"`), ...
    pub assumed: Vec<(&'static str, String)>,
    /// How many blocks were executed.
    pub executed_blocks: u64,
    /// Per program (the analysed one first, then the called ones in the order they were first
    /// called), per line: how often it was executed.
    pub pass_totals: Vec<Vec<u32>>,
    /// Whether the analysed program has labels, jumps, control structures or calls: without them it
    /// runs in program order, every block once.
    pub has_flow: bool,
    /// The first pass of each line of the analysed program, when the run was asked to record them
    /// ([`entry::RunSetup`]).
    pub first_passes: Option<Box<FirstPasses>>,
}

impl Execution {
    /// How often line `line` of the analysed program was executed.
    pub fn passes_of_line(&self, line: usize) -> u32 {
        self.pass_totals
            .first()
            .and_then(|lines| lines.get(line).copied())
            .unwrap_or(0)
    }
}

/// How a block ends a program level, if it does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProgramEnd {
    /// `M17` or `RET`: the end of a subprogram.
    Return,
    /// `M2` or `M30`: the end of the main program.
    End,
}

/// Whether the address word `word` is M2, M30 or M17 (written as a constant).
pub fn ends_program(word: &AddressWord) -> Option<ProgramEnd> {
    if word.kind != AddressKind::MFunction || word.extension.is_some() {
        return None;
    }
    let value = match word.value.expr {
        ValueExpr::Constant { value, .. } => value,
        _ => return None,
    };
    if value == 17.0 {
        Some(ProgramEnd::Return)
    } else if value == 2.0 || value == 30.0 {
        Some(ProgramEnd::End)
    } else {
        None
    }
}
