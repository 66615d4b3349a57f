//! `docent.yaml`'s `corpus:` settings in validated form: what starts a visitor session, how
//! long one a touch started lasts without a touch, the consent each starts with and what the
//! kiosk device records during one. Read by
//! `config_file/screens.rs`; documented for people in `docs/CONFIG.md`.

use std::time::Duration;

use crate::Consent;

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
    /// How much the recordings may take (`corpus: record_limits:`).
    pub record_limits: RecordLimits,
}

/// How much of the disk recordings may take (`corpus: record_limits:`): the kiosks upload
/// without a credential, so a kiosk (or anyone on its network) must not be able to fill the
/// disk the corpus log is written to. Recordings stop first, with the operator told.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RecordLimits {
    /// Bytes all recordings of one session may hold together.
    pub per_session: u64,
    /// Bytes one kiosk's recordings may hold in one session.
    pub per_kiosk: u64,
    /// Bytes left free on the corpus's disk: a chunk that would leave less is refused, so the
    /// event log can always be written.
    pub keep_free: u64,
}

impl Default for RecordLimits {
    fn default() -> Self {
        // An hour of 1080p VP8 with Opus at Chromium's default rate is about 1.1 GB.
        RecordLimits {
            per_session: 4_000_000_000,
            per_kiosk: 2_000_000_000,
            keep_free: 1_000_000_000,
        }
    }
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
            record_limits: RecordLimits::default(),
        }
    }
}
