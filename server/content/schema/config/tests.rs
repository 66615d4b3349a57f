//! Tests that hold the `docent.yaml` schema to the loader: the same keys in every section,
//! and no other keys accepted.

use std::sync::Arc;

use super::*;
use crate::config_file::parse_config;

/// The loader's key list at `path`, read from its unknown-key message (which lists every
/// key it knows there): the loader's own inline lists, without copying them.
fn loader_keys(path: &[&str]) -> Vec<String> {
    let mut yaml = String::new();
    for (depth, key) in path.iter().enumerate() {
        yaml.push_str(&format!("{}{key}:\n", "  ".repeat(depth)));
    }
    yaml.push_str(&format!("{}zz_probe: 1\n", "  ".repeat(path.len())));
    let file = parse_config(&Arc::from("docent.yaml"), yaml.as_bytes());
    let message = file
        .diagnostics
        .iter()
        .find(|d| d.code == "config-unknown-key")
        .map(|d| d.message.clone())
        .unwrap_or_else(|| panic!("no unknown-key problem for {path:?}: {yaml}"));
    let list = message
        .split_once("Known settings here: ")
        .map(|(_, rest)| rest.trim_end_matches('.'))
        .unwrap_or_else(|| panic!("no key list in {message}"));
    let mut keys: Vec<String> = list.split(", ").map(str::to_owned).collect();
    keys.sort();
    keys
}

fn schema_keys(schema: &Value, path: &[&str]) -> Vec<String> {
    let mut node = schema;
    for key in path {
        node = if *key == "*" {
            &node["additionalProperties"]
        } else {
            &node["properties"][*key]
        };
    }
    let properties = node["properties"].as_object().expect("a section");
    for (key, value) in properties {
        assert!(value["description"].is_string(), "{path:?}.{key}");
    }
    let mut keys: Vec<String> = properties.keys().cloned().collect();
    keys.sort();
    keys
}

#[test]
fn section_keys_are_the_loaders() {
    let schema = config_schema();
    for (probe, path) in [
        (&[][..], &[][..]),
        (&["speech"], &["speech"]),
        (&["display"], &["display"]),
        (&["drive"], &["drive"]),
        (&["drive", "bounds"], &["drive", "bounds"]),
        (&["adapters"], &["adapters"]),
        (&["kiosk"], &["kiosk"]),
        (&["projector"], &["projector"]),
        (&["captions"], &["captions"]),
        (&["access"], &["access"]),
        (&["operator"], &["operator"]),
        (&["server"], &["server"]),
        (&["mqtt"], &["mqtt"]),
        (
            &["operator", "visitor_groups"],
            &["operator", "visitor_groups"],
        ),
        (&["verbs", "LIGHTS"], &["verbs", "*"]),
        (&["channels", "speech"], &["channels", "*"]),
        (&["priorities"], &["priorities"]),
        (&["rosbridge"], &["rosbridge"]),
        (&["kiosk", "attract"], &["kiosk", "attract"]),
        (&["schedule"], &["schedule"]),
    ] {
        assert_eq!(
            schema_keys(&schema, path),
            loader_keys(probe),
            "section {probe:?}"
        );
    }
}

#[test]
fn every_section_rejects_other_keys() {
    let schema = config_schema();
    assert_eq!(schema["additionalProperties"], false);
    for key in TOP_KEYS {
        let section = &schema["properties"][*key];
        if section.get("properties").is_some() {
            assert_eq!(section["additionalProperties"], false, "{key}");
        }
    }
}
