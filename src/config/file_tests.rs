//! Tests of reading `sinumerik.toml`: defaults, every key, and the wording and position of every error.

use super::file_keys::position_of;
use super::{
    discover_config_file, load_config_file, parse_config_text, AxisKind, ConfigError,
    MachineConfig, MachineKind, CONFIG_FILE_NAME,
};
use crate::diagnostics::{Code, Severity};
use std::path::Path;

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
    let config = parse(
        "[axes]\nA = \"modulo\"\nZ = \"linear\"\nY = \"linear\"\nU = \"linear\"\nX = \"linear\"\n",
    )
    .unwrap();
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
    let root = std::env::temp_dir().join(format!("sinumerik-config-test-{}", std::process::id()));
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
