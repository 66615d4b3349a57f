//! Saying why a text frame could not be read: malformed JSON, no type, an unknown type, or a
//! known type with wrong fields. Only on the error path, so it may parse twice.

use crate::wire::ErrorCode;
use docent_protocol::client_frames::frame_types;

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
        Some(t) if !frame_types().contains(&t) => {
            let known = frame_types().join(", ");
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
