//! The corpus writer: the only code that writes the event log. It runs on its own thread, off
//! the dispatcher's hot path, appending one JSON line per event and flushing to the operating
//! system after every batch (batches gather for at most 2 ms), so a crash of Docent loses at
//! most the last 2 ms of events; the file
//! is synced to disk at least once a second while events come.
//! Format: `docs/CORPUS.md`.

use std::fs::{File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant, SystemTime};

use tokio::sync::{mpsc, oneshot};

use crate::events::{CorpusMsg, Event};

/// How long the writer lets events gather after each flushed batch.
const GATHER_PAUSE: Duration = Duration::from_millis(2);

/// At most this much of the log is only in the operating system's cache.
const SYNC_INTERVAL: Duration = Duration::from_secs(1);

/// Handle to the running writer thread.
pub struct CorpusWriter {
    path: PathBuf,
    closed: Option<oneshot::Receiver<io::Result<u64>>>,
}

impl CorpusWriter {
    /// Creates `dir` if needed, opens a new log file named after the start time and starts the
    /// writer thread, which ends on [`crate::events::Hub::close_corpus`] or when every hub
    /// handle is gone.
    pub fn start(dir: &Path, events: mpsc::UnboundedReceiver<CorpusMsg>) -> io::Result<Self> {
        std::fs::create_dir_all(dir)?;
        let stamp = humantime::format_rfc3339_seconds(SystemTime::now())
            .to_string()
            .replace(':', "-");
        let path = unique_path(dir, &stamp);
        let file = OpenOptions::new()
            .create_new(true)
            .append(true)
            .open(&path)?;
        let (done_tx, done_rx) = oneshot::channel();
        std::thread::Builder::new()
            .name("corpus-writer".into())
            .spawn(move || {
                let _ = done_tx.send(write_all(file, events));
            })?;
        Ok(CorpusWriter {
            path,
            closed: Some(done_rx),
        })
    }

    /// The log file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Waits until the writer has written, flushed and synced everything (call
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

fn unique_path(dir: &Path, stamp: &str) -> PathBuf {
    let first = dir.join(format!("docent-{stamp}.jsonl"));
    if !first.exists() {
        return first;
    }
    (1..)
        .map(|n| dir.join(format!("docent-{stamp}-{n}.jsonl")))
        .find(|p| !p.exists())
        .unwrap_or(first)
}

fn write_all(file: File, mut events: mpsc::UnboundedReceiver<CorpusMsg>) -> io::Result<u64> {
    let mut out = BufWriter::with_capacity(64 * 1024, file);
    let mut written = 0u64;
    let mut failures = Failures::default();
    let mut last_sync = Instant::now();
    'outer: while let Some(msg) = events.blocking_recv() {
        let mut next = Some(msg);
        // Take whatever else is already queued, then flush once for the whole batch.
        while let Some(msg) = next {
            match msg {
                CorpusMsg::Event(event) => match write_line(&mut out, &event) {
                    Ok(()) => written += 1,
                    Err(e) => failures.note(&e),
                },
                CorpusMsg::Close => break 'outer,
            }
            next = events.try_recv().ok();
        }
        if let Err(e) = out.flush() {
            failures.note(&e);
        }
        // Let the next events gather instead of waking this thread (and its publisher) for
        // each one: under load that wake-up per event cost more than all the writing. A crash
        // can lose at most this pause's worth of events still in the channel.
        std::thread::sleep(GATHER_PAUSE);
        // Flushed lines survive a crash of Docent at once; syncing now and then also bounds
        // what a power cut can take.
        if last_sync.elapsed() >= SYNC_INTERVAL {
            if let Err(e) = out.get_ref().sync_data() {
                failures.note(&e);
            }
            last_sync = Instant::now();
        }
    }
    out.flush()?;
    out.get_ref().sync_all()?;
    match failures.count {
        0 => Ok(written),
        n => Err(io::Error::other(format!(
            "{n} corpus writes failed; see the server log"
        ))),
    }
}

/// Write failures (a full disk, say): the writer keeps going, since space may come back, and
/// says so loudly but not for every event.
#[derive(Default)]
struct Failures {
    count: u64,
    reported: Option<Instant>,
}

impl Failures {
    fn note(&mut self, error: &io::Error) {
        self.count += 1;
        if self
            .reported
            .is_none_or(|t| t.elapsed() >= Duration::from_secs(10))
        {
            tracing::error!(%error, failures = self.count, "cannot write the corpus log: events are being lost");
            self.reported = Some(Instant::now());
        }
    }
}

fn write_line(out: &mut impl Write, event: &Event) -> io::Result<()> {
    out.write_all(event.json().as_bytes())?;
    out.write_all(b"\n")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::events::{EventKind, Hub, Source};

    #[tokio::test]
    async fn every_published_event_is_a_flushed_json_line_in_sequence_order() {
        let dir = std::env::temp_dir().join(format!("docent-corpus-{}", std::process::id()));
        let (hub, rx) = Hub::new();
        let writer = CorpusWriter::start(&dir, rx).unwrap();
        for n in 0..100 {
            hub.publish(EventKind::ContextChanged {
                source: Source::Http,
                context: format!("T{n}"),
            });
        }
        let path = writer.path().to_owned();
        hub.close_corpus();
        assert_eq!(writer.finish().await.unwrap(), 100);
        let text = std::fs::read_to_string(&path).unwrap();
        let seqs: Vec<u64> = text
            .lines()
            .map(|l| {
                serde_json::from_str::<serde_json::Value>(l).unwrap()["seq"]
                    .as_u64()
                    .unwrap()
            })
            .collect();
        assert_eq!(seqs, (1..=100).collect::<Vec<_>>());
        std::fs::remove_dir_all(dir).unwrap();
    }
}
