//! Fleet commands signed and answers checked as docs/FLEET.md describes them, written with
//! the `hmac` crate rather than Docent's own code, so the documented format is what is tested.

use hmac::{Hmac, KeyInit, Mac};
use rand::RngExt;
use serde_json::{Value, json};
use sha2::Sha256;

/// HMAC-SHA256 of `text` keyed by `key`, in lowercase hex.
pub fn hmac_hex(key: &str, text: &str) -> String {
    let mut mac = <Hmac<Sha256> as KeyInit>::new_from_slice(key.as_bytes()).expect("any key");
    mac.update(text.as_bytes());
    let bytes = mac.finalize().into_bytes();
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// A fresh random `ref`.
pub fn fresh_ref() -> String {
    let bits: u128 = rand::rng().random();
    format!("{bits:032x}")
}

/// Milliseconds since the Unix epoch.
pub fn now_ms() -> u64 {
    let since = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH);
    since.expect("after 1970").as_millis() as u64
}

/// The signed command envelope of `frame` for `robot`, as `(role, credential)`, signed now.
pub fn signed(robot: &str, (role, key): (&str, &str), reference: &str, frame: &Value) -> Value {
    signed_at(robot, (role, key), reference, frame, now_ms())
}

/// As [`signed`], with the timestamp `ts`.
pub fn signed_at(
    robot: &str,
    (role, key): (&str, &str),
    reference: &str,
    frame: &Value,
    ts: u64,
) -> Value {
    let frame = frame.to_string();
    let text = format!("docent-command-v1\n{robot}\n{role}\n{reference}\n{ts}\n{frame}");
    json!({"robot": robot, "role": role, "ref": reference, "ts": ts, "frame": frame,
        "mac": hmac_hex(key, &text)})
}

/// A reply envelope for `frame` as `robot` would sign it with `key`.
pub fn signed_reply(robot: &str, reference: &str, frame: &Value, key: &str) -> Value {
    let frame = frame.to_string();
    let text = format!("docent-reply-v1\n{robot}\n{reference}\n{frame}");
    json!({"robot": robot, "ref": reference, "frame": frame, "mac": hmac_hex(key, &text)})
}

/// Whether a reply envelope carries a valid MAC with `key`.
pub fn reply_signed(reply: &Value, key: &str) -> bool {
    let field = |name: &str| reply[name].as_str().unwrap_or_default().to_owned();
    let text = format!(
        "docent-reply-v1\n{}\n{}\n{}",
        field("robot"),
        field("ref"),
        field("frame")
    );
    reply["mac"].as_str() == Some(hmac_hex(key, &text).as_str())
}

/// The answer frame a reply envelope carries.
pub fn reply_frame(reply: &Value) -> Value {
    let frame = reply["frame"]
        .as_str()
        .expect("a reply envelope with a frame");
    serde_json::from_str(frame).expect("the frame is JSON")
}
