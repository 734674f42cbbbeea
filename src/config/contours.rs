//! Contour definitions (`[contours]` in `sinumerik.toml`): the machine data that decide how chamfers
//! and roundings are inserted (reference §14.4) and the names of the contour-definition words
//! (§14.1, MD10652/MD10654/MD10656).

use serde::Deserialize;

/// How chamfers and roundings are inserted and what the contour-definition words are called.
#[derive(Debug, Clone, PartialEq)]
pub struct ContourOptions {
    /// MD20200 `CHFRND_MAXNUM_DUMMY_BLOCKS`: blocks without motion in the plane that may stand
    /// between the two elements of a corner (the default 3 is assumed, reference §14.4 [?]).
    pub max_dummy_blocks: u32,
    /// MD20201 `CHFRND_MODE_MASK` bit 0: `false` (the default) when the element belongs to the
    /// following block (its feed; dummy blocks run before the element), `true` when it belongs to
    /// the preceding one.
    pub element_with_preceding: bool,
    /// MD10652 `CONTOUR_DEF_ANGLE_NAME` (upper case).
    pub angle_name: String,
    /// MD10654 `RADIUS_NAME` (upper case).
    pub radius_name: String,
    /// MD10656 `CHAMFER_NAME` (upper case).
    pub chamfer_name: String,
}

impl Default for ContourOptions {
    fn default() -> ContourOptions {
        ContourOptions {
            max_dummy_blocks: 3,
            element_with_preceding: false,
            angle_name: "ANG".to_string(),
            radius_name: "RND".to_string(),
            chamfer_name: "CHR".to_string(),
        }
    }
}

/// The `[contours]` table as written.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawContours {
    max_dummy_blocks: Option<i64>,
    element_with_preceding: Option<bool>,
    angle_name: Option<String>,
    radius_name: Option<String>,
    chamfer_name: Option<String>,
}

impl RawContours {
    /// The options, or the key and the reason a value is not allowed.
    pub(super) fn convert(&self) -> Result<ContourOptions, (&'static str, String)> {
        let mut options = ContourOptions::default();
        if let Some(value) = self.max_dummy_blocks {
            options.max_dummy_blocks = u32::try_from(value)
                .ok()
                .filter(|value| *value <= 1000)
                .ok_or((
                    "max_dummy_blocks",
                    format!("must be between 0 and 1000, found {value}"),
                ))?;
        }
        if let Some(value) = self.element_with_preceding {
            options.element_with_preceding = value;
        }
        for (key, value, target) in [
            ("angle_name", &self.angle_name, &mut options.angle_name),
            ("radius_name", &self.radius_name, &mut options.radius_name),
            (
                "chamfer_name",
                &self.chamfer_name,
                &mut options.chamfer_name,
            ),
        ] {
            if let Some(value) = value {
                let valid = !value.is_empty()
                    && value.len() <= 32
                    && value.starts_with(|c: char| c.is_ascii_alphabetic())
                    && value.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
                if !valid {
                    return Err((
                        key,
                        format!("must be a name of letters, digits and `_`, found {value:?}"),
                    ));
                }
                *target = value.to_ascii_uppercase();
            }
        }
        Ok(options)
    }
}
