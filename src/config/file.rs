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

use super::file_keys::{describe_serde_message, display_key_path, position_of, KeyLocator};
use super::machine::MachineConfig;
use super::raw::RawConfig;
use std::fmt;
use std::path::{Path, PathBuf};
use toml::de::DeTable;

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
