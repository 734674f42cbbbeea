//! Address words (`X10`, `Z=IC(-32)`, `X1=10`, `CR=5`, `POS[A]=DC(10)`): what an address is, its
//! extension, its value and the position modifiers it may take.

use crate::diagnostics::Span;
use crate::syntax::ast::expr::ExprId;

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
    /// Any other value: a node of `Block::exprs`.
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
