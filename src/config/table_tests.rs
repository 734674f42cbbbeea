//! Tests of the option tables (`[contours]`, `[cycles]`) read through the whole configuration file.

use crate::config::cycles::*;
use crate::config::parse_config_text;
use std::path::Path;

#[test]
fn contours_are_read_and_checked() {
    let config = parse_config_text(
        "[contours]\nmax_dummy_blocks = 5\nelement_with_preceding = true\nradius_name = \"radius\"\n",
        Path::new("sinumerik.toml"),
    )
    .expect("valid");
    assert_eq!(config.contours.max_dummy_blocks, 5);
    assert!(config.contours.element_with_preceding);
    assert_eq!(config.contours.radius_name, "RADIUS");
    assert_eq!(config.contours.angle_name, "ANG");
    for bad in [
        "[contours]\nmax_dummy_blocks = -1\n",
        "[contours]\nangle_name = \"1A\"\n",
        "[contours]\nunknown = 1\n",
    ] {
        let error = parse_config_text(bad, Path::new("sinumerik.toml")).unwrap_err();
        assert!(error.to_string().contains("contours"), "{error}");
    }
}

#[test]
fn the_cycles_table_sets_each_choice_and_rejects_unknown_values() {
    let config = parse_config_text(
        "[cycles]\nrestore_modal = false\nholes1_order = \"near_origin\"\ncycle801_order = \"unknown\"\n",
        Path::new("sinumerik.toml"),
    )
    .expect("a valid table");
    assert_eq!(
        config.cycles,
        CycleOptions {
            restore_modal: false,
            holes1_order: RowOrder::NearOrigin,
            cycle801_order: GridOrder::Unknown,
        }
    );
    let defaults = parse_config_text("", Path::new("sinumerik.toml")).expect("empty file");
    assert_eq!(defaults.cycles, CycleOptions::default());
    let error = parse_config_text(
        "[cycles]\nholes1_order = \"nearest\"\n",
        Path::new("sinumerik.toml"),
    )
    .expect_err("an unknown order");
    let text = error.to_string();
    assert!(
        text.contains("holes1_order") && text.contains("nearest"),
        "{text}"
    );
    assert!(parse_config_text("[cycles]\nsave = true\n", Path::new("sinumerik.toml")).is_err());
}
