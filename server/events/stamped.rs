//! [`Event`]: an [`EventKind`] stamped by the hub with the format version, its sequence
//! number and times, and serialized once into the JSON line every reader shares.

use std::sync::OnceLock;
use std::time::SystemTime;

use serde::Serialize;

use super::EventKind;
use crate::events::EVENT_FORMAT_VERSION;

/// An event stamped by the hub.
#[derive(Debug, Serialize)]
pub struct Event {
    /// Format version.
    pub v: u32,
    /// Sequence number, from 1, without gaps within one server run.
    pub seq: u64,
    /// Wall-clock time, written as RFC 3339 UTC with milliseconds.
    #[serde(serialize_with = "rfc3339_millis")]
    pub time: SystemTime,
    /// Microseconds since the server started (monotonic).
    pub mono_us: u64,
    /// What happened.
    #[serde(flatten)]
    pub kind: EventKind,
    /// The JSON line, made once for all readers.
    #[serde(skip)]
    json: OnceLock<String>,
}

impl Event {
    /// An event with its stamps.
    pub fn new(seq: u64, time: SystemTime, mono_us: u64, kind: EventKind) -> Self {
        Event {
            v: EVENT_FORMAT_VERSION,
            seq,
            time,
            mono_us,
            kind,
            json: OnceLock::new(),
        }
    }

    /// The event as one JSON object (no newline), serialized once.
    pub fn json(&self) -> &str {
        self.json.get_or_init(|| {
            // Serializing plain data with string keys cannot fail.
            serde_json::to_string(self).unwrap_or_else(|e| format!("{{\"error\":\"{e}\"}}"))
        })
    }
}

/// Formats the time when the event is serialized (on the corpus thread), not when published.
fn rfc3339_millis<S: serde::Serializer>(time: &SystemTime, s: S) -> Result<S::Ok, S::Error> {
    s.collect_str(&humantime::format_rfc3339_millis(*time))
}
