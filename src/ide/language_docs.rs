//! One table of short descriptions of the language, in our own words (from reference §2 and §8):
//! G functions with their group, keywords, predefined functions and instructions, position modifiers,
//! common system variables and the standard cycles. Completion, hover documentation and the language
//! server's hover of a G function all read it, so an entry is written once.

use crate::ide::cycles::CYCLES;
use crate::syntax::gcodes::{GCode, TABLE};

/// What kind of word an entry describes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EntryKind {
    /// A G function and its group.
    GCode {
        group: u8,
        modal: bool,
    },
    Keyword,
    Function,
    Instruction,
    Modifier,
    SystemVariable,
    Cycle,
}

/// The documentation of one word.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LanguageDoc {
    /// The canonical spelling (`G1`, `DIAMON`, `GOTOF`, `$P_GG`).
    pub name: String,
    pub kind: EntryKind,
    /// One line saying what it does.
    pub summary: String,
    /// For G functions: "group 1 (motion), modal".
    pub detail: String,
}

/// The name of a G group (reference §2.2).
pub fn group_name(group: u8) -> &'static str {
    match group {
        1 => "motion",
        2 => "non-modal motion",
        3 => "frames, pole, working area",
        4 => "FIFO",
        6 => "working plane",
        7 => "tool radius compensation",
        8 => "settable work offset",
        9 => "frame suppression",
        10 => "exact stop / continuous path",
        11 => "exact stop, non-modal",
        12 => "exact-stop criterion",
        13 => "inch / metric",
        14 => "absolute / incremental",
        15 => "feed type",
        16 => "feed at curved contours",
        17 => "approach and retract with tool offset",
        18 => "corners with tool offset",
        19 => "spline start",
        20 => "spline end",
        21 => "acceleration profile",
        22 => "tool offset type",
        23 => "collision monitoring",
        24 => "feedforward control",
        25 => "tool orientation reference",
        26 => "repositioning point",
        27 => "orientation change at corners",
        28 => "working-area limitation",
        29 => "diameter / radius programming",
        30 => "NC block compression",
        31 | 32 => "OEM G functions",
        33 => "fine tool offset",
        34 => "tool orientation smoothing",
        35 => "punching and nibbling",
        36 => "punching with delay",
        37 => "feed interpolation",
        39 => "programmable contour accuracy",
        40 => "constant cutting rate",
        41 => "thread interruption",
        42 => "tool carrier",
        43 | 44 => "soft approach and retract",
        45 => "path reference for FGROUP axes",
        46 => "fast retraction plane",
        47 => "external NC languages",
        48 => "approach and retract with radius compensation",
        49 => "point-to-point motion",
        50 => "orientation definition",
        51 => "orientation interpolation",
        52 => "frame rotation with the table",
        53 => "frame rotation with the tool",
        54 => "vector rotation in orientation interpolation",
        55 => "rapid traverse interpolation",
        56 => "tool wear coordinate system",
        57 => "corner deceleration",
        59 => "dynamic response of path interpolation",
        61 => "tool orientation smoothing",
        _ => "G group",
    }
}

/// What a G function does, for those a programmer meets most; others are described by their group.
pub fn gcode_summary(name: &str) -> Option<&'static str> {
    Some(match name {
        "G0" => "Rapid traverse to the end point; the programmed feed does not apply.",
        "G1" => "Straight line to the end point at feed F.",
        "G2" => "Circular arc clockwise in the working plane at feed F (centre I/J/K, radius CR, angle AR or polar).",
        "G3" => "Circular arc counter-clockwise in the working plane at feed F.",
        "CIP" => "Circular arc through an intermediate point I1/J1/K1 to the end point.",
        "CT" => "Circular arc that continues the previous path tangentially.",
        "ASPLINE" | "BSPLINE" | "CSPLINE" => "Spline interpolation through the programmed points.",
        "POLY" => "Polynomial interpolation.",
        "G33" => "Thread cutting with constant lead.",
        "G331" => "Rigid tapping into the hole.",
        "G332" => "Rigid tapping, retraction out of the hole.",
        "G34" | "G35" => "Thread cutting with a lead that grows (G34) or shrinks (G35).",
        "G4" => "Dwell for F seconds or S spindle revolutions; neither changes the modal feed or speed.",
        "G63" => "Tapping with a compensating chuck.",
        "G74" => "Approach the reference point.",
        "G75" => "Approach a fixed point.",
        "G9" => "Exact stop in this block only.",
        "TRANS" => "Zero offset that replaces the programmable frame.",
        "ATRANS" => "Zero offset added to the programmable frame.",
        "ROT" => "Rotation that replaces the programmable frame.",
        "AROT" => "Rotation added to the programmable frame.",
        "ROTS" | "AROTS" => "Rotation given by solid angles (replacing or added).",
        "SCALE" => "Scale factors that replace the programmable frame.",
        "ASCALE" => "Scale factors added to the programmable frame.",
        "MIRROR" => "Mirroring that replaces the programmable frame.",
        "AMIRROR" => "Mirroring added to the programmable frame.",
        "G25" => "Lower working-area limit, or minimum spindle speed with S.",
        "G26" => "Upper working-area limit, or maximum spindle speed with S.",
        "G110" => "Pole relative to the last programmed position.",
        "G111" => "Pole relative to the workpiece zero.",
        "G112" => "Pole relative to the last pole.",
        "G58" | "G59" => "Axial zero offset of single axes in the programmable frame.",
        "G17" => "Working plane X/Y; infeed and tool length along Z.",
        "G18" => "Working plane Z/X; infeed along Y, usual on lathes.",
        "G19" => "Working plane Y/Z; infeed along X.",
        "G40" => "Tool radius compensation off.",
        "G41" => "Tool radius compensation on, the tool left of the contour.",
        "G42" => "Tool radius compensation on, the tool right of the contour.",
        "G500" => "Settable work offsets off; the basic frame stays active.",
        "G54" | "G55" | "G56" | "G57" => "Settable work offset from the offset table of the machine.",
        "G53" => "Machine positions in this block: settable and programmable offsets are suppressed.",
        "G153" => "Like G53 and also suppresses the basic frame, in this block.",
        "SUPA" => "Like G153 and also suppresses handwheel, external and PRESET offsets, in this block.",
        "G60" => "Exact stop: each block ends at standstill.",
        "G64" | "G641" | "G642" | "G643" | "G644" | "G645" => "Continuous-path mode: blocks blend without stopping.",
        "G601" | "G602" | "G603" => "When an exact-stop block counts as reached (fine, coarse, interpolation end).",
        "G70" => "Inch values for positions; the feed stays in the basic unit system.",
        "G71" => "Metric values for positions; the feed stays in the basic unit system.",
        "G700" => "Inch values for positions and for feed.",
        "G710" => "Metric values for positions and for feed.",
        "G90" => "Absolute dimensions: axis values are end points.",
        "G91" => "Incremental dimensions: axis values are distances from the last position.",
        "G93" => "Inverse-time feed.",
        "G94" => "Feed per minute.",
        "G95" => "Feed per spindle revolution.",
        "G96" => "Constant cutting speed: S is the surface speed.",
        "G97" => "Constant cutting speed off: S is the spindle speed.",
        "CFC" => "Constant feed at the contour.",
        "CFTCP" => "Constant feed at the tool centre point.",
        "CFIN" => "Constant feed at inner radii only.",
        "G450" => "Corners under radius compensation are rounded by a transition circle.",
        "G451" => "Corners under radius compensation go to the intersection of the offset paths.",
        "BRISK" => "Acceleration in steps, the fastest profile.",
        "SOFT" => "Jerk-limited acceleration.",
        "DIAMOF" => "Diameter programming off: the transverse axis takes radius values.",
        "DIAMON" => "Diameter programming on: values of the transverse axis are diameters.",
        "DIAM90" => "Diameters for absolute values (G90), radius for incremental values (G91).",
        "DIAMCYCOF" => "Diameter programming off inside cycles.",
        "G290" => "Siemens mode (the language this tool reads).",
        "G291" => "ISO dialect mode.",
        "RTLION" => "G0 moves on a straight line.",
        "RTLIOF" => "G0 moves each axis on its own: the path is not a straight line.",
        "STARTFIFO" | "STOPFIFO" | "FIFOCTRL" => "Controls how far the blocks are prepared ahead.",
        _ => return None,
    })
}

/// Keywords, functions, instructions, modifiers and system variables: (name, kind, summary).
const WORDS: &[(&str, EntryKind, &str)] = &[
    ("IF", EntryKind::Keyword, "Starts a conditional block (closed by ENDIF) or a conditional jump `IF cond GOTOF label`."),
    ("ELSE", EntryKind::Keyword, "Starts the part of an IF block run when the condition is false."),
    ("ENDIF", EntryKind::Keyword, "Closes an IF block."),
    ("WHILE", EntryKind::Keyword, "Loop that runs while its condition holds; closed by ENDWHILE."),
    ("ENDWHILE", EntryKind::Keyword, "Closes a WHILE loop."),
    ("FOR", EntryKind::Keyword, "Counting loop `FOR var=start TO end`; counts up by 1; closed by ENDFOR."),
    ("ENDFOR", EntryKind::Keyword, "Closes a FOR loop."),
    ("REPEAT", EntryKind::Keyword, "Loop that runs until the condition of its UNTIL holds; with labels, repeats a program section."),
    ("UNTIL", EntryKind::Keyword, "Closes a REPEAT loop with its end condition."),
    ("LOOP", EntryKind::Keyword, "Endless loop, closed by ENDLOOP; left by a jump."),
    ("ENDLOOP", EntryKind::Keyword, "Closes a LOOP."),
    ("CASE", EntryKind::Keyword, "Jumps by value: `CASE expr OF 1 GOTOF L1 2 GOTOF L2 DEFAULT GOTOF L3`."),
    ("OF", EntryKind::Keyword, "Separates the value of a CASE from its branches."),
    ("DEFAULT", EntryKind::Keyword, "The branch of a CASE taken when no value matches."),
    ("GOTOF", EntryKind::Keyword, "Jumps forward (towards the end) to a label or block number."),
    ("GOTOB", EntryKind::Keyword, "Jumps backward (towards the start) to a label or block number."),
    ("GOTO", EntryKind::Keyword, "Jumps to a label or block number, searching forward first, then backward."),
    ("GOTOC", EntryKind::Keyword, "Like GOTO, but a missing target raises no alarm and the program goes on."),
    ("GOTOS", EntryKind::Keyword, "Jumps back to the start of the program."),
    ("DEF", EntryKind::Keyword, "Defines a variable: `DEF REAL NAME`; before the first executable block (alarm 14500)."),
    ("REDEF", EntryKind::Keyword, "Changes attributes of a defined variable or machine data."),
    ("DEFINE", EntryKind::Keyword, "Defines a macro: `DEFINE NAME AS instructions`."),
    ("AS", EntryKind::Keyword, "Separates a macro's name from its instructions."),
    ("PROC", EntryKind::Keyword, "Header of a subprogram with its parameters: `PROC NAME(REAL A, VAR INT B)`."),
    ("VAR", EntryKind::Keyword, "Marks a PROC parameter passed by reference: the caller gives a variable."),
    ("EXTERN", EntryKind::Keyword, "Declares a subprogram with parameters for its callers: `EXTERN NAME(REAL, INT)`."),
    ("RET", EntryKind::Keyword, "Returns from a subprogram."),
    ("M17", EntryKind::Keyword, "End of a subprogram."),
    ("M2", EntryKind::Keyword, "End of the main program."),
    ("M30", EntryKind::Keyword, "End of the main program."),
    ("CALL", EntryKind::Keyword, "Calls a program whose name is a string or variable: `CALL \"NAME\"`."),
    ("PCALL", EntryKind::Keyword, "Calls a subprogram by its absolute path."),
    ("EXTCALL", EntryKind::Keyword, "Runs a program from an external drive."),
    ("MCALL", EntryKind::Keyword, "Modal call: the cycle runs after every following positioning block until `MCALL` alone."),
    ("SAVE", EntryKind::Keyword, "PROC attribute: the caller's modal G functions and programmable frame come back on return."),
    ("DISPLOF", EntryKind::Keyword, "PROC attribute: the subprogram's blocks are not displayed."),
    ("SBLOF", EntryKind::Keyword, "PROC attribute: the subprogram runs as one block in single-block mode."),
    ("TO", EntryKind::Keyword, "Separates the start value of a FOR loop from its end value."),
    ("WHEN", EntryKind::Keyword, "Synchronized action: the action runs once when the condition holds."),
    ("WHENEVER", EntryKind::Keyword, "Synchronized action: the action runs in every interpolation cycle while the condition holds."),
    ("FROM", EntryKind::Keyword, "Synchronized action: once the condition held, the action runs as long as the action is active."),
    ("EVERY", EntryKind::Keyword, "Synchronized action: the action runs each time the condition becomes true."),
    ("DO", EntryKind::Keyword, "Starts the actions of a synchronized action."),
    ("AND", EntryKind::Keyword, "Logical AND; binds stronger than comparisons, so bracket them: `(A==1) AND (B==2)`."),
    ("OR", EntryKind::Keyword, "Logical OR."),
    ("XOR", EntryKind::Keyword, "Logical exclusive OR."),
    ("NOT", EntryKind::Keyword, "Logical negation."),
    ("DIV", EntryKind::Keyword, "Integer division."),
    ("MOD", EntryKind::Keyword, "Remainder of an integer division."),
    ("B_AND", EntryKind::Keyword, "Bitwise AND."),
    ("B_OR", EntryKind::Keyword, "Bitwise OR."),
    ("B_XOR", EntryKind::Keyword, "Bitwise exclusive OR."),
    ("B_NOT", EntryKind::Keyword, "Bitwise negation."),
    ("INT", EntryKind::Keyword, "Data type: whole number."),
    ("REAL", EntryKind::Keyword, "Data type: floating-point number."),
    ("BOOL", EntryKind::Keyword, "Data type: TRUE or FALSE."),
    ("CHAR", EntryKind::Keyword, "Data type: one character (0 to 255)."),
    ("STRING", EntryKind::Keyword, "Data type: text of up to 200 characters, `STRING[n]`."),
    ("AXIS", EntryKind::Keyword, "Data type: an axis name of the channel."),
    ("FRAME", EntryKind::Keyword, "Data type: translation, rotation, scale and mirroring."),
    ("TRUE", EntryKind::Keyword, "The boolean value 1."),
    ("FALSE", EntryKind::Keyword, "The boolean value 0."),
    ("AC", EntryKind::Modifier, "Absolute value for this axis in this block only: `X=AC(10)`."),
    ("IC", EntryKind::Modifier, "Incremental value for this axis in this block only: `X=IC(5)`."),
    ("DC", EntryKind::Modifier, "Rotary axis: absolute position approached the shortest way."),
    ("ACP", EntryKind::Modifier, "Modulo rotary axis: absolute position approached in positive direction."),
    ("ACN", EntryKind::Modifier, "Modulo rotary axis: absolute position approached in negative direction."),
    ("DAC", EntryKind::Modifier, "Transverse axis: absolute diameter in this block."),
    ("DIC", EntryKind::Modifier, "Transverse axis: incremental diameter in this block."),
    ("RAC", EntryKind::Modifier, "Transverse axis: absolute radius in this block."),
    ("RIC", EntryKind::Modifier, "Transverse axis: incremental radius in this block."),
    ("SIN", EntryKind::Function, "Sine of an angle in degrees."),
    ("COS", EntryKind::Function, "Cosine of an angle in degrees."),
    ("TAN", EntryKind::Function, "Tangent of an angle in degrees."),
    ("ASIN", EntryKind::Function, "Arc sine, in degrees."),
    ("ACOS", EntryKind::Function, "Arc cosine, in degrees."),
    ("ATAN2", EntryKind::Function, "Angle of the vector (x, y) in degrees: `ATAN2(y, x)`."),
    ("SQRT", EntryKind::Function, "Square root."),
    ("POT", EntryKind::Function, "Square of a value."),
    ("ABS", EntryKind::Function, "Absolute value."),
    ("TRUNC", EntryKind::Function, "Cuts off the decimal places."),
    ("ROUND", EntryKind::Function, "Rounds to a whole number."),
    ("LN", EntryKind::Function, "Natural logarithm."),
    ("EXP", EntryKind::Function, "Exponential function."),
    ("MINVAL", EntryKind::Function, "The smaller of two values."),
    ("MAXVAL", EntryKind::Function, "The larger of two values."),
    ("BOUND", EntryKind::Function, "A value limited to a range."),
    ("CTRANS", EntryKind::Function, "A frame with translations: `CTRANS(X, 10, Y, 5)`."),
    ("CROT", EntryKind::Function, "A frame with rotations."),
    ("STRLEN", EntryKind::Function, "The length of a string."),
    ("ISVAR", EntryKind::Function, "Whether a name is a defined variable."),
    ("ISFILE", EntryKind::Function, "Whether a file exists in the program memory."),
    ("MSG", EntryKind::Instruction, "Shows a message on the operator panel; `MSG()` clears it."),
    ("STOPRE", EntryKind::Instruction, "Stops block preparation until the previous blocks have run."),
    ("SETAL", EntryKind::Instruction, "Raises a cycle alarm."),
    ("WRITE", EntryKind::Instruction, "Appends text to a file."),
    ("TRAORI", EntryKind::Instruction, "Five-axis transformation on; positions afterwards depend on the kinematics."),
    ("TRAFOOF", EntryKind::Instruction, "Transformation off."),
    ("TRANSMIT", EntryKind::Instruction, "Face-end transformation on (turning with milling)."),
    ("TRACYL", EntryKind::Instruction, "Peripheral-surface transformation on."),
    ("$P_GG", EntryKind::SystemVariable, "The active G function of a group, as its number inside the group: `$P_GG[13]`."),
    ("$P_EP", EntryKind::SystemVariable, "The interpreter's current set-point of an axis in workpiece coordinates."),
    ("$AA_IW", EntryKind::SystemVariable, "The current set-point of an axis in workpiece coordinates (main run)."),
    ("$AA_IM", EntryKind::SystemVariable, "The current set-point of an axis in machine coordinates (main run)."),
    ("$P_UIFR", EntryKind::SystemVariable, "The stored settable frames (G54 ...); active when selected next."),
    ("$P_PFRAME", EntryKind::SystemVariable, "The programmable frame."),
    ("$P_ACTFRAME", EntryKind::SystemVariable, "The whole active frame."),
    ("$P_IFRAME", EntryKind::SystemVariable, "The active settable frame."),
    ("$P_TOOLR", EntryKind::SystemVariable, "The radius of the active tool."),
    ("$TC_DP", EntryKind::SystemVariable, "Tool edge data: `$TC_DP1[t,d]` ... (type, lengths, radius)."),
    ("$PI", EntryKind::SystemVariable, "The number pi."),
    ("$MC_GCODE_RESET_VALUES", EntryKind::SystemVariable, "Machine data 20150: the G functions active after reset."),
];

/// The documentation of a word (any case): a G function, keyword, function, modifier, system variable
/// or standard cycle. `None` for words the table does not cover.
pub fn describe(word: &str) -> Option<LanguageDoc> {
    let upper = word.to_ascii_uppercase();
    if let Some((name, kind, summary)) = WORDS.iter().find(|(name, _, _)| *name == upper) {
        return Some(LanguageDoc {
            name: name.to_string(),
            kind: *kind,
            summary: summary.to_string(),
            detail: String::new(),
        });
    }
    if let Some(cycle) = CYCLES.iter().find(|cycle| cycle.name == upper) {
        return Some(LanguageDoc {
            name: cycle.name.to_string(),
            kind: EntryKind::Cycle,
            summary: cycle.summary.to_string(),
            detail: format!("{}({})", cycle.name, cycle.parameters.join(", ")),
        });
    }
    let code = match upper
        .strip_prefix('G')
        .and_then(|digits| digits.parse::<u32>().ok())
    {
        Some(number) => GCode::from_number(number),
        None => GCode::from_name(&upper),
    }?;
    Some(gcode_doc(code))
}

fn gcode_doc(code: GCode) -> LanguageDoc {
    let name = code.name().into_owned();
    let group = code.group();
    let modal = code.is_modal();
    let summary = match gcode_summary(&name) {
        Some(summary) => summary.to_string(),
        None if group == 8 => {
            "Settable work offset from the offset table of the machine.".to_string()
        }
        None => format!("A G function of group {group} ({}).", group_name(group)),
    };
    LanguageDoc {
        name,
        kind: EntryKind::GCode { group, modal },
        summary,
        detail: format!(
            "group {group} ({}), {}",
            group_name(group),
            if modal { "modal" } else { "non-modal" }
        ),
    }
}

/// Every entry of the table, for completion: all G functions (G505 ... G599 as one G505 entry),
/// keywords, functions, modifiers, system variables and cycles.
pub fn all_entries() -> Vec<LanguageDoc> {
    let mut entries: Vec<LanguageDoc> = TABLE
        .iter()
        .filter_map(|info| describe(info.name))
        .collect();
    entries.extend(GCode::from_number(505).map(gcode_doc));
    entries.extend(WORDS.iter().filter_map(|(name, _, _)| describe(name)));
    entries.extend(CYCLES.iter().filter_map(|cycle| describe(cycle.name)));
    entries
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn g_functions_keywords_and_cycles_are_described() {
        let g1 = describe("g01").unwrap();
        assert_eq!(g1.name, "G1");
        assert_eq!(
            g1.kind,
            EntryKind::GCode {
                group: 1,
                modal: true
            }
        );
        assert_eq!(g1.detail, "group 1 (motion), modal");
        assert!(describe("DIAMON").unwrap().summary.contains("diameter"));
        assert_eq!(
            describe("G598").unwrap().detail,
            "group 8 (settable work offset), modal"
        );
        assert_eq!(describe("gotob").unwrap().kind, EntryKind::Keyword);
        assert_eq!(
            describe("CYCLE81").unwrap().detail,
            "CYCLE81(RTP, RFP, SDIS, DP, DPR)"
        );
        assert!(describe("G12").is_none() && describe("NOSUCH").is_none());
        // Every G function of the parser's table has an entry.
        assert!(all_entries().len() > TABLE.len());
    }
}
