//! Tests that hold the generated `docent.yaml` schema to the reader: every mapping closed to
//! other keys, every key described, and, where a section's schema is placed by a hand-written
//! function (`Shape::Custom`), the same keys as the reader's unknown-key message lists.

use std::sync::Arc;

use super::*;
use crate::config::{Channel, MAX_PRIORITY, MAX_QUEUE_LIMIT};
use crate::config_file::parse_config;

/// The reader's key list at `path`, read from its unknown-key message (which lists every
/// key it knows there).
fn reader_keys(path: &[&str]) -> Vec<String> {
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
    let mut keys: Vec<String> = properties.keys().cloned().collect();
    keys.sort();
    keys
}

#[test]
fn sections_placed_by_hand_have_the_readers_keys() {
    let schema = config_schema();
    for (probe, path) in [
        (&[][..], &[][..]),
        (&["verbs", "LIGHTS"], &["verbs", "*"]),
        (&["channels", "speech"], &["channels", "*"]),
        (&["kiosk", "attract"], &["kiosk", "attract"]),
    ] {
        assert_eq!(
            schema_keys(&schema, path),
            reader_keys(probe),
            "section {probe:?}"
        );
    }
}

/// Every mapping in `schema` (at `at`) with its own keys: closed to others, each key
/// described, each required key one of them. Returns how many were seen.
fn walk(schema: &Value, at: &str) -> usize {
    let mut seen = 0;
    match schema {
        Value::Object(fields) => {
            if let Some(Value::Object(properties)) = fields.get("properties") {
                seen += 1;
                assert_eq!(fields["additionalProperties"], false, "{at}");
                for (key, value) in properties {
                    assert!(value["description"].is_string(), "{at}.{key}");
                }
                for key in fields
                    .get("required")
                    .and_then(Value::as_array)
                    .into_iter()
                    .flatten()
                {
                    let key = key.as_str().expect("a key");
                    assert!(properties.contains_key(key), "{at}: required {key}");
                }
            }
            for (key, value) in fields {
                seen += walk(value, &format!("{at}/{key}"));
            }
        }
        Value::Array(items) => {
            for (index, item) in items.iter().enumerate() {
                seen += walk(item, &format!("{at}/{index}"));
            }
        }
        _ => {}
    }
    seen
}

#[test]
fn every_section_rejects_other_keys_and_describes_its_own() {
    let schema = config_schema();
    // The top level, its 15 sections of settings, bounds, record limits, visitor groups, a
    // site command, a channel, a reaction, a rosbridge event, attract (thrice), an open entry,
    // a special day, the server's four limits and a language's kiosk shell words.
    assert_eq!(walk(&schema, ""), 33);
}

/// Figures that descriptions write out (they are `const` text) and the code holds.
#[test]
fn descriptions_name_the_codes_figures() {
    let schema = config_schema();
    let text = |path: &[&str]| {
        let mut node = &schema;
        for key in path {
            node = &node["properties"][*key];
        }
        node["description"].as_str().expect("described").to_owned()
    };
    let channels = text(&["channels"]);
    for channel in Channel::BUILT_IN {
        assert!(channels.contains(channel), "{channel}: {channels}");
    }
    let policy = &schema["properties"]["channels"]["additionalProperties"];
    let limit = policy["properties"]["queue_limit"]["description"].as_str();
    assert!(
        limit
            .expect("described")
            .ends_with(&format!("1 to {MAX_QUEUE_LIMIT}."))
    );
    for source in ["operator", "http", "dm", "kiosk"] {
        let priority = text(&["priorities", source]);
        assert!(
            priority.contains(&format!("to {MAX_PRIORITY}:")),
            "{priority}"
        );
    }
}

#[test]
fn whole_limits_are_written_as_whole_numbers() {
    assert_eq!(number(0.0), json!(0));
    assert_eq!(number(50.0), json!(50));
    assert_eq!(number(0.5), json!(0.5));
}
