//! The frames Docent sends a kiosk about recording (`docs/PROTOCOL.md`, "Recording"):
//! `record` (start a recording, with its upload address and token), `record-stop`, and the
//! `clock` answer that puts the kiosk's clock beside the hub's.

use serde_json::json;

use super::Recording;
use super::upload::{MAX_CHUNK_BYTES, chunk_path};
use crate::content::config::RecordTracks;
use crate::events::StopReason;

/// `record`: record `tracks` into `recording`, uploading each chunk to its address with its
/// token, no chunk larger than `max_chunk_bytes` (the kiosk splits a larger piece).
pub(super) fn record_frame(recording: &Recording, tracks: &RecordTracks) -> String {
    let mime = if tracks.video {
        if tracks.audio {
            "video/webm;codecs=vp8,opus"
        } else {
            "video/webm;codecs=vp8"
        }
    } else {
        "audio/webm;codecs=opus"
    };
    json!({
        "type": "record",
        "recording": recording.id,
        "session": recording.session,
        "file": recording.file,
        "tracks": tracks.names(),
        "mime": mime,
        "upload": chunk_path(recording.id),
        "token": recording.token.expose(),
        "max_chunk_bytes": MAX_CHUNK_BYTES,
    })
    .to_string()
}

/// `record-stop`: stop `recording`, upload what is left, then say `recording-stopped`.
pub(super) fn record_stop_frame(recording: u64, reason: StopReason) -> String {
    json!({"type": "record-stop", "recording": recording, "reason": reason}).to_string()
}

/// `clock`: the answer to a kiosk's `clock` frame: its own `t0` back, with the hub's clock
/// (`mono_us`, the clock of every event's `mono_us`) when the answer was made.
pub fn clock_frame(t0: f64, server_us: u64) -> String {
    json!({"type": "clock", "t0": t0, "server_us": server_us}).to_string()
}
