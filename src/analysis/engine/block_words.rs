//! What the engine collects from the words of one block before applying them: the polar words, the
//! circle words and the non-modal G functions that change what the axis words mean, with small
//! helpers over a block's statements.

use crate::diagnostics::Span;
use crate::syntax::ast::{AddressKind, AddressWord, Statement};
use crate::syntax::gcodes::GCode;

/// The polar words of one block: AP (value, written as `=IC(..)`) and RP (basic unit system).
#[derive(Default)]
pub(super) struct PolarWords {
    pub(super) angle: Option<(Option<f64>, bool)>,
    pub(super) radius: Option<Option<f64>>,
    pub(super) span: Option<Span>,
    /// The span of an AP written without `=IC`/`=AC`.
    pub(super) plain_angle_span: Option<Span>,
}
/// The circle words of one block: I, J, K (value, absolute) in the basic unit system, and CR.
#[derive(Default)]
pub(super) struct CircleWords {
    pub(super) centre: [Option<(f64, bool)>; 3],
    /// A centre word whose value is unknown: the circle cannot be checked.
    pub(super) centre_unknown: bool,
    /// Whether CR was written, and its value when known.
    pub(super) radius_written: bool,
    pub(super) radius: Option<f64>,
    pub(super) opening_angle: bool,
    /// The value of AR, when known.
    pub(super) opening_angle_value: Option<f64>,
    /// I1, J1, K1 of CIP: written, with (value, absolute) when known.
    pub(super) intermediate: [Option<Option<(f64, bool)>>; 3],
    /// TURN: its value when known, and its span.
    pub(super) turns: Option<(Option<f64>, Span)>,
    /// The span of the block's words, for findings about the circle as a whole.
    pub(super) span: Option<Span>,
}
/// The non-modal G functions of one block that change what its axis words mean.
#[derive(Default)]
pub(super) struct BlockFunctions {
    pub(super) frame_or_pole: Option<GCode>,
    pub(super) dwell: bool,
    pub(super) machine_coordinates: bool,
    pub(super) reference_point: bool,
}
/// The span from the first to the last of the statements, `None` when there are none.
pub(super) fn statements_span(statements: &[Statement]) -> Option<Span> {
    statements
        .iter()
        .map(Statement::span)
        .reduce(|whole, span| whole.to(span))
}
pub(super) fn find_word(statements: &[Statement], kind: AddressKind) -> Option<&AddressWord> {
    statements.iter().find_map(|statement| match statement {
        Statement::Address(word) if word.kind == kind => Some(word),
        _ => None,
    })
}
/// Instructions after which machine positions cannot be followed (reference §7.5).
pub(super) fn changes_kinematics(upper: &str) -> bool {
    matches!(
        upper,
        "TRAORI"
            | "TRANSMIT"
            | "TRACYL"
            | "TRAANG"
            | "TRACON"
            | "TCARR"
            | "PAROT"
            | "TOROT"
            | "TOFRAME"
            | "TRAFOOF"
    )
}
