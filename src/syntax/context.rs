//! What the parser needs to know about the machine, prepared once from the configuration.

use crate::config::{AxisKind, MachineConfig};

/// Axis names and limits the syntax checks depend on.
#[derive(Debug, Clone)]
pub struct SyntaxContext {
    /// Upper-case axis names with their kinds.
    axes: Vec<(String, AxisKind)>,
    pub max_skip_level: u8,
    pub max_block_length: usize,
    /// Axes whose name is one letter, by letter: the common case, looked up without comparing text.
    single_letter_axes: [Option<AxisKind>; 26],
    /// Upper-case names of macros (`DEFINE name AS ...`) known for the program being parsed.
    macros: std::collections::HashSet<String>,
}

impl SyntaxContext {
    pub fn new(config: &MachineConfig) -> SyntaxContext {
        let mut single_letter_axes = [None; 26];
        for axis in &config.axes {
            if let [letter] = axis.name.as_bytes() {
                if letter.is_ascii_alphabetic() {
                    single_letter_axes[(letter.to_ascii_uppercase() - b'A') as usize] =
                        Some(axis.kind);
                }
            }
        }
        SyntaxContext {
            single_letter_axes,
            axes: config
                .axes
                .iter()
                .map(|axis| (axis.name.to_ascii_uppercase(), axis.kind))
                .collect(),
            max_skip_level: config.max_skip_level,
            max_block_length: config.max_block_length,
            macros: Default::default(),
        }
    }

    /// The kind of a configured one-letter axis.
    pub fn axis_kind_by_letter(&self, letter: u8) -> Option<AxisKind> {
        if letter.is_ascii_alphabetic() {
            self.single_letter_axes[(letter.to_ascii_uppercase() - b'A') as usize]
        } else {
            None
        }
    }

    /// The kind of a configured axis, by name in any case.
    pub fn axis_kind(&self, name: &str) -> Option<AxisKind> {
        if let [letter] = name.as_bytes() {
            if letter.is_ascii_alphabetic() {
                return self.single_letter_axes[(letter.to_ascii_uppercase() - b'A') as usize];
            }
        }
        self.axes
            .iter()
            .find(|(axis, _)| axis.eq_ignore_ascii_case(name))
            .map(|(_, kind)| *kind)
    }

    /// Adds a macro name (any case).
    pub fn add_macro(&mut self, name: &str) {
        self.macros.insert(name.to_ascii_uppercase());
    }

    /// Whether `upper` (an upper-case name) is a known macro.
    pub fn is_macro(&self, upper: &str) -> bool {
        !self.macros.is_empty() && self.macros.contains(upper)
    }

    /// The configured axes for messages, e.g. "axes X, Y, Z".
    pub fn axis_list(&self) -> String {
        let names: Vec<&str> = self.axes.iter().map(|(name, _)| name.as_str()).collect();
        format!("axes {}", names.join(", "))
    }
}

impl Default for SyntaxContext {
    fn default() -> SyntaxContext {
        SyntaxContext::new(&MachineConfig::default())
    }
}
