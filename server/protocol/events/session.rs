//! What the corpus says about a visitor session: its start and end (`session.*`), and what
//! operators note about it meanwhile (`consent.changed`, `visitor.group`, `situation.marked`,
//! `note.written`). The visitors' consent and why a session ended are types of their own,
//! because the session keeper (`operator::Visits`), the corpus writer and `docent corpus` use
//! them on their own.

use serde::{Deserialize, Serialize};

use super::origin::Source;
pub use docent_content::Consent;

/// Why a visitor session ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SessionEnd {
    /// Its end was marked.
    Marked,
    /// The next session was started.
    NextSession,
    /// The server shut down while it ran.
    ServerStopping,
    /// No visitor touched the screen for the site's idle time (a session a touch started).
    Idle,
}

impl SessionEnd {
    /// The name written in the corpus.
    pub fn as_str(self) -> &'static str {
        match self {
            SessionEnd::Marked => "marked",
            SessionEnd::NextSession => "next-session",
            SessionEnd::ServerStopping => "server-stopping",
            SessionEnd::Idle => "idle",
        }
    }
}

/// The fields of a `session.started` event ([`super::EventKind::SessionStarted`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct SessionStarted {
    /// The session's number, from 1 within one server run.
    pub session: u64,
    /// Who marked it.
    pub source: Source,
    /// The marking client.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub client: Option<u64>,
    /// The consent it starts with (the site's `corpus.consent`). Format 3 lines before
    /// consent was logged lack it: read as `recorded`, the site's default then.
    #[serde(default = "recorded")]
    pub consent: Consent,
    /// The page the touchscreen showed as it began (the session's pages start with it).
    pub page: Option<String>,
    /// The film or picture the projector showed as it began.
    pub projector: Option<String>,
}

/// The fields of a `consent.changed` event ([`super::EventKind::ConsentChanged`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct ConsentChanged {
    /// The session.
    pub session: u64,
    /// The new state.
    pub consent: Consent,
    /// Who noted it.
    pub source: Source,
    /// The noting client.
    pub client: u64,
}

/// The fields of a `session.ended` event ([`super::EventKind::SessionEnded`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct SessionEnded {
    /// The session's number.
    pub session: u64,
    /// Who ended it.
    pub source: Source,
    /// The client that ended it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub client: Option<u64>,
    /// Why it ended (format 3). Format 1 and 2 lines lack it: read as `marked`.
    #[serde(default = "marked")]
    pub reason: SessionEnd,
}

/// The fields of a `visitor.group` event ([`super::EventKind::VisitorGroup`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct VisitorGroup {
    /// The running session, if any.
    pub session: Option<u64>,
    /// `single`, `group` or `children`.
    pub group: String,
    /// The context this set, when the site maps the group to one.
    pub context: Option<String>,
    /// Who marked it.
    pub source: Source,
    /// The marking client.
    pub client: u64,
}

/// The fields of a `situation.marked` event ([`super::EventKind::SituationMarked`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct SituationMarked {
    /// The running session, if any.
    pub session: Option<u64>,
    /// The situation's name.
    pub situation: String,
    /// Who marked it.
    pub source: Source,
    /// The marking client.
    pub client: u64,
}

/// The fields of a `note.written` event ([`super::EventKind::NoteWritten`]).
#[derive(Debug, Serialize, Deserialize)]
pub struct NoteWritten {
    /// The running session, if any.
    pub session: Option<u64>,
    /// The note, trimmed.
    pub text: String,
    /// Who wrote it.
    pub source: Source,
    /// The writing client.
    pub client: u64,
}

/// What a `session.started` without `consent` reads as.
fn recorded() -> Consent {
    Consent::Recorded
}

/// What a `session.ended` without `reason` reads as.
fn marked() -> SessionEnd {
    SessionEnd::Marked
}
