//! Key paths and positions in a configuration file: which key a byte offset belongs to, where a key is,
//! and the wording of messages, so that every error names the key and the line and column.

use std::ops::Range;
use toml::de::{DeTable, DeValue};

/// One step of a key path: a table key or an index into an array.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) enum KeySegment {
    Key(String),
    Index(usize),
}

/// A value that passed the TOML types but is not allowed, with the key it belongs to.
pub(super) struct InvalidValue {
    pub(super) key_path: Vec<KeySegment>,
    pub(super) message: String,
    /// Whether the key itself is wrong (an unknown code, a bad axis name) rather than its value, which
    /// decides where the position in the message points.
    pub(super) is_about_key: bool,
}

pub(super) fn invalid(key_path: &[KeySegment], message: String) -> InvalidValue {
    InvalidValue {
        key_path: key_path.to_vec(),
        message,
        is_about_key: false,
    }
}

pub(super) fn invalid_key(key_path: &[KeySegment], message: String) -> InvalidValue {
    InvalidValue {
        is_about_key: true,
        ..invalid(key_path, message)
    }
}

pub(super) fn key(name: &str) -> KeySegment {
    KeySegment::Key(name.to_string())
}

/// Finds keys by position and positions by key in the parsed document, so that errors from serde (which
/// only know a byte span) and from validation (which only know a key) both get a key and a position.
pub(super) struct KeyLocator {
    entries: Vec<LocatedEntry>,
}

/// One key or array element of the document with the spans of its key and its value.
pub(super) struct LocatedEntry {
    pub(super) key_path: Vec<KeySegment>,
    key_span: Option<Range<usize>>,
    value_span: Range<usize>,
}

impl KeyLocator {
    pub(super) fn new(document: &DeTable<'_>) -> KeyLocator {
        let mut locator = KeyLocator {
            entries: Vec::new(),
        };
        locator.add_table(document, &[]);
        locator
    }

    fn add_table(&mut self, table: &DeTable<'_>, prefix: &[KeySegment]) {
        for (table_key, value) in table.iter() {
            let mut key_path = prefix.to_vec();
            key_path.push(KeySegment::Key(table_key.get_ref().to_string()));
            self.entries.push(LocatedEntry {
                key_path: key_path.clone(),
                key_span: Some(table_key.span()),
                value_span: value.span(),
            });
            self.add_value(value.get_ref(), &key_path);
        }
    }

    fn add_value(&mut self, value: &DeValue<'_>, key_path: &[KeySegment]) {
        match value {
            DeValue::Table(table) => self.add_table(table, key_path),
            DeValue::Array(array) => {
                for (index, element) in array.iter().enumerate() {
                    let mut element_path = key_path.to_vec();
                    element_path.push(KeySegment::Index(index));
                    self.entries.push(LocatedEntry {
                        key_path: element_path.clone(),
                        key_span: None,
                        value_span: element.span(),
                    });
                    self.add_value(element.get_ref(), &element_path);
                }
            }
            _ => {}
        }
    }

    /// The deepest key whose name or value covers `offset`. The span of a `[table]` header covers only
    /// the header, not the keys below it, so every entry is searched rather than walking down by spans.
    pub(super) fn path_at(&self, offset: usize) -> Option<Vec<KeySegment>> {
        let covers =
            |span: &Range<usize>| span.start <= offset && offset < span.end.max(span.start + 1);
        self.entries
            .iter()
            .filter(|entry| {
                entry.key_span.as_ref().is_some_and(covers) || covers(&entry.value_span)
            })
            .max_by_key(|entry| entry.key_path.len())
            .map(|entry| entry.key_path.clone())
    }

    /// Where a key's name or value is (the value of a `[table]` is its header).
    pub(super) fn span_of(
        &self,
        key_path: &[KeySegment],
        is_about_key: bool,
    ) -> Option<Range<usize>> {
        let entry = self
            .entries
            .iter()
            .find(|entry| entry.key_path == key_path)?;
        match &entry.key_span {
            Some(key_span) if is_about_key => Some(key_span.clone()),
            _ => Some(entry.value_span.clone()),
        }
    }
}

pub(super) fn display_key_path(key_path: &[KeySegment]) -> String {
    let mut text = String::new();
    for segment in key_path {
        match segment {
            KeySegment::Key(name) => {
                if !text.is_empty() {
                    text.push('.');
                }
                text.push_str(name);
            }
            KeySegment::Index(index) => text.push_str(&format!("[{index}]")),
        }
    }
    text
}

/// Rewords serde's messages for people who write TOML rather than Rust: "unknown key" instead of
/// "unknown field", and TOML type names instead of `i64` or the name of a private struct.
pub(super) fn describe_serde_message(message: &str) -> String {
    if let Some(rest) = message.strip_prefix("unknown field ") {
        return format!("unknown key {rest}");
    }
    if let Some(rest) = message.strip_prefix("invalid type: ") {
        if let Some((found, expected)) = rest.rsplit_once(", expected ") {
            let expected = match expected {
                "i64" => "a whole number",
                "f64" => "a number",
                "a sequence" => "an array",
                "a map" => "a table",
                other if other.starts_with("struct ") => "a table",
                other => other,
            };
            return format!("expected {expected}, found {found}");
        }
    }
    message.to_string()
}

/// The 1-based line and column (in characters) of a byte offset, for messages a person can follow.
pub(super) fn position_of(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line_start = before.rfind('\n').map_or(0, |newline| newline + 1);
    let line = before.matches('\n').count() + 1;
    let column = before[line_start..].chars().count() + 1;
    (line, column)
}
