//! Reading the machine configuration from `sinumerik.toml`: finding the file, parsing it and turning every
//! mistake into a message that names the file, the position and the key.
//!
//! # Format
//!
//! Every table and key is optional; an empty file gives the defaults of a milling machine.
//!
//! ```toml
//! [machine]
//! kind = "mill"                 # "mill" or "turn": picks the defaults; every other key overrides them
//! units = "mm"                  # basic system (MD10240): "mm" or "inch"
//! reset_gcodes = ["G18", "DIAMON"]  # MD20150: G functions active after reset, beyond the Siemens defaults
//! circle_error_const = 0.01     # MD21000 in mm, greater than 0
//! circle_error_factor = 0.001   # MD21010, 0 or greater
//! max_skip_level = 9            # highest skip level /N offered, 0 to 9
//! max_block_length = 512        # longest block in characters, comment included, greater than 0
//! r_parameters = 100            # MD28050: number of R parameters
//! frame_offset_incr_prog = 1    # SD42440: 1 = G91 after an offset change also traverses the change, 0 = not
//! mm_frame_fine_trans = 0       # MD18600: 1 = ATRANS and G59 write a fine translation kept by TRANS and G58
//! modulo_range_error = 0        # MD30455 bit 0 = 0 (1 here): a modulo position outside 0..360 is an error (A234)
//!
//! [offsets]                     # settable work offsets G500, G54 ... G57, G505 ... G599 ($P_UIFR)
//! G54 = { X = 100, Y = 50 }     # per axis in the basic system (degrees on rotary axes, radius on X of a lathe)
//!
//! [axes]                        # when present, replaces the kind's default axes entirely
//! X = "transverse"              # linear | transverse | rotary | modulo
//! Z = "linear"
//! C = "modulo"
//!
//! [diagnostics]                 # severity per diagnostic code: error | warning | info | hint
//! S120 = "error"
//!
//! [check]
//! extensions = ["mpf", "spf"]   # extensions `check` reads from folders, without the dot
//! ```
//!
//! Defaults: `kind = "mill"` has the axes X, Y, Z (linear) and A, B, C (modulo) and no extra reset G functions;
//! `kind = "turn"` has X (transverse), Z (linear) and C (modulo) and `reset_gcodes = ["G18", "DIAMON"]`. Both
//! are metric, with the other values as shown above. No settable offset is configured: G500 is zero, every
//! other offset (G54 ...) is unknown, so machine coordinates under it are unknown. A configured offset's
//! axes that are not listed are 0.
//!
//! Names and values are not case-sensitive (`x = "Linear"` is axis X); axis names are 1 to 8 letters, digits
//! or underscores starting with a letter. A TOML table has no order, so the axes are kept as X, Y, Z first
//! (those present) and the others sorted by name. Unknown keys, unknown diagnostic codes and out-of-range
//! values are errors, never silently ignored: a misspelt key would otherwise leave a default in place
//! without anyone noticing.

use super::axes::{Axis, AxisKind};
use super::machine::{MachineConfig, MachineKind};
use crate::diagnostics::{Code, Severity};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::de::{DeTable, DeValue};

/// The name of the configuration file that `check` and the language server look for.
pub const CONFIG_FILE_NAME: &str = "sinumerik.toml";

/// Why a configuration file could not be used. The message is complete on its own: it names the file,
/// the position and the key, so the CLI prints it as it is and the language server can place it.
#[derive(Debug)]
pub struct ConfigError {
    /// The configuration file, as it was given.
    pub path: PathBuf,
    /// The 1-based line and column (in characters) of the problem, when it is tied to a place in the file.
    pub position: Option<(usize, usize)>,
    /// The dotted key the problem is about (`axes.X`, `machine.reset_gcodes[1]`), when there is one.
    pub key: Option<String>,
    /// What is wrong, without the file name, position or key.
    pub message: String,
    /// The underlying I/O error when the file could not be read.
    io_error: Option<std::io::Error>,
}

impl fmt::Display for ConfigError {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(formatter, "{}", self.path.display())?;
        if let Some((line, column)) = self.position {
            write!(formatter, ":{line}:{column}")?;
        }
        if let Some(key) = &self.key {
            write!(formatter, ": key `{key}`")?;
        }
        write!(formatter, ": {}", self.message)
    }
}

impl std::error::Error for ConfigError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        self.io_error
            .as_ref()
            .map(|error| error as &(dyn std::error::Error + 'static))
    }
}

/// Walks up from `start_dir` (the folder of a program) to the filesystem root and returns the first
/// `sinumerik.toml` found, so one file at the top of a project serves all its subfolders.
pub fn discover_config_file(start_dir: &Path) -> Option<PathBuf> {
    // A relative folder is made absolute first; otherwise the walk would stop at the current folder
    // instead of reaching the root. The empty path is what `Path::parent` gives for a bare file name.
    let start_dir = if start_dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        start_dir
    };
    let start_dir = std::path::absolute(start_dir).unwrap_or_else(|_| start_dir.to_path_buf());
    start_dir
        .ancestors()
        .map(|folder| folder.join(CONFIG_FILE_NAME))
        .find(|candidate| candidate.is_file())
}

/// Reads and parses a configuration file.
pub fn load_config_file(path: &Path) -> Result<MachineConfig, ConfigError> {
    let bytes = std::fs::read(path).map_err(|io_error| ConfigError {
        path: path.to_path_buf(),
        position: None,
        key: None,
        message: format!("cannot read the file: {io_error}"),
        io_error: Some(io_error),
    })?;
    match std::str::from_utf8(&bytes) {
        Ok(text) => parse_config_text(text, path),
        Err(utf8_error) => {
            // TOML is UTF-8 by definition; pointing at the first bad byte saves the user a hex editor.
            let valid_text =
                std::str::from_utf8(&bytes[..utf8_error.valid_up_to()]).unwrap_or_default();
            Err(ConfigError {
                path: path.to_path_buf(),
                position: Some(position_of(valid_text, valid_text.len())),
                key: None,
                message: "the file is not valid UTF-8 (TOML files must be UTF-8)".to_string(),
                io_error: None,
            })
        }
    }
}

/// Parses the text of a configuration file; `path` only names the file in error messages.
pub fn parse_config_text(text: &str, path: &Path) -> Result<MachineConfig, ConfigError> {
    // The document is parsed twice: once into a tree that keeps the position of every key, used only
    // to place error messages, and once by serde into the raw structs, which rejects unknown keys and
    // wrong types. The files are tiny, so clarity wins over the second pass.
    let document = match DeTable::parse(text) {
        Ok(document) => document.into_inner(),
        Err(toml_error) => {
            return Err(ConfigError {
                path: path.to_path_buf(),
                position: toml_error.span().map(|span| position_of(text, span.start)),
                key: None,
                message: format!("invalid TOML: {}", toml_error.message()),
                io_error: None,
            })
        }
    };
    let locator = KeyLocator::new(&document);
    let raw_config: RawConfig = toml::from_str(text).map_err(|toml_error| {
        let key_path = toml_error
            .span()
            .and_then(|span| locator.path_at(span.start));
        ConfigError {
            path: path.to_path_buf(),
            position: toml_error.span().map(|span| position_of(text, span.start)),
            key: key_path.map(|key_path| display_key_path(&key_path)),
            message: describe_serde_message(toml_error.message()),
            io_error: None,
        }
    })?;
    raw_config.into_machine_config().map_err(|invalid| {
        let span = locator.span_of(&invalid.key_path, invalid.is_about_key);
        ConfigError {
            path: path.to_path_buf(),
            position: span.map(|span| position_of(text, span.start)),
            key: Some(display_key_path(&invalid.key_path)),
            message: invalid.message,
            io_error: None,
        }
    })
}

/// The file as written, before validation. Every field is optional so that a missing key keeps the
/// default of the machine kind, and `deny_unknown_fields` turns a misspelt key into an error.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawConfig {
    #[serde(default)]
    machine: RawMachine,
    axes: Option<BTreeMap<String, String>>,
    #[serde(default)]
    diagnostics: BTreeMap<String, String>,
    #[serde(default)]
    check: RawCheck,
    #[serde(default)]
    offsets: BTreeMap<String, BTreeMap<String, f64>>,
    #[serde(default)]
    execution: super::execution::RawExecution,
    #[serde(default)]
    cycles: super::cycles::RawCycles,
    #[serde(default)]
    contours: super::contours::RawContours,
    #[serde(default)]
    timing: super::timing::RawTiming,
}

/// The `[machine]` table. Numbers are read as `i64` and range-checked here, which gives a clearer
/// message than an integer overflow reported by serde.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawMachine {
    kind: Option<String>,
    units: Option<String>,
    reset_gcodes: Option<Vec<String>>,
    circle_error_const: Option<f64>,
    circle_error_factor: Option<f64>,
    max_skip_level: Option<i64>,
    max_block_length: Option<i64>,
    r_parameters: Option<i64>,
    frame_offset_incr_prog: Option<i64>,
    mm_frame_fine_trans: Option<i64>,
    modulo_range_error: Option<i64>,
}

/// The `[check]` table.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawCheck {
    extensions: Option<Vec<String>>,
}

/// One step of a key path: a table key or an index into an array.
#[derive(Debug, Clone, PartialEq, Eq)]
enum KeySegment {
    Key(String),
    Index(usize),
}

/// A value that passed the TOML types but is not allowed, with the key it belongs to.
struct InvalidValue {
    key_path: Vec<KeySegment>,
    message: String,
    /// Whether the key itself is wrong (an unknown code, a bad axis name) rather than its value, which
    /// decides where the position in the message points.
    is_about_key: bool,
}

fn invalid(key_path: &[KeySegment], message: String) -> InvalidValue {
    InvalidValue {
        key_path: key_path.to_vec(),
        message,
        is_about_key: false,
    }
}

fn invalid_key(key_path: &[KeySegment], message: String) -> InvalidValue {
    InvalidValue {
        is_about_key: true,
        ..invalid(key_path, message)
    }
}

fn key(name: &str) -> KeySegment {
    KeySegment::Key(name.to_string())
}

impl RawConfig {
    fn into_machine_config(self) -> Result<MachineConfig, InvalidValue> {
        let machine = self.machine;
        let kind = match &machine.kind {
            None => MachineKind::Mill,
            Some(text) => match text.to_ascii_lowercase().as_str() {
                "mill" => MachineKind::Mill,
                "turn" => MachineKind::Turn,
                _ => {
                    return Err(invalid(
                        &[key("machine"), key("kind")],
                        format!("unknown machine kind {text:?} (expected mill or turn)"),
                    ))
                }
            },
        };
        let mut config = MachineConfig::for_kind(kind);

        if let Some(text) = &machine.units {
            config.metric = match text.to_ascii_lowercase().as_str() {
                "mm" => true,
                "inch" => false,
                _ => {
                    return Err(invalid(
                        &[key("machine"), key("units")],
                        format!("unknown unit system {text:?} (expected mm or inch)"),
                    ))
                }
            };
        }

        if let Some(reset_gcodes) = &machine.reset_gcodes {
            let mut names = Vec::with_capacity(reset_gcodes.len());
            for (index, name) in reset_gcodes.iter().enumerate() {
                let key_path = [
                    key("machine"),
                    key("reset_gcodes"),
                    KeySegment::Index(index),
                ];
                if name.is_empty()
                    || !name
                        .chars()
                        .all(|character| character.is_ascii_alphanumeric())
                {
                    return Err(invalid(
                        &key_path,
                        format!("{name:?} is not a G function name (expected letters and digits, like \"G18\" or \"DIAMON\")"),
                    ));
                }
                names.push(name.to_ascii_uppercase());
            }
            config.reset_gcodes = names;
        }

        if let Some(value) = machine.circle_error_const {
            if !(value.is_finite() && value > 0.0) {
                return Err(invalid(
                    &[key("machine"), key("circle_error_const")],
                    format!("must be a number greater than 0 (in mm), found {value}"),
                ));
            }
            config.circle_error_const = value;
        }

        if let Some(value) = machine.circle_error_factor {
            if !(value.is_finite() && value >= 0.0) {
                return Err(invalid(
                    &[key("machine"), key("circle_error_factor")],
                    format!("must be a number of 0 or greater, found {value}"),
                ));
            }
            config.circle_error_factor = value;
        }

        if let Some(value) = machine.max_skip_level {
            config.max_skip_level = u8::try_from(value)
                .ok()
                .filter(|level| *level <= 9)
                .ok_or_else(|| {
                    invalid(
                        &[key("machine"), key("max_skip_level")],
                        format!("must be a whole number from 0 to 9, found {value}"),
                    )
                })?;
        }

        if let Some(value) = machine.max_block_length {
            config.max_block_length = usize::try_from(value)
                .ok()
                .filter(|length| *length > 0)
                .ok_or_else(|| {
                    invalid(
                        &[key("machine"), key("max_block_length")],
                        format!("must be a whole number greater than 0, found {value}"),
                    )
                })?;
        }

        if let Some(value) = machine.r_parameters {
            config.r_parameters_configured = true;
            config.r_parameter_count = u32::try_from(value).map_err(|_| {
                invalid(
                    &[key("machine"), key("r_parameters")],
                    format!(
                        "must be a whole number from 0 to {}, found {value}",
                        u32::MAX
                    ),
                )
            })?;
        }

        if let Some(value) = machine.frame_offset_incr_prog {
            config.frame_offset_incr_prog = match value {
                0 => false,
                1 => true,
                _ => {
                    return Err(invalid(
                        &[key("machine"), key("frame_offset_incr_prog")],
                        format!("must be 0 or 1 (SD42440), found {value}"),
                    ))
                }
            };
        }

        if let Some(value) = machine.mm_frame_fine_trans {
            config.frame_fine_trans = match value {
                0 => false,
                1 => true,
                _ => {
                    return Err(invalid(
                        &[key("machine"), key("mm_frame_fine_trans")],
                        format!("must be 0 or 1 (MD18600), found {value}"),
                    ))
                }
            };
        }

        if let Some(value) = machine.modulo_range_error {
            config.modulo_range_error = match value {
                0 => false,
                1 => true,
                _ => {
                    return Err(invalid(
                        &[key("machine"), key("modulo_range_error")],
                        format!("must be 0 or 1 (MD30455 bit 0), found {value}"),
                    ))
                }
            };
        }

        if let Some(axes) = &self.axes {
            config.axes = convert_axes(axes)?;
        }

        for (name, values) in &self.offsets {
            let key_path = [key("offsets"), key(name)];
            let index = settable_frame_index(name).ok_or_else(|| {
                invalid_key(
                    &key_path,
                    format!("{name:?} is not a settable work offset (expected G500, G54 to G57 or G505 to G599)"),
                )
            })?;
            let mut axes = Vec::with_capacity(values.len());
            for (axis_name, value) in values {
                let axis_path = [key("offsets"), key(name), key(axis_name)];
                let Some(axis) = config.axis(axis_name) else {
                    return Err(invalid_key(
                        &axis_path,
                        format!("{axis_name:?} is not an axis of this machine"),
                    ));
                };
                if !value.is_finite() {
                    return Err(invalid(
                        &axis_path,
                        format!("must be a finite number, found {value}"),
                    ));
                }
                if axes.iter().any(|(name, _)| *name == axis.name) {
                    return Err(invalid_key(
                        &axis_path,
                        format!(
                            "axis {} is listed twice (axis names are not case-sensitive)",
                            axis.name
                        ),
                    ));
                }
                axes.push((axis.name.clone(), *value));
            }
            // In the order of the configured axes, as everywhere else.
            axes.sort_by_key(|(name, _)| config.axes.iter().position(|axis| axis.name == *name));
            if config.settable_offsets.insert(index, axes).is_some() {
                return Err(invalid_key(
                    &key_path,
                    format!("offset {name} is listed twice (names are not case-sensitive)"),
                ));
            }
        }

        for (code_text, severity_text) in &self.diagnostics {
            let key_path = [key("diagnostics"), key(code_text)];
            let code = Code::parse(code_text).ok_or_else(|| {
                invalid_key(
                    &key_path,
                    format!("unknown diagnostic code {code_text:?} (codes look like \"S101\")"),
                )
            })?;
            let severity = Severity::parse(severity_text).ok_or_else(|| {
                invalid(
                    &key_path,
                    format!("unknown severity {severity_text:?} (expected error, warning, info or hint)"),
                )
            })?;
            if config.severity_overrides.insert(code, severity).is_some() {
                return Err(invalid_key(
                    &key_path,
                    format!("code {code} is listed twice (codes are not case-sensitive)"),
                ));
            }
        }

        if let Some(extensions) = &self.check.extensions {
            if extensions.is_empty() {
                return Err(invalid(
                    &[key("check"), key("extensions")],
                    "list at least one extension, like [\"mpf\", \"spf\"]".to_string(),
                ));
            }
            let mut normalized = Vec::with_capacity(extensions.len());
            for (index, extension) in extensions.iter().enumerate() {
                let is_plain = !extension.is_empty()
                    && !extension.contains(['.', '/', '\\'])
                    && !extension.chars().any(char::is_whitespace);
                if !is_plain {
                    return Err(invalid(
                        &[key("check"), key("extensions"), KeySegment::Index(index)],
                        format!("{extension:?} is not a file extension (write it without the dot, like \"mpf\")"),
                    ));
                }
                normalized.push(extension.to_ascii_lowercase());
            }
            config.extensions = normalized;
        }

        config.execution = self
            .execution
            .convert()
            .map_err(|(name, message)| invalid(&[key("execution"), key(name)], message))?;
        config.cycles = self
            .cycles
            .convert()
            .map_err(|(name, message)| invalid(&[key("cycles"), key(name)], message))?;
        config.contours = self
            .contours
            .convert()
            .map_err(|(name, message)| invalid(&[key("contours"), key(name)], message))?;
        config.timing = self
            .timing
            .convert(&config.axes)
            .map_err(|(path, message)| {
                let keys: Vec<KeySegment> = std::iter::once(key("timing"))
                    .chain(path.iter().map(|name| key(name)))
                    .collect();
                invalid(&keys, message)
            })?;
        Ok(config)
    }
}

/// The `$P_UIFR` index of a settable work offset by its G function: G500 is 0, G54 to G57 are 1 to 4,
/// G505 to G599 are 5 to 99.
fn settable_frame_index(name: &str) -> Option<u8> {
    let digits = name.strip_prefix(['G', 'g'])?;
    if digits.is_empty() || !digits.bytes().all(|byte| byte.is_ascii_digit()) || digits.len() > 3 {
        return None;
    }
    match digits.parse::<u16>().ok()? {
        500 => Some(0),
        number @ 54..=57 => Some((number - 53) as u8),
        number @ 505..=599 => Some((number - 500) as u8),
        _ => None,
    }
}

/// Validates the `[axes]` table and orders it geometry axes first.
fn convert_axes(raw_axes: &BTreeMap<String, String>) -> Result<Vec<Axis>, InvalidValue> {
    if raw_axes.is_empty() {
        return Err(invalid(
            &[key("axes")],
            "no axes listed; list at least one axis or remove the [axes] table to keep the defaults".to_string(),
        ));
    }
    let mut axes: Vec<Axis> = Vec::with_capacity(raw_axes.len());
    for (name, kind_text) in raw_axes {
        let key_path = [key("axes"), key(name)];
        let mut characters = name.chars();
        let is_valid_name = name.len() <= 8
            && characters
                .next()
                .is_some_and(|first| first.is_ascii_alphabetic())
            && characters.all(|character| character.is_ascii_alphanumeric() || character == '_');
        if !is_valid_name {
            return Err(invalid_key(
                &key_path,
                format!("{name:?} is not an axis name (1 to 8 letters, digits or underscores, starting with a letter)"),
            ));
        }
        let kind = match kind_text.to_ascii_lowercase().as_str() {
            "linear" => AxisKind::Linear,
            "transverse" => AxisKind::Transverse,
            "rotary" => AxisKind::Rotary,
            "modulo" => AxisKind::Modulo,
            _ => {
                return Err(invalid(
                    &key_path,
                    format!("unknown axis kind {kind_text:?} (expected linear, transverse, rotary or modulo)"),
                ))
            }
        };
        let name = name.to_ascii_uppercase();
        if axes.iter().any(|axis| axis.name == name) {
            return Err(invalid_key(
                &key_path,
                format!("axis {name} is listed twice (axis names are not case-sensitive)"),
            ));
        }
        axes.push(Axis { name, kind });
    }
    // The geometry axes come first because the rest of the product reads the first axes as the
    // geometry axes; TOML tables carry no order, so the other axes are sorted for determinism.
    axes.sort_by_key(|axis| {
        let geometry_rank = ["X", "Y", "Z"]
            .iter()
            .position(|geometry| *geometry == axis.name)
            .unwrap_or(3);
        (geometry_rank, axis.name.clone())
    });
    Ok(axes)
}

/// Finds keys by position and positions by key in the parsed document, so that errors from serde (which
/// only know a byte span) and from validation (which only know a key) both get a key and a position.
struct KeyLocator {
    entries: Vec<LocatedEntry>,
}

/// One key or array element of the document with the spans of its key and its value.
struct LocatedEntry {
    key_path: Vec<KeySegment>,
    key_span: Option<Range<usize>>,
    value_span: Range<usize>,
}

impl KeyLocator {
    fn new(document: &DeTable<'_>) -> KeyLocator {
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
    fn path_at(&self, offset: usize) -> Option<Vec<KeySegment>> {
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
    fn span_of(&self, key_path: &[KeySegment], is_about_key: bool) -> Option<Range<usize>> {
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

fn display_key_path(key_path: &[KeySegment]) -> String {
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
fn describe_serde_message(message: &str) -> String {
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
fn position_of(text: &str, offset: usize) -> (usize, usize) {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<MachineConfig, ConfigError> {
        parse_config_text(text, Path::new("sinumerik.toml"))
    }

    fn error_of(text: &str) -> ConfigError {
        match parse(text) {
            Ok(config) => panic!("expected an error for {text:?}, got {config:?}"),
            Err(error) => error,
        }
    }

    fn axis_list(config: &MachineConfig) -> Vec<(String, AxisKind)> {
        config
            .axes
            .iter()
            .map(|axis| (axis.name.clone(), axis.kind))
            .collect()
    }

    #[test]
    fn empty_file_gives_mill_defaults() {
        assert_eq!(parse("").unwrap(), MachineConfig::mill());
        assert_eq!(
            parse("# only a comment\n\n").unwrap(),
            MachineConfig::mill()
        );
        assert_eq!(parse("[machine]\n").unwrap(), MachineConfig::mill());
    }

    #[test]
    fn turn_kind_gives_lathe_defaults() {
        let config = parse("[machine]\nkind = \"turn\"\n").unwrap();
        assert_eq!(config, MachineConfig::turn());
        assert_eq!(config.reset_gcodes, vec!["G18", "DIAMON"]);
        assert_eq!(config.axis("X").unwrap().kind, AxisKind::Transverse);
    }

    #[test]
    fn every_key_overrides_the_kind_defaults() {
        let text = r#"
[machine]
kind = "Turn"
units = "inch"
reset_gcodes = ["g18", "DIAMON", "G95"]
circle_error_const = 0.05
circle_error_factor = 0
max_skip_level = 7
max_block_length = 200
r_parameters = 300

[axes]
c = "modulo"
X = "transverse"
z = "linear"
B1 = "rotary"

[diagnostics]
S120 = "error"
s163 = "Hint"

[check]
extensions = ["MPF", "spf", "nc"]
"#;
        let config = parse(text).unwrap();
        assert_eq!(config.kind, MachineKind::Turn);
        assert!(!config.metric);
        assert_eq!(config.reset_gcodes, vec!["G18", "DIAMON", "G95"]);
        assert_eq!(config.circle_error_const, 0.05);
        assert_eq!(config.circle_error_factor, 0.0);
        assert_eq!(config.max_skip_level, 7);
        assert_eq!(config.max_block_length, 200);
        assert_eq!(config.r_parameter_count, 300);
        assert_eq!(
            axis_list(&config),
            vec![
                ("X".to_string(), AxisKind::Transverse),
                ("Z".to_string(), AxisKind::Linear),
                ("B1".to_string(), AxisKind::Rotary),
                ("C".to_string(), AxisKind::Modulo),
            ]
        );
        assert_eq!(config.severity_of(Code::NameReadAsCall), Severity::Error);
        assert_eq!(config.severity_of(Code::BlockTooLong), Severity::Hint);
        assert_eq!(
            config.severity_of(Code::UnexpectedCharacter),
            Severity::Error
        );
        assert_eq!(config.extensions, vec!["mpf", "spf", "nc"]);
    }

    #[test]
    fn geometry_axes_come_first() {
        let config = parse("[axes]\nA = \"modulo\"\nZ = \"linear\"\nY = \"linear\"\nU = \"linear\"\nX = \"linear\"\n").unwrap();
        let names: Vec<&str> = config.axes.iter().map(|axis| axis.name.as_str()).collect();
        assert_eq!(names, vec!["X", "Y", "Z", "A", "U"]);
    }

    #[test]
    fn inline_and_dotted_tables_are_accepted() {
        let config = parse("machine = { kind = \"turn\" }\naxes.X = \"linear\"\n").unwrap();
        assert_eq!(config.kind, MachineKind::Turn);
        assert_eq!(
            axis_list(&config),
            vec![("X".to_string(), AxisKind::Linear)]
        );
    }

    #[test]
    fn syntax_error_names_line_and_column() {
        let error = error_of("[machine]\nkind = \"turn\n");
        assert_eq!(error.key, None);
        assert_eq!(error.position.map(|(line, _)| line), Some(2));
        let message = error.to_string();
        assert!(message.starts_with("sinumerik.toml:2:"), "{message}");
        assert!(message.contains("invalid TOML"), "{message}");

        let error = error_of("[machine]\nkind = \"mill\"\n[machine]\n");
        assert!(
            error.to_string().starts_with("sinumerik.toml:3:"),
            "{error}"
        );
    }

    #[test]
    fn misspelt_key_is_named() {
        let error = error_of("[machine]\nkinds = \"turn\"\n");
        assert_eq!(error.key.as_deref(), Some("machine.kinds"));
        assert_eq!(error.position, Some((2, 1)));
        let message = error.to_string();
        assert!(message.contains("key `machine.kinds`"), "{message}");
        assert!(message.contains("unknown key"), "{message}");
        assert!(message.contains("`kind`"), "{message}");

        let error = error_of("[axis]\nX = \"linear\"\n");
        assert_eq!(error.key.as_deref(), Some("axis"));
        assert!(error.to_string().contains("unknown key `axis`"), "{error}");

        let error = error_of("[check]\nextension = [\"mpf\"]\n");
        assert_eq!(error.key.as_deref(), Some("check.extension"));
    }

    #[test]
    fn wrong_type_is_named_in_toml_words() {
        let error = error_of("[machine]\nmax_skip_level = \"9\"\n");
        assert_eq!(error.key.as_deref(), Some("machine.max_skip_level"));
        assert_eq!(error.position, Some((2, 18)));
        assert!(error.message.contains("expected a whole number"), "{error}");

        let error = error_of("machine = 3\n");
        assert_eq!(error.key.as_deref(), Some("machine"));
        assert!(error.message.contains("expected a table"), "{error}");
        assert!(!error.message.contains("Raw"), "{error}");

        let error = error_of("[machine]\nreset_gcodes = [\"G18\", 3]\n");
        assert_eq!(error.key.as_deref(), Some("machine.reset_gcodes[1]"));

        let error = error_of("[axes]\nX = 1\n");
        assert_eq!(error.key.as_deref(), Some("axes.X"));
        assert!(error.message.contains("expected a string"), "{error}");
    }

    #[test]
    fn unknown_axis_kind_is_named() {
        let error = error_of("[axes]\nX = \"lineer\"\n");
        assert_eq!(
            error.to_string(),
            "sinumerik.toml:2:5: key `axes.X`: unknown axis kind \"lineer\" (expected linear, transverse, rotary or modulo)"
        );
    }

    #[test]
    fn bad_axis_names_are_named() {
        for name in ["1X", "ABCDEFGHI", "X-1", "\"\"", "_X", "\"Ä\""] {
            let error = error_of(&format!("[axes]\n{name} = \"linear\"\n"));
            assert!(
                error.key.as_deref().unwrap().starts_with("axes."),
                "{error}"
            );
            assert!(
                error.message.contains("is not an axis name"),
                "{name}: {error}"
            );
        }
        let error = error_of("[axes]\nx = \"linear\"\nX = \"rotary\"\n");
        assert!(error.message.contains("listed twice"), "{error}");
        assert_eq!(error.position.map(|(_, column)| column), Some(1));
        let error = error_of("[axes]\n");
        assert_eq!(error.key.as_deref(), Some("axes"));
        assert_eq!(error.position, Some((1, 1)));
    }

    #[test]
    fn bad_machine_values_are_named() {
        let cases = [
            ("kind = \"lathe\"", "machine.kind", "mill or turn"),
            ("units = \"cm\"", "machine.units", "mm or inch"),
            (
                "reset_gcodes = [\"G18\", \"G 17\"]",
                "machine.reset_gcodes[1]",
                "not a G function name",
            ),
            (
                "reset_gcodes = [\"\"]",
                "machine.reset_gcodes[0]",
                "not a G function name",
            ),
            (
                "circle_error_const = 0",
                "machine.circle_error_const",
                "greater than 0",
            ),
            (
                "circle_error_const = nan",
                "machine.circle_error_const",
                "greater than 0",
            ),
            (
                "circle_error_factor = -0.1",
                "machine.circle_error_factor",
                "0 or greater",
            ),
            (
                "max_skip_level = 10",
                "machine.max_skip_level",
                "from 0 to 9",
            ),
            (
                "max_skip_level = -1",
                "machine.max_skip_level",
                "from 0 to 9",
            ),
            (
                "max_block_length = 0",
                "machine.max_block_length",
                "greater than 0",
            ),
            ("r_parameters = -5", "machine.r_parameters", "from 0 to"),
        ];
        for (line, expected_key, expected_text) in cases {
            let error = error_of(&format!("[machine]\n{line}\n"));
            assert_eq!(error.key.as_deref(), Some(expected_key), "{line}: {error}");
            assert_eq!(
                error.position.map(|(line, _)| line),
                Some(2),
                "{line}: {error}"
            );
            let message = error.to_string();
            assert!(
                message.contains(&format!("key `{expected_key}`")),
                "{message}"
            );
            assert!(message.contains(expected_text), "{message}");
        }
    }

    #[test]
    fn bad_diagnostics_are_named() {
        let error = error_of("[diagnostics]\nS999 = \"error\"\n");
        assert_eq!(error.key.as_deref(), Some("diagnostics.S999"));
        assert_eq!(error.position, Some((2, 1)));
        assert!(error.message.contains("unknown diagnostic code"), "{error}");

        let error = error_of("[diagnostics]\nS101 = \"off\"\n");
        assert_eq!(error.key.as_deref(), Some("diagnostics.S101"));
        assert!(
            error.message.contains("unknown severity \"off\""),
            "{error}"
        );

        let error = error_of("[diagnostics]\nS101 = \"error\"\ns101 = \"hint\"\n");
        assert!(error.message.contains("listed twice"), "{error}");
    }

    #[test]
    fn r_parameters_and_modulo_range_error_are_marked_as_configured() {
        let config = parse("[machine]\nr_parameters = 300\nmodulo_range_error = 1\n").unwrap();
        assert!(config.r_parameters_configured && config.modulo_range_error);
        let default = parse("[machine]\n").unwrap();
        assert!(!default.r_parameters_configured && !default.modulo_range_error);
        let error = error_of("[machine]\nmodulo_range_error = 2\n");
        assert_eq!(error.key.as_deref(), Some("machine.modulo_range_error"));
    }

    #[test]
    fn settable_offsets_and_sd42440_are_read() {
        let config = parse(
            "[machine]\nframe_offset_incr_prog = 0\nmm_frame_fine_trans = 1\n[offsets]\nG54 = { x = 100, Y = 50.5 }\ng505 = { A = 90 }\nG500 = {}\n",
        )
        .unwrap();
        assert!(!config.frame_offset_incr_prog);
        assert!(config.frame_fine_trans);
        assert_eq!(
            config.settable_offset(1),
            Some(&[("X".to_string(), 100.0), ("Y".to_string(), 50.5)][..])
        );
        assert_eq!(
            config.settable_offset(5),
            Some(&[("A".to_string(), 90.0)][..])
        );
        assert_eq!(config.settable_offset(0), Some(&[][..]));
        assert_eq!(config.settable_offset(2), None);
        assert!(MachineConfig::mill().frame_offset_incr_prog);
        assert_eq!(MachineConfig::mill().settable_offset(0), Some(&[][..]));
    }

    #[test]
    fn bad_offsets_are_named() {
        let error = error_of("[offsets]\nG58 = { X = 1 }\n");
        assert_eq!(error.key.as_deref(), Some("offsets.G58"));
        assert!(
            error.message.contains("not a settable work offset"),
            "{error}"
        );
        let error = error_of("[offsets]\nG54 = { Q = 1 }\n");
        assert_eq!(error.key.as_deref(), Some("offsets.G54.Q"));
        assert!(error.message.contains("not an axis"), "{error}");
        let error = error_of("[offsets]\nG54 = { X = \"1\" }\n");
        assert_eq!(error.key.as_deref(), Some("offsets.G54.X"));
        let error = error_of("[offsets]\nG54 = { X = 1 }\ng54 = { X = 2 }\n");
        assert!(error.message.contains("listed twice"), "{error}");
        let error = error_of("[machine]\nframe_offset_incr_prog = 2\n");
        assert_eq!(error.key.as_deref(), Some("machine.frame_offset_incr_prog"));
        let error = error_of("[machine]\nmm_frame_fine_trans = -1\n");
        assert_eq!(error.key.as_deref(), Some("machine.mm_frame_fine_trans"));
    }

    #[test]
    fn bad_extensions_are_named() {
        let error = error_of("[check]\nextensions = []\n");
        assert_eq!(error.key.as_deref(), Some("check.extensions"));
        let error = error_of("[check]\nextensions = [\"mpf\", \".spf\"]\n");
        assert_eq!(error.key.as_deref(), Some("check.extensions[1]"));
        assert!(error.message.contains("without the dot"), "{error}");
    }

    #[test]
    fn positions_count_characters() {
        assert_eq!(position_of("ab\ncdé f", 8), (2, 5));
        assert_eq!(position_of("", 0), (1, 1));
        assert_eq!(position_of("é", 1), (1, 1));
        assert_eq!(position_of("abc", 99), (1, 4));
    }

    #[test]
    fn files_are_discovered_upwards_and_loaded() {
        let root =
            std::env::temp_dir().join(format!("sinumerik-config-test-{}", std::process::id()));
        let nested = root.join("a").join("b");
        std::fs::create_dir_all(&nested).unwrap();
        let config_path = root.join(CONFIG_FILE_NAME);
        std::fs::write(&config_path, "[machine]\nkind = \"turn\"\n").unwrap();

        let found = discover_config_file(&nested).unwrap();
        assert_eq!(found, std::path::absolute(&config_path).unwrap());
        assert_eq!(load_config_file(&found).unwrap(), MachineConfig::turn());

        std::fs::write(&config_path, b"kind = \"\xC4\"\n").unwrap();
        let error = load_config_file(&config_path).unwrap_err();
        assert!(error.to_string().contains("not valid UTF-8"), "{error}");
        assert_eq!(error.position, Some((1, 9)));

        let missing = load_config_file(&root.join("missing.toml")).unwrap_err();
        assert!(std::error::Error::source(&missing).is_some());
        assert!(
            missing
                .to_string()
                .contains("missing.toml: cannot read the file"),
            "{missing}"
        );

        std::fs::remove_dir_all(&root).unwrap();
    }
}
