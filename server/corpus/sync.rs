//! Syncing the log to disk at a bounded interval, on a thread of its own: `fdatasync` can take
//! milliseconds (more on a busy disk), and the writer must not hold acknowledgements that long.
//! Lines written (and acknowledged) survive a crash of Docent at once; syncing bounds what a
//! power cut or an operating system crash can take to about one interval.

use std::fs::File;
use std::io;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// The sync thread's handle, held by the writer.
pub(super) struct Syncer {
    shared: Arc<Shared>,
    thread: Option<JoinHandle<()>>,
}

struct Shared {
    /// Lines were written since the last sync began.
    dirty: AtomicBool,
    stop: AtomicBool,
}

impl Syncer {
    /// Starts syncing `file` every `interval` while lines are written.
    pub(super) fn start(file: File, interval: Duration) -> io::Result<Syncer> {
        let shared = Arc::new(Shared {
            dirty: AtomicBool::new(false),
            stop: AtomicBool::new(false),
        });
        let theirs = Arc::clone(&shared);
        let thread = std::thread::Builder::new()
            .name("corpus-sync".into())
            .spawn(move || sync_loop(&file, &theirs, interval))?;
        Ok(Syncer {
            shared,
            thread: Some(thread),
        })
    }

    /// Notes that lines were written.
    pub(super) fn written(&self) {
        self.shared.dirty.store(true, Ordering::Release);
    }

    /// Stops the thread, then syncs everything (data and metadata) one last time.
    pub(super) fn finish(mut self, file: &File) -> io::Result<()> {
        self.stop_thread();
        file.sync_all()
    }

    fn stop_thread(&mut self) {
        self.shared.stop.store(true, Ordering::Release);
        if let Some(thread) = self.thread.take() {
            thread.thread().unpark();
            let _ = thread.join();
        }
    }
}

impl Drop for Syncer {
    fn drop(&mut self) {
        self.stop_thread();
    }
}

fn sync_loop(file: &File, shared: &Shared, interval: Duration) {
    let mut reported: Option<Instant> = None;
    loop {
        std::thread::park_timeout(interval);
        if shared.stop.load(Ordering::Acquire) {
            return;
        }
        if !shared.dirty.swap(false, Ordering::AcqRel) {
            continue;
        }
        let began = Instant::now();
        match file.sync_data() {
            Ok(()) => tracing::trace!(took = ?began.elapsed(), "corpus log synced"),
            // Lines already written stay readable until a power cut; the writer's own errors
            // refuse triggers, this one is said loudly (at most every 10 s).
            Err(error) => {
                if reported.is_none_or(|t| t.elapsed() >= Duration::from_secs(10)) {
                    tracing::error!(%error, "cannot sync the corpus log to disk: a power cut could lose the last events");
                    reported = Some(Instant::now());
                }
                shared.dirty.store(true, Ordering::Release);
            }
        }
    }
}
