//! The writer thread's loop: group commit. Each batch of events becomes one buffer of whole
//! JSON lines per file it goes to (`route.rs` decides: a session's log or the day log), each
//! handed to the operating system with one `write(2)` (more only if the kernel takes part of
//! it); only when that returned does the hub learn the batch is logged.
//!
//! The writer never gives up. A failed write (a full or read-only disk, an I/O error) keeps
//! the bytes not written, in order (`unwritten.rs`), reports the failure (acknowledgements
//! are refused meanwhile), publishes `corpus.unwritable` with words for the operator, and
//! tries again every second; the first write that works writes everything kept, then
//! publishes `corpus.gap` (when events had to be dropped) and `corpus.writable`. A log file
//! removed under it (its folder deleted) is made again, its last lines written there, and
//! `corpus.recreated` said.

use std::io;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use crate::failures::Failures;
use crate::files::{Files, Sink};
use crate::route::Route;
use crate::unwritten::{MAX_UNWRITTEN, Unwritten};
use docent_protocol::events::{
    CorpusFault, CorpusGap, CorpusRecreated, CorpusWritable, Event, EventKind,
};

use crate::lock;

/// How far the corpus log is written, as the writer last reported it.
#[derive(Clone, Debug, Default)]
pub struct Logged {
    /// Every event up to this `seq` has been handed to the operating system (`write(2)`
    /// returned), so it survives a crash or `kill -9` of Docent.
    pub through: u64,
    /// Why the log cannot be written now (the operating system's error); `None` while it can.
    pub failure: Option<Arc<str>>,
    /// What the operator is told while it cannot (what happened and what to do).
    pub alert: Option<Arc<str>>,
    /// The writer has stopped: nothing published later will be written.
    pub ended: bool,
    /// Ranges of `seq`s (first, last) dropped while the log could not be written: never
    /// written although `through` passed them (`corpus.gap`), so never acknowledged.
    pub lost: Vec<(u64, u64)>,
}

impl Logged {
    /// Whether event `seq` is in the log: written through, and not in a range dropped.
    pub fn holds(&self, seq: u64) -> bool {
        self.through >= seq
            && !self
                .lost
                .iter()
                .any(|&(from, to)| (from..=to).contains(&seq))
    }
}

/// The writer's end of whoever publishes events (the runtime's hub): where it takes events
/// from, waits for them, and reports how far they are written.
pub trait Feed: Send + Sync + 'static {
    /// Makes the calling thread the writer that publishing wakes. Called once, from it.
    fn attach_current_thread(&self);
    /// Sleeps for up to `tick`, or until an acknowledgement asks for a write or the feed
    /// closes.
    fn wait(&self, tick: Duration);
    /// Moves every pending event into `batch` (which should be empty), without waiting.
    fn take_now(&self, batch: &mut Vec<Arc<Event>>);
    /// Whether the writer is asked to stop.
    fn closed(&self) -> bool;
    /// Lets acknowledgements write the log themselves through `committer` (`None`: no more).
    fn set_committer(&self, committer: Option<Arc<dyn Committer>>);
    /// After a quiet spell: sleeps until the next event, an acknowledgement or a close.
    fn sleep_until_published(&self);
    /// Reports how far the log is written.
    fn report(&self, logged: Logged);
    /// Publishes an event about the log itself (`corpus.*`) like any other: clients see it
    /// at once, and the writer takes it with the next batch.
    fn publish(&self, kind: EventKind);
}

/// Writes the pending events at once, on the caller's thread, if no one else is writing:
/// an acknowledgement that does so spares the writer thread a wake-up and itself the wait.
pub trait Committer: Send + Sync {
    /// False when the log is busy or failing (then the writer thread is asked instead).
    fn try_commit(&self) -> bool;
}

/// How often the writer takes the events no acknowledgement wrote (a command's outcome, a
/// pose) while they come. Publishing does not wake it: a wake-up per event cost more CPU than
/// all the writing, and on the hot path. An acknowledgement writes the log itself, or wakes
/// the writer when the log is busy.
const TICK: Duration = Duration::from_millis(5);

/// Each tick that finds nothing doubles the next, up to `TICK << MAX_BACKOFF` (80 ms): under
/// load acknowledgements do the writing.
const MAX_BACKOFF: u32 = 4;

/// After this many ticks without events (about a second), the writer sleeps until the next
/// publish wakes it.
const QUIET_TICKS: u32 = 16;

/// Runs until the hub closes the corpus; returns the number of events written.
pub(super) fn run<F: Feed>(route: Route, feed: F, sync_interval: Duration) -> io::Result<u64> {
    run_into(Files::new(sync_interval), route, feed)
}

/// Runs with `files` for the files (a test's failing disk).
fn run_into<S: Sink + Send + 'static, F: Feed>(files: S, route: Route, feed: F) -> io::Result<u64> {
    feed.attach_current_thread();
    let shared = Arc::new(Shared {
        log: Mutex::new(Log {
            route,
            files,
            batch: Vec::new(),
            out: Unwritten::new(MAX_UNWRITTEN),
            failures: Failures::default(),
        }),
        feed,
    });
    shared.feed.set_committer(Some(shared.clone()));
    let mut quiet = 0;
    loop {
        if quiet >= QUIET_TICKS && lock(&shared.log).out.is_empty() {
            shared.feed.sleep_until_published();
            quiet = 0;
        }
        shared.feed.wait(TICK * (1 << quiet.min(MAX_BACKOFF)));
        let took = lock(&shared.log).commit(&shared.feed);
        quiet = if took == 0 { quiet + 1 } else { 0 };
        if shared.feed.closed() {
            break;
        }
    }
    // Breaks the cycle hub → committer → feed → hub.
    shared.feed.set_committer(None);
    let mut log = lock(&shared.log);
    log.commit(&shared.feed);
    log.finish(&shared.feed)
}

/// The log, written by the writer thread or, to spare a wake-up, by an acknowledgement itself.
struct Shared<S, F> {
    log: Mutex<Log<S>>,
    feed: F,
}

impl<S: Sink + Send, F: Feed> Committer for Shared<S, F> {
    fn try_commit(&self) -> bool {
        let Ok(mut log) = self.log.try_lock() else {
            return false;
        };
        // A failing disk is left to the writer thread's own pace.
        if log.failures.current.is_some() {
            return false;
        }
        log.commit(&self.feed);
        true
    }
}

struct Log<S> {
    route: Route,
    files: S,
    batch: Vec<Arc<Event>>,
    out: Unwritten,
    failures: Failures,
}

impl<S: Sink> Log<S> {
    /// Takes every pending event and writes it with what still waits; returns the number of
    /// events taken.
    fn commit(&mut self, feed: &impl Feed) -> usize {
        feed.take_now(&mut self.batch);
        let took = self.batch.len();
        for event in self.batch.drain(..) {
            let place = self.route.place(&event);
            self.out.push(&event, place);
        }
        if self.out.is_empty() || !self.failures.may_retry() {
            return took;
        }
        let written = self.out.write_to(&mut self.files);
        self.tell_remade(feed);
        match written {
            Ok(()) => {
                let recovered = self.failures.recovered();
                feed.report(self.out.logged(None));
                // Everything kept is written: events are kept again from here on.
                let lost = self.tell_gap(feed, recovered.map(|(_, fault)| fault));
                if let Some((failed_for, _)) = recovered {
                    self.tell_recovered(feed, failed_for, lost);
                }
            }
            Err(error) => {
                if let Some(event) = self.failures.note(&error, self.route.corpus()) {
                    feed.publish(EventKind::CorpusUnwritable(event));
                }
                feed.report(self.out.logged(self.failures.report()));
            }
        }
        took
    }

    /// Says which files were made again, and writes the session's manifest beside a
    /// session's log made again (its folder went with it).
    fn tell_remade(&mut self, feed: &impl Feed) {
        for path in std::mem::take(&mut self.out.remade) {
            if let Some((folder, manifest)) = self.route.open_session()
                && path.parent() == Some(folder.as_path())
                && let Err(error) = manifest.write_to(&folder)
            {
                tracing::error!(%error, folder = %folder.display(), "cannot write the session's manifest again");
            }
            let path = path.display().to_string();
            feed.publish(EventKind::CorpusRecreated(CorpusRecreated::of(&path)));
        }
    }

    /// Says which events were dropped while what was kept waited, if any; returns the words
    /// for the operator about them.
    fn tell_gap(&mut self, feed: &impl Feed, fault: Option<CorpusFault>) -> Option<String> {
        let (from, to, count) = self.out.dropped.take()?;
        self.failures.lost += count;
        // Told before `through` can pass the range: an acknowledgement waiting for one of
        // these events is refused, never given.
        self.out.lost.push((from, to));
        feed.report(self.out.logged(None));
        tracing::error!(
            from,
            to,
            count,
            "corpus events lost: too many waited to be written"
        );
        let reason = format!(
            "more than {} MiB of events waited for the log to be written",
            MAX_UNWRITTEN >> 20
        );
        feed.publish(EventKind::CorpusGap(CorpusGap {
            from,
            to,
            count,
            fault,
            reason,
        }));
        Some(format!(
            " {count} events published while it could not be were lost (seq {from} to {to})."
        ))
    }

    /// Says that the log is written again (after `failed_for`), with what it `lost`.
    fn tell_recovered(&mut self, feed: &impl Feed, failed_for: Duration, lost: Option<String>) {
        let path = self.route.corpus().display().to_string();
        let mut message =
            format!("The corpus log is written again ({path}): triggers are accepted.");
        message += lost.as_deref().unwrap_or_default();
        let unwritable_ms = u64::try_from(failed_for.as_millis()).unwrap_or(u64::MAX);
        feed.publish(EventKind::CorpusWritable(CorpusWritable {
            path,
            unwritable_ms,
            message,
        }));
    }

    /// The last write, the last sync, and the run's verdict: an error when events were lost.
    fn finish(&mut self, feed: &impl Feed) -> io::Result<u64> {
        if !self.out.is_empty()
            && let Err(error) = self.out.write_to(&mut self.files)
        {
            self.failures.note(&error, self.route.corpus());
            // What is still unwritten now never will be.
            self.failures.lost += self.out.waiting;
        }
        if let Some((_, _, count)) = self.out.dropped.take() {
            self.failures.lost += count;
        }
        feed.report(self.out.logged(self.failures.report()));
        let synced = self.files.close();
        if self.failures.lost > 0 {
            return Err(io::Error::other(self.failures.summary()));
        }
        if self.failures.count > 0 {
            // Every event reached the log in the end: said, but not a failed run.
            tracing::warn!(
                "{}; every event was written in the end",
                self.failures.summary()
            );
        }
        synced.map(|()| self.out.lines)
    }
}

#[cfg(test)]
#[path = "writer_tests.rs"]
mod tests;
