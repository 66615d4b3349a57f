//! The JSON Schemas (`jsonschema` schema encoding) of the MCAP export's channels. Two are
//! Foxglove's well-known schemas, written to match the definitions Foxglove publishes for
//! them, so that Foxglove and Lichtblick show the channels in their Log and 3D panels without
//! a plug-in: `foxglove.Log` and `foxglove.PoseInFrame`. The others are Docent's own typed
//! channels (`docent.Utterance`, ...), which the Raw Messages, Plot and State Transitions
//! panels read by field. Every field of Docent's own messages is required and no other is
//! allowed, so a reader that validates learns of any drift at once.

use serde_json::{Value, json};

/// A Foxglove `Time`: seconds and nanoseconds since the Unix epoch.
fn time(description: &str) -> Value {
    json!({
        "type": "object",
        "title": "time",
        "description": description,
        "properties": {
            "sec": {"type": "integer", "minimum": 0},
            "nsec": {"type": "integer", "minimum": 0, "maximum": 999_999_999}
        }
    })
}

/// `foxglove.Log`: a log message, its level one of Foxglove's `LogLevel` values.
pub fn log() -> Value {
    let levels: Vec<Value> = ["UNKNOWN", "DEBUG", "INFO", "WARNING", "ERROR", "FATAL"]
        .iter()
        .enumerate()
        .map(|(n, title)| json!({"title": title, "const": n}))
        .collect();
    json!({
        "title": "foxglove.Log",
        "description": "A log message",
        "type": "object",
        "properties": {
            "timestamp": time("Timestamp of log message"),
            "level": {"title": "foxglove.LogLevel", "description": "Log level", "oneOf": levels},
            "message": {"type": "string", "description": "Log message"},
            "name": {"type": "string", "description": "Process or node name"},
            "file": {"type": "string", "description": "Filename"},
            "line": {"type": "integer", "minimum": 0, "description": "Line number in the file"}
        }
    })
}

/// `foxglove.PoseInFrame`: a timestamped pose in a named frame.
pub fn pose_in_frame() -> Value {
    let number = |description: &str| json!({"type": "number", "description": description});
    json!({
        "title": "foxglove.PoseInFrame",
        "description": "A timestamped pose for an object or reference frame in 3D space",
        "type": "object",
        "properties": {
            "timestamp": time("Timestamp of pose"),
            "frame_id": {
                "type": "string",
                "description": "Frame of reference for pose position and orientation"
            },
            "pose": {
                "title": "foxglove.Pose",
                "description": "Pose in 3D space",
                "type": "object",
                "properties": {
                    "position": {
                        "title": "foxglove.Vector3",
                        "description": "Point denoting position in 3D space",
                        "type": "object",
                        "properties": {
                            "x": number("x coordinate length"),
                            "y": number("y coordinate length"),
                            "z": number("z coordinate length")
                        }
                    },
                    "orientation": {
                        "title": "foxglove.Quaternion",
                        "description": "Quaternion denoting orientation in 3D space",
                        "type": "object",
                        "properties": {
                            "x": number("x value"),
                            "y": number("y value"),
                            "z": number("z value"),
                            "w": number("w value")
                        }
                    }
                }
            }
        }
    })
}

/// A microsecond on the session clock.
fn session_us(description: &str) -> Value {
    json!({"type": "integer", "minimum": 0, "description": description})
}

/// A string, or null when the log has none.
fn optional_string(description: &str) -> Value {
    json!({"type": ["string", "null"], "description": description})
}

/// How a command ended: its outcome event, or none in the log.
fn outcome() -> Value {
    json!({
        "enum": ["done", "failed", "cancelled", "open"],
        "description": "command.done, command.failed, command.cancelled, or no outcome in the \
                        log (the session was cut off)"
    })
}

/// One of Docent's own schemas: an object with exactly `properties`, all required.
fn closed(title: &str, description: &str, properties: Value) -> Value {
    let required: Vec<&String> = properties
        .as_object()
        .map_or(Vec::new(), |p| p.keys().collect());
    json!({
        "title": title,
        "description": description,
        "type": "object",
        "properties": properties,
        "required": required,
        "additionalProperties": false
    })
}

/// `docent.Utterance`: a `SAY` the speech device began, `/docent/speech`.
pub fn utterance() -> Value {
    closed(
        "docent.Utterance",
        "A SAY the speech device began, from its command.started to its outcome",
        json!({
            "start_us": session_us("Its command.started, on the session clock"),
            "end_us": session_us("Its outcome (the session's end when it has none)"),
            "text": {"type": "string", "description": "The exact text handed to the speech device"},
            "act": {"type": "string", "description": "The label of the act it belongs to"},
            "source": {"type": "string", "description": "Who triggered the act"},
            "variant": optional_string("The variant the act chose, for the SAY of its chosen text"),
            "alternative": {
                "type": ["integer", "null"],
                "minimum": 0,
                "description": "The alternative chosen within the variant, from 0"
            },
            "outcome": outcome(),
            "reason": optional_string("Why it failed or was cancelled")
        }),
    )
}

/// `docent.Command`: any other command, `/docent/commands`.
pub fn command() -> Value {
    closed(
        "docent.Command",
        "A command other than a begun SAY, from its start to its outcome",
        json!({
            "start_us": session_us("Its command.started, else command.sent, else its outcome"),
            "end_us": session_us("Its outcome (the session's end when it has none)"),
            "verb": {"type": "string", "description": "The verb"},
            "arg": optional_string("The argument as written"),
            "outcome": outcome(),
            "reason": optional_string("Why it failed or was cancelled")
        }),
    )
}

/// `docent.Page`: a page the touchscreen showed, `/docent/page`.
pub fn page() -> Value {
    closed(
        "docent.Page",
        "A page the touchscreen showed, until the next one",
        json!({
            "start_us": session_us("The display.changed that showed it"),
            "end_us": session_us("The next page change, or the session's end"),
            "page": {"type": "string", "description": "The page, relative to pages/"}
        }),
    )
}

/// `docent.Projection`: what the projector showed, `/docent/projection`.
pub fn projection() -> Value {
    closed(
        "docent.Projection",
        "What the projector showed from this display.changed on",
        json!({
            "at_us": session_us("The display.changed, on the session clock"),
            "projector": optional_string("The file under media/ (null: black or highlights)"),
            "highlight": optional_string("The areas lit by the last HIGHLIGHT, as written"),
            "projector_state": optional_string(
                "black, loading, shown, playing or held (null in lines older than the field)"
            )
        }),
    )
}

/// `docent.Touch`: a visitor's touch on the kiosk, `/docent/touches`.
pub fn touch() -> Value {
    closed(
        "docent.Touch",
        "A visitor's touch on the kiosk",
        json!({
            "at_us": session_us("Its event, on the session clock"),
            "kind": {
                "enum": ["act", "refused", "page"],
                "description": "Triggered an act, asked for one that was refused, or followed \
                                a link to a page"
            },
            "act": optional_string("The act's label (act, refused)"),
            "code": optional_string("The refusal's code (refused)"),
            "page": optional_string("The page, relative to pages/ (page)")
        }),
    )
}

/// `docent.Mark`: an operator's mark, `/docent/marks`.
pub fn mark() -> Value {
    closed(
        "docent.Mark",
        "An operator's mark",
        json!({
            "at_us": session_us("Its event, on the session clock"),
            "kind": {"enum": ["situation", "group", "note"], "description": "What was marked"},
            "value": {"type": "string", "description": "The situation, the visitor group or the note's text"}
        }),
    )
}

/// `docent.Annotation`: a researcher's annotation (`annotations.jsonl`), at its start.
pub fn annotation() -> Value {
    closed(
        "docent.Annotation",
        "A researcher's annotation with a code of the codebook",
        json!({
            "id": {"type": "string", "description": "Its id within the session (a1, a2, ...)"},
            "tier": {"type": "string", "description": "The codebook tier"},
            "code": {"type": "string", "description": "The tier's code"},
            "start_us": session_us("Its start, on the session clock"),
            "end_us": session_us("Its end, on the session clock; its start for a point"),
            "annotator": optional_string("Who annotated, as they signed in")
        }),
    )
}
