//! Which file each event goes to, decided once per event, in `seq` order, by the corpus
//! writer: a session's events (from its `session.started` through its `session.ended`) to the
//! session's own log, every other event to the day log of its date. A session's manifest
//! changes with the events that change it (start, end, visitor group, context).

use std::collections::HashSet;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

use crate::layout::{SESSION_EVENTS, new_day_log, new_session_dir, utc_date};
use crate::manifest::{MANIFEST_FORMAT, MediaFile, SessionManifest, SessionMark};
use docent_content::DEFAULT_VARIANT;
use docent_protocol::events::{
    BundleReloaded, ConsentChanged, Event, EventKind, RecordingEvent, SessionEnded, SessionStarted,
    VisitorGroup,
};

/// Where one event goes.
pub(super) struct Place {
    /// The log file to append its line to.
    pub file: PathBuf,
    /// The session's start on the monotonic clock, when it goes to a session's log: its line
    /// then carries `session_us`, the time since that start.
    pub session_start_us: Option<u64>,
    /// The session's folder and its manifest as this event left it, when the event changed it.
    pub manifest: Option<(PathBuf, SessionManifest)>,
}

/// The folder of the session the writer routes to now, by the `seq` of its `session.started`:
/// set before that line is written, so whoever waited for the line to be logged finds it here
/// (the recordings, which go into the session's `media/`). Cheap to clone.
#[derive(Clone, Debug, Default)]
pub struct SessionFolders(Arc<Mutex<Option<(u64, PathBuf)>>>);

impl SessionFolders {
    /// The folder of the session that `session.started` number `seq` began, while it runs.
    pub fn folder(&self, seq: u64) -> Option<PathBuf> {
        let open = crate::lock(&self.0);
        open.as_ref()
            .filter(|(started, _)| *started == seq)
            .map(|(_, dir)| dir.clone())
    }

    fn set(&self, open: Option<(u64, PathBuf)>) {
        *crate::lock(&self.0) = open;
    }
}

/// The writer's routing state.
pub(super) struct Route {
    corpus: PathBuf,
    /// The bundle and the context as the log said last (for a new session's manifest).
    bundle: Option<String>,
    bundle_hash: Option<String>,
    context: Option<String>,
    open: Option<(PathBuf, SessionManifest)>,
    /// This run's day log for the date it was made for.
    day: Option<(String, PathBuf)>,
    /// Folders and files handed out in this run: two sessions starting in the same second before the
    /// first one's folder exists must not get the same one.
    given: HashSet<PathBuf>,
    folders: SessionFolders,
}

impl Route {
    /// Routes into the corpus folder `corpus`.
    pub(super) fn new(corpus: PathBuf) -> Self {
        Route {
            corpus,
            bundle: None,
            bundle_hash: None,
            // Every run starts in the default context; changes are logged.
            context: Some(DEFAULT_VARIANT.to_owned()),
            open: None,
            day: None,
            given: HashSet::new(),
            folders: SessionFolders::default(),
        }
    }

    /// The same route, telling `folders` which session folder it writes to.
    pub(super) fn with_folders(self, folders: SessionFolders) -> Self {
        Route { folders, ..self }
    }

    /// The corpus folder.
    pub(super) fn corpus(&self) -> &std::path::Path {
        &self.corpus
    }

    /// The running session's folder and its manifest as the last event placed left it.
    pub(super) fn open_session(&self) -> Option<(PathBuf, SessionManifest)> {
        self.open.clone()
    }

    /// Where `event` goes; call once per event, in `seq` order.
    pub(super) fn place(&mut self, event: &Event) -> Place {
        let mut changed = false;
        match &event.kind {
            EventKind::ServerStarted {
                bundle,
                bundle_hash,
                ..
            } => {
                self.bundle = Some(bundle.clone());
                self.bundle_hash = bundle_hash.clone();
            }
            // A bundle that goes live during a session changes what it was recorded with: the
            // manifest keeps the one it started with, the log has the reload.
            EventKind::BundleReloaded(BundleReloaded { bundle_hash, .. }) => {
                self.bundle_hash = bundle_hash.clone()
            }
            EventKind::ContextChanged { context, .. } => {
                self.context = Some(context.clone());
                if let Some((_, manifest)) = &mut self.open {
                    manifest.context = Some(context.clone());
                    changed = true;
                }
            }
            EventKind::SessionStarted(SessionStarted {
                session,
                source,
                consent,
                ..
            }) => {
                let dir = self.new_dir(event);
                let manifest = SessionManifest {
                    format: MANIFEST_FORMAT,
                    session: dir_name(&dir),
                    number: *session,
                    docent: env!("CARGO_PKG_VERSION").to_owned(),
                    bundle: self.bundle.clone(),
                    bundle_hash: self.bundle_hash.clone(),
                    started: mark(event, source.as_str(), None),
                    ended: None,
                    group: None,
                    context: self.context.clone(),
                    consent: consent.as_str().to_owned(),
                    media: Vec::new(),
                };
                self.folders.set(Some((event.seq, dir.clone())));
                self.open = Some((dir, manifest));
                changed = true;
            }
            EventKind::ConsentChanged(ConsentChanged { consent, .. }) => {
                if let Some((_, manifest)) = &mut self.open {
                    manifest.consent = consent.as_str().to_owned();
                    changed = true;
                }
            }
            EventKind::VisitorGroup(VisitorGroup { group, .. }) => {
                if let Some((_, manifest)) = &mut self.open {
                    manifest.group = Some(group.clone());
                    changed = true;
                }
            }
            EventKind::Recording(recording) => changed = self.media(recording),
            EventKind::SessionEnded(SessionEnded { source, reason, .. }) => {
                if let Some((_, manifest)) = &mut self.open {
                    manifest.ended = Some(mark(event, source.as_str(), Some(reason.as_str())));
                    changed = true;
                }
            }
            _ => {}
        }
        let Some((dir, manifest)) = &self.open else {
            return Place {
                file: self.day_log(event),
                session_start_us: None,
                manifest: None,
            };
        };
        let place = Place {
            file: dir.join(SESSION_EVENTS),
            session_start_us: Some(manifest.started.mono_us),
            manifest: changed.then(|| (dir.clone(), manifest.clone())),
        };
        if matches!(event.kind, EventKind::SessionEnded { .. }) {
            self.open = None;
            self.folders.set(None);
        }
        place
    }

    /// The open session's media list as `event` changes it; whether it did.
    fn media(&mut self, event: &RecordingEvent) -> bool {
        let Some((_, manifest)) = &mut self.open else {
            return false;
        };
        match event {
            RecordingEvent::Started {
                session,
                recording,
                track,
                file,
                mime,
                start_us,
                clock_error_us,
                ..
            } if *session == manifest.number => {
                manifest.media.push(MediaFile {
                    file: file.clone(),
                    track: track.as_str().to_owned(),
                    mime: mime.clone(),
                    start_us: *start_us,
                    clock_error_us: *clock_error_us,
                    recording: *recording,
                });
                true
            }
            RecordingEvent::Deleted { session, .. } if *session == manifest.number => {
                manifest.media.clear();
                true
            }
            _ => false,
        }
    }

    /// This run's day log for `event`'s date, made when the date has none yet.
    fn day_log(&mut self, event: &Event) -> PathBuf {
        let date = utc_date(event.time);
        if let Some((made_for, path)) = &self.day
            && *made_for == date
        {
            return path.clone();
        }
        let given = &self.given;
        let path = new_day_log(&self.corpus, event.time, |p| given.contains(p));
        self.given.insert(path.clone());
        self.day = Some((date, path.clone()));
        path
    }

    fn new_dir(&mut self, event: &Event) -> PathBuf {
        let given = &self.given;
        let dir = new_session_dir(&self.corpus, event.time, |p| given.contains(p));
        self.given.insert(dir.clone());
        dir
    }
}

fn dir_name(dir: &std::path::Path) -> String {
    dir.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

fn mark(event: &Event, source: &str, reason: Option<&str>) -> SessionMark {
    SessionMark {
        seq: event.seq,
        time: humantime::format_rfc3339_millis(event.time).to_string(),
        mono_us: event.mono_us,
        source: source.to_owned(),
        reason: reason.map(str::to_owned),
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;
    use std::time::{Duration, UNIX_EPOCH};

    use super::*;
    use docent_protocol::events::{Consent, SessionEnd, Source};

    fn at(seq: u64, kind: EventKind) -> Event {
        let time = UNIX_EPOCH + Duration::from_secs(1_795_000_000 + seq);
        Event::new(seq, time, seq * 1000, kind)
    }

    fn context(name: &str) -> EventKind {
        EventKind::ContextChanged {
            source: Source::Operator,
            context: name.into(),
        }
    }

    #[test]
    fn a_session_started_before_any_context_change_is_in_the_default_context() {
        let mut route = Route::new("/corpus".into());
        let start = EventKind::SessionStarted(SessionStarted {
            session: 1,
            source: Source::Kiosk,
            client: Some(2),
            consent: Consent::Recorded,
            page: None,
            projector: None,
        });
        let (_, manifest) = route.place(&at(1, start)).manifest.unwrap();
        assert_eq!(manifest.context.as_deref(), Some("Text"));
    }

    #[test]
    fn a_sessions_events_go_to_its_folder_and_the_rest_to_the_day_log() {
        let corpus = Path::new("/corpus");
        let mut route = Route::new(corpus.to_owned());
        let started = EventKind::ServerStarted {
            bundle: "/bundles/tour".into(),
            bundle_hash: Some("sha256:00".into()),
            version: "0.1.0".into(),
            seed: None,
        };
        let day = corpus.join("days/2026-11-18/11-06-41Z.jsonl");
        assert_eq!(route.place(&at(1, started)).file, day);
        assert_eq!(route.place(&at(2, context("TextChild"))).file, day);

        let start = EventKind::SessionStarted(SessionStarted {
            session: 1,
            source: Source::Operator,
            client: Some(4),
            consent: Consent::Declined,
            page: None,
            projector: None,
        });
        let first = route.place(&at(3, start));
        let folder = corpus.join("sessions/2026-11-18T11-06-43Z");
        assert_eq!(first.file, folder.join("events.jsonl"));
        assert_eq!(first.session_start_us, Some(3000));
        let (dir, manifest) = first.manifest.expect("a new session has a manifest");
        assert_eq!(dir, folder);
        assert_eq!(manifest.session, "2026-11-18T11-06-43Z");
        assert_eq!(manifest.bundle.as_deref(), Some("/bundles/tour"));
        assert_eq!(manifest.context.as_deref(), Some("TextChild"));
        assert_eq!(
            (manifest.started.seq, manifest.started.source.as_str()),
            (3, "operator")
        );

        let inside = route.place(&at(4, context("Text")));
        assert_eq!(inside.file, folder.join("events.jsonl"));
        assert_eq!(inside.manifest.unwrap().1.context.as_deref(), Some("Text"));
        let end = EventKind::SessionEnded(SessionEnded {
            session: 1,
            source: Source::Server,
            client: None,
            reason: SessionEnd::ServerStopping,
        });
        let last = route.place(&at(5, end));
        assert_eq!(
            last.file,
            folder.join("events.jsonl"),
            "the end is the session's"
        );
        let ended = last.manifest.unwrap().1.ended.expect("ended");
        assert_eq!(ended.reason.as_deref(), Some("server-stopping"));
        assert_eq!(route.place(&at(6, context("Text"))).file, day);
    }
}
