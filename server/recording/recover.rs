//! After a crash: a recording killed in the middle of an append may hold bytes its index never
//! acknowledged. At start-up every session's recordings that no running server holds are opened
//! once ([`ChunkFile::open`] cuts them back to the indexed length), so what a researcher finds
//! is the acknowledged recording, whole chunks only.

use std::path::{Path, PathBuf};

use super::MEDIA_DIR;
use super::chunks::{ChunkFile, index_path};
use crate::corpus::layout::{SESSION_EVENTS, SESSIONS_DIR};
use crate::corpus::log_lock::{LogLock, log_lock};

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
