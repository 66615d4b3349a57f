//! When recordings start and stop, decided from the hub's events in their order, so that
//! every way a session starts or ends (a mark, a touch, the idle time, a consent, shutdown)
//! is covered by one place: a session that starts with consent `recorded` (or gets it later)
//! asks every connected kiosk to record, and a kiosk that connects meanwhile too; its end, or
//! the server stopping, tells them to stop; a consent declined or withdrawn stops them,
//! closes the recordings and removes the session's media files (`recording.deleted`). The
//! `record` frame goes out only once `session.started` is in the log, so the session folder
//! exists when the first chunk arrives.

use std::path::Path;
use std::sync::Arc;
use std::time::Duration;

use tokio_util::sync::CancellationToken;

use super::frames::{record_frame, record_stop_frame};
use super::quota::SessionQuota;
use super::{
    ChunkFile, Inner, KioskRecording, KioskRecordingState, MEDIA_DIR, Recorded, Recording,
    Recordings,
};
use crate::access::Secret;
use crate::content::config::{CorpusSettings, RecordTracks};
use crate::events::{
    ClientConnected, ClientLeft, ClientRole, Consent, ConsentChanged, Event, EventKind,
    FailureCode, SessionStarted, StopReason, Track,
};
use crate::sync::lock;
use crate::wire::outbox::Frame;

/// How long a kiosk told to stop has to upload its last chunk and say so.
pub const FINAL_UPLOAD_GRACE: Duration = Duration::from_secs(30);

impl Recordings {
    /// Follows the hub until `shutdown`; `settings()` reads the live bundle's `corpus:` (what
    /// is recorded, and its limits).
    /// The events it acts on come without loss ([`crate::events::Hub::follow`]): a session's
    /// start or end missed under load would record visitors nobody asked, or stop nobody.
    pub async fn follow(
        self: Arc<Self>,
        settings: impl Fn() -> CorpusSettings,
        shutdown: CancellationToken,
    ) {
        let mut events = self.hub.follow(acted_on);
        // The running session: its number, the seq and mono_us of its `session.started`.
        let mut running: Option<(u64, u64, u64)> = None;
        loop {
            let event = tokio::select! {
                event = events.recv() => event,
                () = shutdown.cancelled() => return,
            };
            let Some(event) = event else { return };
            self.on_event(&event, &mut running, &settings).await;
        }
    }

    async fn on_event(
        self: &Arc<Self>,
        event: &Event,
        running: &mut Option<(u64, u64, u64)>,
        settings: &impl Fn() -> CorpusSettings,
    ) {
        match &event.kind {
            EventKind::SessionStarted(SessionStarted {
                session, consent, ..
            }) => {
                *running = Some((*session, event.seq, event.mono_us));
                self.forget_failures();
                if *consent == Consent::Recorded {
                    self.begin(*session, event.seq, event.mono_us, settings())
                        .await;
                }
            }
            EventKind::ConsentChanged(ConsentChanged {
                session, consent, ..
            }) => match (consent, *running) {
                (Consent::Recorded, Some((number, seq, mono))) if number == *session => {
                    let recording = lock(&self.inner).session.is_some();
                    if !recording {
                        self.begin(number, seq, mono, settings()).await;
                    }
                }
                // Carried out already, before the mark was answered (`note_consent`); this
                // catches a refusal that raced a recording's start.
                (Consent::Recorded, _) => {}
                (refused, _) => self.refuse(*session, *refused),
            },
            EventKind::SessionEnded { .. } => {
                *running = None;
                self.forget_failures();
                self.stop_all(StopReason::SessionEnded);
            }
            EventKind::ServerStopping => self.stop_all(StopReason::ServerStopping),
            // A session that began while the log could not be written (its folder not made)
            // is recorded from now on.
            EventKind::CorpusWritable(_) => {
                let waiting = lock(&self.inner).session.is_none();
                if let Some((number, seq, mono)) = *running
                    && waiting
                    && self.visits.consent_of(number) == Some(Consent::Recorded)
                {
                    self.begin(number, seq, mono, settings()).await;
                }
            }
            EventKind::ClientConnected(ClientConnected {
                client,
                role: ClientRole::Kiosk,
                ..
            }) => {
                lock(&self.inner).kiosks.insert(*client, off(*client));
                self.start_for(*client).await;
            }
            EventKind::ClientLeft(ClientLeft {
                client,
                role: ClientRole::Kiosk,
                ..
            }) => {
                let mine: Vec<u64> = {
                    let mut inner = lock(&self.inner);
                    inner.kiosks.remove(client);
                    (inner.open.values())
                        .filter(|(r, _)| r.client == *client)
                        .map(|(r, _)| r.id)
                        .collect()
                };
                for id in mine {
                    self.close(id, StopReason::KioskLeft);
                }
            }
            _ => {}
        }
    }

    /// Session `number` may be recorded: once its first line is logged (its folder made), every
    /// connected kiosk is asked to record. While the log cannot be written it waits for
    /// `corpus.writable`, which calls it again.
    async fn begin(
        self: &Arc<Self>,
        number: u64,
        seq: u64,
        start_mono_us: u64,
        settings: CorpusSettings,
    ) {
        let tracks = settings.record;
        if !tracks.any() {
            return;
        }
        if let Err(failure) = self.hub.logged(seq).await {
            // Begun again on `corpus.writable`.
            tracing::warn!(session = number, %failure, "the session is recorded once the corpus can be written");
            return;
        }
        let Some(dir) = self.folders.folder(seq) else {
            return; // It ended already.
        };
        if self.visits.consent_of(number) != Some(Consent::Recorded) {
            return; // Declined or withdrawn meanwhile.
        }
        let kiosks: Vec<u64> = {
            let mut inner = lock(&self.inner);
            inner.session = Some(Recorded {
                number,
                start_mono_us,
                dir,
                next_file: 1,
                tracks,
                quota: Arc::new(SessionQuota::new(settings.record_limits)),
                started: 0,
                first_start_mono_us: None,
            });
            inner.kiosks.keys().copied().collect()
        };
        // A refusal between the check above and now found no session to stop: stop it here.
        if let Some(refused) = self
            .visits
            .consent_of(number)
            .filter(|c| *c != Consent::Recorded)
        {
            return self.refuse(number, refused);
        }
        for client in kiosks {
            self.start_for(client).await;
        }
    }

    /// Asks kiosk `client` to record into a new file of the session being recorded, if any.
    async fn start_for(self: &Arc<Self>, client: u64) {
        let planned = {
            let mut inner = lock(&self.inner);
            plan(&mut inner, client)
        };
        let Some((recording, path, tracks)) = planned else {
            return;
        };
        // The disk keeps room for the event log: no recording starts without it.
        let folder = path
            .parent()
            .and_then(Path::parent)
            .unwrap_or(Path::new("."));
        if let Err(refused) = recording.quota.room_to_start(folder) {
            return self.failed(client, None, refused.code, &refused.message);
        }
        let made = path.clone();
        let opened = tokio::task::spawn_blocking(move || {
            std::fs::create_dir_all(made.parent().unwrap_or(Path::new(".")))?;
            ChunkFile::open(&made)
        })
        .await
        .unwrap_or_else(|e| Err(std::io::Error::other(e)));
        let file = match opened {
            Ok(file) => file,
            Err(e) => {
                let message = format!("the server cannot write {}: {e}", recording.file);
                return self.failed(client, Some(recording.id), FailureCode::DiskError, &message);
            }
        };
        *lock(&recording.chunks) = Some(file);
        let frame = record_frame(&recording, &tracks);
        {
            let mut inner = lock(&self.inner);
            let still = inner.session.as_ref().map(|s| s.number) == Some(recording.session);
            let Some(kiosk) = inner.kiosks.get_mut(&client).filter(|_| still) else {
                // It left, or the session ended or lost its consent meanwhile: the file
                // made for it goes (it was never announced).
                drop(inner);
                lock(&recording.chunks).take();
                remove_unannounced(&path);
                return;
            };
            *kiosk = KioskRecording {
                state: KioskRecordingState::Starting,
                recording: Some(recording.id),
                file: Some(recording.file.clone()),
                ..off(client)
            };
            inner
                .open
                .insert(recording.id, (Arc::clone(&recording), None));
        }
        self.links.send_to(client, &Frame::from(frame));
    }

    /// A session starts or ends: the kiosks' failures were about the one before, so they are
    /// no longer current (`/api/state` shows none; the log keeps each `recording.failed`).
    fn forget_failures(&self) {
        let mut inner = lock(&self.inner);
        for kiosk in inner.kiosks.values_mut() {
            if kiosk.state == KioskRecordingState::Failed {
                *kiosk = off(kiosk.client);
            }
        }
    }

    /// Tells every kiosk recording to stop for `reason`; what is not closed by their reports
    /// within [`FINAL_UPLOAD_GRACE`] is closed then.
    fn stop_all(self: &Arc<Self>, reason: StopReason) {
        let told: Vec<(u64, u64)> = {
            let mut inner = lock(&self.inner);
            inner.session = None;
            let mut told = Vec::new();
            for (recording, stop) in inner.open.values_mut() {
                if stop.is_none() {
                    *stop = Some(reason);
                    told.push((recording.client, recording.id));
                }
            }
            for (client, _) in &told {
                if let Some(kiosk) = inner.kiosks.get_mut(client) {
                    kiosk.state = KioskRecordingState::Stopping;
                }
            }
            told
        };
        if told.is_empty() {
            return;
        }
        for (client, id) in &told {
            let frame = record_stop_frame(*id, reason);
            self.links.send_to(*client, &Frame::from(frame));
        }
        let this = Arc::clone(self);
        let shutdown = self.life.shutdown.clone();
        // At shutdown the server closes every recording itself (`close_all`).
        self.life.spawn(async move {
            tokio::select! {
                () = tokio::time::sleep(FINAL_UPLOAD_GRACE) => {}
                () = shutdown.cancelled() => return,
            }
            for (_, id) in told {
                this.close(id, StopReason::NoFinalReport);
            }
        });
    }
}

/// The events the controller acts on: sessions, consents, kiosks coming and going, shutdown,
/// and the corpus written again (a session begun meanwhile is recorded from then on).
fn acted_on(kind: &EventKind) -> bool {
    matches!(
        kind,
        EventKind::SessionStarted { .. }
            | EventKind::ConsentChanged { .. }
            | EventKind::SessionEnded { .. }
            | EventKind::ServerStopping
            | EventKind::CorpusWritable(_)
            | EventKind::ClientConnected(ClientConnected {
                role: ClientRole::Kiosk,
                ..
            })
            | EventKind::ClientLeft(ClientLeft {
                role: ClientRole::Kiosk,
                ..
            })
    )
}

/// Removes a recording file (and its index) that was made but never announced to its kiosk.
fn remove_unannounced(path: &Path) {
    for file in [path.to_owned(), super::chunks::index_path(path)] {
        if let Err(e) = std::fs::remove_file(&file)
            && e.kind() != std::io::ErrorKind::NotFound
        {
            tracing::warn!(error = %e, file = %file.display(), "could not remove an unused recording file");
        }
    }
}

/// Registers the next recording of the session being recorded for kiosk `client`: its id,
/// file and token. `None` when no session is being recorded.
fn plan(
    inner: &mut Inner,
    client: u64,
) -> Option<(Arc<Recording>, std::path::PathBuf, RecordTracks)> {
    let session = inner.session.as_mut()?;
    let track = if session.tracks.video {
        Track::Video
    } else {
        Track::Audio
    };
    let file = format!("{MEDIA_DIR}/{}-{}.webm", track.as_str(), session.next_file);
    session.next_file += 1;
    let path = session.dir.join(&file);
    let (number, tracks, quota) = (session.number, session.tracks, Arc::clone(&session.quota));
    inner.next_id += 1;
    let recording = Arc::new(Recording {
        id: inner.next_id,
        session: number,
        client,
        track,
        file,
        token: Secret::generate(),
        quota,
        chunks: std::sync::Mutex::new(None),
    });
    Some((recording, path, tracks))
}

fn off(client: u64) -> KioskRecording {
    KioskRecording {
        client,
        state: KioskRecordingState::Off,
        recording: None,
        file: None,
        code: None,
        message: None,
    }
}
