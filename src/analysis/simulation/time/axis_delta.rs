//! The change of one axis in a move as the time models read it: the axis's limits and its distance.

/// The change of one axis in a move: its configuration and the distance (radius on a transverse
/// axis, degrees on a rotary one).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct AxisDelta {
    /// The axis's index in the configuration.
    pub(super) index: usize,
    pub(super) geometry: bool,
    pub(super) rotary: bool,
    pub(super) max_velocity: f64,
    pub(super) max_acceleration: Option<f64>,
    pub(super) delta: f64,
}
