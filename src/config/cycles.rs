//! How the built-in models of the standard cycles behave where the reference leaves the control's
//! behaviour open (`[cycles]` in `sinumerik.toml`, reference §16.2 and §16.6).

use serde::Deserialize;

/// Where HOLES1 starts its row (reference §16.6, §16.7: the order is [?]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RowOrder {
    /// At the end hole nearer to the current position in the plane (the reference's recommendation,
    /// the Siemens cycle description as recalled).
    NearCurrent,
    /// At the end hole nearer to the zero point of the workpiece coordinate system (the copy of the
    /// cycle in public code).
    NearOrigin,
    /// Always at the first hole (FDIS from the reference point).
    First,
    /// Not known: the holes are drawn from the first, and the plane position after the pattern is
    /// unknown.
    Unknown,
}

/// In which order CYCLE801 visits its grid (reference §16.6: [?]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GridOrder {
    /// Rows along the direction of the smaller spacing, in a meander, from the grid's reference
    /// corner (the copy of the cycle in public code): an assumption.
    Meander,
    /// Not known: the holes are drawn in the meander order, and the plane position after the
    /// pattern is unknown.
    Unknown,
}

/// The choices of the built-in cycle models.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CycleOptions {
    /// Whether a built-in cycle restores the modal G functions active at its call, as a `SAVE`
    /// subprogram does (reference §16.2 recommends treating standard cycles so; [?]).
    pub restore_modal: bool,
    pub holes1_order: RowOrder,
    pub cycle801_order: GridOrder,
}

impl Default for CycleOptions {
    fn default() -> CycleOptions {
        CycleOptions {
            restore_modal: true,
            holes1_order: RowOrder::NearCurrent,
            cycle801_order: GridOrder::Meander,
        }
    }
}

/// The `[cycles]` table as written.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawCycles {
    restore_modal: Option<bool>,
    holes1_order: Option<String>,
    cycle801_order: Option<String>,
}

impl RawCycles {
    /// The options, or the key and the reason a value is not allowed.
    pub(super) fn convert(&self) -> Result<CycleOptions, (&'static str, String)> {
        let mut options = CycleOptions::default();
        if let Some(value) = self.restore_modal {
            options.restore_modal = value;
        }
        if let Some(value) = &self.holes1_order {
            options.holes1_order = match value.as_str() {
                "near_current" => RowOrder::NearCurrent,
                "near_origin" => RowOrder::NearOrigin,
                "first" => RowOrder::First,
                "unknown" => RowOrder::Unknown,
                _ => {
                    return Err((
                        "holes1_order",
                        format!("must be \"near_current\", \"near_origin\", \"first\" or \"unknown\", found {value:?}"),
                    ))
                }
            };
        }
        if let Some(value) = &self.cycle801_order {
            options.cycle801_order = match value.as_str() {
                "meander" => GridOrder::Meander,
                "unknown" => GridOrder::Unknown,
                _ => {
                    return Err((
                        "cycle801_order",
                        format!("must be \"meander\" or \"unknown\", found {value:?}"),
                    ))
                }
            };
        }
        Ok(options)
    }
}
