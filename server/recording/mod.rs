//! Recording: the kiosk device's microphone (and camera, `corpus: record: [audio, video]`)
//! recorded in the browser with MediaRecorder during a visitor session whose consent is
//! `recorded`, uploaded chunk by chunk into the session's `media/` folder, and placed on the
//! session clock. Format and guarantees: `docs/CORPUS.md`, "Recording".
//!
//! - `mod.rs`: [`Recordings`], the open recordings and what each kiosk is doing, changed
//!   under one lock; the kiosk's reports (`recording-started`, `-stopped`, `-failed`).
//! - `control.rs`: follows the hub without loss: a session that starts (or gets consent)
//!   starts a recording on every kiosk, one that ends stops them.
//! - `consent.rs`: consent carried out: `note_consent`, the one way it changes; a refusal
//!   closes the session's recordings and removes its media before the mark is answered;
//!   `may_keep`, what every start and chunk asks.
//! - `quota.rs`: `corpus: record_limits`, counted per chunk before it is stored.
//! - `upload.rs`: `PUT /api/recordings/{recording}/chunks/{seq}`, each recording's own
//!   upload token as its Bearer credential.
//! - `frames.rs`: the frames to the kiosk (`record`, `record-stop`, `clock`).
//!
//! The files themselves (`ChunkFile`, one file grown chunk by chunk, acknowledged only once
//! synced; the recovery at start-up) are the corpus crate's `chunks` and `recover`.

mod consent;
mod control;
mod frames;
mod quota;
mod upload;

use std::collections::{BTreeMap, HashMap};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

use serde::Serialize;

use crate::access::Secret;
use crate::content::config::RecordTracks;
use crate::corpus::SessionFolders;
use crate::events::{EventKind, FailureCode, Hub, RecordingEvent, StopReason, Track};
use crate::lifecycle::Lifecycle;
use crate::operator::Visits;
use crate::state::ClientLinks;
use crate::sync::lock;

pub use crate::corpus::chunks::{self, ChunkFile};
pub use crate::corpus::recover::{Cut, cut_unacknowledged, remove_unconsented};
pub use frames::clock_frame;
use quota::OverLimit as Over;
pub use quota::{OverLimit, SessionQuota, available_bytes};
pub use upload::{MAX_CHUNK_BYTES, put_chunk};

/// The folder of a session's recordings, inside its folder (the corpus layout's).
pub use crate::corpus::layout::MEDIA_DIR;

/// What a kiosk's recording is doing, as operators see it (`/api/state`'s `recording`).
#[derive(Clone, Debug, Serialize)]
pub struct KioskRecording {
    /// The kiosk's connection.
    pub client: u64,
    /// What it is doing.
    pub state: KioskRecordingState,
    /// The recording, when there is one.
    pub recording: Option<u64>,
    /// Its file in the session folder.
    pub file: Option<String>,
    /// For `failed`: the code and the words.
    pub code: Option<FailureCode>,
    /// For `failed`: what went wrong.
    pub message: Option<String>,
}

/// What a kiosk's recording is doing, written in `/api/state` in lower case.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum KioskRecordingState {
    /// Not recording.
    Off,
    /// Asked to record; the browser has not begun.
    Starting,
    /// Recording.
    Recording,
    /// Told to stop, its last chunk on its way.
    Stopping,
    /// It failed (`code` and `message` say how).
    Failed,
}

/// The recording state for `/api/state`.
#[derive(Debug, Serialize)]
pub struct RecordingView {
    /// The session being recorded, if any.
    pub session: Option<u64>,
    /// Each connected kiosk: a `failed` one is a failure that is still current (it clears
    /// when the kiosk records again, leaves, or the session ends or the next one starts).
    pub kiosks: Vec<KioskRecording>,
    /// What the session being recorded holds: what a consent declined or withdrawn would
    /// delete now (the console names it before asking to confirm).
    pub kept: Option<KeptMedia>,
}

/// The recordings a session holds so far, as the operator is asked about them.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct KeptMedia {
    /// The session.
    pub session: u64,
    /// Its recordings that began (one file each).
    pub files: u32,
    /// The bytes stored (or being stored).
    pub bytes: u64,
    /// Seconds since its first recording began (0 before one did).
    pub seconds: u64,
}

/// One recording: a kiosk's file in a session's `media/`.
#[derive(Debug)]
pub struct Recording {
    id: u64,
    session: u64,
    client: u64,
    track: Track,
    /// Relative to the session folder: `media/audio-1.webm`.
    file: String,
    token: Secret,
    /// Its session's limits and what its recordings hold.
    quota: Arc<SessionQuota>,
    /// The file; `None` once the recording is closed (chunks are refused then).
    chunks: Mutex<Option<ChunkFile>>,
}

/// What became of a chunk handed to [`Recordings::append`].
enum Appending {
    /// The recording is closed, or its visitors' consent is gone.
    Closed,
    /// A limit of `corpus: record_limits` (or the disk's reserve) refused it.
    OverLimit(Over),
    /// The file's answer.
    Done(std::io::Result<chunks::Appended>),
}

/// The session being recorded.
#[derive(Debug)]
struct Recorded {
    number: u64,
    /// `session.started`'s `mono_us`: the session clock's zero.
    start_mono_us: u64,
    dir: PathBuf,
    /// The number of the next file (`audio-N.webm`), from 1 within the session.
    next_file: u32,
    tracks: RecordTracks,
    /// Its limits, shared by its recordings.
    quota: Arc<SessionQuota>,
    /// Its recordings that began (`recording.started`).
    started: u32,
    /// When the first of them began, on the hub's clock.
    first_start_mono_us: Option<u64>,
}

#[derive(Debug, Default)]
struct Inner {
    next_id: u64,
    session: Option<Recorded>,
    /// Recordings that still take chunks, by id; with the reason they were told to stop.
    open: HashMap<u64, (Arc<Recording>, Option<StopReason>)>,
    /// Connected kiosks and their recording state.
    kiosks: BTreeMap<u64, KioskRecording>,
}

/// Every recording of the run. Shared by the controller, the upload route and the kiosks'
/// websocket reports.
pub struct Recordings {
    hub: Hub,
    /// The visitor sessions: the one source of each session's consent, read before every
    /// recording starts and every chunk is stored.
    visits: Arc<Visits>,
    links: ClientLinks,
    folders: SessionFolders,
    /// Tracks the timers that close recordings whose kiosk never confirmed its last chunk.
    life: Lifecycle,
    /// Chunks being written (each with its `fsync`) at once: half of the server's blocking
    /// threads (`serve::BLOCKING_THREADS`), so that pages are still read from disk for the
    /// kiosks while fifty of them upload.
    writers: tokio::sync::Semaphore,
    inner: Mutex<Inner>,
}

/// How many chunks are written at once, at most.
const CHUNK_WRITERS: usize = 4;

impl Recordings {
    /// No recording yet; recordings go into the session folders `folders` names, for the
    /// sessions `visits` holds.
    pub fn new(
        hub: Hub,
        visits: Arc<Visits>,
        links: ClientLinks,
        folders: SessionFolders,
        life: Lifecycle,
    ) -> Self {
        Recordings {
            hub,
            visits,
            links,
            folders,
            life,
            writers: tokio::sync::Semaphore::new(CHUNK_WRITERS),
            inner: Mutex::default(),
        }
    }

    /// Waits for a turn to write a chunk; the turn ends when the permit is dropped. (An error
    /// only if the semaphore were closed, which nothing does.)
    pub(super) async fn turn_to_write(
        &self,
    ) -> Result<tokio::sync::SemaphorePermit<'_>, tokio::sync::AcquireError> {
        self.writers.acquire().await
    }

    /// What each kiosk's recording is doing.
    pub fn view(&self) -> RecordingView {
        let inner = lock(&self.inner);
        let now = self.hub.mono_us();
        RecordingView {
            session: inner.session.as_ref().map(|s| s.number),
            kiosks: inner.kiosks.values().cloned().collect(),
            kept: inner.session.as_ref().map(|s| KeptMedia {
                session: s.number,
                files: s.started,
                bytes: s.quota.used(),
                seconds: s
                    .first_start_mono_us
                    .map_or(0, |at| now.saturating_sub(at) / 1_000_000),
            }),
        }
    }

    /// The kiosk `client` reports that recording `id` began at `mono_us` on the hub's clock
    /// (within `clock_error_us`): `recording.started` places it on the session clock. False
    /// when it is not this kiosk's open recording.
    pub fn started(
        &self,
        client: u64,
        id: u64,
        mime: &str,
        mono_us: u64,
        clock_error_us: u64,
    ) -> bool {
        let mut inner = lock(&self.inner);
        let Some((recording, None)) = inner.open.get(&id).cloned() else {
            return false;
        };
        if recording.client != client {
            return false;
        }
        let start_mono = match &mut inner.session {
            Some(s) if s.number == recording.session => {
                s.started += 1;
                s.first_start_mono_us = s.first_start_mono_us.or(Some(mono_us));
                s.start_mono_us
            }
            _ => return false,
        };
        if let Some(kiosk) = inner.kiosks.get_mut(&client) {
            // Recording again: an earlier failure of this kiosk is no longer current.
            kiosk.state = KioskRecordingState::Recording;
            kiosk.code = None;
            kiosk.message = None;
        }
        // Published under the lock: a consent withdrawn meanwhile comes after it in the log.
        self.hub
            .publish(EventKind::Recording(RecordingEvent::Started {
                session: recording.session,
                recording: id,
                client,
                track: recording.track,
                file: recording.file.clone(),
                mime: mime.chars().take(100).collect(),
                start_us: mono_us.saturating_sub(start_mono),
                clock_error_us,
            }));
        true
    }

    /// The kiosk `client` could not record (`recording` when it was asked for one): logged,
    /// operators see it at once, and the recording is closed.
    pub fn failed(&self, client: u64, recording: Option<u64>, code: FailureCode, message: &str) {
        let mut inner = lock(&self.inner);
        let session = inner.session.as_ref().map(|s| s.number);
        if let Some(kiosk) = inner.kiosks.get_mut(&client) {
            kiosk.state = KioskRecordingState::Failed;
            kiosk.code = Some(code);
            kiosk.message = Some(message.chars().take(500).collect());
        }
        self.hub
            .publish(EventKind::Recording(RecordingEvent::Failed {
                session,
                recording,
                client,
                code,
                message: message.chars().take(500).collect(),
            }));
        let owned = recording.and_then(|id| {
            inner
                .open
                .get(&id)
                .filter(|(r, _)| r.client == client)
                .map(|(r, _)| r.id)
        });
        drop(inner);
        if let Some(id) = owned {
            self.close(id, StopReason::Failed);
        }
    }

    /// The kiosk `client` stopped recording `id` and uploaded its last chunk.
    pub fn kiosk_stopped(&self, client: u64, id: u64) {
        let reason = {
            let inner = lock(&self.inner);
            match inner.open.get(&id) {
                Some((r, reason)) if r.client == client => reason.unwrap_or(StopReason::Failed),
                _ => return,
            }
        };
        self.close(id, reason);
    }

    /// The open recording `id`, if `token` is its upload token and its session's consent
    /// allows it.
    fn authorised(&self, id: u64, token: &str) -> Result<Arc<Recording>, upload::Refusal> {
        let recording = {
            let inner = lock(&self.inner);
            let (recording, _) = inner.open.get(&id).ok_or(upload::Refusal::Gone)?;
            if !recording.token.matches(token) {
                return Err(upload::Refusal::Unauthorized);
            }
            Arc::clone(recording)
        };
        if !self.may_keep(recording.session) {
            return Err(upload::Refusal::Gone);
        }
        Ok(recording)
    }

    /// Appends chunk `seq` of `recording`, if it is still open, its session's consent, read
    /// under the file's lock, still allows it, and its limits have room: a refusal closes the
    /// file under the same lock ([`Recordings::close`]) once the consent is changed, so no chunk
    /// is stored after it.
    fn append(&self, recording: &Recording, seq: u64, body: &[u8]) -> Appending {
        let mut chunks = lock(&recording.chunks);
        let Some(file) = chunks.as_mut() else {
            return Appending::Closed;
        };
        if !self.may_keep(recording.session) {
            return Appending::Closed;
        }
        // Only a chunk that would be appended counts (a resend is answered as before).
        let counted = if seq == file.chunks() {
            body.len() as u64
        } else {
            0
        };
        if counted > 0 {
            let folder = file.path().parent().unwrap_or(std::path::Path::new("."));
            let available = || available_bytes(folder);
            if let Err(over) = recording.quota.take(recording.client, counted, available) {
                return Appending::OverLimit(over);
            }
        }
        let appended = file.append(seq, body);
        if !matches!(appended, Ok(chunks::Appended::Stored { new: true, .. })) && counted > 0 {
            recording.quota.give_back(recording.client, counted);
        }
        Appending::Done(appended)
    }

    /// Stops recording `id` of kiosk `client` that reached a limit: the kiosk is told to stop,
    /// operators see `recording.failed` with the limit's words, the file keeps what it holds.
    fn over_limit(&self, client: u64, id: u64, over: &Over) {
        let frame = frames::record_stop_frame(id, StopReason::Failed);
        self.links
            .send_to(client, &crate::wire::outbox::Frame::from(frame));
        self.failed(client, Some(id), over.code, &over.message);
    }

    /// Closes recording `id`: no more chunks; `recording.stopped` with what it holds.
    pub fn close(&self, id: u64, reason: StopReason) {
        let mut inner = lock(&self.inner);
        let Some((recording, _)) = inner.open.remove(&id) else {
            return;
        };
        if let Some(kiosk) = inner.kiosks.get_mut(&recording.client)
            && kiosk.recording == Some(id)
            && kiosk.state != KioskRecordingState::Failed
        {
            kiosk.state = KioskRecordingState::Off;
        }
        // The file's lock is taken after the registry's, never the other way round.
        let file = lock(&recording.chunks).take();
        let (bytes, chunks) = file.as_ref().map_or((0, 0), |f| (f.acked(), f.chunks()));
        self.hub
            .publish(EventKind::Recording(RecordingEvent::Stopped {
                session: recording.session,
                recording: id,
                file: recording.file.clone(),
                bytes,
                chunks,
                reason,
            }));
    }

    /// Closes every open recording for `reason` (the server stops: the kiosks cannot upload
    /// any more).
    pub fn close_all(&self, reason: StopReason) {
        let ids: Vec<u64> = lock(&self.inner).open.keys().copied().collect();
        for id in ids {
            self.close(id, reason);
        }
    }
}
