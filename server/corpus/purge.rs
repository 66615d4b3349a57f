//! `docent corpus purge SESSION`: removes one session's folder completely (its events, its
//! manifest, and whatever later slices put there: media, exports, annotations) and tells each
//! file it removed as it goes, so what is printed is what happened even if it stops half-way.
//! It refuses a session a running server is recording, and touches nothing outside
//! `sessions/NAME/`: the session is found only by `catalog::find_session`, `sessions/` and the
//! session's folder must be real folders, and a link inside is removed as a link, never
//! followed.

use std::io;
use std::path::{Path, PathBuf};

use crate::catalog::{CorpusError, FolderContents, find_session, folder_contents};
use crate::layout::{SESSION_EVENTS, SESSIONS_DIR};
use crate::log_lock::LogLock;
use crate::session_folder::SessionFolder;

/// Why a purge did not (completely) happen.
#[derive(Debug, thiserror::Error)]
pub enum PurgeError {
    /// The session could not be found, or the argument names none.
    #[error(transparent)]
    Corpus(#[from] CorpusError),
    /// A running server is recording the session: nothing was removed.
    #[error(
        "session {name} is being recorded by a running server ({why}): end the session from \
         the operator console, or stop the server, then purge it; nothing was removed"
    )]
    Recording {
        /// The session.
        name: String,
        /// How that is known.
        why: String,
    },
    /// Something could not be removed; what was removed before it was printed.
    #[error(
        "could not remove {}: {source}; {removed} file(s) were removed before it (listed \
         above) and the rest of {} is still there",
        path.display(),
        dir.display()
    )]
    Incomplete {
        /// What could not be removed.
        path: PathBuf,
        /// The session's folder.
        dir: PathBuf,
        /// How many files were removed before.
        removed: usize,
        /// The operating system's error.
        source: io::Error,
    },
}

/// A file (or link) a purge removed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RemovedFile {
    /// Its path, relative to the corpus folder (`sessions/NAME/events.jsonl`).
    pub path: PathBuf,
    /// Its size in bytes (a link's own size).
    pub bytes: u64,
}

/// What a purge removed in all.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Purged {
    /// The session's name.
    pub name: String,
    /// The session's folder, relative to the corpus folder (`sessions/NAME`).
    pub folder: PathBuf,
    /// How many files (and links) were removed.
    pub files: usize,
    /// How many folders were removed, the session's own included.
    pub folders: usize,
    /// Their size in bytes.
    pub bytes: u64,
}

/// Removes the session `arg` names from the corpus folder `corpus`, calling `removed` for
/// each file right after it is gone.
pub fn purge(
    corpus: &Path,
    arg: &str,
    mut removed: impl FnMut(&RemovedFile),
) -> Result<Purged, PurgeError> {
    let sessions = corpus.join(SESSIONS_DIR);
    if std::fs::symlink_metadata(&sessions).is_ok_and(|m| m.file_type().is_symlink()) {
        return Err(CorpusError::Linked { path: sessions }.into());
    }
    let (name, dir) = find_session(corpus, arg)?;
    let session = SessionFolder::read(&name, &dir);
    if session.maybe_recording() {
        let why = match &session.lock {
            LogLock::Held => format!("its {SESSION_EVENTS} is locked"),
            LogLock::Newborn => format!("its {SESSION_EVENTS} was created moments ago"),
            LogLock::Unknown(e) => {
                format!("it has no end, and whether its {SESSION_EVENTS} is locked is unknown: {e}")
            }
            LogLock::Free | LogLock::NoLog => "it has no end".to_owned(),
        };
        return Err(PurgeError::Recording { name, why });
    }
    let FolderContents { files, folders } = folder_contents(&dir)?;
    let folder = PathBuf::from(SESSIONS_DIR).join(&name);
    let mut purged = Purged {
        name,
        folder: folder.clone(),
        files: 0,
        folders: 0,
        bytes: 0,
    };
    let incomplete = |path: &Path, removed, source| PurgeError::Incomplete {
        path: path.to_owned(),
        dir: dir.clone(),
        removed,
        source,
    };
    for (path, bytes) in files {
        std::fs::remove_file(&path).map_err(|e| incomplete(&path, purged.files, e))?;
        purged.files += 1;
        purged.bytes += bytes;
        let inside = path.strip_prefix(&dir).unwrap_or(&path);
        removed(&RemovedFile {
            path: folder.join(inside),
            bytes,
        });
    }
    // Deepest first, the session's own folder last; one that is not empty now had a file
    // appear since it was listed, which is said, not removed.
    for path in folders.iter().rev().chain(std::iter::once(&dir)) {
        std::fs::remove_dir(path).map_err(|e| incomplete(path, purged.files, e))?;
        purged.folders += 1;
    }
    Ok(purged)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(unix)]
    #[test]
    fn a_link_inside_a_session_is_removed_as_a_link_and_its_target_is_kept() {
        let corpus = tempfile::tempdir().unwrap();
        let outside = tempfile::tempdir().unwrap();
        let precious = outside.path().join("precious.wav");
        std::fs::write(&precious, "keep me").unwrap();
        let dir = corpus.path().join("sessions/2026-11-24T10-15-02Z");
        std::fs::create_dir_all(dir.join("media")).unwrap();
        std::fs::write(dir.join("events.jsonl"), "{\"type\":\"session.started\"}\n").unwrap();
        std::os::unix::fs::symlink(&precious, dir.join("media/audio.wav")).unwrap();
        std::os::unix::fs::symlink(outside.path(), dir.join("elsewhere")).unwrap();
        let mut told = Vec::new();
        let purged = purge(corpus.path(), "2026-11-24T10-15-02Z", |f| {
            told.push(f.path.clone())
        })
        .unwrap();
        assert_eq!(
            told,
            [
                "sessions/2026-11-24T10-15-02Z/elsewhere",
                "sessions/2026-11-24T10-15-02Z/events.jsonl",
                "sessions/2026-11-24T10-15-02Z/media/audio.wav",
            ]
            .map(PathBuf::from)
        );
        assert_eq!((purged.files, purged.folders), (3, 2));
        assert!(!dir.exists());
        assert_eq!(std::fs::read_to_string(&precious).unwrap(), "keep me");
    }

    #[cfg(unix)]
    #[test]
    fn a_session_folder_that_is_a_link_is_refused() {
        let corpus = tempfile::tempdir().unwrap();
        let outside = tempfile::tempdir().unwrap();
        std::fs::write(outside.path().join("events.jsonl"), "{}\n").unwrap();
        std::fs::create_dir_all(corpus.path().join("sessions")).unwrap();
        let link = corpus.path().join("sessions/2026-11-24T10-15-02Z");
        std::os::unix::fs::symlink(outside.path(), &link).unwrap();
        let error = purge(corpus.path(), "2026-11-24T10-15-02Z", |_| {}).unwrap_err();
        assert!(error.to_string().contains("is a symbolic link"), "{error}");
        assert!(outside.path().join("events.jsonl").exists());
        assert!(link.exists());
    }
}
