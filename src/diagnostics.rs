//! The vocabulary every layer uses to report problems: spans, severities, stable codes and suggested fixes.
//!
//! Nothing here knows about files, JSON or the Language Server Protocol; the CLI and the server convert
//! these plain values at their edges.

use std::fmt;

/// A byte range inside one line of a program (end exclusive). Lines never exceed `u32::MAX` bytes
/// because the reader refuses larger inputs, so both ends fit in 32 bits.
///
/// Both ends are packed into one `u64`: the parser builds millions of spans, and writing a span as one
/// word (instead of two 32-bit halves that are then copied as one) avoids a store-forwarding stall that
/// cost a third of the parse time of plain blocks.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Span(u64);

impl Span {
    pub fn new(start: usize, end: usize) -> Span {
        Span((start as u32) as u64 | ((end as u32) as u64) << 32)
    }

    pub fn start(self) -> usize {
        (self.0 as u32) as usize
    }

    pub fn end(self) -> usize {
        ((self.0 >> 32) as u32) as usize
    }

    pub fn len(self) -> usize {
        self.end().saturating_sub(self.start())
    }

    pub fn is_empty(self) -> bool {
        self.end() <= self.start()
    }

    /// The smallest span that covers both spans.
    pub fn to(self, other: Span) -> Span {
        Span::new(self.start().min(other.start()), self.end().max(other.end()))
    }
}

impl fmt::Debug for Span {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(formatter, "{}..{}", self.start(), self.end())
    }
}

/// How serious a finding is. The order matters: `Error` is the most severe.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    Error,
    Warning,
    Information,
    Hint,
}

impl Severity {
    pub fn as_str(self) -> &'static str {
        match self {
            Severity::Error => "error",
            Severity::Warning => "warning",
            Severity::Information => "info",
            Severity::Hint => "hint",
        }
    }

    /// Parses the names used in configuration files and on the command line.
    pub fn parse(text: &str) -> Option<Severity> {
        match text.to_ascii_lowercase().as_str() {
            "error" => Some(Severity::Error),
            "warning" | "warn" => Some(Severity::Warning),
            "info" | "information" => Some(Severity::Information),
            "hint" => Some(Severity::Hint),
            _ => None,
        }
    }
}

impl fmt::Display for Severity {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        formatter.write_str(self.as_str())
    }
}

/// One replacement of a byte range of the line by new text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TextEdit {
    pub span: Span,
    pub new_text: String,
}

/// A machine-applicable suggestion carried with a diagnostic, later offered as an editor quick fix.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Fix {
    /// What the fix does, as shown to the user, e.g. "Write `Z=AC(17)`".
    pub title: String,
    pub edits: Vec<TextEdit>,
}

impl Fix {
    /// A fix that replaces one span.
    pub fn replace(title: impl Into<String>, span: Span, new_text: impl Into<String>) -> Fix {
        Fix {
            title: title.into(),
            edits: vec![TextEdit {
                span,
                new_text: new_text.into(),
            }],
        }
    }
}

/// A finding inside one line: the span is relative to the start of that line.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    pub code: Code,
    pub severity: Severity,
    pub span: Span,
    pub message: String,
    pub fix: Option<Fix>,
}

impl Diagnostic {
    /// A diagnostic with the code's default severity and no fix.
    pub fn new(code: Code, span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            code,
            severity: code.default_severity(),
            span,
            message: message.into(),
            fix: None,
        }
    }

    pub fn with_fix(mut self, fix: Fix) -> Diagnostic {
        self.fix = Some(fix);
        self
    }
}

/// A diagnostic together with the 0-based line it belongs to.
#[derive(Debug, Clone, PartialEq)]
pub struct LineDiagnostic {
    pub line: usize,
    pub diagnostic: Diagnostic,
}

macro_rules! codes {
    ($( $variant:ident = $text:literal, $severity:ident, $summary:literal; )*) => {
        /// Every diagnostic the product can report. The text form (`S101`, ...) is stable: it is
        /// documented in docs/diagnostics.md, used in configuration files and must never be reused
        /// for another meaning.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum Code {
            $( $variant, )*
        }

        impl Code {
            pub const ALL: &'static [Code] = &[$( Code::$variant, )*];

            pub fn as_str(self) -> &'static str {
                match self {
                    $( Code::$variant => $text, )*
                }
            }

            pub fn default_severity(self) -> Severity {
                match self {
                    $( Code::$variant => Severity::$severity, )*
                }
            }

            /// A one-line description for the documentation and `--explain`-style listings.
            pub fn summary(self) -> &'static str {
                match self {
                    $( Code::$variant => $summary, )*
                }
            }

            pub fn parse(text: &str) -> Option<Code> {
                Code::ALL.iter().copied().find(|code| code.as_str().eq_ignore_ascii_case(text))
            }
        }
    };
}

codes! {
    UnexpectedCharacter = "S100", Error, "A character that has no meaning in the NC language outside strings and comments.";
    ModifierWithoutParentheses = "S101", Error, "A position modifier such as AC or IC is not followed by its value in parentheses (`Z=AC17`, `Z=AC 17`).";
    ModifierUnclosed = "S102", Error, "A position modifier's parenthesis is not closed (`Z=AC(17`).";
    ModifierEmpty = "S103", Error, "A position modifier has no value (`Z=AC()`).";
    ModifierTooManyValues = "S104", Error, "A position modifier has more than one value (`Z=AC(1,2)`).";
    ModifierNested = "S105", Error, "A position modifier inside another one (`Z=AC(IC(3))`).";
    ModifierUnknown = "S106", Error, "An unknown position modifier after an axis address (`Z=AB(3)`).";
    ModifierNotAllowed = "S107", Error, "A position modifier on an address that does not take one (F, S, T, D, M, H, N, G, L, P, CR, AR, RP, ...).";
    ModifierOutsideAddress = "S108", Error, "A position modifier assigned to something that is not an address (`R1=AC(5)`).";
    ModifierNeedsRotaryAxis = "S109", Error, "DC, ACP or ACN on an axis that is not rotary (ACP/ACN also need a modulo axis).";
    ModifierWithoutEquals = "S110", Error, "A position modifier written without `=` (`Z AC(17)`).";
    ModifierNeedsTransverseAxis = "S111", Warning, "DAC, DIC, RAC or RIC on an axis that is not configured as transverse (diameter) axis.";
    NameReadAsCall = "S120", Warning, "A word the control reads as a call of a subprogram, most likely a missing `=` (`ZAC(17)`, `XR1`, `CR5`).";
    UnbalancedParentheses = "S130", Error, "Parentheses that are not balanced.";
    UnbalancedBrackets = "S131", Error, "Square brackets that are not balanced.";
    UnterminatedString = "S132", Error, "A string without its closing `\"` on the same line (strings have no escapes).";
    InvalidNumber = "S133", Error, "A malformed number or numeric literal, or one too large for the control (beyond about 1.8EX308).";
    ParenthesisComment = "S134", Error, "Text in parentheses used as a comment; only `;` starts a comment in Siemens mode.";
    SameGroupTwice = "S140", Error, "Two G functions of the same group in one block (alarm 12060).";
    SyntaxDefiningConflict = "S141", Error, "More than one syntax-defining G function (groups 1, 2, 3) in one block (alarm 12070).";
    InstructionNotAlone = "S142", Error, "A frame or pole instruction (TRANS, ROT, G110, ...) that is not alone in its block.";
    AddressTwice = "S143", Error, "An address or axis programmed twice in one block (alarms 12010, 16420).";
    UnknownGCode = "S144", Error, "A G function number that does not exist (alarm 12470).";
    MissingValue = "S150", Error, "An address without its value (`X` alone; `X0` cannot be shortened to `X`).";
    ValueNeedsEquals = "S151", Error, "A value that is not a single constant needs `=` after the address (`X=R1`, `X=-R2`).";
    ExpectedExpression = "S152", Error, "An expression was expected here.";
    UnexpectedToken = "S153", Error, "Something that cannot stand at this place in a block.";
    InvalidSkipLevel = "S160", Error, "A skip level outside the configured range `/0` to `/9` (alarm 14060).";
    InvalidLabel = "S161", Error, "A label name the control cannot accept (starts with a digit, or is an address letter).";
    LabelStyle = "S162", Warning, "A label or name that breaks the naming recommendations (fewer than two leading letters, longer than 31 characters).";
    BlockTooLong = "S163", Warning, "A block longer than the configured maximum (512 characters including the comment).";
    TooDeeplyNested = "S170", Error, "An expression nested deeper, or chaining more operations, than the parser accepts.";
    UnknownFunction = "S171", Warning, "A call of a function the language does not define.";
    ComparisonPrecedence = "S172", Warning, "A comparison whose operand is an unbracketed AND/OR expression; comparisons bind weakest.";
    UnknownNameBetweenOperands = "S173", Warning, "A name standing between two operands, most likely a macro (DEFINE) whose definition is not known.";
    ComparisonSpelling = "S174", Warning, "A comparison written `=`, `=<` or `=>` instead of `==`, `<=` or `>=`.";
    AxisNotConfigured = "S180", Warning, "An axis address that is not an axis of the configured machine.";
    StructureMismatch = "S190", Warning, "IF/ELSE/ENDIF, WHILE, FOR, REPEAT, LOOP nesting that does not match (alarm 12640).";
    TooManyDiagnostics = "S199", Information, "A line with so many findings that the rest are not shown.";
    IncrementOnUnknownPosition = "A201", Warning, "An incremental move of an axis whose position is not known at that point, so its end point is unknown.";
    RedundantModifier = "A202", Hint, "`=AC(..)` under G90 or `=IC(..)` under G91: the modifier changes nothing.";
    FeedMissing = "A203", Error, "The first feed move (G1, G2, G3, CIP, CT) without a feedrate programmed (alarm 10860).";
    FeedNotPositive = "A204", Error, "A feedrate of 0 or less (alarm 14800).";
    DivisionByZero = "A205", Error, "A division by zero in an expression whose values are known (alarm 14051).";
    CircleEndNotOnCircle = "A206", Error, "A circle whose end point is farther off the circle than the tolerance MD21000/MD21010 allows (alarm 14040).";
    CircleRadiusTooSmall = "A207", Error, "A circle radius CR smaller than half the distance from start to end point.";
    CircleRadiusFullCircle = "A208", Error, "A circle with CR whose end point equals its start point (alarm 14040).";
    CircleWithoutCentre = "A209", Error, "G2/G3 without centre, radius, opening angle or polar values (reported in every plane, also where a subprogram inherits an unknown plane), or AR without end point and centre (`G3 AR=90`).";
    PolarWithoutPole = "A210", Information, "A polar move (AP/RP) while no pole is defined: the pole is the zero point of the workpiece coordinate system.";
    PolarWithPlaneAxis = "A211", Error, "A plane axis programmed together with AP/RP; only the perpendicular axis may join a polar block.";
    PolarRadiusNegative = "A212", Error, "A negative polar radius RP.";
    SettableDataNotActive = "A213", Warning, "A move under a settable offset (G54 ...) whose data `$P_UIFR[n]` were written since it was selected: the new data are not active until it is selected again.";
    OpeningAngleOutOfRange = "A214", Error, "An opening angle AR outside 0 < AR < 360, or AR with the end point equal to the start point: AR cannot program a full circle.";
    IntermediatePointOnLine = "A215", Error, "CIP whose start, intermediate and end point lie on one line, the intermediate point not between the others (alarm 14920).";
    TurnsOutOfRange = "A216", Error, "TURN outside 0 to 999 (alarm 14048).";
    PolarAngleUnderG91 = "A217", Hint, "A plain `AP=` under G91: AP is absolute unless written `AP=IC(..)`.";
    PolarValueAfterPoleChange = "A218", Warning, "The first polar move after a pole or plane change without AP or RP, or with `AP=IC(..)`: it relies on a stored value that belongs to the old pole.";
    CentreLooksAbsolute = "A219", Hint, "A circle rejected for its end point whose I/J/K, read as absolute coordinates, would give a valid circle: I/J/K are incremental unless `=AC(..)`.";
    InchFeedMixed = "A220", Hint, "A program that programs F and uses both G70/G71 and G700/G710: only G700/G710 convert F.";
    UnitsChangeInContour = "A221", Warning, "G70/G71/G700/G710 switches between inch and metric while tool radius compensation G41/G42 is active.";
    SuppressionWithoutAxes = "A222", Hint, "G53, G153 or SUPA in a block without axis values: they act only on the axes of their own block.";
    IncrementAfterOffsetChange = "A223", Hint, "A G91 move of an axis right after a settable offset or frame change: the change is traversed in addition (SD42440 = 1).";
    AxisLeftOutAfterRotation = "A224", Information, "The first move after a frame change that rotates, scales or mirrors leaves out a geometry axis the change affects: it keeps its value in the new coordinates, so the move may move it too.";
    ArithmeticError = "A225", Error, "An arithmetic error other than a division by zero in an expression whose values are known: a result beyond the range of a double, or a function argument outside its domain (`SQRT(-1)`, `ACOS(2)`, `LN(0)`) (alarm 14051).";
    FunctionArgumentCount = "A226", Error, "A predefined function the checker computes, called with a wrong number of arguments (`POT(2,3)`; alarm 14020).";
    IndexOutOfRange = "A227", Error, "A known index outside the dimensions of a defined array, or an R parameter number that is negative or beyond the configured count `r_parameters` (MD28050; alarm 17020).";
    ModuloIncrementOnUnknownPosition = "A228", Information, "An incremental move of a modulo rotary axis whose position is not known at that point (`C=IC(720)`): usual practice for such axes, whose end point is unknown here.";
    CircleWordWithoutCircle = "A229", Warning, "`CR=`, `AR=` or I/J/K in a block whose motion is G0 or G1: the word does nothing; a circle (G2/G3) was probably meant, or the word is left over.";
    CircleDefinedTwice = "A230", Error, "A circle given two ways at once: I/J/K together with CR, or CR together with AR (the control rejects the block; alarm number not confirmed, 14040 is the closest).";
    CircleRadiusZero = "A231", Error, "A circle of radius zero: G2/G3 whose centre is its start point (`I0 J0`), or a polar circle with `RP=0` (alarm 14040).";
    IntermediatePointMissing = "A232", Error, "CIP without an intermediate point (I1/J1/K1), or with one equal to the start or the end point: no circle is defined (alarm 14920).";
    PoleWithOneCoordinate = "A233", Warning, "A pole (G110/G111/G112) with only one coordinate of the plane (`G111 X10`): the other is taken as 0 from the command's reference, which the documentation does not confirm (reference §5.3).";
    ModuloPositionOutOfRange = "A234", Error, "An absolute position of a modulo rotary axis outside 0 to 360 degrees (`A370`, `A=DC(-10)`): reported when `modulo_range_error = 1` says that MD30455 bit 0 is 0 (real programs write `C370` for machines that convert such positions).";
    DiameterWithoutTransverseAxis = "A235", Warning, "Diameter programming (DIAMON, DIAM90, DIAMCYCOF, ...) on a machine without a transverse axis (alarm 16510): configure a lathe with `kind = \"turn\"` in `sinumerik.toml`; reported once per program, as a warning because without a configuration file the mill is an assumption.";
    CuttingSpeedWithoutTransverseAxis = "A236", Warning, "G96 (constant cutting speed) on a machine without a transverse axis (alarm 10870): configure a lathe with `kind = \"turn\"` in `sinumerik.toml`; reported once per program, as a warning because without a configuration file the mill is an assumption.";
    FunctionNotEvaluated = "A237", Information, "A call of a predefined function that the checker does not compute: its result, and what depends on it, is unknown here.";
    AngleDirectionMismatch = "A240", Warning, "A straight line defined by `ANG` and one end coordinate whose angle points away from that coordinate: the control rejects the block (reference §14.6, T109; the alarm is not documented).";
    AngleNoSolution = "A241", Error, "A contour definition by angles that has no solution: `ANG` parallel to the only given axis, or two lines of a two-block definition that are parallel (reference §14.6).";
    RoundingAndChamfer = "A242", Information, "A block that programs both a rounding and a chamfer (`RND` with `CHR` or `CHF`): only the rounding is inserted (reference §14.1).";
    FeedNotReprogrammed = "A250", Error, "A feed move after a change between G93, G94 and G95 without a new F: the control does not reuse the old feed (alarm 10860); its machining time is unknown.";
    EndlessLoop = "E401", Warning, "A loop or jump cycle that the program never leaves: its state repeats unchanged, so the control would run it forever.";
    ExecutionBudgetUsed = "E402", Information, "The configured budget of executed blocks is used up: the rest of the program is read in program order and its values are uncertain.";
    LoopPassLimit = "E403", Information, "A loop that ran more passes than the configured limit: what its body changes is unknown after it.";
    ConditionNotKnown = "E404", Information, "A condition of a loop or jump that depends on values the program does not determine (main-run variables, machine data): every way is followed, and what differs between them becomes unknown.";
    SubprogramLevelExceeded = "E405", Error, "A call that would need more than the control's program levels (16: the main program and 15 nested calls), or a recursion that does not end (alarm 14012).";
    JumpTargetNotFound = "E406", Error, "A jump whose target, computed while the program runs (a STRING variable), names no label of the program (alarm 14080).";
    RestartByPlc = "E407", Information, "GOTOS restarts the program only when the PLC requests it; the analysis follows the configured request.";
    LevelLimitOnUndecidedWay = "E409", Warning, "A call that would need more than the control's program levels, on a way that depends on conditions the program does not determine: the control stops with alarm 14012 if it takes that way.";
    FlowNotFollowed = "E408", Information, "A jump whose target is not known statically, or a control structure whose nesting is broken: from there on the program is read in program order and its values are uncertain.";
    CycleReferencePlane = "E420", Error, "A drilling cycle whose retraction plane and final depth lie on the same side of the reference plane, or whose depth relative to a reference plane equal to the retraction plane cannot be placed (alarm 61101): the cycle makes no motion.";
    PatternWithoutModalCall = "E421", Warning, "A hole pattern (HOLES1, HOLES2) called while no drilling cycle is called modally (alarm 62100): the control stops (M0) and, after NC start, approaches the positions without drilling.";
    PatternWithoutHoles = "E422", Error, "A hole pattern with the number of holes 0 (alarm 61103): the cycle is aborted without motion.";
    CircleOfHolesTooLong = "E423", Error, "HOLES2 whose angle between holes times the number of gaps reaches 360 degrees or more (alarm 61106): the cycle is aborted without motion.";
    CycleDepthDisagrees = "E424", Information, "A drilling cycle given both the final depth DP and the relative depth DPR, which disagree: DPR wins.";
    GridWithoutRowsOrColumns = "E425", Warning, "CYCLE801 with 0 rows or 0 columns (alarm 62105): the control stops (M0) and takes 1.";
    CornerElementReduced = "E430", Warning, "A rounding or chamfer that does not fit the elements of its corner: it is reduced as far as it fits (the control's exact rule is not documented, reference §14.4).";
    CornerReversal = "E431", Error, "A rounding or chamfer at a corner where the path reverses (180°): no element can be inserted (reference §14.3).";
    ChamferAtCircle = "E432", Information, "A chamfer at a circle: the chamfer points lie on the elements at the chord distance from the corner, as the reference recommends; the control's construction is not documented (reference §14.3).";
    CornerNotInserted = "E433", Information, "A rounding or chamfer the control does not insert: more blocks without motion in the plane follow than MD20200 allows, the plane changes, or the program ends before the next element (reference §14.4).";
    UnknownSubprogram = "W301", Warning, "A call of a subprogram that no file of the workspace defines and that is not a cycle of the control (reported only when the workspace index is complete, and not for a word S120 already reports as read as a call).";
    TooManyArguments = "W302", Warning, "A call that passes more arguments than the PROC header of the called subprogram declares.";
    MissingReferenceArgument = "W303", Warning, "A call that leaves out an argument the PROC header passes by reference (`VAR`): the subprogram has no variable to write to.";
    UndefinedJumpTarget = "W304", Error, "A jump to a label or block number that the program does not contain (alarm 14080); GOTOC is exempt.";
    JumpWrongDirection = "W305", Error, "A GOTOF to a target that exists only above it, or a GOTOB to one only below it (alarm 14080).";
    UndefinedVariable = "W306", Warning, "A name read or written as a variable that no DEF, PROC parameter, definition file or macro defines (alarm 12550; reported only when the workspace index is complete).";
    DefinitionAfterExecutable = "W307", Error, "A DEF or PROC after the first executable block of the program (alarm 14500).";
}

impl fmt::Display for Code {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        formatter.write_str(self.as_str())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn code_texts_are_unique_and_parse_back() {
        let mut seen = std::collections::HashSet::new();
        for code in Code::ALL {
            assert!(
                seen.insert(code.as_str()),
                "duplicate code {}",
                code.as_str()
            );
            assert_eq!(Code::parse(code.as_str()), Some(*code));
        }
        assert_eq!(Code::parse("s101"), Some(Code::ModifierWithoutParentheses));
        assert_eq!(Code::parse("S999"), None);
    }

    #[test]
    fn severity_names_parse() {
        assert_eq!(Severity::parse("Warning"), Some(Severity::Warning));
        assert_eq!(Severity::parse("info"), Some(Severity::Information));
        assert_eq!(Severity::parse("fatal"), None);
        assert!(Severity::Error < Severity::Warning);
    }
}
