//! Every line of a session's log as the MCAP export needs it: its place on the session clock,
//! its type and the level the `foxglove.Log` channel gives it, and, for the events only this
//! export draws (the timeline leaves them out), the robot's pose and what the projector shows.
//! Read through the protocol's types (`docent_protocol::events::Line`), as the timeline is.

use docent_protocol::ProjectorState;
use docent_protocol::events::{EventKind, Line, LineEvent};

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
    /// The level of an event (a type newer than this Docent's is `INFO`).
    pub fn of(event: &LineEvent) -> LogLevel {
        use EventKind::*;
        let LineEvent::Event(kind) = event else {
            return LogLevel::Info;
        };
        match kind {
            Pose { .. } => LogLevel::Debug,
            CommandFailed { .. } | BundleWatchFailed { .. } | MediaFailed { .. } => LogLevel::Error,
            TriggerRefused { .. }
            | CommandCancelled { .. }
            | PageMissing { .. }
            | ClientRefused { .. }
            | RequestRefused { .. }
            | BundleRefused { .. }
            | Stop { .. }
            | ProposalWithdrawn { .. } => LogLevel::Warning,
            _ => LogLevel::Info,
        }
    }
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
    pub projector_state: Option<ProjectorState>,
}

/// One line of the log.
pub struct LogEvent<'a> {
    /// Microseconds on the session clock.
    pub session_us: u64,
    /// Its `type`.
    pub kind: String,
    /// Its level on `/docent/log`.
    pub level: LogLevel,
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
/// line) through the protocol's types, as the timeline does; a `pose` without its position
/// and heading is a damaged line, told with its number.
pub fn read(log: &[u8]) -> Result<Vec<LogEvent<'_>>, (usize, String)> {
    let mut events = Vec::new();
    for (n, line) in log.split(|&b| b == b'\n').enumerate() {
        if line.is_empty() {
            continue;
        }
        let damaged = |problem: String| (n + 1, problem);
        let text = std::str::from_utf8(line).map_err(|e| damaged(e.to_string()))?;
        let read = Line::parse(line).map_err(|e| damaged(e.to_string()))?;
        let session_us =
            (read.head.session_us).ok_or_else(|| damaged("the line has no `session_us`".into()))?;
        let (mut pose, mut projection) = (None, None);
        match &read.event {
            LineEvent::Event(EventKind::Pose {
                x,
                y,
                heading,
                frame,
                ..
            }) => {
                // A number the line lacks reads as NaN (`EventKind::Pose`).
                if [x, y, heading].iter().any(|n| n.is_nan()) {
                    return Err(damaged(
                        "a `pose` without its numbers `x`, `y` and `heading`".into(),
                    ));
                }
                pose = Some(Pose {
                    x: *x,
                    y: *y,
                    heading: *heading,
                    frame: frame.clone().unwrap_or_else(|| DEFAULT_FRAME.to_owned()),
                });
            }
            LineEvent::Event(EventKind::DisplayChanged {
                projector,
                highlight,
                projector_state,
                ..
            }) => {
                projection = Some(Projection {
                    projector: projector.clone(),
                    highlight: highlight.clone(),
                    projector_state: Some(*projector_state),
                });
            }
            _ => {}
        }
        events.push(LogEvent {
            session_us,
            kind: read.head.kind.unwrap_or_default(),
            level: LogLevel::of(&read.event),
            line: text,
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
            r#"{"v":4,"session_us":5,"type":"pose","x":1,"y":2.5,"heading":90.0,"moving":true}"#,
            "\n",
            r#"{"v":4,"session_us":6,"type":"pose","x":1,"y":2.5,"heading":0,"moving":false,"frame":"hall"}"#,
            "\n",
            r#"{"v":4,"session_us":7,"type":"site.thing","x":"left","frame":{"a":1},"projector":3}"#,
            "\n",
            r#"{"v":4,"session_us":8,"type":"display.changed","page":"a.html","projector":null,"highlight":"0 0 1 1","projector_state":"shown"}"#,
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
            (shown.projector.as_ref(), shown.projector_state),
            (None, Some(ProjectorState::Shown))
        );
        assert_eq!(events[3].line, log.lines().nth(3).unwrap());

        let bad = "{\"v\":4,\"session_us\":1,\"type\":\"pose\",\"x\":1,\"y\":2,\"heading\":\"north\",\"moving\":true}\n";
        let (line, problem) = read(bad.as_bytes()).err().unwrap();
        assert_eq!(line, 1);
        assert_eq!(
            problem,
            "a `pose` without its numbers `x`, `y` and `heading`"
        );
    }

    #[test]
    fn every_event_type_has_its_level() {
        let level = |line: &str| LogLevel::of(&Line::parse(line.as_bytes()).unwrap().event);
        let pose = r#"{"v":4,"type":"pose","x":1,"y":2,"heading":0,"moving":false}"#;
        assert_eq!(level(pose), LogLevel::Debug);
        let command = r#""command":2,"trigger":1,"source":"http","label":"GO","at":"a.yaml:1","verb":"SAY","reason":"why""#;
        let failed = format!(r#"{{"v":4,"type":"command.failed",{command}}}"#);
        assert_eq!(level(&failed), LogLevel::Error);
        let cancelled = format!(r#"{{"v":4,"type":"command.cancelled",{command}}}"#);
        assert_eq!(level(&cancelled), LogLevel::Warning);
        let done = r#"{"v":4,"type":"drive.arrived","x":1,"y":2}"#;
        assert_eq!(level(done), LogLevel::Info);
        assert_eq!(
            level(r#"{"v":4,"type":"a.type.from.later"}"#),
            LogLevel::Info
        );
    }
}
