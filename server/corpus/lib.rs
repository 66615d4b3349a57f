//! `docent-corpus`: the corpus folder, written and read. No async runtime, no HTTP and no
//! command line here: the runtime hands it events through a [`Feed`], `docent corpus` and the
//! `/sessions` pages read it back through it.
//!
//! Writing. The corpus writer is the only code that writes a log. It runs on its own thread,
//! off the dispatcher's hot path, and commits events in groups: it takes every event published
//! since its last batch, writes their JSON lines with one `write(2)` per file they go to (a
//! visitor session's own log, or the day log), then reports how far the log is written
//! ([`Logged`]), which releases the acknowledgements waiting on that batch. So an acknowledged
//! event survives `kill -9`; a second thread syncs the file to disk at a bounded interval,
//! which bounds what a power cut can take. Format and guarantees: `docs/CORPUS.md`.
//!
//! - `writer`: the writer thread's loop, group commit, and the [`Feed`] it is fed through.
//! - `route`: which file each event goes to, and the session manifest's changes it makes;
//!   `layout`: the folder's names (`days/`, `sessions/`), shared with `docent corpus`.
//! - `files`: the file being appended to, switched when the lines belong elsewhere; `sync`:
//!   the thread that syncs it at the `--corpus-sync` interval.
//! - `manifest`: a session's `session.json`, replaced whole after its lines are written.
//! - `unwritten`: the lines not written yet, kept in order through a failing disk, written
//!   again into a log file removed under the writer.
//! - `failures`: write failures (a full disk) counted, said and retried at a bounded pace.
//!
//! Reading. [`catalog`], [`session_folder`], [`log_lock`], [`log_scan`] and [`purge`] read a
//! corpus (and remove a session); [`export`] reads a session's folder and writes its exports
//! where it is told. None of them writes a log. [`annotations`] keeps researchers'
//! annotations of a session beside its log (`annotations.jsonl`).
//!
//! Recordings. [`chunks`]: one recording's file grown chunk by chunk, acknowledged only once
//! synced; [`recover`]: at start-up, what a crash left unacknowledged cut back, and media a
//! refused consent left behind removed.

pub mod annotations;
pub mod catalog;
pub mod chunks;
pub mod export;
mod failures;
mod files;
pub mod layout;
pub mod log_lock;
pub mod log_scan;
pub mod manifest;
pub mod purge;
pub mod recover;
mod route;
pub mod session_folder;
mod sync;
mod unwritten;
mod writer;

use std::io;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::Duration;

pub use route::SessionFolders;
pub use writer::{Committer, Feed, Logged};

/// How often the log is synced to disk by default (`docent serve --corpus-sync`).
pub const DEFAULT_SYNC_INTERVAL: Duration = Duration::from_secs(1);

/// Handle to the running writer thread.
pub struct CorpusWriter {
    dir: PathBuf,
    folders: SessionFolders,
    thread: JoinHandle<io::Result<u64>>,
}

impl CorpusWriter {
    /// Creates the corpus folder `dir` if needed (and checks that a file can be made in it),
    /// then starts the writer thread (each file it writes synced every `sync_interval`), which
    /// ends when `feed` closes.
    pub fn start(dir: &Path, feed: impl Feed, sync_interval: Duration) -> io::Result<Self> {
        std::fs::create_dir_all(dir.join(layout::DAYS_DIR))?;
        let dir = dir.canonicalize()?;
        // A folder Docent cannot write is said at start-up, not at the first event.
        tempfile_probe(&dir.join(layout::DAYS_DIR))?;
        let folders = SessionFolders::default();
        let route = route::Route::new(dir.clone()).with_folders(folders.clone());
        let thread = std::thread::Builder::new()
            .name("corpus-writer".into())
            .spawn(move || writer::run(route, feed, sync_interval))?;
        Ok(CorpusWriter {
            dir,
            folders,
            thread,
        })
    }

    /// Where the writer put the running session's folder, for the recordings beside its log.
    pub fn session_folders(&self) -> SessionFolders {
        self.folders.clone()
    }

    /// The corpus folder, absolute.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Waits until the writer has written and synced everything (close its feed first),
    /// blocking the calling thread. Returns the number of events written.
    pub fn finish(self) -> io::Result<u64> {
        self.thread
            .join()
            .unwrap_or_else(|_| Err(io::Error::other("corpus writer panicked")))
    }
}

/// Locks `m`, taking the data even if another thread panicked while holding it (as the
/// runtime's `sync::lock`): a log line is whole or not written.
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|p| p.into_inner())
}

/// Makes and removes a file in `dir`, to learn early whether it can be written.
fn tempfile_probe(dir: &Path) -> io::Result<()> {
    let probe = dir.join(format!(".docent-probe-{}", std::process::id()));
    std::fs::File::create(&probe)?;
    std::fs::remove_file(&probe)
}
