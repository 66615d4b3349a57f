//! A corpus line read back, through the types that wrote it: [`Head`], the stamps and type
//! every line begins with (`stamped.rs` writes them), and [`LineEvent`], what happened: an
//! [`EventKind`], or a type newer than this Docent, passed over by name so that a log with
//! newer types still reads. A line of a known type whose fields do not read is an error,
//! naming the field, as serde says it.

use std::sync::OnceLock;

use serde::de::DeserializeOwned;
use serde::{Deserialize, Deserializer};

use super::EventKind;
use super::recording::RecordingEvent;
use crate::tags::tags_of;

/// The fields every corpus line begins with, read alone: the hub's stamps and the `type`. A
/// reader that only counts and places lines (`docent corpus list`) reads no more of them.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
pub struct Head {
    /// Format version.
    pub v: Option<u32>,
    /// Sequence number within the run.
    pub seq: Option<u64>,
    /// Wall-clock time, RFC 3339 UTC.
    pub time: Option<String>,
    /// Microseconds since the server started.
    pub mono_us: Option<u64>,
    /// Microseconds on the session clock (a session's log only; format 3 on).
    pub session_us: Option<u64>,
    /// The event type.
    #[serde(rename = "type")]
    pub kind: Option<String>,
}

/// What a corpus line says happened.
#[derive(Debug)]
pub enum LineEvent {
    /// An event of a type this Docent knows.
    Event(EventKind),
    /// A type this Docent does not know (a newer one's), by name; its fields are not read.
    Newer(String),
}

/// A whole corpus line: its stamps and type, and what happened.
#[derive(Debug)]
pub struct Line {
    /// The stamps and type.
    pub head: Head,
    /// What happened.
    pub event: LineEvent,
}

impl Line {
    /// Reads one line (without its `\n`).
    pub fn parse(line: &[u8]) -> Result<Line, serde_json::Error> {
        let head = Head::parse(line)?;
        let event = LineEvent::parse(line, &head)?;
        Ok(Line { head, event })
    }
}

impl Head {
    /// Reads the stamps and type of one line (without its `\n`), and no other field.
    pub fn parse(line: &[u8]) -> Result<Head, serde_json::Error> {
        serde_json::from_slice(line)
    }
}

impl LineEvent {
    /// Reads what happened on `line`, whose stamps and type `head` read: the event of the
    /// type `head` names, straight from the line's bytes into the enum that has that type
    /// (no intermediate value: exports read every line of an hour's log this way).
    pub fn parse(line: &[u8], head: &Head) -> Result<LineEvent, serde_json::Error> {
        let Some(name) = head.kind.as_deref() else {
            // No `type` (or `null`): serde's own words, with the column.
            let missing = serde_json::from_slice::<Typed>(line).err();
            return Err(missing.unwrap_or_else(|| serde::de::Error::missing_field("type")));
        };
        if has_type::<RecordingEvent>(name) {
            read::<RecordingEvent>(line).map(|r| LineEvent::Event(EventKind::Recording(r)))
        } else if has_type::<EventKind>(name) {
            read::<Derived>(line).map(|kind| LineEvent::Event(kind.0))
        } else {
            Ok(LineEvent::Newer(name.to_owned()))
        }
    }
}

/// `line` read into `T` (its stamps passed over). A line that does not read is read again
/// inside an object ([`Flat`]), for serde_json to say where it went wrong, as it does for
/// any struct: a field error of a tagged enum has no column otherwise.
fn read<T: DeserializeOwned>(line: &[u8]) -> Result<T, serde_json::Error> {
    serde_json::from_slice(line)
        .or_else(|_| serde_json::from_slice::<Flat<T>>(line).map(|f| f.kind))
}

/// A line read into `T` inside an object, for the column of what is wrong.
#[derive(Deserialize)]
struct Flat<T> {
    #[serde(flatten)]
    kind: T,
}

/// An [`EventKind`] read by serde's derived (inherent) deserializer: every type but the
/// recordings', which [`LineEvent::parse`] reads as [`RecordingEvent`].
struct Derived(EventKind);

impl<'de> Deserialize<'de> for Derived {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        EventKind::deserialize(deserializer).map(Derived)
    }
}

/// A line that must have a `type`, a string.
#[derive(Deserialize)]
struct Typed {
    #[serde(rename = "type")]
    _kind: String,
}

/// Whether `name` is the `type` of a pose line ([`EventKind::Pose`], asked of serde once, so
/// the name is written nowhere else). Readers that draw no poses (the tier exports) pass such
/// lines over after their stamps: they are most of a log, and reading each whole costs.
pub fn is_pose(name: &str) -> bool {
    static POSE: OnceLock<String> = OnceLock::new();
    let pose = POSE.get_or_init(|| {
        let sample = EventKind::Pose {
            x: 0.0,
            y: 0.0,
            heading: 0.0,
            moving: false,
            frame: None,
        };
        let written = serde_json::to_value(&sample).unwrap_or_default();
        written["type"].as_str().unwrap_or_default().to_owned()
    });
    !pose.is_empty() && name == pose
}

/// Whether `name` is an event type this Docent knows: an [`EventKind`] or a recording's.
pub fn is_event_type(name: &str) -> bool {
    has_type::<EventKind>(name) || has_type::<RecordingEvent>(name)
}

/// Whether the internally tagged enum `T` has a variant tagged `name`.
pub(super) fn has_type<T: Tagged>(name: &str) -> bool {
    T::names().contains(&name)
}

/// An enum tagged by `type`, with the tags its derived deserializer knows.
pub(super) trait Tagged {
    /// Its tags (asked once).
    fn names() -> &'static [&'static str];
}

impl Tagged for EventKind {
    fn names() -> &'static [&'static str] {
        static TAGS: OnceLock<&'static [&'static str]> = OnceLock::new();
        // The derived one (inherent, `remote = "Self"`), without recordings.
        TAGS.get_or_init(|| tags_of(|probe| EventKind::deserialize(probe).map(drop)))
    }
}

impl Tagged for RecordingEvent {
    fn names() -> &'static [&'static str] {
        static TAGS: OnceLock<&'static [&'static str]> = OnceLock::new();
        TAGS.get_or_init(|| {
            tags_of(|probe| <RecordingEvent as Deserialize>::deserialize(probe).map(drop))
        })
    }
}

#[cfg(test)]
#[path = "line_samples.rs"]
mod samples;
#[cfg(test)]
#[path = "line_tests.rs"]
mod tests;
