//! Saying why a text frame could not be read: malformed JSON, no type, an unknown type, or a
//! known type with wrong fields. Only on the error path, so it may parse twice.

use crate::wire::ErrorCode;

/// Why a text frame could not be read: an error code, a message and the frame's `ref` if any.
pub fn diagnose(text: &str, error: &serde_json::Error) -> (ErrorCode, String, Option<String>) {
    let Ok(value) = serde_json::from_str::<serde_json::Value>(text) else {
        return (
            ErrorCode::MalformedJson,
            format!("the frame is not valid JSON: {error}"),
            None,
        );
    };
    let reference = value.get("ref").and_then(|r| r.as_str()).map(str::to_owned);
    match value.get("type").and_then(|t| t.as_str()) {
        None => (
            ErrorCode::MissingType,
            "every frame needs a \"type\" field".into(),
            reference,
        ),
        Some(t) if !KNOWN_TYPES.contains(&t) => {
            let known = KNOWN_TYPES.join(", ");
            (
                ErrorCode::UnknownType,
                format!("unknown frame type {t:?}; known types: {known}"),
                reference,
            )
        }
        Some(t) => (
            ErrorCode::BadFrame,
            format!("a {t:?} frame is not right: {error}"),
            reference,
        ),
    }
}

/// Every frame type a client may send.
const KNOWN_TYPES: [&str; 18] = [
    "hello",
    "trigger",
    "stop",
    "context",
    "page",
    "robot",
    "propose",
    "accept",
    "dismiss",
    "mark",
    "signal",
    "started",
    "done",
    "failed",
    "clock",
    "recording-started",
    "recording-stopped",
    "recording-failed",
];
