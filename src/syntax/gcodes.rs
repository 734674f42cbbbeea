//! The G functions of Siemens mode with their groups (reference §2.2), by number and by name.
//!
//! Groups 1, 2 and 3 are "syntax-defining": they decide what the axis words of a block mean, so a
//! block may hold only one of them.

/// A known G function: an entry of [`TABLE`], or one of the settable work offsets G505 to G599.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum GCode {
    Known(u16),
    /// G505 ... G599, stored as the G number.
    WorkOffset(u16),
}

/// One row of the G-function table.
#[derive(Debug, Clone, Copy)]
pub struct GCodeInfo {
    pub name: &'static str,
    /// The G number when the function is written `G<n>`.
    pub number: Option<u16>,
    pub group: u8,
    /// The internal number inside its group (used by `$P_GG` and MD20150); 0 where unknown.
    pub index_in_group: u8,
    pub modal: bool,
}

const fn g(number: u16, name: &'static str, group: u8, index: u8, modal: bool) -> GCodeInfo {
    GCodeInfo {
        name,
        number: Some(number),
        group,
        index_in_group: index,
        modal,
    }
}

const fn n(name: &'static str, group: u8, index: u8, modal: bool) -> GCodeInfo {
    GCodeInfo {
        name,
        number: None,
        group,
        index_in_group: index,
        modal,
    }
}

/// Every G function the parser recognises. G505 ... G599 are handled by [`GCode::WorkOffset`].
pub static TABLE: &[GCodeInfo] = &[
    // Group 1: motion.
    g(0, "G0", 1, 1, true),
    g(1, "G1", 1, 2, true),
    g(2, "G2", 1, 3, true),
    g(3, "G3", 1, 4, true),
    n("CIP", 1, 5, true),
    n("ASPLINE", 1, 6, true),
    n("BSPLINE", 1, 7, true),
    n("CSPLINE", 1, 8, true),
    n("POLY", 1, 9, true),
    g(33, "G33", 1, 10, true),
    g(331, "G331", 1, 11, true),
    g(332, "G332", 1, 12, true),
    n("OEMIPO1", 1, 13, true),
    n("OEMIPO2", 1, 14, true),
    n("CT", 1, 15, true),
    g(34, "G34", 1, 16, true),
    g(35, "G35", 1, 17, true),
    n("INVCW", 1, 18, true),
    n("INVCCW", 1, 19, true),
    g(335, "G335", 1, 20, true),
    g(336, "G336", 1, 21, true),
    // Group 2: non-modal motions.
    g(4, "G4", 2, 1, false),
    g(63, "G63", 2, 2, false),
    g(74, "G74", 2, 3, false),
    g(75, "G75", 2, 4, false),
    n("REPOSL", 2, 5, false),
    n("REPOSQ", 2, 6, false),
    n("REPOSH", 2, 7, false),
    n("REPOSA", 2, 8, false),
    n("REPOSQA", 2, 9, false),
    n("REPOSHA", 2, 10, false),
    g(147, "G147", 2, 11, false),
    g(247, "G247", 2, 12, false),
    g(347, "G347", 2, 13, false),
    g(148, "G148", 2, 14, false),
    g(248, "G248", 2, 15, false),
    g(348, "G348", 2, 16, false),
    g(5, "G5", 2, 17, false),
    g(7, "G7", 2, 18, false),
    // Group 3: write memory, frames, pole.
    n("TRANS", 3, 1, false),
    n("ROT", 3, 2, false),
    n("SCALE", 3, 3, false),
    n("MIRROR", 3, 4, false),
    n("ATRANS", 3, 5, false),
    n("AROT", 3, 6, false),
    n("ASCALE", 3, 7, false),
    n("AMIRROR", 3, 8, false),
    g(25, "G25", 3, 9, false),
    g(26, "G26", 3, 11, false),
    g(110, "G110", 3, 12, false),
    g(111, "G111", 3, 13, false),
    g(112, "G112", 3, 14, false),
    g(58, "G58", 3, 15, false),
    g(59, "G59", 3, 16, false),
    n("ROTS", 3, 17, false),
    n("AROTS", 3, 18, false),
    // Group 4: FIFO.
    n("STARTFIFO", 4, 1, true),
    n("STOPFIFO", 4, 2, true),
    n("FIFOCTRL", 4, 3, true),
    // Group 6: plane.
    g(17, "G17", 6, 1, true),
    g(18, "G18", 6, 2, true),
    g(19, "G19", 6, 3, true),
    // Group 7: tool radius compensation.
    g(40, "G40", 7, 1, true),
    g(41, "G41", 7, 2, true),
    g(42, "G42", 7, 3, true),
    // Group 8: settable work offset (G505 ... G599 are WorkOffset).
    g(500, "G500", 8, 1, true),
    g(54, "G54", 8, 2, true),
    g(55, "G55", 8, 3, true),
    g(56, "G56", 8, 4, true),
    g(57, "G57", 8, 5, true),
    // Group 9: frame suppression.
    g(53, "G53", 9, 1, false),
    n("SUPA", 9, 2, false),
    g(153, "G153", 9, 3, false),
    // Group 10: exact stop / continuous path.
    g(60, "G60", 10, 1, true),
    g(64, "G64", 10, 2, true),
    g(641, "G641", 10, 3, true),
    g(642, "G642", 10, 4, true),
    g(643, "G643", 10, 5, true),
    g(644, "G644", 10, 6, true),
    g(645, "G645", 10, 7, true),
    // Group 11: exact stop, non-modal.
    g(9, "G9", 11, 1, false),
    // Group 12: exact-stop criterion.
    g(601, "G601", 12, 1, true),
    g(602, "G602", 12, 2, true),
    g(603, "G603", 12, 3, true),
    // Group 13: inch/metric.
    g(70, "G70", 13, 1, true),
    g(71, "G71", 13, 2, true),
    g(700, "G700", 13, 3, true),
    g(710, "G710", 13, 4, true),
    // Group 14: absolute/incremental.
    g(90, "G90", 14, 1, true),
    g(91, "G91", 14, 2, true),
    // Group 15: feed type.
    g(93, "G93", 15, 1, true),
    g(94, "G94", 15, 2, true),
    g(95, "G95", 15, 3, true),
    g(96, "G96", 15, 4, true),
    g(97, "G97", 15, 5, true),
    g(931, "G931", 15, 6, true),
    g(961, "G961", 15, 7, true),
    g(971, "G971", 15, 8, true),
    g(942, "G942", 15, 9, true),
    g(952, "G952", 15, 10, true),
    g(962, "G962", 15, 11, true),
    g(972, "G972", 15, 12, true),
    g(973, "G973", 15, 13, true),
    // Group 16: feed override on curvature.
    n("CFC", 16, 1, true),
    n("CFTCP", 16, 2, true),
    n("CFIN", 16, 3, true),
    // Group 17: approach and retract behaviour with tool offset.
    n("NORM", 17, 1, true),
    n("KONT", 17, 2, true),
    n("KONTT", 17, 3, true),
    n("KONTC", 17, 4, true),
    // Group 18: corner behaviour with tool offset.
    g(450, "G450", 18, 1, true),
    g(451, "G451", 18, 2, true),
    // Groups 19 and 20: spline start and end.
    n("BNAT", 19, 1, true),
    n("BTAN", 19, 2, true),
    n("BAUTO", 19, 3, true),
    n("ENAT", 20, 1, true),
    n("ETAN", 20, 2, true),
    n("EAUTO", 20, 3, true),
    // Group 21: acceleration profile.
    n("BRISK", 21, 1, true),
    n("SOFT", 21, 2, true),
    n("DRIVE", 21, 3, true),
    // Group 22: tool offset type.
    n("CUT2D", 22, 1, true),
    n("CUT2DF", 22, 2, true),
    n("CUT3DC", 22, 3, true),
    n("CUT3DF", 22, 4, true),
    n("CUT3DFS", 22, 5, true),
    n("CUT3DFF", 22, 6, true),
    n("CUT3DCC", 22, 7, true),
    n("CUT3DCCD", 22, 8, true),
    n("CUT2DD", 22, 9, true),
    n("CUT2DFD", 22, 10, true),
    n("CUT3DCD", 22, 11, true),
    // Group 23: collision monitoring.
    n("CDOF", 23, 1, true),
    n("CDON", 23, 2, true),
    n("CDOF2", 23, 3, true),
    // Group 24: feedforward control.
    n("FFWOF", 24, 1, true),
    n("FFWON", 24, 2, true),
    // Group 25: tool orientation reference.
    n("ORIWKS", 25, 1, true),
    n("ORIMKS", 25, 2, true),
    // Group 26: repositioning point.
    n("RMI", 26, 1, true),
    n("RMB", 26, 2, true),
    n("RME", 26, 3, true),
    n("RMN", 26, 4, true),
    // Group 27: orientation change at corners.
    n("ORIC", 27, 1, true),
    n("ORID", 27, 2, true),
    // Group 28: working-area limitation.
    n("WALIMON", 28, 1, true),
    n("WALIMOF", 28, 2, true),
    // Group 29: radius/diameter programming.
    n("DIAMOF", 29, 1, true),
    n("DIAMON", 29, 2, true),
    n("DIAM90", 29, 3, true),
    n("DIAMCYCOF", 29, 4, true),
    // Group 30: NC block compression.
    n("COMPOF", 30, 1, true),
    n("COMPON", 30, 2, true),
    n("COMPCURV", 30, 3, true),
    n("COMPCAD", 30, 4, true),
    n("COMPSURF", 30, 5, true),
    // Groups 31 and 32: OEM G functions.
    g(810, "G810", 31, 1, true),
    g(811, "G811", 31, 2, true),
    g(812, "G812", 31, 3, true),
    g(813, "G813", 31, 4, true),
    g(814, "G814", 31, 5, true),
    g(815, "G815", 31, 6, true),
    g(816, "G816", 31, 7, true),
    g(817, "G817", 31, 8, true),
    g(818, "G818", 31, 9, true),
    g(819, "G819", 31, 10, true),
    g(820, "G820", 32, 1, true),
    g(821, "G821", 32, 2, true),
    g(822, "G822", 32, 3, true),
    g(823, "G823", 32, 4, true),
    g(824, "G824", 32, 5, true),
    g(825, "G825", 32, 6, true),
    g(826, "G826", 32, 7, true),
    g(827, "G827", 32, 8, true),
    g(828, "G828", 32, 9, true),
    g(829, "G829", 32, 10, true),
    // Group 33: fine tool offset.
    n("FTOCOF", 33, 1, true),
    n("FTOCON", 33, 2, true),
    // Group 34: tool orientation smoothing.
    n("OSOF", 34, 1, true),
    n("OSC", 34, 2, true),
    n("OSS", 34, 3, true),
    n("OSSE", 34, 4, true),
    n("OST", 34, 5, true),
    n("OSD", 34, 6, true),
    // Groups 35 to 37: punching and nibbling, feed interpolation.
    n("SPOF", 35, 1, true),
    n("SON", 35, 2, true),
    n("PON", 35, 3, true),
    n("SONS", 35, 4, true),
    n("PONS", 35, 5, true),
    n("PDELAYON", 36, 1, true),
    n("PDELAYOF", 36, 2, true),
    n("FNORM", 37, 1, true),
    n("FLIN", 37, 2, true),
    n("FCUB", 37, 3, true),
    n("FPO", 37, 4, true),
    // Group 39: programmable contour accuracy.
    n("CPRECOF", 39, 1, true),
    n("CPRECON", 39, 2, true),
    // Group 40: constant cutting rate.
    n("CUTCONOF", 40, 1, true),
    n("CUTCONON", 40, 2, true),
    // Group 41: thread interruption.
    n("LFOF", 41, 1, true),
    n("LFON", 41, 2, true),
    // Group 42: tool carrier.
    n("TCOABS", 42, 1, true),
    n("TCOFR", 42, 2, true),
    n("TCOFRZ", 42, 3, true),
    n("TCOFRY", 42, 4, true),
    n("TCOFRX", 42, 5, true),
    // Groups 43 and 44: soft approach and retract.
    g(140, "G140", 43, 1, true),
    g(141, "G141", 43, 2, true),
    g(142, "G142", 43, 3, true),
    g(143, "G143", 43, 4, true),
    g(340, "G340", 44, 1, true),
    g(341, "G341", 44, 2, true),
    // Group 45: path reference for FGROUP axes.
    n("SPATH", 45, 1, true),
    n("UPATH", 45, 2, true),
    // Group 46: fast retraction plane.
    n("LFTXT", 46, 1, true),
    n("LFWP", 46, 2, true),
    n("LFPOS", 46, 3, true),
    // Group 47: external NC languages.
    g(290, "G290", 47, 1, true),
    g(291, "G291", 47, 2, true),
    // Group 48: approach and retract with tool radius compensation.
    g(460, "G460", 48, 1, true),
    g(461, "G461", 48, 2, true),
    g(462, "G462", 48, 3, true),
    // Group 49: point-to-point motion.
    n("CP", 49, 1, true),
    n("PTP", 49, 2, true),
    n("PTPG0", 49, 3, true),
    n("PTPWOC", 49, 4, true),
    // Group 50: orientation definition.
    n("ORIEULER", 50, 1, true),
    n("ORIRPY", 50, 2, true),
    n("ORIVIRT1", 50, 3, true),
    n("ORIVIRT2", 50, 4, true),
    n("ORIRPY2", 50, 5, true),
    // Group 51: orientation interpolation.
    n("ORIVECT", 51, 1, true),
    n("ORIAXES", 51, 2, true),
    n("ORIPATH", 51, 3, true),
    n("ORIPLANE", 51, 4, true),
    n("ORICONCW", 51, 5, true),
    n("ORICONCCW", 51, 6, true),
    n("ORICONIO", 51, 7, true),
    n("ORICONTO", 51, 8, true),
    n("ORICURVE", 51, 9, true),
    n("ORIPATHS", 51, 10, true),
    // Groups 52 and 53: frames aligned with the table or the tool.
    n("PAROTOF", 52, 1, true),
    n("PAROT", 52, 2, true),
    n("TOROTOF", 53, 1, true),
    n("TOROT", 53, 2, true),
    n("TOROTZ", 53, 3, true),
    n("TOROTY", 53, 4, true),
    n("TOROTX", 53, 5, true),
    n("TOFRAME", 53, 6, true),
    n("TOFRAMEZ", 53, 7, true),
    n("TOFRAMEY", 53, 8, true),
    n("TOFRAMEX", 53, 9, true),
    // Group 54: vector rotation in orientation interpolation.
    n("ORIROTA", 54, 1, true),
    n("ORIROTR", 54, 2, true),
    n("ORIROTT", 54, 3, true),
    n("ORIROTC", 54, 4, true),
    // Group 55: rapid traverse with or without linear interpolation.
    n("RTLION", 55, 1, true),
    n("RTLIOF", 55, 2, true),
    // Group 56: tool wear.
    n("TOWSTD", 56, 1, true),
    n("TOWMCS", 56, 2, true),
    n("TOWWCS", 56, 3, true),
    n("TOWBCS", 56, 4, true),
    n("TOWTCS", 56, 5, true),
    n("TOWKCS", 56, 6, true),
    // Group 57: corner deceleration.
    n("FENDNORM", 57, 1, true),
    g(62, "G62", 57, 2, true),
    g(621, "G621", 57, 3, true),
    // Group 59: dynamic response for path interpolation.
    n("DYNNORM", 59, 1, true),
    n("DYNPOS", 59, 2, true),
    n("DYNROUGH", 59, 3, true),
    n("DYNSEMIFIN", 59, 4, true),
    n("DYNFINISH", 59, 5, true),
    n("DYNPREC", 59, 6, true),
    // Group 61: tool orientation smoothing.
    n("ORISOF", 61, 1, true),
    n("ORISON", 61, 2, true),
];

/// The functions the analysis asks about in every block, found in [`TABLE`] when the program is
/// compiled: asking whether G91 is active then compares two numbers instead of two names. Table names
/// are unique (tested), so comparing these codes says the same as comparing the names.
pub mod known {
    use super::GCode;

    pub const G0: GCode = GCode::in_table("G0");
    pub const G1: GCode = GCode::in_table("G1");
    pub const G2: GCode = GCode::in_table("G2");
    pub const G3: GCode = GCode::in_table("G3");
    pub const CIP: GCode = GCode::in_table("CIP");
    pub const CT: GCode = GCode::in_table("CT");
    pub const G17: GCode = GCode::in_table("G17");
    pub const G18: GCode = GCode::in_table("G18");
    pub const G19: GCode = GCode::in_table("G19");
    pub const G41: GCode = GCode::in_table("G41");
    pub const G42: GCode = GCode::in_table("G42");
    pub const G70: GCode = GCode::in_table("G70");
    pub const G700: GCode = GCode::in_table("G700");
    pub const G710: GCode = GCode::in_table("G710");
    pub const G91: GCode = GCode::in_table("G91");
    pub const DIAMON: GCode = GCode::in_table("DIAMON");
    pub const DIAM90: GCode = GCode::in_table("DIAM90");
}

/// Index of [`TABLE`] by G number and by name, built once.
struct LookupTables {
    /// `u16::MAX` where no G function has that number.
    by_number: Vec<u16>,
    by_name: std::collections::HashMap<&'static str, u16>,
}

fn lookup_tables() -> &'static LookupTables {
    static TABLES: std::sync::OnceLock<LookupTables> = std::sync::OnceLock::new();
    TABLES.get_or_init(|| {
        let mut by_number = vec![u16::MAX; 1000];
        let mut by_name = std::collections::HashMap::new();
        for (index, info) in TABLE.iter().enumerate() {
            match info.number {
                Some(number) => by_number[number as usize] = index as u16,
                None => {
                    by_name.insert(info.name, index as u16);
                }
            }
        }
        LookupTables { by_number, by_name }
    })
}

/// Groups whose functions decide the meaning of the axis words of their block.
pub fn is_syntax_defining_group(group: u8) -> bool {
    matches!(group, 1..=3)
}

impl GCode {
    /// The entry of [`TABLE`] with exactly this canonical name, found at compile time; a name that
    /// is not in the table stops the compilation.
    const fn in_table(name: &str) -> GCode {
        let name = name.as_bytes();
        let mut index = 0;
        while index < TABLE.len() {
            let candidate = TABLE[index].name.as_bytes();
            if candidate.len() == name.len() {
                let mut position = 0;
                while position < name.len() && candidate[position] == name[position] {
                    position += 1;
                }
                if position == name.len() {
                    return GCode::Known(index as u16);
                }
            }
            index += 1;
        }
        panic!("a G function the analysis names is missing from the table");
    }

    /// Looks up `G<number>`; leading zeros do not matter (`G01` is `G1`).
    pub fn from_number(number: u32) -> Option<GCode> {
        if (505..=599).contains(&number) {
            return Some(GCode::WorkOffset(number as u16));
        }
        let index = *lookup_tables().by_number.get(number as usize)?;
        (index != u16::MAX).then_some(GCode::Known(index))
    }

    /// Looks up a G function written by name (`DIAMON`, `TRANS`), case-insensitively. Names of
    /// numbered functions (`G90`) are not found here: those are written with the letter G.
    pub fn from_name(name: &str) -> Option<GCode> {
        let mut buffer = [0u8; 32];
        let upper = crate::syntax::case::uppercase(name, &mut buffer)?;
        lookup_tables()
            .by_name
            .get(upper)
            .map(|index| GCode::Known(*index))
    }

    pub fn group(self) -> u8 {
        match self {
            GCode::Known(index) => TABLE[index as usize].group,
            GCode::WorkOffset(_) => 8,
        }
    }

    pub fn is_modal(self) -> bool {
        match self {
            GCode::Known(index) => TABLE[index as usize].modal,
            GCode::WorkOffset(_) => true,
        }
    }

    /// The canonical spelling, e.g. `G1`, `DIAMON`, `G505`.
    pub fn name(self) -> std::borrow::Cow<'static, str> {
        match self {
            GCode::Known(index) => std::borrow::Cow::Borrowed(TABLE[index as usize].name),
            GCode::WorkOffset(number) => std::borrow::Cow::Owned(format!("G{number}")),
        }
    }

    /// The internal number inside the group, as `$P_GG` returns it.
    pub fn index_in_group(self) -> u8 {
        match self {
            GCode::Known(index) => TABLE[index as usize].index_in_group,
            GCode::WorkOffset(number) => (number - 505 + 6) as u8,
        }
    }

    /// G4, the dwell: group 2, first in its group.
    pub fn is_dwell(self) -> bool {
        self.group() == 2 && self.index_in_group() == 1
    }

    /// Frame and pole instructions (group 3) must stand alone in their block.
    pub fn must_stand_alone(self) -> bool {
        self.group() == 3
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_and_names_resolve() {
        assert_eq!(GCode::from_number(1).unwrap().name(), "G1");
        assert_eq!(GCode::from_number(710).unwrap().group(), 13);
        assert_eq!(GCode::from_number(505), Some(GCode::WorkOffset(505)));
        assert_eq!(GCode::from_number(599).unwrap().group(), 8);
        assert_eq!(GCode::from_number(12), None);
        assert_eq!(GCode::from_number(600), None);
        assert_eq!(GCode::from_name("diamon").unwrap().group(), 29);
        assert_eq!(GCode::from_name("TRANS").unwrap().group(), 3);
        assert_eq!(GCode::from_name("G90"), None);
    }

    #[test]
    fn known_functions_carry_their_names() {
        use known::*;
        for (code, name) in [
            (G0, "G0"),
            (G1, "G1"),
            (G2, "G2"),
            (G3, "G3"),
            (CIP, "CIP"),
            (CT, "CT"),
            (G17, "G17"),
            (G18, "G18"),
            (G19, "G19"),
            (G41, "G41"),
            (G42, "G42"),
            (G70, "G70"),
            (G700, "G700"),
            (G710, "G710"),
            (G91, "G91"),
            (DIAMON, "DIAMON"),
            (DIAM90, "DIAM90"),
        ] {
            assert_eq!(code.name(), name);
        }
    }

    #[test]
    fn table_names_are_unique() {
        let mut names = std::collections::HashSet::new();
        for info in TABLE {
            assert!(names.insert(info.name), "duplicate {}", info.name);
        }
    }
}
