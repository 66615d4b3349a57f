//! The frames a websocket client sends Docent (JSON text, tagged by `type`), read strictly:
//! an unknown type or field is refused (`docs/PROTOCOL.md`, "Client frames"). What Docent
//! sends back is in `server_frames.rs`.

use serde::{Deserialize, Serialize};

use crate::events::{AttractEnd, AttractState, ClientRole, FailureCode, KioskCause};

/// Largest text frame Docent reads; larger ones are answered with an error.
pub const MAX_FRAME_BYTES: usize = 16 * 1024;

/// `hello`: who the client is. Its own struct, so that the session takes it whole.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HelloFrame {
    /// Its role.
    pub role: ClientRole,
    /// Verbs served (adapters only).
    #[serde(default)]
    pub verbs: Vec<String>,
    /// The robot events it may send (adapters only): what its sensors notice.
    #[serde(default)]
    pub robot_events: Vec<String>,
    /// A name for logs and the operator's view.
    #[serde(default)]
    pub name: Option<String>,
    /// The credential (operator and dialog-manager roles; adapters not on this machine).
    #[serde(default)]
    pub token: Option<String>,
    /// Whether an operator or dialog manager wants the event stream (default true); a
    /// client that only triggers can say false and save both sides the traffic.
    #[serde(default = "yes")]
    pub events: bool,
    /// The page a reconnecting kiosk shows (relative to `pages/`): a restarted server
    /// adopts it instead of sending the kiosk home (docs/PROTOCOL.md, `hello`).
    #[serde(default)]
    pub page: Option<String>,
    /// The visitor's language a reconnecting kiosk shows its pages in: a restarted
    /// server goes on in it instead of the default (docs/PROTOCOL.md, `hello`).
    #[serde(default)]
    pub language: Option<String>,
}

/// `trigger`: an act to trigger. Its own struct, so that the session takes it whole.
///
/// `context`, `interrupt` and `ref` mean what they mean in the HTTP trigger's body,
/// [`TriggerOptions`]; they are declared in both because serde cannot nest one struct in
/// another without `flatten`, and `flatten` would change what a strict frame answers (an
/// unknown field no longer lists the known ones, and is reported after a missing `label`).
/// `trigger_frame_and_http_body_read_options_alike` holds the two to the same defaults.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TriggerFrame {
    /// The act.
    pub label: String,
    /// A context variant.
    #[serde(default)]
    pub context: Option<String>,
    /// Clear speech first.
    #[serde(default)]
    pub interrupt: bool,
    /// Echoed back.
    #[serde(default, rename = "ref")]
    pub reference: Option<String>,
    /// A kiosk's reason: a visitor's touch (the default), a timer, the idle return, a
    /// script. Only a touch starts a session and is logged as a `touch`.
    #[serde(default)]
    pub via: Option<KioskCause>,
    /// The element touched, as the kiosk describes it.
    #[serde(default)]
    pub element: Option<String>,
}

/// The body of `POST /api/acts/{label}/trigger` (the label is in the address): a trigger's
/// options, each optional; an empty body is all defaults. Strict like a frame: an unknown field
/// is a `400 bad-request` naming the known ones.
#[derive(Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(deny_unknown_fields)]
pub struct TriggerOptions {
    /// The context variant for this trigger only; the current context when absent.
    #[serde(default)]
    pub context: Option<String>,
    /// Cancel queued and current speech first.
    #[serde(default)]
    pub interrupt: bool,
    /// The caller's reference, echoed in the answer and logged.
    #[serde(default, rename = "ref")]
    pub reference: Option<String>,
}

/// A frame from a client.
#[derive(Debug, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum ClientFrame {
    /// First frame: who the client is.
    Hello(HelloFrame),
    /// Trigger an act.
    Trigger(TriggerFrame),
    /// Stop everything.
    Stop {
        /// Echoed back.
        #[serde(default, rename = "ref")]
        reference: Option<String>,
    },
    /// Set the current context.
    Context {
        /// The new context.
        context: String,
        /// Echoed back.
        #[serde(default, rename = "ref")]
        reference: Option<String>,
    },
    /// Set the visitor's language (a kiosk: only one its page offers a button for).
    Language {
        /// The language, one of the bundle's `languages:`.
        language: String,
        /// Echoed back.
        #[serde(default, rename = "ref")]
        reference: Option<String>,
    },
    /// An adapter process tells of something the robot noticed (one of its `robot_events`).
    Robot {
        /// The event's name.
        event: String,
        /// What it says about it, as the adapter likes (logged as sent).
        #[serde(default)]
        data: serde_json::Value,
    },
    /// A kiosk shows another page of the bundle on its own (a link, the idle return home).
    Page {
        /// The page, relative to `pages/`.
        page: String,
        /// Why: a visitor's touch on a link (the default), the idle return home, a script.
        #[serde(default)]
        via: Option<KioskCause>,
        /// The link touched, as the kiosk describes it.
        #[serde(default)]
        element: Option<String>,
    },
    /// A kiosk's attract loop began or ended (`static/attract.js`).
    Attract {
        /// Began or ended.
        state: AttractState,
        /// What ended it (with `ended`).
        #[serde(default)]
        by: Option<AttractEnd>,
    },
    /// A dialog manager proposes an act to the operators.
    Propose {
        /// The act.
        label: String,
        /// A context variant (the current one when absent).
        #[serde(default)]
        context: Option<String>,
        /// Why, for the operator.
        #[serde(default)]
        reason: Option<String>,
        /// Echoed back.
        #[serde(default, rename = "ref")]
        reference: Option<String>,
    },
    /// An operator accepts a proposal: its act is triggered.
    Accept {
        /// The proposal's id.
        proposal: u64,
        /// Echoed back.
        #[serde(default, rename = "ref")]
        reference: Option<String>,
    },
    /// An operator dismisses a proposal.
    Dismiss {
        /// The proposal's id.
        proposal: u64,
        /// Echoed back.
        #[serde(default, rename = "ref")]
        reference: Option<String>,
    },
    /// An operator marks the corpus: a visitor session, the visitor group, a situation.
    Mark {
        /// What is marked.
        mark: MarkKind,
        /// The group (`single`, `group`, `children`) or the situation's name.
        #[serde(default)]
        value: Option<String>,
        /// For a consent that deletes the session's recordings (`recorded` to `declined` or
        /// `withdrawn`): the operator confirmed it. Without it such a mark is refused
        /// (`confirmation-required`).
        #[serde(default)]
        confirm: bool,
        /// Echoed back.
        #[serde(default, rename = "ref")]
        reference: Option<String>,
    },
    /// WebRTC signalling between an operator and a kiosk, relayed as is.
    Signal {
        /// The receiving client's id.
        to: u64,
        /// Offer, answer, candidate...: opaque to the server.
        data: serde_json::Value,
    },
    /// An adapter began a command.
    Started {
        /// Command id.
        id: u64,
    },
    /// An adapter finished a command (a screen: showed it, or played the film to its end).
    Done {
        /// Command id.
        id: u64,
        /// Projector only: the ended film's last frame stays on screen.
        #[serde(default)]
        held: bool,
    },
    /// An adapter could not carry out a command.
    Failed {
        /// Command id.
        id: u64,
        /// Why.
        #[serde(default)]
        reason: Option<String>,
    },
    /// A kiosk asks for the hub's clock (answered `clock` at once), to place its recordings.
    Clock {
        /// The kiosk's own time when it asked, echoed back.
        t0: f64,
    },
    /// A kiosk's recording began: its first sample on the hub's clock.
    #[serde(rename = "recording-started")]
    RecordingStarted {
        /// The recording, from its `record` frame.
        recording: u64,
        /// The type the browser records (`audio/webm;codecs=opus`).
        mime: String,
        /// When its first sample was taken, on the hub's clock (µs, as `clock` gave it).
        mono_us: u64,
        /// The bound on that time's error (half the best clock round trip), µs.
        clock_error_us: u64,
    },
    /// A kiosk stopped a recording and uploaded its last chunk.
    #[serde(rename = "recording-stopped")]
    RecordingStopped {
        /// The recording.
        recording: u64,
    },
    /// A kiosk could not record (permission, device, recorder, uploads).
    #[serde(rename = "recording-failed")]
    RecordingFailed {
        /// The recording, when one was asked for.
        #[serde(default)]
        recording: Option<u64>,
        /// What failed.
        code: FailureCode,
        /// The browser's words.
        #[serde(default)]
        message: String,
    },
}

/// What a `mark` frame marks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MarkKind {
    /// A visitor session begins (ending the running one).
    SessionStart,
    /// The visitor session ends.
    SessionEnd,
    /// Who the visitors are: `value` is `single`, `group` or `children`.
    Group,
    /// A dialog situation: `value` is one of the site's situations.
    Situation,
    /// What the session's visitors agreed to: `value` is `recorded`, `declined` or
    /// `withdrawn`.
    Consent,
    /// An operator's note in their own words: `value` is its text.
    Note,
}

fn yes() -> bool {
    true
}

/// The `type` of every frame a client may send, in [`ClientFrame`]'s order, asked of serde
/// (`tags`): what an `unknown-type` error lists, never written a second time.
pub fn frame_types() -> &'static [&'static str] {
    static TYPES: std::sync::OnceLock<&'static [&'static str]> = std::sync::OnceLock::new();
    TYPES.get_or_init(|| {
        crate::tags::tags_of(|probe| {
            <ClientFrame as serde::Deserialize>::deserialize(probe).map(drop)
        })
    })
}

#[cfg(test)]
mod tags_tests {
    use super::*;

    /// The list an `unknown-type` error gives is every frame a client may send, each of which
    /// reads as a frame (a malformed one then gets `bad-frame`, never `unknown-type`).
    #[test]
    fn every_frame_type_a_client_may_send_is_known_and_no_other() {
        let types = frame_types();
        assert_eq!(types.len(), 20, "{types:?}");
        assert_eq!(types.first(), Some(&"hello"));
        for t in ["language", "attract", "recording-started", "clock"] {
            assert!(types.contains(&t), "{t} in {types:?}");
        }
        for t in types {
            let frame = serde_json::json!({ "type": t, "zz_not_a_field": 1 });
            let error = serde_json::from_value::<ClientFrame>(frame).expect_err("a bad frame");
            assert!(
                !error.to_string().contains("unknown variant"),
                "{t}: {error}"
            );
        }
    }
}
