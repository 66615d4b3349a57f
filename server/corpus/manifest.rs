//! A session's manifest, `session.json`: what a researcher (or `docent corpus`) needs to know
//! about a session without reading its log. The corpus writer keeps it from the events it
//! writes into the session's log, and replaces it whole (written beside, then renamed) after
//! those lines are written, so a crash leaves the previous manifest or the new one, never half
//! of one, and never one that claims lines the log does not have.

use std::io::{self, Write};
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::layout::SESSION_MANIFEST;
use docent_protocol::events::Consent;

/// The manifest's format version: fields change meaning only with a new one.
pub const MANIFEST_FORMAT: u32 = 1;

/// The contents of `session.json`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SessionManifest {
    /// [`MANIFEST_FORMAT`].
    pub format: u32,
    /// The session's name: its folder's name.
    pub session: String,
    /// The session's number within its server run (the `session` field of its events).
    pub number: u64,
    /// Docent's version.
    pub docent: String,
    /// The bundle folder served, as `server.started` logged it.
    pub bundle: Option<String>,
    /// The bundle's content when the session started (`sha256:…`, see
    /// `content::bundle_fingerprint`); `None` when unknown (an older manifest, or a file
    /// that could not be read).
    #[serde(default)]
    pub bundle_hash: Option<String>,
    /// The first line of the session's log.
    pub started: SessionMark,
    /// The line that ended it; `None` while it runs, or when the server stopped without
    /// ending it (killed, crashed).
    pub ended: Option<SessionMark>,
    /// The visitor group the operator noted last, if any.
    pub group: Option<String>,
    /// The context in force when the session started, then as it changed.
    pub context: Option<String>,
    /// What the visitors agreed to, as last noted: `recorded`, `declined` or `withdrawn`.
    pub consent: String,
    /// The recordings in the session's `media/` folder, in order of start; emptied when the
    /// visitors decline or withdraw consent (their files are removed). Missing: none.
    #[serde(default)]
    pub media: Vec<MediaFile>,
}

/// One recording file of a session, placed on the session clock.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MediaFile {
    /// Its path in the session folder (`media/audio-1.webm`).
    pub file: String,
    /// `audio`, or `video` (with the microphone too when audio is recorded).
    pub track: String,
    /// Its type as recorded (`audio/webm;codecs=opus`).
    pub mime: String,
    /// Where its first sample lies on the session clock: µs after `session.started`.
    pub start_us: u64,
    /// The bound on `start_us`'s error from the clock exchange (half the best round trip).
    #[serde(default)]
    pub clock_error_us: u64,
    /// The recording's id in its `recording.*` events.
    pub recording: u64,
}

/// A session's start or end, as its event was stamped.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SessionMark {
    /// The event's `seq`.
    pub seq: u64,
    /// Its wall-clock time (RFC 3339, UTC, milliseconds).
    pub time: String,
    /// Its `mono_us`: the session clock's zero is the start's.
    pub mono_us: u64,
    /// Who started or ended it (`operator`, `dm`, `server`, ...).
    pub source: String,
    /// Why it ended (`marked`, `next-session`, `server-stopping`); none for a start.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub reason: Option<String>,
}

impl SessionManifest {
    /// Replaces `dir`'s manifest with this one, atomically.
    pub fn write_to(&self, dir: &Path) -> io::Result<()> {
        let mut text = serde_json::to_vec_pretty(self).map_err(io::Error::other)?;
        text.push(b'\n');
        let path = dir.join(SESSION_MANIFEST);
        let partial = dir.join(format!("{SESSION_MANIFEST}.partial"));
        let mut file = std::fs::File::create(&partial)?;
        file.write_all(&text)?;
        file.sync_data()?;
        std::fs::rename(&partial, &path)
    }

    /// Whether the visitors' consent, as last noted, lets their recordings be kept and used:
    /// only `recorded` does. A manifest whose word is none Docent writes keeps nothing.
    pub fn media_allowed(&self) -> bool {
        media_allowed(&self.consent)
    }

    /// Reads `dir`'s manifest.
    pub fn read_from(dir: &Path) -> io::Result<SessionManifest> {
        let text = std::fs::read(dir.join(SESSION_MANIFEST))?;
        serde_json::from_slice(&text).map_err(|e| io::Error::new(io::ErrorKind::InvalidData, e))
    }
}

/// Whether a manifest's `consent` word lets a session's recordings be kept and used: only
/// `recorded` does (declined, withdrawn, or anything unreadable keeps nothing). The one rule
/// for every reader of media: exports, the `/sessions` page, start-up recovery.
pub fn media_allowed(consent: &str) -> bool {
    Consent::from_word(consent) == Some(Consent::Recorded)
}
