//! [`Event`]: an [`EventKind`] stamped by the hub with the format version, its sequence
//! number and times, and serialized once into the JSON line every reader shares.

use std::fmt::Write;
use std::sync::OnceLock;
use std::time::SystemTime;

use super::EventKind;
use crate::EVENT_FORMAT_VERSION;

/// An event stamped by the hub.
#[derive(Debug)]
pub struct Event {
    /// Format version.
    pub v: u32,
    /// Sequence number, from 1, without gaps within one server run.
    pub seq: u64,
    /// Wall-clock time, written as RFC 3339 UTC with milliseconds.
    pub time: SystemTime,
    /// Microseconds since the server started (monotonic).
    pub mono_us: u64,
    /// What happened.
    pub kind: EventKind,
    /// The JSON line, made once for all readers, and where its stamps end.
    json: OnceLock<(String, usize)>,
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

    /// The event as one JSON object (no newline), serialized once: the stamps, then the
    /// kind's own fields. (Written out rather than through `#[serde(flatten)]`, which goes
    /// through a generic map: serializing events was 3.2 % of Docent's CPU under load.)
    pub fn json(&self) -> &str {
        &self.line().0
    }

    /// Appends the event's corpus line, with its `\n`, to `out`. In a session's log
    /// (`session_start_us` given) the line carries `session_us`, the microseconds since the
    /// session started on the same monotonic clock, right after `mono_us`.
    pub fn write_line(&self, out: &mut Vec<u8>, session_start_us: Option<u64>) {
        let (json, stamps) = self.line();
        match session_start_us {
            None => out.extend_from_slice(json.as_bytes()),
            Some(start) => {
                let (stamps, kind) = json.split_at(*stamps);
                out.extend_from_slice(stamps.as_bytes());
                let session_us = self.mono_us.saturating_sub(start);
                out.extend_from_slice(format!("\"session_us\":{session_us},").as_bytes());
                out.extend_from_slice(kind.as_bytes());
            }
        }
        out.push(b'\n');
    }

    fn line(&self) -> &(String, usize) {
        self.json.get_or_init(|| {
            // The kind is an internally tagged enum: an object that starts with its "type".
            // Plain data with string keys always serializes; the fallback keeps the line JSON.
            let kind = serde_json::to_string(&self.kind)
                .unwrap_or_else(|_| r#"{"type":"unserializable"}"#.to_owned());
            let mut line = String::with_capacity(kind.len() + 80);
            // Writing to a String cannot fail.
            let _ = write!(
                line,
                "{{\"v\":{},\"seq\":{},\"time\":\"{}\",\"mono_us\":{},",
                self.v,
                self.seq,
                humantime::format_rfc3339_millis(self.time),
                self.mono_us
            );
            let stamps = line.len();
            line.push_str(kind.strip_prefix('{').unwrap_or(&kind));
            (line, stamps)
        })
    }
}

#[cfg(test)]
mod tests {
    use std::time::{Duration, UNIX_EPOCH};

    use super::*;
    use crate::events::Source;

    #[test]
    fn the_line_is_the_stamps_then_the_kind_with_its_type_first() {
        let time = UNIX_EPOCH + Duration::from_millis(1_795_000_000_123);
        let kind = EventKind::ContextChanged {
            source: Source::Http,
            context: "Text \"quoted\"".into(),
        };
        let event = Event::new(7, time, 42, kind);
        let line = event.json();
        assert_eq!(
            line,
            r#"{"v":4,"seq":7,"time":"2026-11-18T11:06:40.123Z","mono_us":42,"type":"context.changed","source":"http","context":"Text \"quoted\""}"#
        );
        let parsed: serde_json::Value = serde_json::from_str(line).expect("valid JSON");
        assert_eq!(parsed["context"], "Text \"quoted\"");
        let mut in_session = Vec::new();
        event.write_line(&mut in_session, Some(40));
        assert_eq!(
            String::from_utf8(in_session).unwrap(),
            r#"{"v":4,"seq":7,"time":"2026-11-18T11:06:40.123Z","mono_us":42,"session_us":2,"type":"context.changed","source":"http","context":"Text \"quoted\""}"#.to_owned() + "\n"
        );
    }
}
