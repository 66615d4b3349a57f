//! Whether a running server holds a session's log. The corpus writer locks the file it
//! appends to (an advisory `flock`, `corpus/files.rs`) and the lock goes when the file is
//! closed or the server dies, so a locked log is one being written now.

use std::fs::{File, TryLockError};
use std::io;
use std::path::Path;
use std::time::{Duration, SystemTime};

/// The writer creates a session's log and locks it before it writes the first line. An empty
/// log younger than this may be one it has created and not locked yet, so it is not probed
/// (a probe's shared lock would make the writer's own lock fail) and counts as being recorded.
const NEWBORN: Duration = Duration::from_secs(10);

/// Whether a running server holds the session's log.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LogLock {
    /// Nobody holds it.
    Free,
    /// A server holds it: it is writing this session now, or just ended it and has not yet
    /// written anything elsewhere.
    Held,
    /// The log was created moments ago and is still empty: a server is starting the session.
    Newborn,
    /// No log to lock.
    NoLog,
    /// The file system would not say (locks unsupported, say): the operating system's words.
    Unknown(String),
}

/// Whether a server holds the log at `path`. The probe takes a shared lock for an instant;
/// a log that may not be locked yet (empty and new) is not probed (see [`NEWBORN`]).
pub fn log_lock(path: &Path) -> LogLock {
    let file = match File::open(path) {
        Ok(file) => file,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return LogLock::NoLog,
        Err(e) => return LogLock::Unknown(e.to_string()),
    };
    if let Ok(meta) = file.metadata()
        && meta.len() == 0
        && (meta.modified().ok())
            .and_then(|m| SystemTime::now().duration_since(m).ok())
            .is_none_or(|age| age < NEWBORN)
    {
        return LogLock::Newborn;
    }
    match file.try_lock_shared() {
        Ok(()) => LogLock::Free,
        Err(TryLockError::WouldBlock) => LogLock::Held,
        Err(TryLockError::Error(e)) => LogLock::Unknown(e.to_string()),
    }
}
