//! What the corpus says about a visitor session beyond its events: the visitors' consent and
//! why the session ended. Beside the event variants because the session keeper
//! (`operator::Visits`), the corpus writer and `docent corpus` use them on their own.

use serde::Serialize;

/// What a session's visitors agreed to: whether its audio and video may be kept.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Consent {
    /// They agreed (or the site records by default, with notice).
    Recorded,
    /// They did not agree: nothing of them is recorded.
    Declined,
    /// They took it back: what was recorded is removed, and nothing more is recorded.
    Withdrawn,
}

impl Consent {
    /// The name written in the corpus and in `mark` frames.
    pub fn as_str(self) -> &'static str {
        match self {
            Consent::Recorded => "recorded",
            Consent::Declined => "declined",
            Consent::Withdrawn => "withdrawn",
        }
    }

    /// The state named `word`, if any.
    pub fn from_word(word: &str) -> Option<Consent> {
        [Consent::Recorded, Consent::Declined, Consent::Withdrawn]
            .into_iter()
            .find(|c| c.as_str() == word)
    }
}

/// Why a visitor session ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
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
