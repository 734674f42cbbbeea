//! The quick fixes that edit the machine configuration (the server in this process, files in a
//! temporary folder): DIAMON or G96 on a machine without a transverse axis (A235, A236) get
//! `kind = "turn"`, and an axis the machine does not have (S180) is added to `[axes]`. The workspace
//! edit creates `sinumerik.toml` next to the program when there is none, and otherwise edits the file
//! in use, keeping its other keys; applied, the configuration it gives removes the finding.

#[path = "support/lsp_client.rs"]
mod lsp_client;

use lsp_client::{apply_text_edits, file_uri, temp_folder, TestClient};
use serde_json::{json, Value};
use sinumerik_lsp::analysis::{diagnose_program, ProgramKind};
use sinumerik_lsp::config::{parse_config_text, AxisKind, MachineConfig, MachineKind};
use std::path::Path;

/// The code actions of the whole document `name` (written to `folder` with `text`) whose finding has
/// `code`.
async fn actions_for(
    client: &mut TestClient,
    folder: &Path,
    name: &str,
    text: &str,
    code: &str,
) -> Vec<Value> {
    let path = folder.join(name);
    std::fs::write(&path, text).unwrap();
    let uri = file_uri(&path);
    client.open(&uri, 1, text).await;
    let diagnostics = client.diagnostics(&uri, 1).await;
    assert!(
        diagnostics
            .iter()
            .any(|diagnostic| diagnostic["code"] == code),
        "{code} expected in {diagnostics:#?}"
    );
    let actions = client
        .request(
            "textDocument/codeAction",
            json!({"textDocument": {"uri": uri}, "range": {"start": {"line": 0, "character": 0}, "end": {"line": 100, "character": 0}}, "context": {"diagnostics": diagnostics}}),
        )
        .await
        .expect("code actions are answered");
    client
        .notify(
            "textDocument/didClose",
            json!({"textDocument": {"uri": uri}}),
        )
        .await;
    actions
        .as_array()
        .unwrap()
        .iter()
        .filter(|action| action["diagnostics"][0]["code"] == code)
        .cloned()
        .collect()
}

/// Applies the workspace edit of `action` to the configuration file `toml` (its text, `None` when it
/// does not exist): returns whether it created the file and the text after the edit.
fn apply_to_config(action: &Value, toml: &Path, text: Option<&str>) -> (bool, String) {
    let operations = action["edit"]["documentChanges"]
        .as_array()
        .expect("the fix is a workspace edit with documentChanges");
    let uri = file_uri(toml);
    let mut created = false;
    let mut result = text.map(str::to_string);
    for operation in operations {
        if operation["kind"] == "create" {
            assert_eq!(operation["uri"], uri.as_str());
            assert_eq!(operation["options"]["overwrite"], false);
            assert!(result.is_none(), "an existing file is never created");
            created = true;
            result = Some(String::new());
            continue;
        }
        assert_eq!(operation["textDocument"]["uri"], uri.as_str());
        let current = result.as_deref().expect("the file exists or was created");
        result = Some(apply_text_edits(
            current,
            operation["edits"].as_array().unwrap(),
        ));
    }
    (created, result.expect("the file is edited"))
}

/// The configuration the text gives.
fn config_of(text: &str) -> MachineConfig {
    parse_config_text(text, Path::new("sinumerik.toml"))
        .unwrap_or_else(|error| panic!("the edited file parses: {error}\n{text}"))
}

const LATHE_PROGRAM: &str = "G18 DIAMON\nG0 X20 Z5\nG96 S200 LIMS=3000\nG1 Z-10 F0.2\nM30\n";

#[tokio::test]
async fn diameter_programming_on_a_mill_configures_a_lathe() {
    let mut client = TestClient::in_process();
    client.initialize(json!({}), Value::Null).await;

    // Without a configuration file: it is created next to the program.
    let folder = temp_folder("config-fix-create");
    let toml = folder.join("sinumerik.toml");
    let actions = actions_for(&mut client, &folder, "PART.MPF", LATHE_PROGRAM, "A235").await;
    assert_eq!(actions.len(), 1, "{actions:#?}");
    assert!(actions[0]["title"]
        .as_str()
        .unwrap()
        .contains("kind = \"turn\""));
    let (created, text) = apply_to_config(&actions[0], &toml, None);
    assert!(created);
    assert_eq!(text, "[machine]\nkind = \"turn\"\n");
    let config = config_of(&text);
    let findings = diagnose_program(LATHE_PROGRAM, &config, ProgramKind::Main);
    assert!(
        findings
            .iter()
            .all(|item| !matches!(item.diagnostic.code.as_str(), "A235" | "A236")),
        "{findings:#?}"
    );

    // A file with other keys: kind is replaced, everything else stays.
    let folder = temp_folder("config-fix-edit");
    let toml = folder.join("sinumerik.toml");
    let existing = "# the shop's lathe\n[machine]\nkind = \"mill\" # to be checked\nunits = \"mm\"\nmax_skip_level = 7\n\n[diagnostics]\nS120 = \"error\"\n";
    std::fs::write(&toml, existing).unwrap();
    let actions = actions_for(&mut client, &folder, "PART.MPF", LATHE_PROGRAM, "A235").await;
    let (created, text) = apply_to_config(&actions[0], &toml, Some(existing));
    assert!(!created);
    assert_eq!(
        text,
        existing.replace("kind = \"mill\"", "kind = \"turn\""),
        "only the value of kind changes"
    );
    let config = config_of(&text);
    assert_eq!(config.kind, MachineKind::Turn);
    assert_eq!(config.max_skip_level, 7);

    // A file without [machine] (found in a parent folder): the table is added at its end.
    let folder = temp_folder("config-fix-parent");
    let toml = folder.join("sinumerik.toml");
    let existing = "[diagnostics]\nS120 = \"error\"\n";
    std::fs::write(&toml, existing).unwrap();
    let programs = folder.join("programs");
    std::fs::create_dir_all(&programs).unwrap();
    let program = "G18 G0 X20 Z5\nG96 S200 LIMS=3000\nG1 Z-10 F0.2\nM30\n";
    let actions = actions_for(&mut client, &programs, "PART.MPF", program, "A236").await;
    assert_eq!(actions.len(), 1, "G96 has the fix too: {actions:#?}");
    let (created, text) = apply_to_config(&actions[0], &toml, Some(existing));
    assert!(!created);
    assert!(text.starts_with(existing), "{text}");
    assert_eq!(config_of(&text).kind, MachineKind::Turn);
    assert!(!programs.join("sinumerik.toml").exists());
}

#[tokio::test]
async fn an_axis_the_machine_does_not_have_is_added_to_the_axes() {
    let mut client = TestClient::in_process();
    client.initialize(json!({}), Value::Null).await;
    let folder = temp_folder("config-fix-axis");
    let toml = folder.join("sinumerik.toml");
    let existing = "[machine]\nkind = \"turn\"\n";
    std::fs::write(&toml, existing).unwrap();
    let program = "G18 G0 X20 Z5\nG1 Y3 F100\nG1 Y4 B10\nM30\n";
    let actions = actions_for(&mut client, &folder, "PART.MPF", program, "S180").await;
    let titles: Vec<&str> = actions
        .iter()
        .map(|action| action["title"].as_str().unwrap())
        .collect();
    assert_eq!(titles.len(), 2, "one finding and fix per axis: {titles:?}");
    let y = actions
        .iter()
        .find(|action| action["title"].as_str().unwrap().contains(" Y "))
        .expect("a fix for Y");
    let (created, text) = apply_to_config(y, &toml, Some(existing));
    assert!(!created);
    assert!(text.starts_with(existing), "{text}");
    let config = config_of(&text);
    for (name, kind) in [
        ("X", AxisKind::Transverse),
        ("Z", AxisKind::Linear),
        ("C", AxisKind::Modulo),
        ("Y", AxisKind::Linear),
    ] {
        assert_eq!(
            config.axis(name).map(|axis| axis.kind),
            Some(kind),
            "{text}"
        );
    }
    let findings = diagnose_program(program, &config, ProgramKind::Main);
    let axes: Vec<&str> = findings
        .iter()
        .filter(|item| item.diagnostic.code.as_str() == "S180")
        .map(|item| item.diagnostic.message.as_str())
        .collect();
    assert_eq!(axes.len(), 1, "only B is left: {axes:?}");
    assert!(axes[0].starts_with("`B`"), "{axes:?}");
}
