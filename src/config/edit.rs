//! Changes to the text of a `sinumerik.toml` that the quick fixes offer: `kind = "turn"` for a program
//! that needs a transverse axis (A235, A236), and an axis the machine does not have yet (S180). The
//! text is edited in place, one key at a time, so that every other key, comment and blank line stays
//! as the user wrote it; each result is parsed again and given only when it configures what it
//! should. No IO: the caller reads the file and applies the edit.

use super::{parse_config_text, AxisKind, MachineConfig};
use std::path::Path;

/// One replacement in the text of a configuration file: the bytes `start..end` become `text`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ConfigTextEdit {
    pub start: usize,
    pub end: usize,
    pub text: String,
}

impl ConfigTextEdit {
    fn insert(at: usize, text: String) -> ConfigTextEdit {
        ConfigTextEdit {
            start: at,
            end: at,
            text,
        }
    }
}

/// Applies `edits` (sorted, not overlapping) to `text`.
pub fn apply_config_edits(text: &str, edits: &[ConfigTextEdit]) -> String {
    let mut result = String::with_capacity(text.len() + 64);
    let mut at = 0;
    for edit in edits {
        result.push_str(&text[at..edit.start]);
        result.push_str(&edit.text);
        at = edit.end;
    }
    result.push_str(&text[at..]);
    result
}

/// The edits that make the file `text` (`None`: no file yet, the text is created) configure a lathe:
/// `kind = "turn"` in `[machine]`, and an `X` listed in `[axes]` made transverse. `None` when the text
/// cannot be edited so (a `machine` written as an inline table, a file that does not parse).
pub fn lathe_edits(text: Option<&str>) -> Option<Vec<ConfigTextEdit>> {
    let text = text.unwrap_or("");
    let mut edits = vec![set_key(text, "machine", "kind", "\"turn\"")];
    let tables = Tables::of(text);
    if tables.key(text, "axes", "X").is_some() {
        edits.push(set_key(text, "axes", "X", "\"transverse\""));
    }
    edits.sort_by_key(|edit| edit.start);
    let config = parsed(&apply_config_edits(text, &edits))?;
    let lathe = config.kind == super::MachineKind::Turn
        && config
            .axes
            .iter()
            .any(|axis| axis.kind == AxisKind::Transverse);
    lathe.then_some(edits)
}

/// The kind a new axis gets: A, B and C are rotary axes, every other name a linear axis.
pub fn new_axis_kind(name: &str) -> AxisKind {
    match name.as_bytes().first() {
        Some(b'A' | b'B' | b'C' | b'a' | b'b' | b'c') => AxisKind::Rotary,
        _ => AxisKind::Linear,
    }
}

/// The edits that add the axis `name` of kind `kind` to the file `text` (`None`: no file yet), whose
/// machine is `current`: a line in `[axes]`, or a new `[axes]` table that lists the current axes too
/// (the table replaces the kind's default axes). `None` when the result would not configure the
/// current axes and the new one.
pub fn axis_edits(
    text: Option<&str>,
    current: &MachineConfig,
    name: &str,
    kind: AxisKind,
) -> Option<Vec<ConfigTextEdit>> {
    let text = text.unwrap_or("");
    let tables = Tables::of(text);
    let line = format!("{name} = \"{}\"\n", kind.as_str());
    let edit = match tables.after_header("axes", line) {
        Some(edit) => edit,
        None => {
            let mut table = String::from("[axes]\n");
            for axis in &current.axes {
                table.push_str(&format!("{} = \"{}\"\n", axis.name, axis.kind.as_str()));
            }
            table.push_str(&format!("{name} = \"{}\"\n", kind.as_str()));
            append(text, table)
        }
    };
    let config = parsed(&apply_config_edits(text, std::slice::from_ref(&edit)))?;
    let has = |wanted: &str, kind: Option<AxisKind>| {
        config
            .axes
            .iter()
            .any(|axis| axis.name == wanted && kind.is_none_or(|kind| axis.kind == kind))
    };
    let complete = has(name, Some(kind)) && current.axes.iter().all(|axis| has(&axis.name, None));
    complete.then_some(vec![edit])
}

fn parsed(text: &str) -> Option<MachineConfig> {
    parse_config_text(text, Path::new("sinumerik.toml")).ok()
}

/// `text` appended at the end of the file, after a blank line when the file has content.
fn append(text: &str, table: String) -> ConfigTextEdit {
    let separator = match text {
        "" => "",
        _ if text.ends_with("\n\n") => "",
        _ if text.ends_with('\n') => "\n",
        _ => "\n\n",
    };
    ConfigTextEdit::insert(text.len(), format!("{separator}{table}"))
}

/// The edit that gives `key` in `[table]` the value `value` (TOML text): its value replaced where the
/// key is written, else a line after the table's header, else the table appended.
fn set_key(text: &str, table: &str, key: &str, value: &str) -> ConfigTextEdit {
    let tables = Tables::of(text);
    if let Some((start, end)) = tables.key(text, table, key) {
        return ConfigTextEdit {
            start,
            end,
            text: format!(" {value}"),
        };
    }
    tables
        .after_header(table, format!("{key} = {value}\n"))
        .unwrap_or_else(|| append(text, format!("[{table}]\n{key} = {value}\n")))
}

/// The lines of a TOML text by the table they belong to (`""`: before the first header).
struct Tables<'t> {
    /// (table, start of the line, end of the line with its line end).
    lines: Vec<(&'t str, usize, usize)>,
    /// (table, end of its header line with its line end, whether it has one).
    headers: Vec<(&'t str, usize, bool)>,
}

impl<'t> Tables<'t> {
    fn of(text: &'t str) -> Tables<'t> {
        let mut lines = Vec::new();
        let mut headers = Vec::new();
        let mut table = "";
        let mut start = 0;
        for line in text.split_inclusive('\n') {
            let end = start + line.len();
            let code = line.split('#').next().unwrap_or("").trim();
            if let Some(name) = code
                .strip_prefix('[')
                .filter(|rest| !rest.starts_with('['))
                .and_then(|rest| rest.strip_suffix(']'))
            {
                table = name.trim();
                headers.push((table, end, line.ends_with('\n')));
            } else {
                lines.push((table, start, end));
            }
            start = end;
        }
        Tables { lines, headers }
    }

    /// An insertion of `line` (with its line end) right after the first header of `table`; a header
    /// at the end of a text without a line end gets one first.
    fn after_header(&self, table: &str, line: String) -> Option<ConfigTextEdit> {
        let (_, end, line_end) = self.headers.iter().find(|(name, ..)| *name == table)?;
        let text = if *line_end { line } else { format!("\n{line}") };
        Some(ConfigTextEdit::insert(*end, text))
    }

    /// The bytes of the value of `key` in `[table]` (after its `=`, up to a comment or the line end).
    fn key(&self, text: &str, table: &str, key: &str) -> Option<(usize, usize)> {
        self.lines
            .iter()
            .filter(|(name, ..)| *name == table)
            .find_map(|(_, start, end)| {
                let line = &text[*start..*end];
                let rest = line.trim_start().strip_prefix(key)?;
                let rest = rest.trim_start().strip_prefix('=')?;
                let value_start = end - line.len() + (line.len() - rest.len());
                // The value is a string or a word: it ends at a comment or the line end.
                let value = rest.split('#').next().unwrap_or("");
                let value = value.trim_end_matches(['\n', '\r']);
                let value_end = value_start + value.trim_end().len();
                Some((value_start, value_end))
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lathe(text: Option<&str>) -> String {
        let edits = lathe_edits(text).expect("a lathe can be configured");
        apply_config_edits(text.unwrap_or(""), &edits)
    }

    #[test]
    fn a_lathe_is_created_or_edited_in_place() {
        assert_eq!(lathe(None), "[machine]\nkind = \"turn\"\n");
        assert_eq!(
            lathe(Some(
                "# shop\n[machine]\nkind = \"mill\"  # was\nunits = \"mm\"\n"
            )),
            "# shop\n[machine]\nkind = \"turn\"  # was\nunits = \"mm\"\n"
        );
        assert_eq!(
            lathe(Some(
                "[machine]\nunits = \"mm\"\n[check]\nextensions = [\"mpf\"]\n"
            )),
            "[machine]\nkind = \"turn\"\nunits = \"mm\"\n[check]\nextensions = [\"mpf\"]\n"
        );
        assert_eq!(
            lathe(Some("[check]\nextensions = [\"mpf\"]")),
            "[check]\nextensions = [\"mpf\"]\n\n[machine]\nkind = \"turn\"\n"
        );
        // An [axes] table replaces the kind's axes: its X becomes the transverse axis.
        assert_eq!(
            lathe(Some("[axes]\nX = \"linear\"\nZ = \"linear\"\n")),
            "[axes]\nX = \"transverse\"\nZ = \"linear\"\n\n[machine]\nkind = \"turn\"\n"
        );
        assert_eq!(lathe(Some("[machine]")), "[machine]\nkind = \"turn\"\n");
        // Written as an inline table, `machine` cannot get a [machine] table: no edit.
        assert_eq!(lathe_edits(Some("machine = { units = \"mm\" }\n")), None);
    }

    #[test]
    fn an_axis_joins_the_axes_table_or_a_new_one_with_the_current_axes() {
        let turn = MachineConfig::turn();
        let created = axis_edits(None, &turn, "Y", AxisKind::Linear).unwrap();
        let text = apply_config_edits("", &created);
        assert_eq!(
            text,
            "[axes]\nX = \"transverse\"\nZ = \"linear\"\nC = \"modulo\"\nY = \"linear\"\n"
        );
        let existing = "[machine]\nkind = \"turn\"\n\n[axes]\nX = \"transverse\"\nZ = \"linear\"\n";
        let config = parse_config_text(existing, Path::new("t")).unwrap();
        let edits = axis_edits(Some(existing), &config, "B", AxisKind::Rotary).unwrap();
        assert_eq!(
            apply_config_edits(existing, &edits),
            "[machine]\nkind = \"turn\"\n\n[axes]\nB = \"rotary\"\nX = \"transverse\"\nZ = \"linear\"\n"
        );
        assert_eq!(new_axis_kind("B"), AxisKind::Rotary);
        assert_eq!(new_axis_kind("U"), AxisKind::Linear);
    }
}
