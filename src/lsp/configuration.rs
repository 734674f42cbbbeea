//! The client's settings: asked with `workspace/configuration` (bounded by a timeout), applied to
//! the open documents and the index when they change, and the registration that makes the client
//! tell about changed program and configuration files.

use crate::lsp::locks::lock;
use crate::lsp::state::Shared;
use serde_json::Value;
use std::sync::Arc;
use std::time::Duration;
use tower_lsp_server::ls_types::{
    ConfigurationItem, DidChangeWatchedFilesRegistrationOptions, FileSystemWatcher, GlobPattern,
    Registration,
};

/// How long the server waits for the client's answer to `workspace/configuration`.
const CONFIGURATION_TIMEOUT: Duration = Duration::from_secs(10);

/// Sends `workspace/configuration` from a task of its own, bounded by a timeout, so no handler
/// waits for the client (a client that answers late cannot stall the server's input).
pub fn request_configuration(shared: &Arc<Shared>) {
    let shared = Arc::clone(shared);
    tokio::spawn(async move {
        let request = shared.client.configuration(vec![ConfigurationItem {
            scope_uri: None,
            section: Some("sinumerik".to_string()),
        }]);
        match tokio::time::timeout(CONFIGURATION_TIMEOUT, request).await {
            Ok(Ok(values)) => {
                if let Some(value) = values.first() {
                    apply_settings(&shared, value);
                }
            }
            Ok(Err(error)) => shared
                .outgoing
                .log_warning(format!("workspace/configuration failed: {error}")),
            Err(_) => shared.outgoing.log_warning(
                "the client did not answer workspace/configuration in time".to_string(),
            ),
        }
    });
}
/// Asks the client to tell about changed program files and configuration files.
pub fn watch_files(shared: &Shared) {
    let client = shared.client.clone();
    let outgoing = shared.outgoing.clone();
    tokio::spawn(async move {
        let watcher = |pattern: &str| FileSystemWatcher {
            glob_pattern: GlobPattern::String(pattern.to_string()),
            kind: None,
        };
        let options = DidChangeWatchedFilesRegistrationOptions {
            watchers: vec![
                watcher("**/*.{mpf,spf,def,MPF,SPF,DEF}"),
                watcher("**/sinumerik.toml"),
            ],
        };
        let registration = Registration {
            id: "sinumerik/watchedFiles".to_string(),
            method: "workspace/didChangeWatchedFiles".to_string(),
            register_options: serde_json::to_value(options).ok(),
        };
        if let Err(error) = client.register_capability(vec![registration]).await {
            outgoing.log_warning(format!("cannot watch the workspace's files: {error}"));
        }
    });
}

/// Applies new settings: documents whose configuration changed are analysed again.
pub fn apply_settings(shared: &Arc<Shared>, value: &Value) {
    let (old, new) = {
        let mut settings = lock(&shared.settings);
        let old = settings.clone();
        if let Err(message) = settings.apply(value) {
            shared.warn(format!("settings: {message}"));
        }
        (old, settings.clone())
    };
    if old.config_file != new.config_file || old.machine_kind != new.machine_kind {
        let context = shared.context();
        for document in shared.documents.all() {
            let config = shared.machine_config(document.path.as_deref());
            document.set_config(config, &context);
        }
    }
    if old.cycle_folders != new.cycle_folders {
        crate::lsp::workspace::updates::reindex(shared);
    }
    if old.max_diagnostics != new.max_diagnostics {
        let context = shared.context();
        for document in shared.documents.all() {
            document.republish(&context);
        }
    }
    if old.inlay_hints != new.inlay_hints && lock(&shared.info).refreshes_inlay_hints {
        let client = shared.client.clone();
        tokio::spawn(async move {
            let _ = client.inlay_hint_refresh().await;
        });
    }
}
