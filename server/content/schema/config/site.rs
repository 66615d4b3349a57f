//! The schema of the `docent.yaml` sections about the site and who reaches it: `verbs:`
//! (the site's own commands), `access:` (credentials), `server:` (trusted proxies) and
//! `operator:` (what the console shows). Separate from the device and channel sections in
//! `config.rs`, which describe how the robot behaves.

use serde_json::{Value, json};

use super::SITE_VERB_KEYS;
use crate::config::Credential;
use crate::config_file::captions::KEYS as CAPTION_KEYS;
use crate::config_file::operator::{MAP_FORMATS, VISITOR_GROUPS};
use crate::model::Verb;
use crate::schema::{VARIANT_KEY_PATTERN, any_case, choice, section, words};

pub(super) fn verbs() -> Value {
    let built_in: Vec<&str> = Verb::BUILT_IN.iter().map(Verb::as_str).collect();
    let verb = section(
        SITE_VERB_KEYS,
        |key| match key {
            "adapter" => choice(
                &["ws", "log"],
                "Who carries the command out: `ws` (a program connected over the websocket, \
                 the default) or `log` (nobody: it is only written to the log).",
            ),
            "argument" => choice(
                &["required", "optional", "none"],
                "Whether the command needs something after it: `required`, `optional` (the \
                 default) or `none`.",
            ),
            "description" => words("What the command does, in a few words for people."),
            _ => json!({}),
        },
        "One command of this site.",
    );
    json!({
        "type": ["object", "null"],
        "description": "This site's own commands, by name, e.g. \
                        `verbs: { LIGHTS: { adapter: ws, argument: required } }`.",
        "propertyNames": {
            "pattern": "^[A-Z][A-Z0-9_]*$",
            "not": { "enum": built_in },
            "description": "A command name: capital letters, digits and `_`, starting with a \
                            letter, and not one of the built-in commands.",
        },
        "additionalProperties": verb,
    })
}

pub(super) fn access(key: &str) -> Value {
    let who = if key == "operator_token" {
        "operator console"
    } else {
        "dialog manager"
    };
    json!({
        "type": "string",
        "pattern": format!("^[!-~]{{{},}}$", Credential::MIN_CHARS),
        "description": format!(
            "The credential the {who} shows to connect: at least {} characters, no spaces, \
             e.g. the output of `openssl rand -hex 16`.",
            Credential::MIN_CHARS
        ),
    })
}

pub(super) fn mqtt(key: &str) -> Value {
    match key {
        "url" => json!({
            "type": "string",
            "pattern": "^mqtt://[^@/?#]+/?$",
            "description": "The fleet's MQTT broker, e.g. `mqtt://broker.local:1883` (port 1883 \
                            when left out). No user name or password in it.",
        }),
        "robot_id" => json!({
            "type": "string",
            "pattern": "^[A-Za-z0-9_-]{1,64}$",
            "description": "This robot's id in the topics (`docent/ID/state`): 1 to 64 letters, \
                            digits, - and _, e.g. `robot-1`.",
        }),
        "username" => json!({
            "type": "string",
            "description": "The broker's user name for this robot.",
        }),
        "ca_file" => json!({
            "type": "string",
            "pattern": "^/",
            "description": "For an mqtts:// broker: the absolute path of the PEM file with the \
                            CA certificates it is checked against (the system's without one).",
        }),
        "password" => json!({
            "type": "string",
            "description": "The broker's password for `username`. Better kept out of the \
                            bundle: set DOCENT_MQTT_PASSWORD instead.",
        }),
        _ => json!({
            "type": "string",
            "pattern": "^https?://",
            "description": "This robot's console as the fleet view links to it, e.g. \
                            `http://robot-1.local:8080/operator` (by default the --listen \
                            address's).",
        }),
    }
}

pub(super) fn server(_key: &str) -> Value {
    let address = json!({
        "type": "string",
        "description": "The IP address of a reverse proxy, e.g. `127.0.0.1` or `fd00::2`.",
    });
    json!({
        "description": "The reverse proxies in front of Docent whose X-Forwarded-For header \
                        is believed, e.g. `[127.0.0.1]`; every other client's header is \
                        ignored.",
        "anyOf": [
            { "type": "null" },
            address,
            { "type": "array", "items": address, "uniqueItems": true },
        ],
    })
}

pub(super) fn operator(key: &str) -> Value {
    match key {
        "map" => {
            let formats: Vec<String> = MAP_FORMATS.iter().map(|f| any_case(f)).collect();
            json!({
                "type": "string",
                "pattern": format!(r"^\s*(pages|media)/.+\.({})\s*$", formats.join("|")),
                "description": format!(
                    "A picture of the area the robot drives in, spanning `drive: bounds`, \
                     written from the bundle folder, e.g. `pages/images/map.png` ({}).",
                    MAP_FORMATS.join(", ")
                ),
            })
        }
        "camera" => json!({
            "description": "The camera the operator sees: `webrtc` (the touchscreen's own \
                            camera, the default), `none`, or the address of an MJPEG stream \
                            starting with http:// or https://.",
            "anyOf": [
                { "enum": ["webrtc", "none"] },
                {
                    "type": "string",
                    "pattern": r#"^\s*[hH][tT][tT][pP][sS]?://[^/?#@\s"'<>`\\{}|^][^\s"'<>`\\{}|^]*\s*$"#,
                },
            ],
        }),
        "situations" => {
            let name = words("A short name the operator marks, e.g. `question`.");
            json!({
                "description": "1 to 9 short names the operator marks during a session with \
                                Alt+Shift+1 to 9, e.g. `[question, laughter, leaving]`.",
                "anyOf": [
                    { "type": "null" },
                    name,
                    { "type": "array", "minItems": 1, "maxItems": 9, "uniqueItems": true, "items": name },
                ],
            })
        }
        "visitor_groups" => section(
            VISITOR_GROUPS,
            |group| {
                json!({
                    "type": "string",
                    "pattern": VARIANT_KEY_PATTERN,
                    "description": format!(
                        "The context the console switches to for the `{group}` visitor group: \
                         `Text` or a text variant key, e.g. `TextChild`."
                    ),
                })
            },
            "Which context each visitor group button of the console switches to.",
        ),
        _ => json!({}),
    }
}

/// `captions:`: which screens show what the robot says while it is said.
pub(super) fn captions() -> Value {
    section(
        CAPTION_KEYS,
        |key| {
            let (screen, default) = match key {
                "kiosk" => ("the touchscreen", "true"),
                _ => ("the projector", "false"),
            };
            json!({
                "type": "boolean",
                "description": format!(
                    "Whether {screen} shows what the robot says as a caption while it is said \
                     (default `{default}`)."
                ),
            })
        },
        "Captions of the robot's speech: on the touchscreen by default (a page may opt out \
         with <meta name=\"docent-captions\" content=\"off\">), on the projector when asked.",
    )
}
