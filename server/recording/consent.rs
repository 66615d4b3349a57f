//! Consent, carried out: the visitors' consent is one state, held by [`Visits`](crate::operator::Visits) with the
//! session; a consent declined or withdrawn is carried out here before the mark is answered
//! (recordings closed, media removed), and every step that keeps a recording asks
//! [`Recordings::may_keep`] (`docs/CORPUS.md`, "Consent is final before it is answered").

use std::path::Path;

use super::frames::record_stop_frame;
use super::{MEDIA_DIR, Recordings};
use crate::events::{Consent, EventKind, FailureCode, RecordingEvent, Source, StopReason};
use crate::operator::{Confirmation, ConsentRefused};
use crate::sync::lock;
use crate::wire::outbox::Frame;

impl Recordings {
    /// Notes what the running session's visitors agreed to (see [`crate::operator::Visits::set_consent`]) and
    /// carries it out before returning: a consent declined or withdrawn has stopped and closed
    /// the session's recordings and removed its media by then, so the mark's answer never
    /// precedes it. The only way consent changes; a refusal that deletes recordings must be
    /// `confirmed`.
    pub fn note_consent(
        &self,
        consent: Consent,
        confirmed: Confirmation,
        source: Source,
        client: u64,
    ) -> Result<u64, ConsentRefused> {
        let session = self
            .visits
            .set_consent(consent, confirmed, source, client)?;
        if consent != Consent::Recorded {
            self.refuse(session, consent);
        }
        Ok(session)
    }

    /// Whether session `number`'s media may be kept: its consent, as it stands, is `recorded`.
    pub(super) fn may_keep(&self, number: u64) -> bool {
        self.visits.consent_of(number) == Some(Consent::Recorded)
    }

    /// The visitors of session `number` declined or withdrew consent: its recordings stop and
    /// close now (later chunks are refused: 410), each kiosk is told, and the session's media
    /// files are removed (`recording.deleted`), all before the caller answers the mark.
    /// Nothing when the session is not being recorded (nothing of it was kept).
    pub(super) fn refuse(&self, number: u64, consent: Consent) {
        let (dir, told) = {
            let mut inner = lock(&self.inner);
            let dir = match &inner.session {
                Some(s) if s.number == number => Some(s.dir.clone()),
                _ => None,
            };
            if dir.is_some() {
                inner.session = None;
            }
            let told: Vec<(u64, u64)> = (inner.open.values())
                .filter(|(r, _)| r.session == number)
                .map(|(r, _)| (r.client, r.id))
                .collect();
            (dir, told)
        };
        for (client, id) in told {
            let frame = record_stop_frame(id, StopReason::Consent);
            self.links.send_to(client, &Frame::from(frame));
            self.close(id, StopReason::Consent);
        }
        let Some(dir) = dir else { return };
        // On this thread, not a blocking task: the mark is answered only once the files
        // are gone (a session's media are a few files, one per recording).
        match remove_media(&dir.join(MEDIA_DIR)) {
            Ok((files, bytes)) => {
                self.hub
                    .publish(EventKind::Recording(RecordingEvent::Deleted {
                        session: number,
                        files,
                        bytes,
                        consent,
                    }));
            }
            Err(e) => {
                tracing::error!(error = %e, "could not remove a session's media after consent");
                self.hub
                    .publish(EventKind::Recording(RecordingEvent::Failed {
                        session: Some(number),
                        recording: None,
                        client: 0,
                        code: FailureCode::DiskError,
                        message: format!(
                            "the session's recordings could not all be removed after its \
                             consent was {}: {e}; remove its media folder by hand",
                            consent.as_str()
                        ),
                    }));
            }
        }
    }
}

/// Removes every file in a session's `media/` folder (the server made them all), then the
/// folder; returns the files removed, relative to the session folder, sorted, and their
/// bytes together (what the log says was deleted).
fn remove_media(media: &Path) -> std::io::Result<(Vec<String>, u64)> {
    let entries = match std::fs::read_dir(media) {
        Ok(entries) => entries,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok((Vec::new(), 0)),
        Err(e) => return Err(e),
    };
    let mut removed = Vec::new();
    let mut bytes = 0;
    for entry in entries {
        let entry = entry?;
        bytes += entry.metadata().map_or(0, |m| m.len());
        std::fs::remove_file(entry.path())?;
        removed.push(format!(
            "{MEDIA_DIR}/{}",
            entry.file_name().to_string_lossy()
        ));
    }
    match std::fs::remove_dir(media) {
        // A recording being opened this moment made a file; it removes it itself when it
        // finds the session no longer recorded.
        Err(e) if e.kind() == std::io::ErrorKind::DirectoryNotEmpty => {}
        other => other?,
    }
    removed.sort();
    Ok((removed, bytes))
}
