//! After a crash: a recording killed in the middle of an append may hold bytes its index never
//! acknowledged. At start-up every session's recordings that no running server holds are opened
//! once ([`ChunkFile::open`] cuts them back to the indexed length), so what a researcher finds
//! is the acknowledged recording, whole chunks only. And a session whose visitors declined or
//! withdrew consent keeps no media, even when a crash came between the consent and the removal
//! ([`remove_unconsented`]).

use std::path::{Path, PathBuf};

use crate::chunks::{ChunkFile, index_path};
use crate::layout::{MEDIA_DIR, SESSION_EVENTS, SESSIONS_DIR};
use crate::log_lock::{LogLock, log_lock};
use crate::manifest::SessionManifest;

/// A recording cut back to what was acknowledged.
#[derive(Debug, PartialEq, Eq)]
pub struct Cut {
    /// The media file.
    pub file: PathBuf,
    /// The bytes removed from its end.
    pub bytes: u64,
}

/// Cuts every recording in `corpus`'s sessions back to its acknowledged length, skipping
/// sessions a running server holds; returns what was cut, and what could not be read.
pub fn cut_unacknowledged(corpus: &Path) -> (Vec<Cut>, Vec<String>) {
    let (mut cuts, mut problems) = (Vec::new(), Vec::new());
    let Ok(sessions) = std::fs::read_dir(corpus.join(SESSIONS_DIR)) else {
        return (cuts, problems);
    };
    for session in sessions.flatten() {
        let media = session.path().join(MEDIA_DIR);
        let Ok(files) = std::fs::read_dir(&media) else {
            continue;
        };
        if log_lock(&session.path().join(SESSION_EVENTS)) != LogLock::Free {
            continue;
        }
        for file in files.flatten().map(|f| f.path()) {
            if !index_path(&file).is_file() {
                continue;
            }
            let before = std::fs::metadata(&file).map(|m| m.len()).unwrap_or(0);
            match ChunkFile::open(&file) {
                Ok(opened) if opened.acked() < before => cuts.push(Cut {
                    bytes: before - opened.acked(),
                    file,
                }),
                Ok(_) => {}
                Err(e) => problems.push(format!("{}: {e}", file.display())),
            }
        }
    }
    (cuts, problems)
}

/// Removes the media files of every session in `corpus` whose manifest says its visitors
/// declined or withdrew consent (a crash between the consent and the removal, or a server that
/// missed it), skipping sessions a running server holds and sessions whose manifest cannot be
/// read (nothing is removed on a guess); returns the files removed, and what could not be.
pub fn remove_unconsented(corpus: &Path) -> (Vec<PathBuf>, Vec<String>) {
    let (mut removed, mut problems) = (Vec::new(), Vec::new());
    let Ok(sessions) = std::fs::read_dir(corpus.join(SESSIONS_DIR)) else {
        return (removed, problems);
    };
    for session in sessions.flatten().map(|s| s.path()) {
        let media = session.join(MEDIA_DIR);
        let Ok(files) = std::fs::read_dir(&media) else {
            continue;
        };
        let refused = SessionManifest::read_from(&session).is_ok_and(|m| !m.media_allowed());
        if !refused || log_lock(&session.join(SESSION_EVENTS)) != LogLock::Free {
            continue;
        }
        for file in files.flatten().map(|f| f.path()) {
            // Only files: a link is removed as a link, never followed.
            match std::fs::remove_file(&file) {
                Ok(()) => removed.push(file),
                Err(e) => problems.push(format!("{}: {e}", file.display())),
            }
        }
        if let Err(e) = std::fs::remove_dir(&media) {
            problems.push(format!("{}: {e}", media.display()));
        }
    }
    (removed, problems)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::manifest::{MANIFEST_FORMAT, SessionMark};

    fn session(corpus: &Path, name: &str, consent: &str) -> PathBuf {
        let dir = corpus.join(SESSIONS_DIR).join(name);
        std::fs::create_dir_all(dir.join(MEDIA_DIR)).unwrap();
        std::fs::write(dir.join(MEDIA_DIR).join("audio-1.webm"), b"webm").unwrap();
        std::fs::write(dir.join(SESSION_EVENTS), b"{}\n").unwrap();
        let mark = SessionMark {
            seq: 1,
            time: "2026-11-28T12:00:00.000Z".into(),
            mono_us: 0,
            source: "operator".into(),
            reason: None,
        };
        let manifest = SessionManifest {
            format: MANIFEST_FORMAT,
            session: name.into(),
            number: 1,
            docent: "0".into(),
            bundle: None,
            bundle_hash: None,
            started: mark,
            ended: None,
            group: None,
            context: None,
            consent: consent.into(),
            media: Vec::new(),
        };
        manifest.write_to(&dir).unwrap();
        dir
    }

    #[test]
    fn media_a_refused_consent_left_behind_are_removed_and_nothing_else() {
        let corpus = tempfile::tempdir().unwrap();
        let withdrawn = session(corpus.path(), "a", "withdrawn");
        let declined = session(corpus.path(), "b", "declined");
        let recorded = session(corpus.path(), "c", "recorded");
        let unreadable = session(corpus.path(), "d", "recorded");
        std::fs::write(unreadable.join("session.json"), b"{").unwrap();
        let (removed, problems) = remove_unconsented(corpus.path());
        assert_eq!(problems, Vec::<String>::new());
        let mut removed = removed;
        removed.sort();
        assert_eq!(
            removed,
            [
                withdrawn.join("media/audio-1.webm"),
                declined.join("media/audio-1.webm")
            ]
        );
        assert!(!withdrawn.join(MEDIA_DIR).exists() && !declined.join(MEDIA_DIR).exists());
        assert!(
            recorded.join("media/audio-1.webm").is_file(),
            "consent kept"
        );
        assert!(
            unreadable.join("media/audio-1.webm").is_file(),
            "nothing on a guess"
        );
    }
}
