//! What a move asks of the corner at its end (reference §14): the corner element, its feed and an open
//! two-block definition by angles, as plain values the corner stage of the simulation reads.

/// The element a block asks for at the corner at its end, in the basic unit system.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CornerElement {
    /// `RND` (or `RNDM`): a tangential arc of this radius.
    Rounding(f64),
    /// `CHR`: a chamfer whose legs along the two elements have this length.
    ChamferLeg(f64),
    /// `CHF`: a chamfer of this length.
    ChamferLength(f64),
}

/// What a move asks of the corner at its end (reference §14.1, §14.5).
#[derive(Debug, Clone, PartialEq)]
pub struct ContourRequest {
    /// The element: `Some(None)` when one is programmed with a value the analysis does not know.
    pub element: Option<Option<CornerElement>>,
    /// `FRC` of the block, else `FRCM` when active, in the basic unit system: `Some(None)` when
    /// programmed with an unknown value.
    pub feed: Option<Option<f64>>,
    /// The block is the first line of a two-block definition by angles: its end in the plane is the
    /// start of the next block's move (reference §14.6).
    pub angle_open: bool,
    /// The element comes from `RNDM`, not from a word of the block.
    pub modal: bool,
}

/// The first line of a two-block definition, waiting for the line that closes it: its start and
/// angle in the plane (by index) it was programmed in, in the basic unit system.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OpenAngle {
    pub plane: usize,
    pub start: (f64, f64),
    pub degrees: f64,
}
