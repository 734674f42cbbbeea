//! The entries of a document's symbol table (labels, variables, R parameters, the PROC header, macros,
//! EXTERN declarations, calls, jumps, tool changes, comment sections, name uses, control structures) and
//! the table itself. `symbols.rs` builds it from the parser's blocks.

use crate::diagnostics::Span;
pub use crate::ide::block_numbers::{BlockNumberEntry, BlockNumbers};
use crate::syntax::ast::{JumpKind, StructureKeyword};

/// `NAME:` at the start of a block.
#[derive(Debug, Clone, PartialEq)]
pub struct LabelDefinition {
    /// Upper case, without the colon.
    pub name: String,
    pub line: usize,
    pub span: Span,
}

/// A variable declared with `DEF`.
#[derive(Debug, Clone, PartialEq)]
pub struct VariableDefinition {
    pub name: String,
    /// `REAL`, `INT`, `STRING[32]`, ...; empty when the declaration names no type.
    pub type_name: String,
    /// `[3]` or `[2,3]` when the variable is an array.
    pub dimensions: Option<String>,
    /// `NCK` or `CHAN` for global user data (GUD), `None` for local data.
    pub global_attribute: Option<String>,
    pub line: usize,
    pub span: Span,
}

/// An R parameter read or written: `R1`, `$R1`, `R[expr]` (whose number is not known statically).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RParameterUse {
    pub number: Option<u32>,
    pub line: usize,
    pub span: Span,
    pub write: bool,
}

/// A formal parameter of a `PROC`.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    pub name: String,
    pub type_name: String,
    /// `VAR`: passed by reference, so the caller must give a variable.
    pub by_reference: bool,
    pub dimensions: Option<String>,
    pub line: usize,
    pub span: Span,
}

/// `PROC NAME(params) attributes`.
#[derive(Debug, Clone, PartialEq)]
pub struct ProcedureDefinition {
    pub name: String,
    pub line: usize,
    /// The span of the name.
    pub span: Span,
    pub parameters: Vec<Parameter>,
    /// Whether the header has a parameter list in parentheses.
    pub has_parameter_list: bool,
    /// The comment lines written directly above the header, without `;` and rule lines.
    pub documentation: Option<String>,
}

/// `DEFINE NAME AS body`.
#[derive(Debug, Clone, PartialEq)]
pub struct MacroDefinition {
    pub name: String,
    pub body: String,
    pub line: usize,
    pub span: Span,
}

/// `EXTERN NAME(types)`.
#[derive(Debug, Clone, PartialEq)]
pub struct ExternDeclaration {
    pub name: String,
    /// The parameter types as written (`REAL`, `VAR INT`); `None` without a parameter list.
    pub parameter_types: Option<Vec<String>>,
    pub line: usize,
    pub span: Span,
}

/// How a call names its program.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CallStyle {
    /// `NAME` or `NAME(args)`.
    Named,
    /// `MCALL NAME(args)`.
    Modal,
    /// `CALL "NAME"`, `PCALL /_N_DIR/_N_NAME_SPF`: the name inside a string or path.
    Indirect,
    /// `L123`: a subprogram by number (leading zeros count).
    Number,
}

/// A call of a subprogram or cycle (or the use of a macro, which reads like one).
#[derive(Debug, Clone, PartialEq)]
pub struct CallSite {
    /// The called program's name, upper case.
    pub name: String,
    pub style: CallStyle,
    pub line: usize,
    /// The span of the name alone (inside the quotes for `CALL "NAME"`).
    pub span: Span,
    /// The number of arguments written in parentheses, empty ones included; `None` without them.
    pub argument_count: Option<usize>,
    /// The span of the whole call statement.
    pub statement_span: Span,
    /// The parser reported the name as an address word that lacks its `=` (S120: `XR1`, `CR10`,
    /// `ZAC(17)`). Saying again that no program has that name would only repeat the finding.
    pub reads_as_address_word: bool,
}

/// Where a jump goes.
#[derive(Debug, Clone, PartialEq)]
pub enum JumpDestination {
    Label {
        name: String,
        span: Span,
    },
    BlockNumber {
        value: u64,
        span: Span,
    },
    /// A target computed at run time (a string variable): not resolved.
    Computed,
    /// `GOTOS`, or a jump without target.
    None,
}

/// `GOTOF`/`GOTOB`/`GOTO`/`GOTOC`/`GOTOS`, conditional or not.
#[derive(Debug, Clone, PartialEq)]
pub struct JumpSite {
    pub kind: JumpKind,
    pub destination: JumpDestination,
    pub line: usize,
    /// The span of the jump keyword.
    pub keyword_span: Span,
    /// Written in a `CASE` block.
    pub in_case: bool,
}

/// A block that changes the tool: a `T` word and/or `M6`.
#[derive(Debug, Clone, PartialEq)]
pub struct ToolChange {
    pub line: usize,
    /// From the first to the last tool word of the block.
    pub span: Span,
    /// The tool words as written, e.g. `T5 M6`.
    pub text: String,
}

/// A comment that titles a section of the program (`;--- ROUGHING ---`, or a title under a rule line).
#[derive(Debug, Clone, PartialEq)]
pub struct CommentSection {
    /// The first line of the section's header (the rule line above the title, if there is one).
    pub line: usize,
    pub title_line: usize,
    pub title: String,
}

/// A name read or written as a variable (or parameter, or macro) in an expression or assignment.
#[derive(Debug, Clone, PartialEq)]
pub struct NameUse {
    pub name: String,
    pub line: usize,
    pub span: Span,
    pub write: bool,
}

/// A control-structure keyword (IF, ELSE, ENDIF, WHILE, ... CASE) and where it stands.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StructureMark {
    pub keyword: StructureKeyword,
    pub line: usize,
    pub span: Span,
}

/// Everything one document declares and uses, in line order within each list.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SymbolTable {
    pub labels: Vec<LabelDefinition>,
    pub block_numbers: BlockNumbers,
    pub variables: Vec<VariableDefinition>,
    pub r_parameters: Vec<RParameterUse>,
    pub procedure: Option<ProcedureDefinition>,
    pub macros: Vec<MacroDefinition>,
    pub externs: Vec<ExternDeclaration>,
    pub calls: Vec<CallSite>,
    pub jumps: Vec<JumpSite>,
    pub tool_changes: Vec<ToolChange>,
    pub sections: Vec<CommentSection>,
    pub name_uses: Vec<NameUse>,
    pub structures: Vec<StructureMark>,
    /// The first block that executes something (not a declaration, label, number or comment).
    pub first_executable_line: Option<usize>,
    pub line_count: usize,
}
