//! `docent.yaml`'s `corpus:` settings in validated form: what starts a visitor session, how
//! long one a touch started lasts without a touch, and the consent each starts with. Read by
//! `config_file/screens.rs`; documented for people in `docs/CONFIG.md`.

use std::time::Duration;

use crate::events::Consent;

/// What starts a visitor session (`corpus: session_start:`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SessionStart {
    /// A visitor's first touch when none runs (the default), or a mark.
    Touch,
    /// Only an operator's or a dialog manager's mark.
    Marked,
}

/// How the corpus is cut into visitor sessions (`corpus:`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CorpusSettings {
    /// What starts a session.
    pub session_start: SessionStart,
    /// A session a touch started ends after this long without a touch; zero: never.
    pub session_idle: Duration,
    /// The consent each session starts with.
    pub consent: Consent,
}

impl Default for CorpusSettings {
    fn default() -> Self {
        CorpusSettings {
            session_start: SessionStart::Touch,
            session_idle: Duration::from_secs(120),
            consent: Consent::Recorded,
        }
    }
}
