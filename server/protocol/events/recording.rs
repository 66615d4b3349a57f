//! The corpus events of recordings: the kiosk device's microphone (and camera) recorded in the
//! browser and uploaded into the session's `media/` folder (the runtime's `recording`). Their own
//! enum, carried by [`super::EventKind::Recording`] and serialized with its own `type` tag, so
//! that the format of these four lines is read in one place. Documented in `docs/CORPUS.md`,
//! "Recording".

use serde::{Deserialize, Serialize};

use super::session::Consent;

/// What a recording file holds: `audio` (the microphone) or `video` (the camera, with the
/// microphone when audio is recorded too).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Track {
    /// The microphone alone.
    Audio,
    /// The camera (and the microphone when both are recorded).
    Video,
}

impl Track {
    /// The name used in file names and in the corpus.
    pub fn as_str(self) -> &'static str {
        match self {
            Track::Audio => "audio",
            Track::Video => "video",
        }
    }
}

/// Why a recording stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StopReason {
    /// Its session ended.
    SessionEnded,
    /// The visitors declined or withdrew their consent.
    Consent,
    /// The server shut down.
    ServerStopping,
    /// The kiosk's connection ended (a reload, a lost network): its next recording is a new file.
    KioskLeft,
    /// The kiosk reported a failure (`recording.failed` says which).
    Failed,
    /// The kiosk did not confirm its last upload in time after being told to stop.
    NoFinalReport,
}

impl StopReason {
    /// The name written in the corpus.
    pub fn as_str(self) -> &'static str {
        match self {
            StopReason::SessionEnded => "session-ended",
            StopReason::Consent => "consent",
            StopReason::ServerStopping => "server-stopping",
            StopReason::KioskLeft => "kiosk-left",
            StopReason::Failed => "failed",
            StopReason::NoFinalReport => "no-final-report",
        }
    }
}

/// Why a recording could not start or go on: reported by the kiosk (or found by the server,
/// `disk-error`, `limit-reached`, `disk-full`), logged as `recording.failed` and shown to operators at once.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FailureCode {
    /// The browser refused the microphone or camera (permission not granted).
    PermissionDenied,
    /// The device has no microphone or camera (or it is in use by another program).
    NoDevice,
    /// The browser cannot record WebM with Opus (and VP8).
    Unsupported,
    /// MediaRecorder reported an error while recording.
    RecorderError,
    /// Uploads kept failing beyond the retry budget: later audio is lost.
    UploadFailed,
    /// The kiosk's queue of chunks waiting for upload is full: later audio is lost.
    QueueFull,
    /// The server could not write the recording to disk.
    DiskError,
    /// The recording reached a limit of `corpus: record_limits` (its session's or its
    /// kiosk's share): the server stopped it.
    LimitReached,
    /// The corpus's disk has no more room than the reserve kept for the event log
    /// (`record_limits: keep_free`): the server stopped recording.
    DiskFull,
    /// Any other failure a kiosk reports (a newer kiosk's code).
    #[serde(other)]
    Other,
}

/// One recording event.
#[derive(Debug, Serialize, Deserialize)]
#[serde(tag = "type")]
pub enum RecordingEvent {
    /// A recording's first chunk began on the kiosk: where it lies on the session clock.
    #[serde(rename = "recording.started")]
    Started {
        /// The session.
        session: u64,
        /// The recording's id within the server run (the upload address names it).
        recording: u64,
        /// The kiosk recording it.
        client: u64,
        /// What it holds.
        track: Track,
        /// Its file, relative to the session folder (`media/audio-1.webm`).
        file: String,
        /// Its type, as the browser recorded it (`audio/webm;codecs=opus`).
        mime: String,
        /// Where its first sample lies on the session clock (µs after `session.started`).
        start_us: u64,
        /// The bound on `start_us`'s clock error: half the best round trip of the kiosk's
        /// clock exchange with the server.
        clock_error_us: u64,
    },
    /// A recording ended; its file holds `bytes` in `chunks` acknowledged chunks.
    #[serde(rename = "recording.stopped")]
    Stopped {
        /// The session.
        session: u64,
        /// The recording.
        recording: u64,
        /// Its file, relative to the session folder.
        file: String,
        /// Bytes acknowledged (the file's length).
        bytes: u64,
        /// Chunks acknowledged.
        chunks: u64,
        /// Why it stopped.
        reason: StopReason,
    },
    /// A recording could not start or go on.
    #[serde(rename = "recording.failed")]
    Failed {
        /// The session, if one runs.
        session: Option<u64>,
        /// The recording, when one had been asked for.
        recording: Option<u64>,
        /// The kiosk.
        client: u64,
        /// What failed.
        code: FailureCode,
        /// The browser's or server's words.
        message: String,
    },
    /// The session's media files were removed because its visitors declined or withdrew
    /// consent.
    #[serde(rename = "recording.deleted")]
    Deleted {
        /// The session.
        session: u64,
        /// The files removed, relative to the session folder.
        files: Vec<String>,
        /// The bytes removed, the files' sizes together (added without a version change:
        /// older logs lack it, read as 0).
        #[serde(default)]
        bytes: u64,
        /// The consent that removed them.
        consent: Consent,
    },
}
