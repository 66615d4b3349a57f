//! The MCAP export, `NAME.mcap`, for Foxglove and Lichtblick (and any MCAP reader): every
//! event of the session's log on `/docent/log` as a `foxglove.Log`, the robot's pose on
//! `/docent/pose` as a `foxglove.PoseInFrame`, and Docent's own typed channels for speech,
//! commands, pages, projections, touches, marks and annotations; JSON messages with JSON Schemas
//! (`mcap/schemas.rs`), so no plug-in is needed. The session's manifest and its media files
//! are metadata records (`mcap/metadata.rs`). Messages are written in time order into lz4
//! chunks, indexed, with a summary, so readers can seek. The clock: `log_time` and
//! `publish_time` are the session's start (its manifest's `started.time`) plus `session_us`,
//! in nanoseconds since the Unix epoch. Layout and choices: `docs/CORPUS.md`, "MCAP".

mod events;
mod messages;
mod metadata;
mod schemas;

use std::collections::BTreeMap;
use std::io::{self, Cursor};
use std::ops::Range;
use std::path::Path;
use std::time::UNIX_EPOCH;

use ::mcap::records::{MessageHeader, Metadata};
use ::mcap::{Compression, McapError, WriteOptions};
use serde::Serialize;
use serde_json::Value;

use crate::annotations::Annotation;
use crate::export::timeline::Timeline;
use crate::export::{ExportError, ExportWarning, SessionExport};
use crate::layout::{SESSION_EVENTS, SESSION_MANIFEST};
use events::{LogEvent, Projection};

/// A channel of the export: its topic and the schema its messages follow.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Topic {
    Log,
    Pose,
    Speech,
    Commands,
    Page,
    Projection,
    Touches,
    Marks,
    Annotations,
}

impl Topic {
    /// Every channel, in the order the file declares them.
    const ALL: [Topic; 9] = [
        Topic::Log,
        Topic::Pose,
        Topic::Speech,
        Topic::Commands,
        Topic::Page,
        Topic::Projection,
        Topic::Touches,
        Topic::Marks,
        Topic::Annotations,
    ];

    fn name(self) -> &'static str {
        match self {
            Topic::Log => "/docent/log",
            Topic::Pose => "/docent/pose",
            Topic::Speech => "/docent/speech",
            Topic::Commands => "/docent/commands",
            Topic::Page => "/docent/page",
            Topic::Projection => "/docent/projection",
            Topic::Touches => "/docent/touches",
            Topic::Marks => "/docent/marks",
            Topic::Annotations => "/docent/annotations",
        }
    }

    fn schema(self) -> Value {
        match self {
            Topic::Log => schemas::log(),
            Topic::Pose => schemas::pose_in_frame(),
            Topic::Speech => schemas::utterance(),
            Topic::Commands => schemas::command(),
            Topic::Page => schemas::page(),
            Topic::Projection => schemas::projection(),
            Topic::Touches => schemas::touch(),
            Topic::Marks => schemas::mark(),
            Topic::Annotations => schemas::annotation(),
        }
    }
}

/// What the MCAP is made from.
pub struct Session<'a> {
    /// The session's folder (media files are looked for there).
    pub dir: &'a Path,
    /// `session.json` as it is, read tolerantly (fields this Docent does not know are kept).
    pub manifest: &'a Value,
    /// The log's whole lines.
    pub log: &'a [u8],
    /// The log read once.
    pub timeline: &'a Timeline,
    /// The researchers' annotations (`annotations.jsonl`), live ones only.
    pub annotations: &'a [Annotation],
}

/// Why the MCAP could not be made.
#[derive(Debug)]
pub enum McapProblem {
    /// The manifest's `started.time` is not an RFC 3339 time: there is no clock.
    NoClock(String),
    /// A line of the log the timeline passes over is damaged (1-based line number).
    DamagedLine(usize, String),
    /// The MCAP writer refused (never for a session's data; said as it is).
    Writer(McapError),
}

/// The MCAP file, and the media files the manifest lists that are not in the session's folder.
pub struct Written {
    /// The file's bytes.
    pub bytes: Vec<u8>,
    /// Each media `file` not found in the session's folder.
    pub media_not_found: Vec<String>,
}

/// The session clock's zero in nanoseconds since the Unix epoch: its `started.time`.
fn clock_zero_ns(manifest: &Value) -> Result<u64, McapProblem> {
    let time = manifest["started"]["time"].as_str().unwrap_or_default();
    let parsed = humantime::parse_rfc3339(time).map_err(|e| {
        McapProblem::NoClock(format!(
            "its `started.time` {time:?} is not an RFC 3339 time, which the MCAP's clock \
             starts from: {e}"
        ))
    })?;
    let since = parsed
        .duration_since(UNIX_EPOCH)
        .map_err(|_| McapProblem::NoClock(format!("its `started.time` {time:?} is before 1970")))?;
    Ok(since.as_nanos() as u64)
}

/// Writes `session` as an MCAP file.
pub fn write(session: &Session<'_>) -> Result<Written, McapProblem> {
    let zero_ns = clock_zero_ns(session.manifest)?;
    let events = events::read(session.log).map_err(|(n, p)| McapProblem::DamagedLine(n, p))?;
    let mut messages = Messages::new(zero_ns);
    collect(&mut messages, &events, session.timeline);
    for a in session.annotations {
        let message = messages::Annotation::from(a);
        messages.push(a.start_us, Topic::Annotations, &message);
    }
    // Stable: messages of one instant keep the order they were collected in.
    messages.list.sort_by_key(|m| m.0);

    let options = WriteOptions::new()
        .compression(Some(Compression::Lz4))
        .profile("")
        .library(concat!("docent ", env!("CARGO_PKG_VERSION")));
    let mut writer = options
        .create(Cursor::new(Vec::new()))
        .map_err(McapProblem::Writer)?;
    let mut channels = [0u16; Topic::ALL.len()];
    for topic in Topic::ALL {
        let schema = topic.schema();
        let name = schema["title"].as_str().unwrap_or_default();
        let bytes = serde_json::to_vec(&schema).expect("a schema serializes");
        let schema_id =
            (writer.add_schema(name, "jsonschema", &bytes)).map_err(McapProblem::Writer)?;
        let no_metadata = BTreeMap::new();
        channels[topic as usize] = writer
            .add_channel(schema_id, topic.name(), "json", &no_metadata)
            .map_err(McapProblem::Writer)?;
    }
    let mut sequence = [0u32; Topic::ALL.len()];
    for (log_time, topic, bytes) in &messages.list {
        let n = &mut sequence[*topic as usize];
        *n += 1;
        let header = MessageHeader {
            channel_id: channels[*topic as usize],
            sequence: *n,
            log_time: *log_time,
            publish_time: *log_time,
        };
        writer
            .write_to_known_channel(&header, &messages.data[bytes.clone()])
            .map_err(McapProblem::Writer)?;
    }
    let mut media_not_found = Vec::new();
    let record = Metadata {
        name: "docent.session".to_owned(),
        metadata: metadata::session(session.manifest, zero_ns),
    };
    writer
        .write_metadata(&record)
        .map_err(McapProblem::Writer)?;
    for media in metadata::media(session.manifest, zero_ns, session.dir) {
        media_not_found.extend(media.not_found);
        let record = Metadata {
            name: "docent.media".to_owned(),
            metadata: media.fields,
        };
        writer
            .write_metadata(&record)
            .map_err(McapProblem::Writer)?;
    }
    writer.finish().map_err(McapProblem::Writer)?;
    Ok(Written {
        bytes: writer.into_inner().into_inner(),
        media_not_found,
    })
}

/// The messages of every channel: log time (ns), channel, and where its JSON is in `data`
/// (one buffer for all: an hour has 40,000 messages).
struct Messages {
    zero_ns: u64,
    list: Vec<(u64, Topic, Range<usize>)>,
    data: Vec<u8>,
}

impl Messages {
    fn new(zero_ns: u64) -> Messages {
        Messages {
            zero_ns,
            list: Vec::new(),
            data: Vec::new(),
        }
    }

    /// The instant `session_us` on the MCAP's clock.
    fn ns(&self, session_us: u64) -> u64 {
        self.zero_ns + session_us * 1000
    }

    fn push(&mut self, session_us: u64, topic: Topic, message: &impl Serialize) {
        let start = self.data.len();
        serde_json::to_writer(&mut self.data, message).expect("a message serializes");
        let at = self.ns(session_us);
        self.list.push((at, topic, start..self.data.len()));
    }
}

/// Every channel's messages: each event, each pose, each change of what the projector shows
/// (a `display.changed` that changed only the page is not one), and the timeline's intervals
/// (at their start) and points.
fn collect(out: &mut Messages, events: &[LogEvent<'_>], timeline: &Timeline) {
    let mut projected: Option<&Projection> = None;
    for e in events {
        let ns = out.ns(e.session_us);
        out.push(e.session_us, Topic::Log, &messages::Log::of(e, ns));
        if let Some(pose) = &e.pose {
            out.push(
                e.session_us,
                Topic::Pose,
                &messages::PoseInFrame::of(pose, ns),
            );
        }
        if let Some(p) = &e.projection
            && projected != Some(p)
        {
            out.push(
                e.session_us,
                Topic::Projection,
                &messages::Projection::of(p, e.session_us),
            );
            projected = Some(p);
        }
    }
    for u in &timeline.utterances {
        out.push(u.start_us, Topic::Speech, &messages::Utterance::from(u));
    }
    for c in &timeline.commands {
        out.push(c.start_us, Topic::Commands, &messages::Command::from(c));
    }
    for p in &timeline.pages {
        out.push(p.start_us, Topic::Page, &messages::Page::from(p));
    }
    for t in &timeline.touches {
        out.push(t.at_us, Topic::Touches, &messages::Touch::from(t));
    }
    for m in &timeline.marks {
        out.push(m.at_us, Topic::Marks, &messages::Mark::from(m));
    }
}

impl SessionExport {
    /// The MCAP file's bytes; the manifest is read again as it is, so that fields this Docent
    /// does not know (a newer one's) reach the metadata too.
    pub(super) fn mcap(
        &self,
        file: &Path,
        warnings: &mut Vec<ExportWarning>,
    ) -> Result<Vec<u8>, ExportError> {
        let path = self.dir.join(SESSION_MANIFEST);
        let damaged = |problem: String| ExportError::DamagedManifest {
            path: path.clone(),
            problem,
        };
        let text = std::fs::read(&path).map_err(|e| damaged(e.to_string()))?;
        let mut manifest: serde_json::Value =
            serde_json::from_slice(&text).map_err(|e| damaged(e.to_string()))?;
        if !self.manifest.media_allowed() {
            // Read again as it is, but consent holds here too (`SessionExport::open`).
            manifest["media"] = serde_json::Value::Array(Vec::new());
        }
        let session = Session {
            dir: &self.dir,
            manifest: &manifest,
            log: &self.log,
            timeline: &self.timeline,
            annotations: self.annotations(),
        };
        let written = write(&session).map_err(|problem| match problem {
            McapProblem::NoClock(problem) => damaged(problem),
            McapProblem::DamagedLine(line, problem) => ExportError::DamagedLog {
                path: self.dir.join(SESSION_EVENTS),
                line,
                problem,
            },
            McapProblem::Writer(e) => ExportError::Write {
                path: file.to_owned(),
                source: io::Error::other(e),
            },
        })?;
        for file in written.media_not_found {
            warnings.push(ExportWarning::MediaNotInSession { file });
        }
        Ok(written.bytes)
    }
}
