//! What the corpus says about a visitor session beyond its events: the visitors' consent and
//! why the session ended. Beside the event variants because the session keeper
//! (`operator::Visits`), the corpus writer and `docent corpus` use them on their own.

use serde::{Deserialize, Serialize};

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
