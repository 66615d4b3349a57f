//! The acts file's schema: a list of acts, each a mapping of `Label`, `Text` and its variants,
//! `Cmds`, `Group`, `Key` and `Keywords`, nothing else (so a misspelt key is flagged where it is typed).

use serde_json::{Value, json};

use super::{DRAFT, words};
use crate::acts_file::KEYS;
use crate::model::{DEFAULT_VARIANT, Verb};

/// A variant key other than `Text` itself (which has its own entry): `Text` then letters,
/// digits or `_` in any alphabet, as the loader's `is_variant_key` accepts. `\p{...}` needs the
/// `u` flag, which ajv and yaml-language-server both set. Any variant, `Text` too, may end in
/// `@` and a language tag (`Text@de`, `TextChild@pt-br`): its translation.
const OTHER_VARIANT_PATTERN: &str = r"^Text(?:[\p{Alphabetic}\p{N}_]+(?:@[A-Za-z]{2,3}(?:-(?:[A-Za-z]{2}|[0-9]{3}|[A-Za-z]{4}))?)?|@[A-Za-z]{2,3}(?:-(?:[A-Za-z]{2}|[0-9]{3}|[A-Za-z]{4}))?)$";

/// The schema of an acts file (`acts.yaml`, `tour.yaml`, ...).
pub fn acts_schema() -> Value {
    let properties: serde_json::Map<String, Value> = KEYS
        .iter()
        .map(|key| ((*key).to_owned(), key_schema(key)))
        .collect();
    json!({
        "$schema": DRAFT,
        "title": "Docent acts file",
        "description": "A list of dialog acts. Each act starts with `- Label:` and says what \
                        the robot says (`Text`) and does (`Cmds`) when it is triggered.",
        "type": ["array", "null"],
        "items": {
            "type": "object",
            "description": "One dialog act: a unique `Label`, the texts to say (`Text`, and \
                            variants such as `TextChild`), the commands to run (`Cmds`), and \
                            for the operator console `Group` and `Key`.",
            "required": ["Label"],
            "properties": properties,
            "patternProperties": {
                OTHER_VARIANT_PATTERN: texts(
                    "A text variant: what the robot says instead of `Text` when the operator \
                     or a page has chosen this context (e.g. `TextChild` for children). One \
                     text, or a list of alternatives (one is picked at random, never the same \
                     twice in a row).",
                ),
            },
            "additionalProperties": false,
        },
        "definitions": { "command": command() },
    })
}

/// The schema of one of the loader's act keys (`acts_file::KEYS`).
fn key_schema(key: &str) -> Value {
    match key {
        "Label" => words(
            "The act's name, unique in the whole bundle, e.g. `WELCOME`. Pages trigger the act \
             with `data-act=\"WELCOME\"`, and the operator finds it by this name.",
        ),
        DEFAULT_VARIANT => texts(
            "What the robot says: one text, or a list of alternatives (one is picked at \
             random, never the same twice in a row). Put a text in quotes when it contains \
             `: ` or ` #`.",
        ),
        "Cmds" => json!({
            "description": "What the robot does, in order: one command or a list. Each \
                            starts with a command word in capitals, e.g. `DISPLAY_PAGE \
                            start.html`, `PROJECT painting.jpg`, `WAIT 2s`.",
            "anyOf": [
                { "type": "null" },
                { "$ref": "#/definitions/command" },
                { "type": "array", "items": { "$ref": "#/definitions/command" } },
            ],
        }),
        "Group" => words(
            "The heading the operator console lists this act under, e.g. `Small talk`. \
             Without it, the act is listed under its file's name.",
        ),
        "Key" => json!({
            "type": ["string", "integer"],
            "pattern": r"^\s*[A-Za-z0-9]\s*$",
            "minimum": 0,
            "maximum": 9,
            "description": "A shortcut for the operator console: one letter (A to Z) or \
                            digit (0 to 9). `Key: W` fires this act with Alt+W. Write only \
                            the letter, not `Alt+W`.",
            "examples": ["W", "1"],
        }),
        "Keywords" => {
            let one = words("One word (or a few) the operator may search this act by.");
            json!({
                "description": "Words the operator console's search also finds this act by, \
                                in any language: what the act means that it neither says nor \
                                shows, e.g. `Keywords: [film, video]` for an act projecting \
                                `card-punch.webm`. Never spoken.",
                "anyOf": [one, { "type": "array", "items": one }],
            })
        }
        // A key added to the loader without a schema here fails the tests (no description).
        _ => json!({}),
    }
}

/// A text variant's value: one text or a non-empty list of texts.
fn texts(description: &str) -> Value {
    let one = words("One text the robot says.");
    json!({
        "description": description,
        "anyOf": [one, { "type": "array", "minItems": 1, "items": one }],
    })
}

/// A command: a built-in verb with what it needs, or a capitalised site command.
fn command() -> Value {
    let mut branches: Vec<Value> = Verb::BUILT_IN.iter().map(verb_schema).collect();
    let built_in: Vec<&str> = Verb::BUILT_IN.iter().map(Verb::as_str).collect();
    branches.push(json!({
        "pattern": format!(r"^\s*(?!(?:{})(?:\s|$))[A-Z][A-Z0-9_]*(?:\s|$)", built_in.join("|")),
        "description": "A command of this site, declared in docent.yaml under `verbs:` \
                        (capital letters, digits and `_`). `docent check` tells whether it \
                        is declared.",
    }));
    json!({
        "type": "string",
        "description": format!(
            "A command: a word in capitals, then what it needs. Built in: {}; more can be \
             declared in docent.yaml under `verbs:`.",
            built_in.join(", ")
        ),
        "examples": Verb::BUILT_IN.iter().map(example).collect::<Vec<_>>(),
        "anyOf": branches,
    })
}

/// A built-in verb's branch: a pattern for the verb and the shape of its argument.
fn verb_schema(verb: &Verb) -> Value {
    let name = verb.as_str();
    let (argument, description) = match verb {
        Verb::Say => (r"\s+\S", "SAY text: say this text."),
        Verb::Project => (
            r"\s+\S",
            "PROJECT file: show a picture or video from the media folder on the projector.",
        ),
        Verb::DisplayPage => (
            r"\s+\S",
            "DISPLAY_PAGE file: show a page from the pages folder on the touchscreen.",
        ),
        Verb::SetWaypoint => (
            r"\s+\S",
            "SET_WAYPOINT x y [heading]: where the robot drives next, in metres on the map \
             (heading in degrees).",
        ),
        Verb::DriveStart => (r"\s*$", "DRIVE_START: drive to the waypoint."),
        Verb::DriveStop => (r"\s*$", "DRIVE_STOP: stop driving at once."),
        Verb::Wait => (
            r"(\s+(\d+(\.\d*)?|\.\d+)(ms|s|m|h))?\s*$",
            "WAIT: wait until the act's earlier commands are done; WAIT 2s: pause for a time \
             (ms, s, m or h).",
        ),
        Verb::Highlight => (
            r"(\s|$)",
            "HIGHLIGHT left top width height; ...: light areas of the projected picture; \
             HIGHLIGHT alone turns the light off.",
        ),
        Verb::Site(_) => (r"(\s|$)", "A command of this site."),
    };
    json!({ "pattern": format!(r"^\s*{name}{argument}"), "description": description })
}

/// A sample command for completion lists.
fn example(verb: &Verb) -> String {
    let argument = match verb {
        Verb::Say => " Welcome to the museum",
        Verb::Project => " painting.jpg",
        Verb::DisplayPage => " start.html",
        Verb::SetWaypoint => " 3.5 2",
        Verb::Wait => " 2s",
        Verb::Highlight => " 0.1 0.2 0.3 0.3",
        Verb::DriveStart | Verb::DriveStop | Verb::Site(_) => "",
    };
    format!("{}{argument}", verb.as_str())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_act_key_the_loader_knows_is_described_and_nothing_else_is_allowed() {
        let schema = acts_schema();
        let act = &schema["items"];
        let properties = act["properties"].as_object().expect("properties");
        let mut written: Vec<&str> = properties.keys().map(String::as_str).collect();
        let mut known = KEYS.to_vec();
        written.sort_unstable();
        known.sort_unstable();
        assert_eq!(written, known);
        for (key, value) in properties {
            assert!(value["description"].is_string(), "{key} has no description");
        }
        assert_eq!(act["additionalProperties"], false);
        assert_eq!(act["required"], json!(["Label"]));
    }

    #[test]
    fn every_built_in_verb_has_its_own_branch() {
        let schema = acts_schema();
        let branches = schema["definitions"]["command"]["anyOf"]
            .as_array()
            .expect("branches");
        for verb in Verb::BUILT_IN {
            let start = format!(r"^\s*{}", verb.as_str());
            assert!(
                branches
                    .iter()
                    .any(|b| b["pattern"].as_str().is_some_and(|p| p.starts_with(&start))),
                "{verb}"
            );
        }
        assert_eq!(branches.len(), Verb::BUILT_IN.len() + 1);
    }
}
