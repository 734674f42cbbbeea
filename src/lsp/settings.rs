//! The server's settings (from `initializationOptions`, `workspace/configuration` and
//! `workspace/didChangeConfiguration`) and the machine configuration of each document
//! (`sinumerik.toml` from the document's folder upward, or the file the settings name).

use crate::config::{
    discover_config_file, load_config_file, ConfigError, MachineConfig, MachineKind,
};
use serde::Deserialize;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Which moving blocks get an inlay hint with their resolved end point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum InlayHintMode {
    Off,
    /// Only blocks whose end point is not plain to read from their words (the default).
    #[default]
    NotPlain,
    All,
}

/// Every setting the server reads. Unknown keys are ignored (clients send their whole section).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Settings {
    pub inlay_hints: InlayHintMode,
    /// One `sinumerik.toml` for every document instead of the nearest one (like `check --config`).
    pub config_file: Option<PathBuf>,
    /// The machine of documents without a `sinumerik.toml`: a mill (the default) or a lathe.
    pub machine_kind: MachineKind,
    /// Folders of cycles and subprograms outside the workspace folders that the index reads too.
    pub cycle_folders: Vec<PathBuf>,
    /// At most this many diagnostics are published per document (`publish/limit.rs`); `None`:
    /// all of them.
    pub max_diagnostics: Option<usize>,
}

impl Settings {
    /// Applies the settings in `value`, either the section itself or an object holding it under
    /// `sinumerik`. Returns a message for a value that could not be read; the other keys still apply.
    pub fn apply(&mut self, value: &Value) -> Result<(), String> {
        let section = value.get("sinumerik").unwrap_or(value);
        if section.is_null() {
            return Ok(());
        }
        let Value::Object(map) = section else {
            return Err(format!("settings must be an object, not {section}"));
        };
        let mut problems = Vec::new();
        for (key, value) in map {
            match key.as_str() {
                "inlayHints" => match serde_json::from_value::<InlayHintMode>(value.clone()) {
                    Ok(mode) => self.inlay_hints = mode,
                    Err(error) => problems.push(format!("setting `inlayHints`: {error}")),
                },
                "configFile" => match value {
                    Value::Null => self.config_file = None,
                    Value::String(path) if path.is_empty() => self.config_file = None,
                    Value::String(path) => self.config_file = Some(PathBuf::from(path)),
                    other => problems.push(format!(
                        "setting `configFile`: expected a path or null, not {other}"
                    )),
                },
                "machineKind" => match value.as_str() {
                    Some("mill") => self.machine_kind = MachineKind::Mill,
                    Some("turn") => self.machine_kind = MachineKind::Turn,
                    _ => problems.push(format!(
                        "setting `machineKind`: expected \"mill\" or \"turn\", not {value}"
                    )),
                },
                "cycleFolders" => {
                    match serde_json::from_value::<Option<Vec<PathBuf>>>(value.clone()) {
                        Ok(folders) => self.cycle_folders = folders.unwrap_or_default(),
                        Err(error) => problems.push(format!(
                            "setting `cycleFolders`: expected a list of paths: {error}"
                        )),
                    }
                }
                // Clients send their whole section; keys of other versions are not an error.
                "maxDiagnostics" => match value {
                    Value::Null => self.max_diagnostics = None,
                    // 0 means no limit, as null does.
                    Value::Number(number) if number.as_u64().is_some() => {
                        self.max_diagnostics = number
                            .as_u64()
                            .filter(|&limit| limit > 0)
                            .map(|limit| usize::try_from(limit).unwrap_or(usize::MAX));
                    }
                    other => problems.push(format!(
                        "setting `maxDiagnostics`: expected a whole number (0 or null: no limit), not {other}"
                    )),
                },
                _ => {}
            }
        }
        if problems.is_empty() {
            Ok(())
        } else {
            Err(problems.join("; "))
        }
    }
}

/// The machine configuration for a document at `path` (`None` for a document that is not a file).
/// A configuration file that cannot be used gives the defaults and the error, which the caller
/// reports: the document is still checked.
pub fn machine_config_for(
    path: Option<&Path>,
    settings: &Settings,
    workspace_root: Option<&Path>,
) -> (Arc<MachineConfig>, Option<ConfigError>) {
    let config_path = match &settings.config_file {
        Some(config_file) if config_file.is_relative() => Some(
            workspace_root
                .map(|root| root.join(config_file))
                .unwrap_or_else(|| config_file.clone()),
        ),
        Some(config_file) => Some(config_file.clone()),
        None => path.and_then(Path::parent).and_then(discover_config_file),
    };
    let without_file = || match settings.machine_kind {
        MachineKind::Mill => MachineConfig::mill(),
        MachineKind::Turn => MachineConfig::turn(),
    };
    match config_path.map(|config_path| load_config_file(&config_path)) {
        None => (Arc::new(without_file()), None),
        Some(Ok(config)) => (Arc::new(config), None),
        Some(Err(error)) => (Arc::new(without_file()), Some(error)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn settings_apply_flat_or_under_the_section() {
        let mut settings = Settings::default();
        assert_eq!(settings.inlay_hints, InlayHintMode::NotPlain);
        settings
            .apply(&json!({"sinumerik": {"inlayHints": "all"}}))
            .unwrap();
        assert_eq!(settings.inlay_hints, InlayHintMode::All);
        settings
            .apply(&json!({"inlayHints": "off", "configFile": "m.toml"}))
            .unwrap();
        assert_eq!(settings.inlay_hints, InlayHintMode::Off);
        assert_eq!(settings.config_file, Some(PathBuf::from("m.toml")));
        settings.apply(&json!({"configFile": null})).unwrap();
        assert_eq!(settings.config_file, None);
        assert_eq!(settings.machine_kind, MachineKind::Mill);
        settings.apply(&json!({"machineKind": "turn"})).unwrap();
        assert_eq!(settings.machine_kind, MachineKind::Turn);
        assert!(settings
            .apply(&json!({"machineKind": "mill-turn"}))
            .is_err());
        assert_eq!(settings.machine_kind, MachineKind::Turn);
    }

    #[test]
    fn the_machine_kind_decides_the_machine_of_documents_without_a_configuration_file() {
        let mut settings = Settings::default();
        let folder = std::env::temp_dir().join(format!(
            "sinumerik-settings-{}/no-config-here",
            std::process::id()
        ));
        let path = folder.join("a.mpf");
        let (config, error) = machine_config_for(Some(&path), &settings, None);
        assert!(error.is_none());
        assert_eq!(config.kind, MachineKind::Mill);
        settings.machine_kind = MachineKind::Turn;
        let (config, _) = machine_config_for(Some(&path), &settings, None);
        assert_eq!(*config, MachineConfig::turn());
    }

    #[test]
    fn a_bad_value_is_reported_and_the_rest_applies() {
        let mut settings = Settings::default();
        let error = settings
            .apply(&json!({"inlayHints": "sometimes", "configFile": "a.toml", "other": 1}))
            .unwrap_err();
        assert!(error.contains("inlayHints"), "{error}");
        assert_eq!(settings.inlay_hints, InlayHintMode::NotPlain);
        assert_eq!(settings.config_file, Some(PathBuf::from("a.toml")));
        assert!(settings.apply(&json!(42)).is_err());
    }

    #[test]
    fn the_diagnostics_limit_is_a_whole_number_and_zero_or_null_mean_none() {
        let mut settings = Settings::default();
        assert_eq!(settings.max_diagnostics, None);
        settings.apply(&json!({"maxDiagnostics": 1000})).unwrap();
        assert_eq!(settings.max_diagnostics, Some(1000));
        settings.apply(&json!({"maxDiagnostics": 0})).unwrap();
        assert_eq!(settings.max_diagnostics, None);
        settings.apply(&json!({"maxDiagnostics": 5})).unwrap();
        settings.apply(&json!({"maxDiagnostics": null})).unwrap();
        assert_eq!(settings.max_diagnostics, None);
        for bad in [json!(-1), json!(2.5), json!("1000")] {
            settings.max_diagnostics = Some(7);
            let error = settings
                .apply(&json!({ "maxDiagnostics": bad }))
                .unwrap_err();
            assert!(error.contains("maxDiagnostics"), "{error}");
            assert_eq!(
                settings.max_diagnostics,
                Some(7),
                "a bad value changes nothing"
            );
        }
    }
}
