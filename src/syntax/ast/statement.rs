//! The statements of a block: G functions, address words, assignments, control flow and jumps, calls,
//! declarations, instructions and the parts of synchronized actions.

use crate::diagnostics::Span;
use crate::syntax::ast::address::AddressWord;
use crate::syntax::ast::declaration::{DataType, Declarator, ProcParameter};
use crate::syntax::ast::expr::ExprId;
use crate::syntax::gcodes::GCode;

/// The left side of an assignment that is not an address word.
#[derive(Debug, Clone, PartialEq)]
pub enum AssignTarget {
    RParameter(u32),
    RParameterIndexed(ExprId),
    /// A user variable or PROC parameter, possibly indexed.
    Variable {
        indexes: Vec<ExprId>,
    },
    SystemVariable {
        indexes: Vec<ExprId>,
    },
    /// `G[8]=2`: select a G function of a group by number.
    GGroup {
        group: ExprId,
    },
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JumpKind {
    Gotof,
    Gotob,
    Goto,
    Gotoc,
    Gotos,
}

/// Where a jump goes.
#[derive(Debug, Clone, PartialEq)]
pub enum JumpTarget {
    Label(Span),
    BlockNumber {
        value: u64,
        span: Span,
    },
    /// A string expression evaluated at run time.
    Computed(ExprId),
    /// Nothing was written after the jump keyword (only `GOTOS` may stand alone).
    None,
}

/// How a subprogram is called.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CallKind {
    /// A bare name, or `NAME(args)`.
    Named,
    /// `CALL`, `PCALL`, `EXTCALL`: indirect or external calls.
    Indirect,
    /// `MCALL NAME(args)`: modal call; `MCALL` alone switches it off.
    Modal,
}

/// The control-flow and declaration keywords that shape a program across blocks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StructureKeyword {
    If,
    Else,
    EndIf,
    While,
    EndWhile,
    For,
    EndFor,
    Repeat,
    Until,
    Loop,
    EndLoop,
    Case,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Statement {
    /// A G function written by number (`G1`) or by name (`DIAMON`, `TRANS`).
    GCode {
        code: GCode,
        span: Span,
    },
    /// A G number that does not exist; reported with S144.
    UnknownGCode {
        number: u32,
        span: Span,
    },
    Address(AddressWord),
    Assignment {
        target: AssignTarget,
        /// The name (or whole target) as written.
        target_span: Span,
        value: Option<ExprId>,
        span: Span,
    },
    /// A structure keyword with its expression (the condition of IF/WHILE/UNTIL/CASE, the end
    /// value of FOR).
    Structure {
        keyword: StructureKeyword,
        condition: Option<ExprId>,
        span: Span,
    },
    Jump {
        kind: JumpKind,
        target: JumpTarget,
        /// The condition of `IF <condition> GOTOF ...`; `None` for an unconditional jump.
        condition: Option<ExprId>,
        span: Span,
    },
    /// A subprogram or cycle call. `name` is the span of the called name (the string for `CALL "X"`).
    Call {
        kind: CallKind,
        name: Option<Span>,
        args: Vec<Option<ExprId>>,
        span: Span,
    },
    /// `DEF ...` declarations with the spans of the declared names.
    Definition {
        names: Vec<Span>,
        /// The type written after the attributes; `None` when the definition names none.
        data_type: Option<DataType>,
        /// One entry per name in `names`, in the same order, with its array sizes and initial value.
        declarators: Vec<Declarator>,
        span: Span,
    },
    /// `DEFINE name AS body`.
    MacroDefinition {
        name: Option<Span>,
        body: Span,
        span: Span,
    },
    /// `PROC name(params) attributes`, with the spans of the parameter names.
    ProcedureHeader {
        name: Option<Span>,
        /// The parameter names as the editor features read them: every name at the top level of the
        /// list that ends a parameter, read token by token.
        parameters: Vec<Span>,
        /// The parameters read one comma-separated entry at a time, with type, `VAR` and default.
        /// An entry without a name (`INT` alone) has no element here.
        params: Vec<ProcParameter>,
        /// `SAVE` follows the parameter list: the caller's modal G functions and frames come back at
        /// the return (reference §8.3).
        save: bool,
        span: Span,
    },
    /// `EXTERN name(types)`.
    ExternDeclaration {
        name: Option<Span>,
        span: Span,
    },
    /// `RET`.
    Return {
        span: Span,
    },
    /// A predefined instruction without G group (`STOPRE`, `TRAORI`, `MSG(..)`, `WRITE(..)`, ...),
    /// with its arguments when it has parentheses.
    Instruction {
        name: Span,
        args: Vec<Option<ExprId>>,
        span: Span,
    },
    /// `REPEAT start [end|ENDLABEL] [P=count]`: runs the section from the label `start` to the label
    /// `end` (with `ENDLABEL`: to the next block labelled `ENDLABEL:`; without either: to the block
    /// before the REPEAT) again, `count` times (once when `P` is left out; reference §17.7).
    SectionRepeat {
        start: Span,
        /// The second label, or the word `ENDLABEL`.
        end: Option<Span>,
        end_is_endlabel: bool,
        count: Option<ExprId>,
        span: Span,
    },
    /// `REPEATB label [P=count]`: runs the block with that label again `count` times.
    BlockRepeat {
        label: Option<Span>,
        count: Option<ExprId>,
        span: Span,
    },
    /// One branch of a `CASE` block: the value compared with the CASE expression (`None` for
    /// `DEFAULT`). The branch's jump is the statement that follows.
    CaseBranch {
        value: Option<ExprId>,
        span: Span,
    },
    /// `WHEN`/`WHENEVER`/`FROM`/`EVERY` condition `DO`: the statements after it in the block are
    /// actions of the main run.
    SyncCondition {
        condition: Option<ExprId>,
        span: Span,
    },
}

impl Statement {
    pub fn span(&self) -> Span {
        match self {
            Statement::GCode { span, .. }
            | Statement::UnknownGCode { span, .. }
            | Statement::Assignment { span, .. }
            | Statement::Structure { span, .. }
            | Statement::Jump { span, .. }
            | Statement::Call { span, .. }
            | Statement::Definition { span, .. }
            | Statement::MacroDefinition { span, .. }
            | Statement::ProcedureHeader { span, .. }
            | Statement::ExternDeclaration { span, .. }
            | Statement::Return { span }
            | Statement::Instruction { span, .. }
            | Statement::SectionRepeat { span, .. }
            | Statement::BlockRepeat { span, .. }
            | Statement::CaseBranch { span, .. }
            | Statement::SyncCondition { span, .. } => *span,
            Statement::Address(word) => word.span,
        }
    }
}
