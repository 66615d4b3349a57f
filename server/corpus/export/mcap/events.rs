//! Every line of a session's log as the MCAP export needs it: its place on the session clock,
//! its type and the level the `foxglove.Log` channel gives it, and, for the events only this
//! export draws (the timeline leaves them out), the robot's pose and what the projector shows.

use serde::Deserialize;

/// Foxglove's `LogLevel`, as `/docent/log` gives each event type (`UNKNOWN` and `FATAL` are
/// never given: every event type has its level, and none stops Docent).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum LogLevel {
    /// Poses, several a second: hidden when the Log panel shows INFO and up.
    Debug = 1,
    /// What went as asked.
    Info = 2,
    /// Refused, cancelled or missing: something a researcher may look for.
    Warning = 3,
    /// A command that failed, a bundle folder that cannot be watched.
    Error = 4,
}

impl LogLevel {
    /// The level of an event `kind` (its `type`).
    pub fn of(kind: &str) -> LogLevel {
        match kind {
            "pose" => LogLevel::Debug,
            "command.failed" | "bundle.watch-failed" => LogLevel::Error,
            "trigger.refused" | "command.cancelled" | "page.missing" | "client.refused"
            | "request.refused" | "bundle.refused" | "stop" | "proposal.withdrawn" => {
                LogLevel::Warning
            }
            _ => LogLevel::Info,
        }
    }
}

/// What every line has: its place on the session clock and its type.
#[derive(Deserialize)]
struct Stamp {
    session_us: Option<u64>,
    #[serde(rename = "type")]
    kind: String,
}

/// The fields of a `pose` this export reads (read only from a `pose`, so that another event
/// type may have fields of these names and other types).
#[derive(Deserialize)]
struct PoseFields {
    x: Option<f64>,
    y: Option<f64>,
    heading: Option<f64>,
    frame: Option<String>,
}

/// The projector's fields of a `display.changed`.
#[derive(Deserialize)]
struct DisplayFields {
    projector: Option<String>,
    highlight: Option<String>,
    projector_state: Option<String>,
}

/// The robot's pose from a `pose` event.
#[derive(Clone, Debug, PartialEq)]
pub struct Pose {
    /// Metres.
    pub x: f64,
    /// Metres.
    pub y: f64,
    /// Degrees, counter-clockwise from the x axis.
    pub heading: f64,
    /// The frame the log names, else `map`.
    pub frame: String,
}

/// What the projector shows, from a `display.changed`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Projection {
    /// The file under `media/`.
    pub projector: Option<String>,
    /// The areas lit, as written.
    pub highlight: Option<String>,
    /// What the projector reported.
    pub projector_state: Option<String>,
}

/// One line of the log.
pub struct LogEvent<'a> {
    /// Microseconds on the session clock.
    pub session_us: u64,
    /// Its `type`.
    pub kind: String,
    /// The line as written, without its `\n`.
    pub line: &'a str,
    /// Its pose, for a `pose`.
    pub pose: Option<Pose>,
    /// The projector's part of a `display.changed`.
    pub projection: Option<Projection>,
}

/// The frame a pose is in when the log names none: the map the drive's waypoints are in.
pub const DEFAULT_FRAME: &str = "map";

/// Reads the log's whole lines (already read once into the timeline, so each is a corpus
/// line); a `pose` without its position and heading is a damaged line, told with its number.
pub fn read(log: &[u8]) -> Result<Vec<LogEvent<'_>>, (usize, String)> {
    let mut events = Vec::new();
    for (n, line) in log.split(|&b| b == b'\n').enumerate() {
        if line.is_empty() {
            continue;
        }
        let damaged = |problem: String| (n + 1, problem);
        let line = std::str::from_utf8(line).map_err(|e| damaged(e.to_string()))?;
        let parse_error = |e: serde_json::Error| damaged(e.to_string());
        let stamp: Stamp = serde_json::from_str(line).map_err(parse_error)?;
        let session_us = stamp
            .session_us
            .ok_or_else(|| damaged("the line has no `session_us`".into()))?;
        let (mut pose, mut projection) = (None, None);
        match stamp.kind.as_str() {
            "pose" => {
                let p: PoseFields = serde_json::from_str(line).map_err(parse_error)?;
                let (Some(x), Some(y), Some(heading)) = (p.x, p.y, p.heading) else {
                    return Err(damaged(
                        "a `pose` without its numbers `x`, `y` and `heading`".into(),
                    ));
                };
                let frame = p.frame.unwrap_or_else(|| DEFAULT_FRAME.to_owned());
                pose = Some(Pose {
                    x,
                    y,
                    heading,
                    frame,
                });
            }
            "display.changed" => {
                let d: DisplayFields = serde_json::from_str(line).map_err(parse_error)?;
                projection = Some(Projection {
                    projector: d.projector,
                    highlight: d.highlight,
                    projector_state: d.projector_state,
                });
            }
            _ => {}
        }
        events.push(LogEvent {
            session_us,
            kind: stamp.kind,
            line,
            pose,
            projection,
        });
    }
    Ok(events)
}
