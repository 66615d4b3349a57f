//! The corpus writer: the only code that writes the corpus folder. It runs on its own thread,
//! off the dispatcher's hot path, and commits events in groups: it takes every event published
//! since its last batch, writes their JSON lines with one `write(2)` per file they go to (a
//! visitor session's own log, or the day log: `layout.rs`, `route.rs`), then reports through
//! the hub how far the log is written, which releases the acknowledgements waiting on that
//! batch ([`crate::events::Hub::logged`]). So an acknowledged event survives `kill -9`; a
//! second thread syncs the file to disk at a bounded interval ([`sync`]), which bounds what a
//! power cut can take. Format and guarantees: `docs/CORPUS.md`.
//!
//! The corpus folder is read (and a session removed) by `docent corpus`: [`catalog`],
//! [`session_folder`], [`log_lock`], [`log_scan`], [`purge`], printed by [`cli`] (`show.rs`,
//! `units.rs`); [`export`] reads a session's folder and writes its exports where it is told.
//! None of them writes a log. [`annotations`] keeps researchers' annotations of a session
//! beside its log (`annotations.jsonl`), for the `/sessions` page and the exports.

pub mod annotations;
pub mod catalog;
pub mod cli;
pub mod export;
mod export_command;
mod failures;
mod files;
pub mod layout;
pub mod log_lock;
pub mod log_scan;
pub mod manifest;
pub mod purge;
mod route;
pub mod session_folder;
mod show;
mod sync;
mod units;
mod writer;

use std::io;
use std::path::{Path, PathBuf};
use std::time::Duration;

use tokio::sync::oneshot;

use crate::events::CorpusFeed;

pub use route::SessionFolders;

/// How often the log is synced to disk by default (`docent serve --corpus-sync`).
pub const DEFAULT_SYNC_INTERVAL: Duration = Duration::from_secs(1);

/// Handle to the running writer thread.
pub struct CorpusWriter {
    dir: PathBuf,
    folders: SessionFolders,
    closed: Option<oneshot::Receiver<io::Result<u64>>>,
}

impl CorpusWriter {
    /// Creates the corpus folder `dir` if needed (and checks that a file can be made in it),
    /// then starts the writer thread (each file it writes synced every `sync_interval`), which
    /// ends on [`crate::events::Hub::close_corpus`].
    pub fn start(dir: &Path, feed: CorpusFeed, sync_interval: Duration) -> io::Result<Self> {
        std::fs::create_dir_all(dir.join(layout::DAYS_DIR))?;
        let dir = dir.canonicalize()?;
        // A folder Docent cannot write is said at start-up, not at the first event.
        tempfile_probe(&dir.join(layout::DAYS_DIR))?;
        let (done_tx, done_rx) = oneshot::channel();
        let folders = SessionFolders::default();
        let route = route::Route::new(dir.clone()).with_folders(folders.clone());
        std::thread::Builder::new()
            .name("corpus-writer".into())
            .spawn(move || {
                let _ = done_tx.send(writer::run(route, feed, sync_interval));
            })?;
        Ok(CorpusWriter {
            dir,
            folders,
            closed: Some(done_rx),
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

    /// Waits until the writer has written and synced everything (call
    /// [`crate::events::Hub::close_corpus`] first). Returns the number of events written.
    pub async fn finish(mut self) -> io::Result<u64> {
        match self.closed.take() {
            Some(rx) => rx
                .await
                .unwrap_or_else(|_| Err(io::Error::other("corpus writer panicked"))),
            None => Ok(0),
        }
    }
}

/// Makes and removes a file in `dir`, to learn early whether it can be written.
fn tempfile_probe(dir: &Path) -> io::Result<()> {
    let probe = dir.join(format!(".docent-probe-{}", std::process::id()));
    std::fs::File::create(&probe)?;
    std::fs::remove_file(&probe)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::events::{EventKind, Hub, Source};

    fn context(n: usize) -> EventKind {
        EventKind::ContextChanged {
            source: Source::Http,
            context: format!("T{n}"),
        }
    }

    /// The `seq` of every line in the corpus folder, in file order.
    fn seqs(corpus: &Path) -> Vec<u64> {
        let mut seqs = Vec::new();
        for log in layout::event_logs(corpus).unwrap() {
            let text = std::fs::read_to_string(log).unwrap();
            seqs.extend(text.lines().map(|l| {
                serde_json::from_str::<serde_json::Value>(l).unwrap()["seq"]
                    .as_u64()
                    .unwrap()
            }));
        }
        seqs
    }

    #[tokio::test]
    async fn every_published_event_is_a_json_line_in_sequence_order() {
        let dir = tempfile::tempdir().unwrap();
        let (hub, feed) = Hub::new();
        let writer = CorpusWriter::start(dir.path(), feed, DEFAULT_SYNC_INTERVAL).unwrap();
        for n in 0..100 {
            hub.publish(context(n));
        }
        let corpus = writer.dir().to_owned();
        hub.close_corpus();
        assert_eq!(writer.finish().await.unwrap(), 100);
        assert_eq!(seqs(&corpus), (1..=100).collect::<Vec<_>>());
    }

    #[tokio::test]
    async fn an_event_is_in_the_file_when_logged_returns() {
        let dir = tempfile::tempdir().unwrap();
        let (hub, feed) = Hub::new();
        // A long sync interval: what is read back was written, not synced.
        let writer = CorpusWriter::start(dir.path(), feed, Duration::from_secs(3600)).unwrap();
        for round in 1..=50u64 {
            let event = hub.publish(context(round as usize));
            hub.logged(event.seq).await.unwrap();
            // Read back while the writer still runs.
            assert_eq!(seqs(writer.dir()), (1..=round).collect::<Vec<_>>());
        }
        hub.close_corpus();
        writer.finish().await.unwrap();
    }

    #[tokio::test]
    async fn after_the_writer_stopped_an_acknowledgement_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let (hub, feed) = Hub::new();
        let writer = CorpusWriter::start(dir.path(), feed, DEFAULT_SYNC_INTERVAL).unwrap();
        hub.close_corpus();
        writer.finish().await.unwrap();
        let late = hub.publish(context(1));
        let refused = hub.logged(late.seq).await.unwrap_err();
        assert!(
            refused
                .to_string()
                .contains("the corpus writer has stopped")
        );
        assert!(hub.log_failure().is_some());
    }
}
