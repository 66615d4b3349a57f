//! The messages of the MCAP export's channels, as the JSON their schemas (`schemas.rs`)
//! describe: made from the session's timeline (utterances, commands, pages, touches, marks)
//! and from its log's lines (every event, poses, projections).

use serde::Serialize;

use crate::export::mcap::events::{LogEvent, Pose, Projection as Projected};
use crate::export::timeline::{
    CommandRun, Mark as MarkEvent, Marked, Outcome, PageShown, Touch as TouchEvent, Touched,
    Utterance as Said,
};
use docent_protocol::ProjectorState;

/// Foxglove's `Time`.
#[derive(Serialize)]
pub struct Time {
    sec: u64,
    nsec: u32,
}

impl Time {
    /// `ns` nanoseconds since the Unix epoch.
    pub fn of_ns(ns: u64) -> Time {
        Time {
            sec: ns / 1_000_000_000,
            nsec: (ns % 1_000_000_000) as u32,
        }
    }
}

/// `foxglove.Log`: one event of the log.
#[derive(Serialize)]
pub struct Log<'a> {
    timestamp: Time,
    level: u8,
    /// The log line as written: nothing of the event is lost.
    message: &'a str,
    /// The event's type.
    name: &'a str,
    file: &'static str,
    line: u32,
}

impl<'a> Log<'a> {
    /// The event `e`, logged at `ns`.
    pub fn of(e: &'a LogEvent<'a>, ns: u64) -> Log<'a> {
        Log {
            timestamp: Time::of_ns(ns),
            level: e.level as u8,
            message: e.line,
            name: &e.kind,
            file: "",
            line: 0,
        }
    }
}

/// `foxglove.Vector3`.
#[derive(Serialize)]
struct Vector3 {
    x: f64,
    y: f64,
    z: f64,
}

/// `foxglove.Quaternion`.
#[derive(Serialize)]
struct Quaternion {
    x: f64,
    y: f64,
    z: f64,
    w: f64,
}

/// `foxglove.Pose`.
#[derive(Serialize)]
struct Pose3 {
    position: Vector3,
    orientation: Quaternion,
}

/// `foxglove.PoseInFrame`: the robot on the floor, its heading a turn about the z axis.
#[derive(Serialize)]
pub struct PoseInFrame<'a> {
    timestamp: Time,
    frame_id: &'a str,
    pose: Pose3,
}

impl<'a> PoseInFrame<'a> {
    /// The pose `p`, at `ns`.
    pub fn of(p: &'a Pose, ns: u64) -> PoseInFrame<'a> {
        let half = p.heading.to_radians() / 2.0;
        PoseInFrame {
            timestamp: Time::of_ns(ns),
            frame_id: &p.frame,
            pose: Pose3 {
                position: Vector3 {
                    x: p.x,
                    y: p.y,
                    z: 0.0,
                },
                orientation: Quaternion {
                    x: 0.0,
                    y: 0.0,
                    z: half.sin(),
                    w: half.cos(),
                },
            },
        }
    }
}

/// An outcome's name, and its reason.
fn outcome(o: &Outcome) -> (&'static str, Option<&str>) {
    match o {
        Outcome::Done => ("done", None),
        Outcome::Failed(reason) => ("failed", Some(reason)),
        Outcome::Cancelled(reason) => ("cancelled", Some(reason)),
        Outcome::Open => ("open", None),
    }
}

/// `docent.Utterance`.
#[derive(Serialize)]
pub struct Utterance<'a> {
    start_us: u64,
    end_us: u64,
    text: &'a str,
    act: &'a str,
    source: &'a str,
    variant: Option<&'a str>,
    alternative: Option<u64>,
    outcome: &'static str,
    reason: Option<&'a str>,
}

impl<'a> From<&'a Said> for Utterance<'a> {
    fn from(u: &'a Said) -> Self {
        let (outcome, reason) = outcome(&u.outcome);
        Utterance {
            start_us: u.start_us,
            end_us: u.end_us,
            text: &u.text,
            act: &u.label,
            source: u.source.as_str(),
            variant: u.variant.as_deref(),
            alternative: u.alternative,
            outcome,
            reason,
        }
    }
}

/// `docent.Command`.
#[derive(Serialize)]
pub struct Command<'a> {
    start_us: u64,
    end_us: u64,
    verb: &'a str,
    arg: Option<&'a str>,
    outcome: &'static str,
    reason: Option<&'a str>,
}

impl<'a> From<&'a CommandRun> for Command<'a> {
    fn from(c: &'a CommandRun) -> Self {
        let (outcome, reason) = outcome(&c.outcome);
        Command {
            start_us: c.start_us,
            end_us: c.end_us,
            verb: &c.verb,
            arg: c.arg.as_deref(),
            outcome,
            reason,
        }
    }
}

/// `docent.Page`.
#[derive(Serialize)]
pub struct Page<'a> {
    start_us: u64,
    end_us: u64,
    page: &'a str,
}

impl<'a> From<&'a PageShown> for Page<'a> {
    fn from(p: &'a PageShown) -> Self {
        Page {
            start_us: p.start_us,
            end_us: p.end_us,
            page: &p.page,
        }
    }
}

/// `docent.Projection`.
#[derive(Serialize)]
pub struct Projection<'a> {
    at_us: u64,
    projector: Option<&'a str>,
    highlight: Option<&'a str>,
    projector_state: Option<ProjectorState>,
}

impl<'a> Projection<'a> {
    /// What `p` shows from `at_us` on.
    pub fn of(p: &'a Projected, at_us: u64) -> Projection<'a> {
        Projection {
            at_us,
            projector: p.projector.as_deref(),
            highlight: p.highlight.as_deref(),
            projector_state: p.projector_state,
        }
    }
}

/// `docent.Touch`.
#[derive(Serialize)]
pub struct Touch<'a> {
    at_us: u64,
    kind: &'static str,
    act: Option<&'a str>,
    code: Option<&'a str>,
    page: Option<&'a str>,
}

impl<'a> From<&'a TouchEvent> for Touch<'a> {
    fn from(t: &'a TouchEvent) -> Self {
        let (kind, act, code, page) = match &t.what {
            Touched::Act { label } => ("act", Some(label.as_str()), None, None),
            Touched::Refused { label, code } => {
                ("refused", Some(label.as_str()), Some(code.as_str()), None)
            }
            Touched::Page { page } => ("page", None, None, Some(page.as_str())),
        };
        Touch {
            at_us: t.at_us,
            kind,
            act,
            code,
            page,
        }
    }
}

/// `docent.Mark`.
#[derive(Serialize)]
pub struct Mark<'a> {
    at_us: u64,
    kind: &'static str,
    value: &'a str,
}

impl<'a> From<&'a MarkEvent> for Mark<'a> {
    fn from(m: &'a MarkEvent) -> Self {
        let (kind, value) = match &m.what {
            Marked::Situation(s) => ("situation", s),
            Marked::Group(g) => ("group", g),
            Marked::Note(text) => ("note", text),
        };
        Mark {
            at_us: m.at_us,
            kind,
            value,
        }
    }
}

/// `docent.Annotation`.
#[derive(Serialize)]
pub struct Annotation<'a> {
    id: &'a str,
    tier: &'a str,
    code: &'a str,
    start_us: u64,
    end_us: u64,
    annotator: Option<&'a str>,
}

impl<'a> From<&'a crate::annotations::Annotation> for Annotation<'a> {
    fn from(a: &'a crate::annotations::Annotation) -> Self {
        Annotation {
            id: &a.id,
            tier: &a.tier,
            code: &a.code,
            start_us: a.start_us,
            end_us: a.end_us,
            annotator: a.annotator.as_deref(),
        }
    }
}
