//! The machine's axes: a name and how the axis moves, shared by the configuration and its tables.

/// How an axis moves, which decides the position modifiers it accepts and whether values are lengths.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AxisKind {
    /// A linear axis; values are lengths and are converted by G70/G700.
    Linear,
    /// A linear axis used for diameter programming (MD20100 `DIAMETER_AX_DEF`).
    Transverse,
    /// A rotary axis without modulo range; DC is allowed, ACP/ACN are not.
    Rotary,
    /// A rotary axis with modulo 360° range; DC, ACP and ACN are allowed.
    Modulo,
}

impl AxisKind {
    pub fn is_rotary(self) -> bool {
        matches!(self, AxisKind::Rotary | AxisKind::Modulo)
    }

    pub fn as_str(self) -> &'static str {
        match self {
            AxisKind::Linear => "linear",
            AxisKind::Transverse => "transverse",
            AxisKind::Rotary => "rotary",
            AxisKind::Modulo => "modulo",
        }
    }
}

/// One channel axis, by the name the part program uses (upper case).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Axis {
    pub name: String,
    pub kind: AxisKind,
}

impl Axis {
    pub fn new(name: &str, kind: AxisKind) -> Axis {
        Axis {
            name: name.to_string(),
            kind,
        }
    }
}
