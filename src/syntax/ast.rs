//! The parsed form of one block. A block owns its expression nodes in a small arena (`exprs`) so that a
//! caller can reuse one `Block` for every line of a program without allocating again.

use crate::diagnostics::Span;
use crate::syntax::gcodes::GCode;

/// Index of an expression node in [`Block::exprs`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ExprId(pub u32);

/// A binary operator, in the control's precedence order (see `Expr`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinaryOp {
    Multiply,
    Divide,
    IntegerDivide,
    Modulo,
    Add,
    Subtract,
    BitAnd,
    BitXor,
    BitOr,
    And,
    Xor,
    Or,
    Concat,
    Equal,
    NotEqual,
    Less,
    Greater,
    LessEqual,
    GreaterEqual,
    /// The frame chain operator `:`.
    Chain,
}

impl BinaryOp {
    pub fn is_logical(self) -> bool {
        matches!(
            self,
            BinaryOp::And
                | BinaryOp::Or
                | BinaryOp::Xor
                | BinaryOp::BitAnd
                | BinaryOp::BitOr
                | BinaryOp::BitXor
        )
    }

    pub fn is_comparison(self) -> bool {
        matches!(
            self,
            BinaryOp::Equal
                | BinaryOp::NotEqual
                | BinaryOp::Less
                | BinaryOp::Greater
                | BinaryOp::LessEqual
                | BinaryOp::GreaterEqual
        )
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnaryOp {
    Negate,
    Plus,
    Not,
    BitNot,
    /// `<<` with a right operand only: converts the operand to a string.
    ToString,
}

/// One expression node.
#[derive(Debug, Clone, PartialEq)]
pub enum ExprKind {
    Number(f64),
    /// A string literal; the span (of the node) includes the quotes.
    String,
    /// `R1`, also written `$R1` in synchronized actions.
    RParameter(u32),
    /// `R[expr]`.
    RParameterIndexed(ExprId),
    /// A name: variable, parameter, axis (`X`, `X1`, `SP1`), constant (`TRUE`). `indexes` holds the
    /// `[...]` arguments when present.
    Name {
        indexes: Vec<ExprId>,
    },
    /// A system variable such as `$P_GG[13]`.
    SystemVariable {
        indexes: Vec<ExprId>,
    },
    /// A function call `NAME(args)`; empty arguments (`F(1,,3)`) are `None`.
    Call {
        name: Span,
        args: Vec<Option<ExprId>>,
    },
    Unary(UnaryOp, ExprId),
    Binary(BinaryOp, ExprId, ExprId),
    Parenthesized(ExprId),
    /// `(a, b, c)`: a list of values, as some instructions take (`OSCTRL[Z]=(1,2)`).
    List(Vec<ExprId>),
    /// Something that could not be parsed; a diagnostic has been reported.
    Error,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
}

/// The non-modal position modifiers written as `X=AC(..)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Modifier {
    Ac,
    Ic,
    Dc,
    Acp,
    Acn,
    Dac,
    Dic,
    Rac,
    Ric,
    Cac,
    Cic,
    Cdc,
    Cacp,
    Cacn,
}

impl Modifier {
    pub const ALL: &'static [Modifier] = &[
        Modifier::Ac,
        Modifier::Ic,
        Modifier::Dc,
        Modifier::Acp,
        Modifier::Acn,
        Modifier::Dac,
        Modifier::Dic,
        Modifier::Rac,
        Modifier::Ric,
        Modifier::Cac,
        Modifier::Cic,
        Modifier::Cdc,
        Modifier::Cacp,
        Modifier::Cacn,
    ];

    pub fn from_name(name: &str) -> Option<Modifier> {
        Modifier::ALL
            .iter()
            .copied()
            .find(|modifier| modifier.as_str().eq_ignore_ascii_case(name))
    }

    pub fn as_str(self) -> &'static str {
        match self {
            Modifier::Ac => "AC",
            Modifier::Ic => "IC",
            Modifier::Dc => "DC",
            Modifier::Acp => "ACP",
            Modifier::Acn => "ACN",
            Modifier::Dac => "DAC",
            Modifier::Dic => "DIC",
            Modifier::Rac => "RAC",
            Modifier::Ric => "RIC",
            Modifier::Cac => "CAC",
            Modifier::Cic => "CIC",
            Modifier::Cdc => "CDC",
            Modifier::Cacp => "CACP",
            Modifier::Cacn => "CACN",
        }
    }

    /// DC, ACP and ACN approach a rotary target by a chosen direction.
    pub fn needs_rotary_axis(self) -> bool {
        matches!(self, Modifier::Dc | Modifier::Acp | Modifier::Acn)
    }

    /// ACP and ACN only make sense on a modulo axis.
    pub fn needs_modulo_axis(self) -> bool {
        matches!(self, Modifier::Acp | Modifier::Acn)
    }

    /// DAC, DIC, RAC and RIC give diameter or radius values of a transverse axis.
    pub fn needs_transverse_axis(self) -> bool {
        matches!(
            self,
            Modifier::Dac | Modifier::Dic | Modifier::Rac | Modifier::Ric
        )
    }
}

/// What an address word addresses. Axis names are kept as text in the word's `name` span.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AddressKind {
    /// A configured axis, or an axis letter that is not configured (reported separately).
    Axis,
    /// I, J, K: circle centre (and I1, J1, K1: CIP intermediate point).
    Interpolation,
    Feed,
    Spindle,
    Tool,
    ToolEdge,
    MFunction,
    HFunction,
    /// `L123`: subprogram by number.
    SubprogramNumber,
    /// `P3`: number of repetitions of a subprogram call.
    Repetitions,
    /// CR, AR, AP, RP, TURN, RPL and the other multi-letter addresses that take a plain value.
    Named(NamedAddress),
}

/// The multi-letter addresses the parser knows, with their rules for modifiers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NamedAddress {
    CircleRadius,
    OpeningAngle,
    PolarAngle,
    PolarRadius,
    Turns,
    RotationInPlane,
    /// `POS[X]`, `POSA[X]`, `SPOS`, `SPOSA`: positioning axes and spindles, which take all modifiers.
    Positioning,
    /// `AX[name]=`: an axis given indirectly; takes the position modifiers of an axis.
    IndirectAxis,
    /// Any other known address (`LIMS`, `FA[X]`, `OVR`, `CHF`, `RND`, ...): no position modifiers.
    Other,
}

impl AddressKind {
    /// Whether `=AC(..)` and friends are allowed on this address (reference §1.8).
    pub fn accepts_modifier(self) -> bool {
        matches!(
            self,
            AddressKind::Axis
                | AddressKind::Interpolation
                | AddressKind::Named(NamedAddress::PolarAngle)
                | AddressKind::Named(NamedAddress::Positioning)
                | AddressKind::Named(NamedAddress::IndirectAxis)
        )
    }
}

/// The value part of an address word.
#[derive(Debug, Clone, PartialEq)]
pub struct Value {
    /// The position modifier and the span of its name, if one was written.
    pub modifier: Option<(Modifier, Span)>,
    /// The value (inside the modifier's parentheses when there is one).
    pub expr: ValueExpr,
    /// Whether `=` was written.
    pub has_equals: bool,
}

/// What an address word's value is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ValueExpr {
    /// No value was written; a diagnostic has been reported.
    Missing,
    /// A constant written without `=` (`X10`, `Z-5.5`, sign included). Most words of a program are
    /// such constants, so they are kept inline instead of as a node of the expression arena.
    Constant { value: f64, span: Span },
    /// Any other value: a node of [`Block::exprs`].
    Expr(ExprId),
}

impl ValueExpr {
    /// The expression node, when the value is one.
    pub fn expr_id(self) -> Option<ExprId> {
        match self {
            ValueExpr::Expr(id) => Some(id),
            _ => None,
        }
    }
}

/// An address with its value, e.g. `X10`, `Z=IC(-32)`, `X1=10`, `S1=470`, `CR=5`, `POS[A]=DC(10)`.
#[derive(Debug, Clone, PartialEq)]
pub struct AddressWord {
    pub kind: AddressKind,
    /// The address name without extension (`X`, `CR`, `POS`).
    pub name: Span,
    /// The numeric extension (`1` in `X1=10`) or the bracketed index (`[X]` in `POS[X]`).
    pub extension: Option<Extension>,
    pub value: Value,
    /// The whole word.
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Extension {
    /// Digits written right after the address letter and followed by `=`.
    Number { value: u32, span: Span },
    /// `[expr, ...]` after the address.
    Index { indexes: Vec<ExprId>, span: Span },
}

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

/// The data types of `DEF` and of `PROC` parameters (reference §8.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DataType {
    Int,
    Real,
    Bool,
    Char,
    /// `STRING[n]`; the length is not kept.
    String,
    Axis,
    Frame,
}

impl DataType {
    /// The type a name (in upper case) stands for.
    pub fn from_name(upper: &str) -> Option<DataType> {
        Some(match upper {
            "INT" => DataType::Int,
            "REAL" => DataType::Real,
            "BOOL" => DataType::Bool,
            "CHAR" => DataType::Char,
            "STRING" => DataType::String,
            "AXIS" => DataType::Axis,
            "FRAME" => DataType::Frame,
            _ => return None,
        })
    }
}

/// One name of a `DEF` with its array sizes and initial value: `TAB[3,4]=REP(0)`.
#[derive(Debug, Clone, PartialEq)]
pub struct Declarator {
    /// The whole name, also where `names` has only its first letter (`V1AR`, reported as S162).
    pub name: Span,
    /// The array sizes, one per dimension (the control allows up to three); empty for a scalar.
    pub dimensions: Vec<ExprId>,
    pub initial: Option<Initializer>,
}

/// The initial value of a `DEF` name.
#[derive(Debug, Clone, PartialEq)]
pub enum Initializer {
    /// `=5`, `="ABC"`, `=X`: one value.
    Value(ExprId),
    /// `=(1,2,3)` for an array: its elements in order; an empty element (`(1,,3)`) is `None`.
    List(Vec<Option<ExprId>>),
    /// `=SET(1,2,3)`: the same as a list.
    Set(Vec<Option<ExprId>>),
    /// `=REP(value)` fills the whole array, `=REP(value, count)` its first `count` elements.
    Repeat {
        value: ExprId,
        count: Option<ExprId>,
    },
}

/// One parameter of a `PROC` header: `REAL PA=5`, `VAR REAL TAB[,]`.
#[derive(Debug, Clone, PartialEq)]
pub struct ProcParameter {
    pub name: Span,
    pub data_type: Option<DataType>,
    /// `VAR`: passed by reference, the caller must give a variable.
    pub by_reference: bool,
    /// The number of array dimensions: 1 for `A[]`, 2 for `A[,]`, 0 for a scalar.
    pub dimensions: usize,
    /// The value an omitted argument takes (`PROC SUB(REAL PA=5)`).
    pub default: Option<ExprId>,
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

/// `N10` or `:10` at the start of a block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BlockNumber {
    pub value: u64,
    /// `:10` marks a main block.
    pub main: bool,
    pub span: Span,
}

/// One parsed line. Spans are byte offsets into the line.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Block {
    /// Skip level (`/` is level 0) and the span of the marker.
    pub skip: Option<(u8, Span)>,
    pub number: Option<BlockNumber>,
    /// The label name, without its colon.
    pub label: Option<Span>,
    pub statements: Vec<Statement>,
    pub comment: Option<Span>,
    /// Index in `statements` from which on the statements are actions of a synchronized action.
    pub sync_actions_from: Option<usize>,
    /// The line is a program header in punched-tape format (`%_N_NAME_MPF`).
    pub is_header: bool,
    pub exprs: Vec<Expr>,
}

impl Block {
    /// Empties the block but keeps its allocations for the next line.
    pub fn clear(&mut self) {
        self.skip = None;
        self.number = None;
        self.label = None;
        self.statements.clear();
        self.comment = None;
        self.sync_actions_from = None;
        self.is_header = false;
        self.exprs.clear();
    }

    pub fn expr(&self, id: ExprId) -> &Expr {
        &self.exprs[id.0 as usize]
    }

    /// The statements the interpreter executes (not the main-run actions of a synchronized action).
    pub fn interpreted_statements(&self) -> &[Statement] {
        match self.sync_actions_from {
            Some(index) => &self.statements[..index],
            None => &self.statements,
        }
    }
}
