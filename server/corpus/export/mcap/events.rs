//! Every line of a session's log as the MCAP export needs it: its place on the session clock,
//! its type and the level the `foxglove.Log` channel gives it, and, for the events only this
//! export draws (the timeline leaves them out), the robot's pose and what the projector shows.

use serde::Deserialize;
use serde::de::IgnoredAny;

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

/// A field read only for the event types that define it: another type may have a field of
/// the same name holding something else, which is then passed over (`Other`).
#[derive(Deserialize)]
#[serde(untagged)]
enum Lenient<T> {
    Is(T),
    Other(IgnoredAny),
}

/// A field of the event type that defines it: its value, `Ok(None)` when absent or `null`,
/// `Err` when it holds something else.
fn defined<T>(field: Option<Lenient<T>>) -> Result<Option<T>, ()> {
    match field {
        None => Ok(None),
        Some(Lenient::Is(value)) => Ok(Some(value)),
        Some(Lenient::Other(_)) => Err(()),
    }
}

/// The fields of a line this export reads, in one pass: its place on the session clock, its
/// type, and the fields of `pose` and `display.changed`.
#[derive(Deserialize)]
struct Fields {
    session_us: Option<u64>,
    #[serde(rename = "type")]
    kind: String,
    x: Option<Lenient<f64>>,
    y: Option<Lenient<f64>>,
    heading: Option<Lenient<f64>>,
    frame: Option<Lenient<String>>,
    projector: Option<Lenient<String>>,
    highlight: Option<Lenient<String>>,
    projector_state: Option<Lenient<String>>,
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
        let f: Fields = serde_json::from_str(line).map_err(|e| damaged(e.to_string()))?;
        let session_us = f
            .session_us
            .ok_or_else(|| damaged("the line has no `session_us`".into()))?;
        let (mut pose, mut projection) = (None, None);
        match f.kind.as_str() {
            "pose" => {
                let numbers = (defined(f.x), defined(f.y), defined(f.heading));
                let (Ok(Some(x)), Ok(Some(y)), Ok(Some(heading))) = numbers else {
                    return Err(damaged(
                        "a `pose` without its numbers `x`, `y` and `heading`".into(),
                    ));
                };
                let frame = defined(f.frame)
                    .map_err(|()| damaged("a `pose` whose `frame` is not a string".into()))?;
                pose = Some(Pose {
                    x,
                    y,
                    heading,
                    frame: frame.unwrap_or_else(|| DEFAULT_FRAME.to_owned()),
                });
            }
            "display.changed" => {
                let fields = (
                    defined(f.projector),
                    defined(f.highlight),
                    defined(f.projector_state),
                );
                let (Ok(projector), Ok(highlight), Ok(projector_state)) = fields else {
                    return Err(damaged(
                        "a `display.changed` whose `projector`, `highlight` or \
                         `projector_state` is neither a string nor null"
                            .into(),
                    ));
                };
                projection = Some(Projection {
                    projector,
                    highlight,
                    projector_state,
                });
            }
            _ => {}
        }
        events.push(LogEvent {
            session_us,
            kind: f.kind,
            line,
            pose,
            projection,
        });
    }
    Ok(events)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn poses_and_projections_are_read_from_their_own_types_only() {
        let log = concat!(
            r#"{"session_us":5,"type":"pose","x":1,"y":2.5,"heading":90.0,"moving":true}"#,
            "\n",
            r#"{"session_us":6,"type":"pose","x":1,"y":2.5,"heading":0,"frame":"hall"}"#,
            "\n",
            r#"{"session_us":7,"type":"site.thing","x":"left","frame":{"a":1},"projector":3}"#,
            "\n",
            r#"{"session_us":8,"type":"display.changed","page":"a.html","projector":null,"highlight":"0 0 1 1"}"#,
            "\n",
        );
        let events = read(log.as_bytes()).unwrap();
        let kinds: Vec<&str> = events.iter().map(|e| e.kind.as_str()).collect();
        assert_eq!(kinds, ["pose", "pose", "site.thing", "display.changed"]);
        let pose = events[0].pose.as_ref().unwrap();
        assert_eq!((pose.x, pose.y, pose.frame.as_str()), (1.0, 2.5, "map"));
        assert_eq!(events[1].pose.as_ref().unwrap().frame, "hall");
        assert!(events[2].pose.is_none() && events[2].projection.is_none());
        let shown = events[3].projection.as_ref().unwrap();
        assert_eq!(shown.highlight.as_deref(), Some("0 0 1 1"));
        assert_eq!(
            (shown.projector.as_ref(), shown.projector_state.as_ref()),
            (None, None)
        );
        assert_eq!(events[3].line, log.lines().nth(3).unwrap());

        let bad = "{\"session_us\":1,\"type\":\"pose\",\"x\":1,\"y\":2,\"heading\":\"north\"}\n";
        let (line, problem) = read(bad.as_bytes()).err().unwrap();
        assert_eq!(line, 1);
        assert_eq!(
            problem,
            "a `pose` without its numbers `x`, `y` and `heading`"
        );
    }

    #[test]
    fn every_event_type_has_its_level() {
        assert_eq!(LogLevel::of("pose"), LogLevel::Debug);
        assert_eq!(LogLevel::of("command.failed"), LogLevel::Error);
        assert_eq!(LogLevel::of("command.cancelled"), LogLevel::Warning);
        assert_eq!(LogLevel::of("a.type.from.later"), LogLevel::Info);
    }
}
