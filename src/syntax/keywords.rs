//! Classification of names: keywords, multi-letter addresses, predefined functions and instructions.
//! Names are compared in upper case (the language is case-insensitive, reference §1.1).

use crate::syntax::ast::{JumpKind, NamedAddress, StructureKeyword};

// Kept here under its old name, where the parser looks up keywords; the function lives in a file of
// its own so that `gcodes.rs`, which this file's types reach, does not import this file back.
pub use crate::syntax::case::uppercase;

/// Keywords that start a statement with its own grammar.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StatementKeyword {
    Structure(StructureKeyword),
    Jump(JumpKind),
    Def,
    Define,
    Proc,
    Extern,
    Return,
    Call,
    PCall,
    ExtCall,
    MCall,
    /// WHEN, WHENEVER, FROM, EVERY: the condition of a synchronized action.
    SyncCondition,
    /// DO: the actions of a synchronized action follow.
    Do,
    /// REPEATB: section repeat backwards.
    RepeatBackward,
}

pub fn statement_keyword(upper: &str) -> Option<StatementKeyword> {
    use StatementKeyword as K;
    use StructureKeyword as S;
    Some(match upper {
        "IF" => K::Structure(S::If),
        "ELSE" => K::Structure(S::Else),
        "ENDIF" => K::Structure(S::EndIf),
        "WHILE" => K::Structure(S::While),
        "ENDWHILE" => K::Structure(S::EndWhile),
        "FOR" => K::Structure(S::For),
        "ENDFOR" => K::Structure(S::EndFor),
        "REPEAT" => K::Structure(S::Repeat),
        "UNTIL" => K::Structure(S::Until),
        "LOOP" => K::Structure(S::Loop),
        "ENDLOOP" => K::Structure(S::EndLoop),
        "CASE" => K::Structure(S::Case),
        "GOTOF" => K::Jump(JumpKind::Gotof),
        "GOTOB" => K::Jump(JumpKind::Gotob),
        "GOTO" => K::Jump(JumpKind::Goto),
        "GOTOC" => K::Jump(JumpKind::Gotoc),
        "GOTOS" => K::Jump(JumpKind::Gotos),
        "DEF" | "REDEF" => K::Def,
        "DEFINE" => K::Define,
        "PROC" => K::Proc,
        "EXTERN" => K::Extern,
        "RET" => K::Return,
        "CALL" => K::Call,
        "PCALL" => K::PCall,
        "EXTCALL" => K::ExtCall,
        "MCALL" => K::MCall,
        "WHEN" | "WHENEVER" | "FROM" | "EVERY" => K::SyncCondition,
        "DO" => K::Do,
        "REPEATB" => K::RepeatBackward,
        _ => return None,
    })
}

/// Multi-letter addresses that take a value with `=` (`CR=5`), and how they treat modifiers.
pub fn named_address(upper: &str) -> Option<NamedAddress> {
    Some(match upper {
        "CR" => NamedAddress::CircleRadius,
        "AR" => NamedAddress::OpeningAngle,
        "AP" => NamedAddress::PolarAngle,
        "RP" => NamedAddress::PolarRadius,
        "TURN" => NamedAddress::Turns,
        "RPL" => NamedAddress::RotationInPlane,
        "POS" | "POSA" | "SPOS" | "SPOSA" | "MOV" => NamedAddress::Positioning,
        "AX" => NamedAddress::IndirectAxis,
        "FA" | "FL" | "OVR" | "OVRA" | "OVRRAP" | "LIMS" | "CHF" | "CHR" | "RND" | "RNDM"
        | "ADIS" | "ADISPOS" | "SF" | "DISR" | "DISCL" | "DISRP" | "FAD" | "ACC" | "ACCLIMA"
        | "VELOLIMA" | "JERKLIMA" | "FB" | "FRC" | "FRCM" | "FGREF" | "FMA" | "FPR" | "FPRAON"
        | "FPRAOF" | "FXS" | "FXST" | "FXSW" | "FOC" | "FOCON" | "FOCOF" | "SCC" | "SVC" | "ID"
        | "IDS" | "PM" | "PR" | "STOPFIFO" | "CTOL" | "OTOL" | "ATOL" | "SD" | "PL" | "CPRECT"
        | "SPCON" | "SPCOF" | "SETMS" | "DITS" | "DITE" | "LIFTFAST" | "ALF" | "LFPOS" | "DL"
        | "SA" | "SPI" | "TOFF" | "TOFFL" | "TOFFR" | "ORIS" | "THETA" | "PHI" | "PSI" | "LEAD"
        | "TILT" | "SPN" | "SPP" | "DELAYFSTON" | "DELAYFSTOF" | "GP" | "BLSYNC" | "SCPARA"
        | "MEAS" | "MEAW" | "MEASA" | "MEAWA" | "MEAC" | "WAITP" | "CORROF" => NamedAddress::Other,
        _ => return None,
    })
}

/// Functions that return a value and may stand in expressions (reference §8.2, plus the predefined
/// functions common in real programs). A call of another name in an expression gets a warning.
pub fn is_function(upper: &str) -> bool {
    matches!(
        upper,
        "SIN"
            | "COS"
            | "TAN"
            | "ASIN"
            | "ACOS"
            | "ATAN"
            | "ATAN2"
            | "SQRT"
            | "POT"
            | "LN"
            | "EXP"
            | "ABS"
            | "TRUNC"
            | "ROUND"
            | "ROUNDUP"
            | "BOUND"
            | "MIN"
            | "MAX"
            | "MINVAL"
            | "MAXVAL"
            | "ITOR"
            | "RTOI"
            | "STRLEN"
            | "SPRINT"
            | "SUBSTR"
            | "INDEX"
            | "RINDEX"
            | "MINDEX"
            | "MATCH"
            | "TOUPPER"
            | "TOLOWER"
            | "NUMBER"
            | "ISNUMBER"
            | "AXNAME"
            | "AXSTRING"
            | "AXTOSPI"
            | "SPITOAX"
            | "CTRANS"
            | "CROT"
            | "CROTS"
            | "CSCALE"
            | "CMIRROR"
            | "CFINE"
            | "INVFRAME"
            | "ADDFRAME"
            | "MEAFRAME"
            | "ISVAR"
            | "ISFILE"
            | "ISAXIS"
            | "ISPOINTER"
            | "ISDEF"
            | "GETT"
            | "GETACTT"
            | "GETSELT"
            | "GETACTTD"
            | "GETTENV"
            | "GETDNO"
            | "SETDNO"
            | "CHKDNO"
            | "GETEDGENO"
            | "GETFREELOC"
            | "GETVARTYP"
            | "GETVARAP"
            | "GETVARLIM"
            | "GETVARDFT"
            | "GETVARPHU"
            | "GETSTATE"
            | "NEWT"
            | "DELT"
            | "DELDL"
            | "DELTC"
            | "DELTOOLENV"
            | "GETTCOR"
            | "SETTCOR"
            | "SETTA"
            | "RESETTA"
            | "SETTIA"
            | "SIZEOFARRAY"
            | "CALCDAT"
            | "CALCPOSI"
            | "CALCTRAVAR"
            | "INTERSEC"
            | "MODAXVAL"
            | "POSRANGE"
            | "PROTA"
            | "PROTS"
            | "PROTD"
            | "NAMETOINT"
            | "INTTONAME"
            | "STRINGIS"
            | "STRINGFELD"
            | "CHECKSUM"
            | "CALLPATH"
            | "TRUE"
            | "FALSE"
            | "AXIS"
            | "ACTBLOCNO"
            | "GETSTRDAT"
            | "GETMDACT"
            | "GETT_"
            | "SUMTCOR"
            | "GETNEXT"
            | "TOOLENV"
            | "COUPON"
            | "SPLINEPATH"
            | "FGROUP"
            | "WRITE"
            | "READ"
            | "DELETE"
            | "FILEDATE"
            | "FILETIME"
            | "FILESIZE"
            | "FILESTAT"
            | "FILEINFO"
            | "GETFILEINFO"
            | "CHKFILE"
            | "CRC"
            | "CUTMOD"
            | "NPROT"
            | "NPROTDEF"
            | "LOCK"
            | "UNLOCK"
            | "DISABLE"
            | "ENABLE"
            | "PUTFTOC"
            | "PUTFTOCF"
            | "SYNFCT"
            | "FTOC"
            | "SET"
            | "REP"
            | "ACTFRAME"
            | "VALUEOF"
            | "ISFILEEXIST"
            | "EXECUTE"
            | "EXECSTRING"
    )
}

/// Operators written as words.
pub fn word_operator(upper: &str) -> Option<crate::syntax::ast::BinaryOp> {
    use crate::syntax::ast::BinaryOp;
    Some(match upper {
        "DIV" => BinaryOp::IntegerDivide,
        "MOD" => BinaryOp::Modulo,
        "AND" => BinaryOp::And,
        "OR" => BinaryOp::Or,
        "XOR" => BinaryOp::Xor,
        "B_AND" => BinaryOp::BitAnd,
        "B_OR" => BinaryOp::BitOr,
        "B_XOR" => BinaryOp::BitXor,
        _ => return None,
    })
}

/// The names of the non-modal position modifiers, recognised after `=`.
pub fn is_modifier_name(upper: &str) -> bool {
    matches!(
        upper,
        "AC" | "IC"
            | "DC"
            | "ACP"
            | "ACN"
            | "DAC"
            | "DIC"
            | "RAC"
            | "RIC"
            | "CAC"
            | "CIC"
            | "CDC"
            | "CACP"
            | "CACN"
    )
}

/// Instructions without a G group that do not call a subprogram: they never move axes by themselves
/// through a program the analyser cannot see. `TRAORI` and friends do change kinematics; the analysis
/// layer treats them specially.
pub fn is_instruction(upper: &str) -> bool {
    is_function(upper)
        || matches!(
            upper,
            "STOPRE"
                | "MSG"
                | "SETAL"
                | "RESETMON"
                | "CANCEL"
                | "TRAORI"
                | "TRAFOOF"
                | "TRANSMIT"
                | "TRACYL"
                | "TRAANG"
                | "TRACON"
                | "TCARR"
                | "WAITM"
                | "WAITMC"
                | "WAITE"
                | "WAITS"
                | "GET"
                | "GETD"
                | "RELEASE"
                | "SAVE"
                | "SBLOF"
                | "SBLON"
                | "DISPLOF"
                | "DISPLON"
                | "ACTBLOCNO"
                | "STOPREOF"
                | "M6"
                | "SPOSA"
                | "SPOS"
                | "SETPIECE"
                | "PRESETON"
                | "PRESETONS"
                | "CORROF"
                | "DRFOF"
                | "FGROUP"
                | "FCTDEF"
                | "CLEARM"
                | "SETM"
                | "INIT"
                | "START"
                | "STARTA"
                | "NEWCONF"
                | "SUPD"
                | "DRIVEON"
                | "DRIVEOF"
                | "CPROT"
                | "CPROTDEF"
                | "LEADON"
                | "LEADOF"
                | "TRAILON"
                | "TRAILOF"
                | "EGON"
                | "EGONSYN"
                | "EGOFS"
                | "EGOFC"
                | "EGDEF"
                | "COUPDEF"
                | "COUPOF"
                | "COUPOFS"
                | "COUPDEL"
                | "COUPRES"
                | "COUPON"
                | "COUPONC"
                | "MASLON"
                | "MASLOF"
                | "MASLDEF"
                | "MASLDEL"
                | "MASLOFS"
                | "CTABDEF"
                | "CTABEND"
                | "CTABDEL"
                | "CTABLOCK"
                | "CTABUNLOCK"
                | "OSCILL"
                | "OSP1"
                | "OSP2"
                | "OST1"
                | "OST2"
                | "OSCTRL"
                | "OSNSC"
                | "OSE"
                | "OSB"
                | "FA"
                | "WALIMON"
                | "CHANDATA"
                | "TOOLGNUM"
                | "MCALL"
                | "EXECTAB"
                | "EXECSTRING"
                | "ROTS"
                | "STOPFIFO"
                | "STARTFIFO"
                | "SPCON"
                | "SPCOF"
                | "SETMS"
                | "LIFTFAST"
                | "POLF"
                | "POLFMASK"
                | "POLFMLIN"
                | "PTP"
                | "FPRAON"
                | "FPRAOF"
                | "FOCON"
                | "FOCOF"
                | "ALF"
                | "ORIRESET"
                | "PAROT"
                | "TOROT"
                | "DIAMCHAN"
                | "DIAMONA"
                | "DIAM90A"
                | "DIAMOFA"
                | "DIACYCOFA"
                | "DIAMCHANA"
                | "SOFTA"
                | "BRISKA"
                | "DRIVEA"
                | "JERKA"
                | "FIFOCTRL"
                | "SUPA"
                | "G_MSG"
                | "WRTPR"
                | "STOPRE_"
                | "RDISABLE"
                | "ENAT"
                | "PRIO"
                | "SETINT"
                | "ENABLE"
                | "DISABLE"
                | "CLRINT"
                | "PROTA"
                | "PROTS"
                | "MMC"
                | "RET"
                | "M17"
                | "SPATH"
                | "TANGON"
                | "TANGOF"
                | "TANG"
                | "TLIFT"
                | "TANGDEL"
                | "AA_OFF"
                | "CYCLE_LOCK"
                | "RELEASE_"
                | "DEFAULT"
                | "BLOCKSEARCH"
                | "TMON"
                | "TMOF"
                | "TCI"
                | "TCA"
                | "PUNCHACC"
                | "STOPREOF_"
        )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keywords_are_classified() {
        assert_eq!(
            statement_keyword("ENDIF"),
            Some(StatementKeyword::Structure(StructureKeyword::EndIf))
        );
        assert_eq!(named_address("CR"), Some(NamedAddress::CircleRadius));
        assert!(is_function("ATAN2"));
        assert!(!is_function("AC"));
        assert!(is_modifier_name("ACP"));
        assert!(is_instruction("STOPRE"));
    }
}
