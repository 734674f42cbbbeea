//! The configuration index of the axis an address word names. Almost every axis word is one letter
//! without extension (`X10`), so those are looked up in a table by that letter, built once from the
//! configuration; other words (`X1=10`, names of several letters) compare the configured names.

use crate::config::MachineConfig;
use crate::syntax::ast::{AddressWord, Extension};

/// In [`AxisLookup`]'s table: no configured axis has this one-letter name.
const NOT_CONFIGURED: u8 = u8::MAX;
/// In [`AxisLookup`]'s table: the axis's index does not fit the table, the names are compared.
const COMPARE_NAMES: u8 = u8::MAX - 1;

/// Finds the configured axis of a word, like comparing its name with each configured name in any
/// case and taking the first that is equal.
#[derive(Debug, Clone)]
pub struct AxisLookup {
    /// By the byte of a one-letter word: the index of the first configured axis of that name.
    by_letter: [u8; 256],
}

impl AxisLookup {
    pub fn new(config: &MachineConfig) -> AxisLookup {
        let mut by_letter = [NOT_CONFIGURED; 256];
        // From the last axis to the first, so that of two axes with the same name the first one
        // stays in the table, as the comparison in configuration order finds it.
        for (index, axis) in config.axes.iter().enumerate().rev() {
            let [letter] = axis.name.as_bytes() else {
                continue;
            };
            let entry = u8::try_from(index)
                .ok()
                .filter(|entry| *entry < COMPARE_NAMES)
                .unwrap_or(COMPARE_NAMES);
            // `eq_ignore_ascii_case` makes a written letter equal to the name in either case of an
            // ASCII letter, and to the very byte otherwise.
            by_letter[letter.to_ascii_lowercase() as usize] = entry;
            by_letter[letter.to_ascii_uppercase() as usize] = entry;
        }
        AxisLookup { by_letter }
    }

    /// The configuration index of the axis `word` (in `line`) names, if the machine has that axis.
    /// Inlined, with the comparison of names kept out of line: a call per axis word, with the
    /// registers the comparison needs saved and restored, cost more than the table lookup itself.
    #[inline]
    pub fn index(&self, config: &MachineConfig, line: &str, word: &AddressWord) -> Option<usize> {
        let numbered = matches!(word.extension, Some(Extension::Number { .. }));
        if let (false, Some(&[letter])) = (
            numbered,
            line.as_bytes().get(word.name.start()..word.name.end()),
        ) {
            match self.by_letter[letter as usize] {
                NOT_CONFIGURED => return None,
                COMPARE_NAMES => {}
                entry => return Some(entry as usize),
            }
        }
        configured_axis_index(config, line, word)
    }
}

/// The configuration index of the axis a word names, compared without building its name.
#[inline(never)]
fn configured_axis_index(config: &MachineConfig, line: &str, word: &AddressWord) -> Option<usize> {
    let letters = line
        .as_bytes()
        .get(word.name.start()..word.name.end())
        .unwrap_or_default();
    let mut digits_buffer = [0u8; 10];
    let digits: &[u8] = match &word.extension {
        Some(Extension::Number { value, .. }) => {
            // The decimal digits of the extension, as `to_string` writes them.
            let mut remaining = *value;
            let mut start = digits_buffer.len();
            loop {
                start -= 1;
                digits_buffer[start] = b'0' + (remaining % 10) as u8;
                remaining /= 10;
                if remaining == 0 {
                    break;
                }
            }
            &digits_buffer[start..]
        }
        _ => &[],
    };
    // Compared byte by byte: these names are one to three bytes long, and a call of the library's
    // memcmp per configured axis and word cost more than the rest of the lookup.
    config.axes.iter().position(|axis| {
        let name = axis.name.as_bytes();
        name.len() == letters.len() + digits.len()
            && name
                .iter()
                .zip(letters.iter().chain(digits))
                .all(|(configured, written)| configured.eq_ignore_ascii_case(written))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::{Axis, AxisKind};
    use crate::syntax::ast::Statement;
    use crate::syntax::{parse_line, SyntaxContext};

    /// Every axis word of `line` looked up both ways.
    fn both_ways(config: &MachineConfig, line: &str) -> Vec<(Option<usize>, Option<usize>)> {
        let lookup = AxisLookup::new(config);
        let (block, _) = parse_line(line, &SyntaxContext::new(config));
        block
            .statements
            .iter()
            .filter_map(|statement| match statement {
                Statement::Address(word) => Some((
                    lookup.index(config, line, word),
                    configured_axis_index(config, line, word),
                )),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn the_table_finds_what_comparing_the_names_finds() {
        let mut config = MachineConfig::mill();
        config.axes = vec![
            Axis::new("x", AxisKind::Linear),
            Axis::new("Y", AxisKind::Linear),
            Axis::new("X", AxisKind::Modulo),
            Axis::new("C1", AxisKind::Modulo),
            Axis::new("AX", AxisKind::Linear),
            Axis::new("Ä", AxisKind::Linear),
        ];
        let line = "X1 x2 Y3 y4 Z5 C1=6 C7 AX=8 U9 F10 I1 POS[X]=2";
        let found = both_ways(&config, line);
        assert_eq!(found.len(), 12, "{found:?}");
        for (table, compared) in &found {
            assert_eq!(table, compared);
        }
        assert_eq!(found[0].0, Some(0), "the first of two axes named X");
        assert_eq!(found[1].0, Some(0));
        assert_eq!(found[2].0, Some(1));
        assert_eq!(found[4].0, None, "Z is not configured");
        assert_eq!(found[5].0, Some(3), "C1= by its extension");
        assert_eq!(found[7].0, Some(4), "AX by its name");
    }

    #[test]
    fn an_axis_beyond_the_table_is_found_by_its_name() {
        let mut config = MachineConfig::mill();
        config.axes = (0..300)
            .map(|index| Axis::new(&format!("Q{index}"), AxisKind::Linear))
            .chain(["U", "X"].map(|name| Axis::new(name, AxisKind::Linear)))
            .collect();
        let found = both_ways(&config, "U1 X2 Y3");
        assert_eq!(
            found,
            vec![(Some(300), Some(300)), (Some(301), Some(301)), (None, None)]
        );
    }
}
