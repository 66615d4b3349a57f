//! The schema of `docent.yaml`: every section `config_file*.rs` reads, with its keys and the
//! shape of each value. Sections may be left empty (`speech:` alone), as the loader allows.

use serde_json::{Value, json};

use super::{DRAFT, choice, duration, section, words};
use crate::config::{Channel, MAX_PRIORITY, MAX_QUEUE_LIMIT};
use crate::config_file::TOP_KEYS;
use crate::config_file::mqtt::KEYS as MQTT_KEYS;
use crate::config_file::operator::KEYS as OPERATOR_KEYS;
use crate::config_file::policy::{CHANNEL_KEYS, PRIORITY_KEYS};
use crate::config_file::reactions::REACTION_KEYS;
use crate::config_file::screens::{CORPUS_KEYS, RECORD_LIMITS_KEYS};
use crate::config_file::server::KEYS as SERVER_KEYS;

mod rosbridge;
mod screens;
mod site;

use site::{access, mqtt, operator, server, verbs};

/// The keys of the sections whose lists live inline in the loader's functions; the test
/// `section_keys_are_the_loaders` asks the loader for each list and compares.
const SPEECH_KEYS: &[&str] = &["adapter", "voice", "voices", "rate", "max_seconds"];
/// A short BCP 47 language tag, as `content::Language::parse` reads it (any case).
const LANGUAGE_PATTERN: &str = "^[A-Za-z]{2,3}(-([A-Za-z]{2}|[0-9]{3}|[A-Za-z]{4}))?$";
const DISPLAY_KEYS: &[&str] = &["adapter"];
const DRIVE_KEYS: &[&str] = &["adapter", "speed", "pose_rate", "bounds"];
const BOUNDS_KEYS: &[&str] = &["min_x", "min_y", "max_x", "max_y"];
const ADAPTERS_KEYS: &[&str] = &["timeout"];
const KIOSK_KEYS: &[&str] = &["idle", "idle_act", "leave_page_stops_speech", "attract"];
const PROJECTOR_KEYS: &[&str] = &["after_video", "highlight_edge"];
const ACCESS_KEYS: &[&str] = &["operator_token", "dm_token"];
const SITE_VERB_KEYS: &[&str] = &["adapter", "argument", "description"];

/// The schema of a bundle's `docent.yaml`.
pub fn config_schema() -> Value {
    let mut schema = section(
        TOP_KEYS,
        top_level,
        "Docent's settings for this bundle. Every setting is optional; leave out what you do \
         not need.",
    );
    let fields = schema.as_object_mut().expect("section() builds an object");
    fields.insert("$schema".into(), json!(DRAFT));
    fields.insert("title".into(), json!("Docent settings (docent.yaml)"));
    schema
}

fn top_level(key: &str) -> Value {
    match key {
        "home" => words("The page under pages/ the touchscreen starts on, e.g. `index.html`."),
        "contexts" => {
            let context = json!({
                "type": "string",
                "pattern": "^Text.",
                "description": "A context: the name of a text variant key, e.g. `TextChild`.",
            });
            json!({
                "description": "The text variants this bundle uses as contexts, e.g. \
                                `[TextGroup, TextChild]`. Listing them lets `docent check` \
                                catch a misspelt variant key.",
                "anyOf": [
                    { "type": "null" },
                    context,
                    { "type": "array", "items": context, "uniqueItems": true },
                ],
            })
        }
        "languages" => {
            let language = json!({
                "type": "string",
                "pattern": LANGUAGE_PATTERN,
                "description": "A short language tag, e.g. `en`, `de` or `pt-br`.",
            });
            json!({
                "description": "The bundle's languages, the default first, e.g. `[en, de]`. \
                                Texts in another language are written `Text@de:` beside \
                                `Text:`, pages in `pages/de/`. Without it the bundle has one \
                                language: that of `speech: voice`, else `en`.",
                "anyOf": [
                    language,
                    { "type": "array", "items": language, "minItems": 1, "uniqueItems": true },
                ],
            })
        }
        "speech" => section(SPEECH_KEYS, speech, "How the robot speaks."),
        "display" => section(
            DISPLAY_KEYS,
            |_| {
                choice(
                    &["display", "ws"],
                    "Who shows pages and pictures: `display` (Docent's own touchscreen and projector pages, the default) or `ws` (a program connected over the websocket).",
                )
            },
            "The touchscreen and the projector.",
        ),
        "drive" => section(DRIVE_KEYS, drive, "The robot's driving base."),
        "adapters" => section(
            ADAPTERS_KEYS,
            |_| {
                duration(
                    "How long a device (a websocket adapter, the touchscreen or projector page) may take to report a command before Docent reports it failed, e.g. `30s`; a film only until it plays. Not zero.",
                )
            },
            "Settings shared by all devices.",
        ),
        "kiosk" => section(KIOSK_KEYS, kiosk, "How the touchscreen behaves."),
        "projector" => section(PROJECTOR_KEYS, projector, "How the projector behaves."),
        "corpus" => section(
            CORPUS_KEYS,
            corpus,
            "How the corpus is cut into visitor sessions.",
        ),
        "verbs" => verbs(),
        "access" => section(
            ACCESS_KEYS,
            access,
            "Credentials the operator console and a dialog manager show to connect. Better \
             kept out of the bundle: set DOCENT_OPERATOR_TOKEN and DOCENT_DM_TOKEN instead.",
        ),
        "operator" => section(OPERATOR_KEYS, operator, "What the operator console shows."),
        "server" => section(SERVER_KEYS, server, "How Docent itself is reached."),
        "channels" => channels(),
        "priorities" => section(
            PRIORITY_KEYS,
            |source| {
                json!({
                    "type": "integer",
                    "minimum": 1,
                    "maximum": MAX_PRIORITY,
                    "description": format!(
                        "The priority of `{source}` triggers, 1 (lowest) to {MAX_PRIORITY}: a \
                         lower priority never interrupts a higher one."
                    ),
                })
            },
            "Which trigger source wins when several ask for the same channel (defaults: \
             operator 3, http 3, dm 2, kiosk 1).",
        ),
        "codebook" => codebook(),
        "reactions" => reactions(),
        "mqtt" => section(
            MQTT_KEYS,
            mqtt,
            "The fleet's MQTT broker and this robot's id in it (docs/FLEET.md); `docent serve \
             --mqtt URL --robot-id ID` overrides both.",
        ),
        "rosbridge" => rosbridge::rosbridge(),
        "schedule" => screens::schedule(),
        "captions" => site::captions(),
        // A key added to the loader without a schema here fails the tests (no description).
        _ => json!({}),
    }
}

/// `reactions:`: a list of robot events mapped to acts.
fn reactions() -> Value {
    let mut reaction = section(
        REACTION_KEYS,
        |key| match key {
            "event" => json!({
                "type": "string",
                "pattern": "^[a-z][a-z0-9._-]{0,63}$",
                "description": "The robot event that sets it off, e.g. `person.near`.",
            }),
            "if" => words(
                "A condition on the event's data: comparisons (<, <=, >, >=, ==, !=) of a \
                 field with a number, \"quoted text\", true or false, joined by `and`, e.g. \
                 `distance < 1.5`.",
            ),
            "act" => words("The label of the act it triggers."),
            _ => duration("The least time between two of its triggers (default 30s)."),
        },
        "A reaction: when the robot notices `event` and its data passes `if`, trigger `act`.",
    );
    let fields = reaction
        .as_object_mut()
        .expect("section() builds an object");
    fields.insert("type".into(), json!("object"));
    fields.insert("required".into(), json!(["event", "act"]));
    json!({
        "description": "Robot events mapped to acts, each with an optional condition and a \
                        cool-down, e.g. `- {event: person.near, if: distance < 1.5, act: \
                        GREETING, cooldown: 2m}`.",
        "anyOf": [{ "type": "null" }, { "type": "array", "items": reaction }],
    })
}

/// `codebook:`: tier name to codes, each code with a one-key shortcut or none; or a list of
/// codes without shortcuts.
fn codebook() -> Value {
    let key = json!({
        "anyOf": [
            { "type": "null" },
            { "type": "string", "pattern": "^[A-Za-z0-9]$" },
            { "type": "integer", "minimum": 0, "maximum": 9 },
        ],
        "description": "The code's shortcut on the /sessions page: one letter or digit, or \
                        nothing (chosen by click only).",
    });
    let code = json!({ "type": "string", "minLength": 1, "maxLength": 64 });
    let tier = json!({
        "description": "A tier's codes: `{question: q, laughter: l}` (code: shortcut), or a \
                        list of codes without shortcuts.",
        "anyOf": [
            { "type": "object", "minProperties": 1, "additionalProperties": key },
            { "type": "array", "minItems": 1, "items": code, "uniqueItems": true },
        ],
    });
    json!({
        "description": "The annotation tiers researchers code recorded sessions with on the \
                        /sessions page, e.g. `{situation: {question: q, laughter: l}}`. \
                        Without it: one `situation` tier of `operator.situations`, keyed 1 to 9.",
        "anyOf": [
            { "type": "null" },
            {
                "type": "object",
                "propertyNames": { "pattern": "^[A-Za-z][A-Za-z0-9._-]{0,63}$" },
                "additionalProperties": tier,
            },
        ],
    })
}

fn speech(key: &str) -> Value {
    match key {
        "adapter" => choice(
            &["espeak", "log", "ws", "browser"],
            "Who speaks: `espeak` (this computer's speech synthesiser), `browser` (the \
             touchscreen's browser), `ws` (a program connected over the websocket) or `log` \
             (nobody: speech is only written to the log).",
        ),
        "voice" => json!({
            "type": "string",
            "pattern": "^[A-Za-z0-9+_/][A-Za-z0-9+_/-]*$",
            "description": "The voice: a language such as `en`, `en-us` or `de`.",
        }),
        "voices" => json!({
            "type": "object",
            "propertyNames": { "pattern": LANGUAGE_PATTERN },
            "additionalProperties": {
                "type": "string",
                "pattern": "^[A-Za-z0-9+_/][A-Za-z0-9+_/-]*$",
            },
            "description": "The espeak-ng voice of each language, e.g. `{en: en-gb, de: de}`. \
                            A language without one speaks with the voice named like it (the \
                            default language with `voice`, when that is written).",
        }),
        "rate" => json!({
            "type": "integer",
            "minimum": 40,
            "maximum": 600,
            "description": "Speaking speed in words per minute, from 40 to 600, e.g. `160`.",
        }),
        "max_seconds" => json!({
            "type": "integer",
            "minimum": 1,
            "maximum": 3600,
            "description": "The longest one text may take to say, in seconds (30 unless set). `docent check` warns above it, and refuses texts over four times as long.",
        }),
        _ => json!({}),
    }
}

fn drive(key: &str) -> Value {
    let number = |description: &str| json!({ "type": "number", "description": description });
    match key {
        "adapter" => choice(
            &["sim", "ws", "rosbridge"],
            "Who drives: `sim` (a simulated robot, for trying things out), `ws` (the real \
             robot's program, connected over the websocket) or `rosbridge` (a ROS 2 robot \
             through a rosbridge server, see `rosbridge:`).",
        ),
        "speed" => json!({
            "type": "number",
            "exclusiveMinimum": 0,
            "description": "The simulated driving speed in metres per second, e.g. `0.5`.",
        }),
        "pose_rate" => json!({
            "type": "number",
            "exclusiveMinimum": 0,
            "maximum": 50,
            "description": "How many position updates per second the simulated robot sends \
                            (at most 50), e.g. `5`.",
        }),
        "bounds" => {
            let mut bounds = section(
                BOUNDS_KEYS,
                |k| number(&format!("`{k}`: in metres; each min below its max.")),
                "The area the robot drives in, in metres: \
                 `{ min_x: 0, min_y: 0, max_x: 20, max_y: 12 }`.",
            );
            bounds["type"] = json!("object");
            bounds["required"] = json!(BOUNDS_KEYS);
            bounds
        }
        _ => json!({}),
    }
}

fn corpus(key: &str) -> Value {
    match key {
        "session_start" => choice(
            &["touch", "marked"],
            "What starts a visitor session: `touch` (a visitor's first touch when none runs, \
             or an operator's or dialog manager's mark; the default) or `marked` (only a mark).",
        ),
        "consent" => choice(
            &["recorded", "declined"],
            "The consent each visitor session starts with: `recorded` (the default: the site \
             records with notice, and an operator marks `declined` or `withdrawn` when \
             visitors object) or `declined` (nothing is recorded until an operator marks \
             `recorded`).",
        ),
        "session_idle" => duration(
            "How long a session that a touch started goes on without a touch before it ends, \
             e.g. `2m` (the default) or `90s`; `0s`: until it is marked ended.",
        ),
        "session_start_events" => json!({
            "description": "The robot events (sent by an adapter process on the robot, e.g. a \
                            people tracker's `person.near`) that start a visitor session when \
                            none runs and `session_start` is `touch`; such a session ends after \
                            `session_idle` like one a touch started. None by default.",
            "type": "array",
            "uniqueItems": true,
            "items": { "type": "string", "pattern": "^[a-z][a-z0-9._-]{0,63}$" },
        }),
        "record_limits" => section(
            RECORD_LIMITS_KEYS,
            |key| {
                let what = match key {
                    "per_session" => {
                        "All recordings of one visitor session together (default 4 GB)."
                    }
                    "per_kiosk" => "One kiosk's recordings in one visitor session (default 2 GB).",
                    _ => {
                        "Left free on the corpus's disk, so the event log can always be \
                          written (default 1 GB)."
                    }
                };
                json!({
                    "type": "string",
                    "pattern": r"^\s*(\d+(\.\d*)?|\.\d+)\s*([bB]|[kKmMgGtT][iI]?[bB])\s*$",
                    "description": format!("{what} An amount with its unit: `4 GB`, `500 MB`, `1.5 GiB`."),
                    "examples": ["4 GB", "500 MB"],
                })
            },
            "How much of the disk recordings may take; a chunk beyond a limit is refused, the \
             recording stops and operators are told.",
        ),
        "record" => json!({
            "description": "What the kiosk device records during a session whose consent is \
                            `recorded`: `[audio]` (the default, its microphone), \
                            `[audio, video]` (and its camera), `[video]`, or `[]` or `none` \
                            for nothing.",
            "anyOf": [
                { "const": "none" },
                {
                    "type": "array",
                    "uniqueItems": true,
                    "items": { "enum": ["audio", "video"] },
                },
            ],
        }),
        _ => json!({}),
    }
}

fn kiosk(key: &str) -> Value {
    match key {
        "idle" => duration(
            "How long the touchscreen waits without a touch before it goes back to the home \
             page, e.g. `2m` or `90s`; `0s` turns this off.",
        ),
        "idle_act" => json!({
            "type": "string",
            "pattern": r"^\S+$",
            "description": "The label of the act to trigger when the touchscreen goes idle, \
                            e.g. `INVITE`.",
        }),
        "attract" => screens::attract(),
        "leave_page_stops_speech" => json!({
            "type": "boolean",
            "description": "Whether leaving a page stops the speech that page started (true \
                            unless set).",
        }),
        _ => json!({}),
    }
}

fn channels() -> Value {
    let policy = section(
        CHANNEL_KEYS,
        |key| match key {
            "when_busy" => choice(
                &["queue", "replace", "drop"],
                "What a command arriving while another of the same priority runs does: \
                 `queue` (waits its turn), `replace` (stops what runs) or `drop` (is not \
                 carried out).",
            ),
            "queue_limit" => json!({
                "type": "integer",
                "minimum": 1,
                "maximum": MAX_QUEUE_LIMIT,
                "description": format!(
                    "How many commands may wait on this channel, 1 to {MAX_QUEUE_LIMIT}."
                ),
            }),
            _ => json!({}),
        },
        "One output channel's policy.",
    );
    json!({
        "type": ["object", "null"],
        "description": format!(
            "What each output channel ({} or a command under `verbs`) does with a command \
             that arrives while another runs.",
            Channel::BUILT_IN.join(", ")
        ),
        "propertyNames": {
            "pattern": format!("^({}|[A-Z][A-Z0-9_]*)$", Channel::BUILT_IN.join("|")),
            "description": "A built-in channel or a site command's name.",
        },
        "additionalProperties": policy,
    })
}

fn projector(key: &str) -> Value {
    match key {
        "after_video" => choice(
            &["black", "hold"],
            "What the projector shows when a video ends: `black` (the default) or `hold` (its \
             last picture).",
        ),
        "highlight_edge" => json!({
            "type": "number",
            "minimum": 0,
            "maximum": 0.5,
            "description": "How soft the edge of a HIGHLIGHT area is, as a fraction of the \
                            projected width: 0 (sharp) to 0.5, e.g. `0.02`.",
        }),
        _ => json!({}),
    }
}

#[cfg(test)]
mod tests;
