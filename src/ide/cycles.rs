//! The standard cycles of reference §8.7 with their parameters in order, for signature help,
//! completion snippets and the check that a call is not of an unknown program. Newer control
//! versions append optional parameters; left-out trailing or empty parameters take defaults.

/// A standard cycle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cycle {
    pub name: &'static str,
    /// What the cycle does, in one line.
    pub summary: &'static str,
    pub parameters: &'static [&'static str],
}

const DRILL_BASE: [&str; 5] = ["RTP", "RFP", "SDIS", "DP", "DPR"];

macro_rules! params {
    ($($name:literal),* $(,)?) => { &[$($name),*] };
}

/// The standard cycles with known parameter lists.
pub static CYCLES: &[Cycle] = &[
    Cycle { name: "CYCLE81", summary: "Drilling, centring: feed to depth, retract at rapid.", parameters: &DRILL_BASE },
    Cycle { name: "CYCLE82", summary: "Drilling with a dwell at the bottom.", parameters: params!["RTP", "RFP", "SDIS", "DP", "DPR", "DTB"] },
    Cycle {
        name: "CYCLE83",
        summary: "Deep-hole drilling with chip breaking or swarf removal.",
        parameters: params!["RTP", "RFP", "SDIS", "DP", "DPR", "FDEP", "FDPR", "DAM", "DTB", "DTS", "FRF", "VARI", "_AXN", "_MDEP", "_VRT", "_DTD", "_DIS1"],
    },
    Cycle {
        name: "CYCLE84",
        summary: "Rigid tapping with the spindle in position control.",
        parameters: params!["RTP", "RFP", "SDIS", "DP", "DPR", "DTB", "SDAC", "MPIT", "PIT", "POSS", "SST", "SST1"],
    },
    Cycle {
        name: "CYCLE840",
        summary: "Tapping with a compensating chuck.",
        parameters: params!["RTP", "RFP", "SDIS", "DP", "DPR", "DTB", "SDR", "SDAC", "ENC", "MPIT", "PIT", "AXN"],
    },
    Cycle { name: "CYCLE85", summary: "Reaming: feed in and feed out.", parameters: params!["RTP", "RFP", "SDIS", "DP", "DPR", "DTB", "FFR", "RFF"] },
    Cycle {
        name: "CYCLE86",
        summary: "Boring with an oriented spindle stop and lift-off before the retraction.",
        parameters: params!["RTP", "RFP", "SDIS", "DP", "DPR", "DTB", "SDIR", "RPA", "RPO", "RPAP", "POSS"],
    },
    Cycle { name: "CYCLE87", summary: "Boring with a spindle stop at the bottom.", parameters: params!["RTP", "RFP", "SDIS", "DP", "DPR", "SDIR"] },
    Cycle { name: "CYCLE88", summary: "Boring with a dwell and a spindle stop at the bottom.", parameters: params!["RTP", "RFP", "SDIS", "DP", "DPR", "DTB", "SDIR"] },
    Cycle { name: "CYCLE89", summary: "Boring with a dwell at the bottom, feed out.", parameters: params!["RTP", "RFP", "SDIS", "DP", "DPR", "DTB"] },
    Cycle { name: "HOLES1", summary: "A row of holes for the modal drilling cycle.", parameters: params!["SPCA", "SPCO", "STA1", "FDIS", "DBH", "NUM"] },
    Cycle { name: "HOLES2", summary: "A circle of holes for the modal drilling cycle.", parameters: params!["CPA", "CPO", "RAD", "STA1", "INDA", "NUM"] },
    Cycle { name: "CYCLE801", summary: "A grid of holes for the modal drilling cycle.", parameters: params!["_SPCA", "_SPCO", "_STA", "_DIS1", "_DIS2", "_NUM1", "_NUM2"] },
    Cycle {
        name: "CYCLE800",
        summary: "Swivelling the working plane (tool carrier); positions are unknown afterwards. CYCLE800() resets.",
        parameters: params!["_FR", "_TC", "_ST", "_MODE", "_X0", "_Y0", "_Z0", "_A", "_B", "_C", "_X1", "_Y1", "_Z1", "_DIR", "_FR_I", "_DMODE"],
    },
    Cycle { name: "CYCLE832", summary: "High-speed settings: contour tolerance and machining type. CYCLE832() switches off.", parameters: params!["_TOL", "_TOLM", "_OTOL"] },
];

/// The meaning of a common cycle parameter, for signature help.
pub fn parameter_meaning(name: &str) -> Option<&'static str> {
    Some(match name {
        "RTP" => "retraction plane (absolute)",
        "RFP" => "reference plane (absolute)",
        "SDIS" => "safety distance (without sign)",
        "DP" => "final drilling depth (absolute)",
        "DPR" => "final drilling depth relative to the reference plane (without sign)",
        "DTB" => "dwell at the final depth in seconds",
        "FDEP" => "first drilling depth (absolute)",
        "FDPR" => "first drilling depth relative to the reference plane",
        "DAM" => "degression (amount by which each infeed shrinks)",
        "DTS" => "dwell at the start point for swarf removal",
        "FRF" => "feed factor for the first drilling depth",
        "VARI" => "machining type (0 chip breaking, 1 swarf removal)",
        "SDAC" => "direction of rotation after the cycle (3, 4 or 5)",
        "MPIT" => "thread lead as thread size (3 for M3 ... 48 for M48)",
        "PIT" => "thread lead as a value",
        "POSS" => "spindle position for the oriented stop, in degrees",
        "SST" => "speed for tapping",
        "SST1" => "speed for retraction",
        "SDIR" => "direction of rotation (3 or 4)",
        "FFR" => "feed into the hole",
        "RFF" => "feed out of the hole",
        _ => return None,
    })
}

/// The standard cycle named `name` (upper case), if the table knows it.
pub fn cycle(name: &str) -> Option<&'static Cycle> {
    CYCLES.iter().find(|cycle| cycle.name == name)
}

/// Whether `name` (upper case) belongs to the control: a standard cycle, a measuring or turning
/// cycle the reference names, or a name with a prefix reserved for Siemens cycles (reference §1.4,
/// §8.7). Such a call is never reported as unknown, since the cycle lives on the control.
pub fn is_control_cycle(name: &str) -> bool {
    cycle(name).is_some()
        || matches!(name, "POCKET3" | "POCKET4" | "SLOT1" | "SLOT2" | "LONGHOLE")
        || [
            "CYCLE", "CUST_", "GROUP_", "_", "S_", "E_", "F_", "CCS_", "CC_",
        ]
        .iter()
        .any(|prefix| name.starts_with(prefix))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cycles_are_found_with_their_parameters() {
        assert_eq!(
            cycle("CYCLE81").unwrap().parameters,
            ["RTP", "RFP", "SDIS", "DP", "DPR"]
        );
        assert_eq!(cycle("CYCLE82").unwrap().parameters.len(), 6);
        assert!(cycle("CYCLE1234").is_none());
        assert!(is_control_cycle("CYCLE1234") && is_control_cycle("CUST_800"));
        assert!(!is_control_cycle("PART2"));
        assert_eq!(
            parameter_meaning("RTP"),
            Some("retraction plane (absolute)")
        );
    }
}
