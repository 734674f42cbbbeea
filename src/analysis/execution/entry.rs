//! The entry state of a subprogram analysed on its own, taken from the places that call it: when
//! every call site the caller knows has the same units (G70/G71/G700/G710), distance mode (G90/G91)
//! and plane (G17–G19), the run starts from that state instead of the assumed reset state
//! (docs/execution.md). The states at the call sites are found by the caller of the analysis (the
//! server reads them from the calling programs); this module only decides and applies.

use crate::syntax::gcodes::GCode;
use std::sync::Arc;

/// The groups every call site must agree on: plane, units, distance.
const DECIDING_GROUPS: [u8; 3] = [6, 13, 14];

/// The modal state at one call site, by the names of its G functions (`None`: not known there).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CallSiteState {
    /// The file of the calling program, as it is shown.
    pub file: String,
    pub motion: Option<String>,
    pub plane: Option<String>,
    pub units: Option<String>,
    pub distance: Option<String>,
    pub diameter: Option<String>,
}

/// The entry state the call sites agree on.
#[derive(Debug, Clone, PartialEq)]
pub struct CallerEntry {
    /// The G functions every call site has: plane, units and distance always, motion and diameter
    /// programming when they agree too.
    pub groups: Vec<GCode>,
    pub call_sites: usize,
    /// The calling files, each once, in the order first met.
    pub files: Vec<String>,
}

impl CallerEntry {
    /// The entry state of `sites`, when there is at least one and every one has the same known
    /// plane, units and distance mode.
    pub fn agreed(sites: &[CallSiteState]) -> Option<CallerEntry> {
        let first = sites.first()?;
        let fields: [fn(&CallSiteState) -> &Option<String>; 5] = [
            |site| &site.plane,
            |site| &site.units,
            |site| &site.distance,
            |site| &site.motion,
            |site| &site.diameter,
        ];
        let mut groups = Vec::new();
        for (index, field) in fields.iter().enumerate() {
            let value = field(first);
            let agreed = value.is_some() && sites.iter().all(|site| field(site) == value);
            let code = value.as_deref().and_then(code_named);
            match (agreed, code) {
                (true, Some(code)) => groups.push(code),
                // The first three decide: without them the reset state stays the assumption.
                _ if index < DECIDING_GROUPS.len() => return None,
                _ => {}
            }
        }
        let mut files: Vec<String> = Vec::new();
        for site in sites {
            if !files.contains(&site.file) {
                files.push(site.file.clone());
            }
        }
        Some(CallerEntry {
            groups,
            call_sites: sites.len(),
            files,
        })
    }

    /// How the hover and the preview name the entry state.
    pub fn describe(&self) -> String {
        let sites = if self.call_sites == 1 {
            "the call site".to_string()
        } else {
            format!("the {} call sites", self.call_sites)
        };
        format!("entry state from {sites} in {}", self.files.join(", "))
    }
}

/// The G function written `name`: `G18` by its number, `DIAMOF` by its name.
fn code_named(name: &str) -> Option<GCode> {
    match name.strip_prefix(['G', 'g']).map(str::parse::<u32>) {
        Some(Ok(number)) => GCode::from_number(number),
        _ => GCode::from_name(name),
    }
}

/// What a run does beyond running: where a subprogram starts, and what it records of first passes.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RunSetup {
    /// The entry state from the call sites, for a subprogram analysed on its own.
    pub entry: Option<Arc<CallerEntry>>,
    /// Keep the state of each line's first pass (`first_pass.rs`).
    pub record_first_passes: bool,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn site(file: &str, units: &str, distance: &str, motion: &str) -> CallSiteState {
        CallSiteState {
            file: file.to_string(),
            motion: Some(motion.to_string()),
            plane: Some("G17".to_string()),
            units: Some(units.to_string()),
            distance: Some(distance.to_string()),
            diameter: None,
        }
    }

    #[test]
    fn call_sites_that_agree_give_the_entry_state() {
        let sites = [
            site("A.MPF", "G70", "G91", "G1"),
            site("B.MPF", "G70", "G91", "G0"),
            site("A.MPF", "G70", "G91", "G1"),
        ];
        let entry = CallerEntry::agreed(&sites).expect("they agree");
        let names: Vec<String> = entry
            .groups
            .iter()
            .map(|code| code.name().into_owned())
            .collect();
        assert_eq!(names, ["G17", "G70", "G91"]);
        assert_eq!(
            entry.describe(),
            "entry state from the 3 call sites in A.MPF, B.MPF"
        );
    }

    #[test]
    fn call_sites_that_differ_or_are_unknown_give_none() {
        assert!(CallerEntry::agreed(&[]).is_none());
        let differ = [
            site("A.MPF", "G70", "G90", "G1"),
            site("B.MPF", "G71", "G90", "G1"),
        ];
        assert!(CallerEntry::agreed(&differ).is_none());
        let mut unknown = site("A.MPF", "G71", "G90", "G1");
        unknown.plane = None;
        assert!(CallerEntry::agreed(&[unknown]).is_none());
    }
}
