//! `docent.yaml`'s `corpus:` settings in validated form: what starts a visitor session, how
//! long one a touch started lasts without a touch, the consent each starts with and what the
//! kiosk device records during one. Read by
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
    /// What the kiosk device records during a session whose consent is `recorded`.
    pub record: RecordTracks,
}

/// What the kiosk device records (`corpus: record:`): its microphone, its camera, both or
/// nothing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RecordTracks {
    /// The microphone.
    pub audio: bool,
    /// The camera.
    pub video: bool,
}

impl RecordTracks {
    /// Nothing is recorded.
    pub const OFF: RecordTracks = RecordTracks {
        audio: false,
        video: false,
    };

    /// Whether anything is recorded.
    pub fn any(self) -> bool {
        self.audio || self.video
    }

    /// The tracks by name, `audio` before `video`, as the `record` frame lists them.
    pub fn names(self) -> Vec<&'static str> {
        [("audio", self.audio), ("video", self.video)]
            .into_iter()
            .filter_map(|(name, on)| on.then_some(name))
            .collect()
    }
}

impl Default for CorpusSettings {
    fn default() -> Self {
        CorpusSettings {
            session_start: SessionStart::Touch,
            session_idle: Duration::from_secs(120),
            consent: Consent::Recorded,
            record: RecordTracks {
                audio: true,
                video: false,
            },
        }
    }
}
