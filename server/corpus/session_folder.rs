//! One session's folder as `docent corpus` reads it: its manifest, its event log scanned
//! (`log_scan.rs`), whether a running server holds the log (`log_lock.rs`), and from these
//! its state: ended, being recorded, interrupted (a killed or crashed server left it open), or
//! damaged (something a researcher must look at).

use std::fmt;
use std::fs::File;
use std::io::{self, BufReader};
use std::path::{Path, PathBuf};

use docent_protocol::events::EventKind;

use crate::layout::{SESSION_EVENTS, SESSION_MANIFEST};
use crate::log_lock::{LogLock, log_lock};
use crate::log_scan::LogScan;
use crate::manifest::SessionManifest;

/// What a session is now, as `docent corpus list` says it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SessionState {
    /// Its end is in its log and its manifest.
    Ended,
    /// A running server is writing its log (the log is locked).
    Recording,
    /// Not ended, and no server is writing it: a server was killed or crashed while it ran.
    Interrupted,
    /// Its manifest or its log is missing or unreadable, or a line of the log is not an event.
    Damaged,
}

impl SessionState {
    /// The word for it: `ended`, `recording`, `interrupted`, `damaged`.
    pub fn word(self) -> &'static str {
        match self {
            SessionState::Ended => "ended",
            SessionState::Recording => "recording",
            SessionState::Interrupted => "interrupted",
            SessionState::Damaged => "damaged",
        }
    }
}

/// Something wrong with a session's folder, in words that name the file (and line).
#[derive(Clone, Debug, PartialEq)]
pub enum Damage {
    /// `session.json` is not there.
    NoManifest,
    /// `session.json` cannot be read or is not a manifest.
    BadManifest(String),
    /// `events.jsonl` is not there.
    NoLog,
    /// `events.jsonl` cannot be read.
    UnreadableLog(String),
    /// A line of `events.jsonl` (not an incomplete last one) is not an event.
    BadLine(crate::log_scan::BadLine),
    /// More bad lines than are listed one by one.
    MoreBadLines(u64),
    /// The session's folder is a symbolic link, which is not followed.
    Linked,
}

impl fmt::Display for Damage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Damage::NoManifest => write!(f, "{SESSION_MANIFEST} is missing"),
            Damage::BadManifest(why) => write!(f, "{SESSION_MANIFEST} cannot be read: {why}"),
            Damage::NoLog => write!(f, "{SESSION_EVENTS} is missing"),
            Damage::UnreadableLog(why) => write!(f, "{SESSION_EVENTS} cannot be read: {why}"),
            Damage::BadLine(bad) => write!(f, "{SESSION_EVENTS}:{}: {}", bad.line, bad.fault),
            Damage::MoreBadLines(n) => write!(f, "{SESSION_EVENTS}: {n} more bad lines"),
            Damage::Linked => write!(f, "a symbolic link, not a folder: not followed"),
        }
    }
}

/// A session's folder, read.
#[derive(Clone, Debug)]
pub struct SessionFolder {
    /// The session's name: its folder's name.
    pub name: String,
    /// The folder.
    pub dir: PathBuf,
    /// Its manifest, when it could be read.
    pub manifest: Option<SessionManifest>,
    /// Its event log, when it could be read.
    pub log: Option<LogScan>,
    /// Whether a server holds the log.
    pub lock: LogLock,
    /// What is wrong with it, if anything.
    pub damage: Vec<Damage>,
}

impl SessionFolder {
    /// Reads the session folder `dir` (named `name`); never fails: what cannot be read is
    /// [`Damage`].
    pub fn read(name: &str, dir: &Path) -> SessionFolder {
        let mut damage = Vec::new();
        if std::fs::symlink_metadata(dir).is_ok_and(|m| m.file_type().is_symlink()) {
            // What it points at may be anywhere: not the corpus's to read.
            return SessionFolder {
                name: name.to_owned(),
                dir: dir.to_owned(),
                manifest: None,
                log: None,
                lock: LogLock::NoLog,
                damage: vec![Damage::Linked],
            };
        }
        let manifest = match SessionManifest::read_from(dir) {
            Ok(manifest) => Some(manifest),
            Err(e) if e.kind() == io::ErrorKind::NotFound => {
                damage.push(Damage::NoManifest);
                None
            }
            Err(e) => {
                damage.push(Damage::BadManifest(e.to_string()));
                None
            }
        };
        let log_path = dir.join(SESSION_EVENTS);
        let lock = log_lock(&log_path);
        let log = match File::open(&log_path) {
            Ok(file) => match LogScan::read(BufReader::new(file)) {
                Ok(scan) => Some(scan),
                Err(e) => {
                    damage.push(Damage::UnreadableLog(e.to_string()));
                    None
                }
            },
            Err(e) if e.kind() == io::ErrorKind::NotFound => {
                damage.push(Damage::NoLog);
                None
            }
            Err(e) => {
                damage.push(Damage::UnreadableLog(e.to_string()));
                None
            }
        };
        if let Some(scan) = &log {
            damage.extend(scan.bad_lines.iter().cloned().map(Damage::BadLine));
            let listed = scan.bad_lines.len() as u64;
            if scan.bad_line_count > listed {
                damage.push(Damage::MoreBadLines(scan.bad_line_count - listed));
            }
        }
        SessionFolder {
            name: name.to_owned(),
            dir: dir.to_owned(),
            manifest,
            log,
            lock,
            damage,
        }
    }

    /// Whether its end is recorded: in the manifest, or (without one) as the log's last event.
    pub fn ended(&self) -> bool {
        match &self.manifest {
            Some(manifest) => manifest.ended.is_some(),
            None => self
                .last_event()
                .is_some_and(|last| matches!(last, EventKind::SessionEnded { .. })),
        }
    }

    /// Whether a server may be writing it now: its log is held (or too new to tell, or the
    /// file system cannot say) and its end is not recorded. A server holds the log of a
    /// session it has just ended until it writes elsewhere, but writes no more lines to it.
    pub fn maybe_recording(&self) -> bool {
        let held = matches!(
            self.lock,
            LogLock::Held | LogLock::Newborn | LogLock::Unknown(_)
        );
        held && !self.ended()
    }

    /// Its state, from the lock, the damage and the manifest in that order: a session being
    /// recorded may look damaged for a moment (its manifest follows its first line).
    pub fn state(&self) -> SessionState {
        if self.maybe_recording() {
            SessionState::Recording
        } else if !self.damage.is_empty() {
            SessionState::Damaged
        } else if self.ended() {
            SessionState::Ended
        } else {
            SessionState::Interrupted
        }
    }

    /// When it started (RFC 3339, UTC): the manifest's, else its log's first line's if that is
    /// its `session.started`.
    pub fn started(&self) -> Option<&str> {
        if let Some(manifest) = &self.manifest {
            return Some(&manifest.started.time);
        }
        let first = self.log.as_ref()?.first.as_ref()?;
        let started = matches!(first.event()?, EventKind::SessionStarted { .. });
        started.then_some(first.time.as_deref()).flatten()
    }

    /// Its length on the session clock when it ended: the `session_us` of its last line.
    pub fn duration_us(&self) -> Option<u64> {
        if !self.ended() {
            return None;
        }
        self.last_session_us()
    }

    /// The `session_us` of the log's last event.
    pub fn last_session_us(&self) -> Option<u64> {
        self.log.as_ref()?.last.as_ref()?.session_us
    }

    /// The visitor group the manifest names.
    pub fn group(&self) -> Option<&str> {
        self.manifest.as_ref()?.group.as_deref()
    }

    /// The number of events in its log (0 without a readable log).
    pub fn events(&self) -> u64 {
        self.log.as_ref().map_or(0, |log| log.events)
    }

    /// The log's last event, read whole.
    fn last_event(&self) -> Option<EventKind> {
        self.log.as_ref()?.last.as_ref()?.event()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::manifest::{MANIFEST_FORMAT, SessionMark};

    const NAME: &str = "2026-11-24T10-15-02Z";

    fn manifest(ended: bool) -> SessionManifest {
        let mark = |seq, reason: Option<&str>| SessionMark {
            seq,
            time: "2026-11-24T10:15:02.629Z".into(),
            mono_us: 6_121_454,
            source: "operator".into(),
            reason: reason.map(str::to_owned),
        };
        SessionManifest {
            format: MANIFEST_FORMAT,
            session: NAME.into(),
            number: 1,
            docent: "0.1.0".into(),
            bundle: Some("/srv/docent/tour".into()),
            bundle_hash: None,
            started: mark(28, None),
            ended: ended.then(|| mark(32, Some("marked"))),
            group: Some("children".into()),
            context: None,
            consent: "recorded".into(),
            media: Vec::new(),
        }
    }

    /// A session folder with this manifest (if any) and log text (if any).
    fn folder(manifest: Option<SessionManifest>, log: Option<&str>) -> tempfile::TempDir {
        let dir = tempfile::tempdir().unwrap();
        if let Some(manifest) = manifest {
            manifest.write_to(dir.path()).unwrap();
        }
        if let Some(log) = log {
            std::fs::write(dir.path().join(SESSION_EVENTS), log).unwrap();
        }
        dir
    }

    const ENDED_LOG: &str = concat!(
        r#"{"v":4,"seq":28,"time":"2026-11-24T10:15:02.629Z","mono_us":6121454,"session_us":0,"type":"session.started","session":1,"source":"operator","client":2,"consent":"recorded","page":null,"projector":null}"#,
        "\n",
        r#"{"v":4,"seq":32,"time":"2026-11-24T10:15:04.405Z","mono_us":6123230,"session_us":1776,"type":"session.ended","session":1,"source":"operator","client":2,"reason":"marked"}"#,
        "\n",
    );

    #[test]
    fn an_ended_session_is_ended_with_its_length_on_the_session_clock() {
        let dir = folder(Some(manifest(true)), Some(ENDED_LOG));
        let read = SessionFolder::read(NAME, dir.path());
        assert_eq!(read.state(), SessionState::Ended);
        assert_eq!(read.duration_us(), Some(1776));
        assert_eq!(read.events(), 2);
        assert_eq!(read.group(), Some("children"));
    }

    #[test]
    fn a_session_without_an_end_whose_log_nobody_holds_was_interrupted() {
        let dir = folder(
            Some(manifest(false)),
            Some("{\"type\":\"session.started\",\"session_us\":0}\n{\"ty"),
        );
        let read = SessionFolder::read(NAME, dir.path());
        assert_eq!(read.lock, LogLock::Free);
        assert_eq!(read.state(), SessionState::Interrupted);
        assert_eq!(read.duration_us(), None);
        assert_eq!(read.log.unwrap().incomplete_last_line, Some(2));
    }

    #[test]
    fn a_session_whose_log_a_writer_holds_is_being_recorded() {
        let dir = folder(
            Some(manifest(false)),
            Some("{\"type\":\"session.started\"}\n"),
        );
        let writer = File::options()
            .append(true)
            .open(dir.path().join(SESSION_EVENTS))
            .unwrap();
        writer.try_lock().unwrap();
        let read = SessionFolder::read(NAME, dir.path());
        assert_eq!(read.state(), SessionState::Recording);
        drop(writer);
        let read = SessionFolder::read(NAME, dir.path());
        assert_eq!(read.state(), SessionState::Interrupted);
    }

    #[test]
    fn an_ended_session_still_held_by_its_writer_is_ended() {
        let dir = folder(Some(manifest(true)), Some(ENDED_LOG));
        let writer = File::options()
            .append(true)
            .open(dir.path().join(SESSION_EVENTS))
            .unwrap();
        writer.try_lock().unwrap();
        let read = SessionFolder::read(NAME, dir.path());
        assert_eq!(read.lock, LogLock::Held);
        assert_eq!(read.state(), SessionState::Ended);
    }

    #[test]
    fn an_empty_log_just_created_counts_as_being_recorded_and_is_not_probed() {
        let dir = folder(None, Some(""));
        let read = SessionFolder::read(NAME, dir.path());
        assert_eq!(read.lock, LogLock::Newborn);
        assert_eq!(read.state(), SessionState::Recording);
    }

    #[test]
    fn a_missing_manifest_or_a_bad_line_in_the_middle_is_damage_named_by_file_and_line() {
        let dir = folder(None, Some(ENDED_LOG));
        let read = SessionFolder::read(NAME, dir.path());
        assert_eq!(read.state(), SessionState::Damaged);
        assert_eq!(read.damage, [Damage::NoManifest]);
        assert!(read.ended(), "the log's last line ends it");
        assert_eq!(read.duration_us(), Some(1776));

        let dir = folder(
            Some(manifest(true)),
            Some("{\"type\":\"session.started\"}\nnot json\n{\"type\":\"session.ended\"}\n"),
        );
        let read = SessionFolder::read(NAME, dir.path());
        assert_eq!(read.state(), SessionState::Damaged);
        let words: Vec<String> = read.damage.iter().map(ToString::to_string).collect();
        assert_eq!(words, ["events.jsonl:2: not JSON at column 2"]);
    }

    #[cfg(unix)]
    #[test]
    fn a_session_folder_that_is_a_link_is_damaged_and_not_read() {
        let target = folder(Some(manifest(true)), Some(ENDED_LOG));
        let sessions = tempfile::tempdir().unwrap();
        let link = sessions.path().join(NAME);
        std::os::unix::fs::symlink(target.path(), &link).unwrap();
        let read = SessionFolder::read(NAME, &link);
        assert_eq!(read.state(), SessionState::Damaged);
        assert_eq!(
            (read.damage, read.manifest, read.log),
            (vec![Damage::Linked], None, None)
        );
    }

    #[test]
    fn a_manifest_that_is_not_one_is_damage_saying_why() {
        let dir = folder(None, Some(ENDED_LOG));
        std::fs::write(dir.path().join(SESSION_MANIFEST), "{\"format\":1}").unwrap();
        let read = SessionFolder::read(NAME, dir.path());
        let words = read.damage[0].to_string();
        assert!(
            words.starts_with("session.json cannot be read: missing field"),
            "{words}"
        );
    }
}
