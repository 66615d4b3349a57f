//! The writer thread's loop: group commit. Each batch of events becomes one buffer of whole
//! JSON lines handed to the operating system with one `write(2)` (more only if the kernel takes
//! part of it); only when that returned does the hub learn the batch is logged. A failed write
//! (a full disk) keeps the bytes not written, in order, and retries them, so the file never
//! gets a line with a gap in it; meanwhile acknowledgements are refused, and events wait in
//! memory up to [`MAX_UNWRITTEN`].

use std::fs::File;
use std::io::{self, Write};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use crate::corpus::sync::Syncer;
use crate::events::{Committer, CorpusFeed, Event, Logged};
use crate::sync::lock;

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

/// How often writing is tried again after it failed.
const RETRY_INTERVAL: Duration = Duration::from_secs(1);

/// While the log cannot be written, at most this many bytes of events wait for it; events
/// beyond are lost (counted, and the run ends with an error).
const MAX_UNWRITTEN: usize = 64 * 1024 * 1024;

/// Runs until the hub closes the corpus; returns the number of events written.
pub(super) fn run(file: File, feed: CorpusFeed, syncer: Syncer) -> io::Result<u64> {
    feed.attach_current_thread();
    let shared = Arc::new(Shared {
        log: Mutex::new(Log {
            file,
            batch: Vec::new(),
            out: Unwritten::default(),
            failures: Failures::default(),
            syncer: Some(syncer),
        }),
        feed,
    });
    shared.feed.set_committer(Some(shared.clone()));
    let mut quiet = 0;
    loop {
        if quiet >= QUIET_TICKS && lock(&shared.log).out.bytes.is_empty() {
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
struct Shared {
    log: Mutex<Log>,
    feed: CorpusFeed,
}

impl Committer for Shared {
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

struct Log {
    file: File,
    batch: Vec<Arc<Event>>,
    out: Unwritten,
    failures: Failures,
    syncer: Option<Syncer>,
}

impl Log {
    /// Takes every pending event and writes it with what still waits; returns the number of
    /// events taken.
    fn commit(&mut self, feed: &CorpusFeed) -> usize {
        feed.take_now(&mut self.batch);
        let took = self.batch.len();
        for event in self.batch.drain(..) {
            self.out.push(&event, &mut self.failures);
        }
        if self.out.bytes.is_empty() || !self.failures.may_retry() {
            return took;
        }
        match self.out.write_to(&mut self.file) {
            Ok(()) => {
                self.failures.recovered();
                if let Some(syncer) = &self.syncer {
                    syncer.written();
                }
                feed.report(self.out.logged(None));
            }
            Err(error) => {
                let message = self.failures.note(&error);
                feed.report(self.out.logged(Some(message)));
            }
        }
        took
    }

    /// The last write, the last sync, and the run's verdict.
    fn finish(&mut self, feed: &CorpusFeed) -> io::Result<u64> {
        if !self.out.bytes.is_empty()
            && let Err(error) = self.out.write_to(&mut self.file)
        {
            self.failures.note(&error);
            // What is still unwritten now never will be.
            self.failures.lost += self.out.waiting;
        }
        feed.report(self.out.logged(self.failures.current.clone()));
        let synced = match self.syncer.take() {
            Some(syncer) => syncer.finish(&self.file),
            None => Ok(()),
        };
        match self.failures.count + self.failures.lost {
            0 => synced.map(|()| self.out.lines),
            _ => Err(io::Error::other(self.failures.summary())),
        }
    }
}

/// Lines handed to the writer and not yet written, and how far the file is.
#[derive(Default)]
struct Unwritten {
    bytes: Vec<u8>,
    /// The `seq` of the last line in `bytes` (or written, when `bytes` is empty).
    last_seq: u64,
    /// Every line up to this `seq` is written.
    through: u64,
    /// Lines written.
    lines: u64,
    /// Lines in `bytes`.
    waiting: u64,
}

impl Unwritten {
    fn push(&mut self, event: &Event, failures: &mut Failures) {
        let json = event.json();
        if self.bytes.len() + json.len() >= MAX_UNWRITTEN {
            failures.lost += 1;
            return;
        }
        self.bytes.reserve(json.len() + 1);
        self.bytes.extend_from_slice(json.as_bytes());
        self.bytes.push(b'\n');
        self.last_seq = event.seq;
        self.waiting += 1;
    }

    /// Writes every waiting byte, keeping what the kernel did not take when it fails.
    fn write_to(&mut self, file: &mut impl Write) -> io::Result<()> {
        let mut done = 0;
        let result = loop {
            if done == self.bytes.len() {
                break Ok(());
            }
            match file.write(&self.bytes[done..]) {
                Ok(0) => break Err(io::Error::from(io::ErrorKind::WriteZero)),
                Ok(n) => done += n,
                Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                Err(e) => break Err(e),
            }
        };
        if result.is_ok() {
            self.bytes.clear();
            self.through = self.last_seq;
            self.lines += std::mem::take(&mut self.waiting);
        } else {
            // The rest goes out with the next attempt, right after what the file ends with.
            self.bytes.drain(..done);
        }
        result
    }

    fn logged(&self, failure: Option<Arc<str>>) -> Logged {
        Logged {
            through: self.through,
            failure,
            ended: false,
        }
    }
}

/// Write failures (a full disk, say): the writer keeps going, since space may come back, and
/// says so loudly at once, then at most every 10 s.
#[derive(Default)]
struct Failures {
    count: u64,
    /// Events dropped because too much waited unwritten.
    lost: u64,
    reported: Option<Instant>,
    /// The current failure, while writing fails.
    current: Option<Arc<str>>,
    /// When writing last failed.
    failed_at: Option<Instant>,
}

impl Failures {
    /// Whether to write now: always, unless the last attempt failed less than
    /// [`RETRY_INTERVAL`] ago.
    fn may_retry(&self) -> bool {
        self.current.is_none() || self.failed_at.is_none_or(|t| t.elapsed() >= RETRY_INTERVAL)
    }

    fn note(&mut self, error: &io::Error) -> Arc<str> {
        self.count += 1;
        self.failed_at = Some(Instant::now());
        if self
            .reported
            .is_none_or(|t| t.elapsed() >= Duration::from_secs(10))
        {
            tracing::error!(
                %error,
                failures = self.count,
                lost = self.lost,
                "cannot write the corpus log: events wait in memory and new triggers are refused"
            );
            self.reported = Some(Instant::now());
        }
        let message: Arc<str> = error.to_string().into();
        self.current = Some(Arc::clone(&message));
        message
    }

    fn recovered(&mut self) {
        if self.current.take().is_some() {
            tracing::warn!(
                failures = self.count,
                lost = self.lost,
                "the corpus log can be written again"
            );
        }
    }

    fn summary(&self) -> String {
        let mut text = format!("{} corpus writes failed", self.count);
        if self.lost > 0 {
            text += &format!(" and {} events were lost", self.lost);
        }
        text + "; see the server log"
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::events::{EventKind, Hub, Source};

    fn event(seq: u64) -> Event {
        let kind = EventKind::ContextChanged {
            source: Source::Http,
            context: format!("T{seq}"),
        };
        Event::new(seq, std::time::SystemTime::now(), seq, kind)
    }

    /// Takes `room` bytes, then fails as a full disk does, until given more room.
    struct Disk {
        data: Vec<u8>,
        room: usize,
    }

    impl Write for Disk {
        fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
            let n = buf.len().min(self.room);
            if n == 0 {
                return Err(io::Error::from(io::ErrorKind::StorageFull));
            }
            self.data.extend_from_slice(&buf[..n]);
            self.room -= n;
            Ok(n)
        }

        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn a_write_cut_short_by_a_full_disk_is_completed_without_a_gap_when_space_returns() {
        let mut out = Unwritten::default();
        let mut failures = Failures::default();
        let mut disk = Disk {
            data: Vec::new(),
            room: 30,
        };
        let (first, second) = (event(1), event(2));
        out.push(&first, &mut failures);
        out.push(&second, &mut failures);
        assert!(out.write_to(&mut disk).is_err());
        assert_eq!(out.logged(None).through, 0, "nothing confirmed");
        disk.room = usize::MAX;
        out.write_to(&mut disk).unwrap();
        let expected = format!("{}\n{}\n", first.json(), second.json());
        assert_eq!(String::from_utf8(disk.data).unwrap(), expected);
        assert_eq!((out.logged(None).through, out.lines), (2, 2));
    }

    #[tokio::test]
    async fn a_full_disk_refuses_acknowledgements_and_ends_the_run_with_an_error() {
        let file = File::options().append(true).open("/dev/full").unwrap();
        let (hub, feed) = Hub::new();
        let syncer = Syncer::start(file.try_clone().unwrap(), Duration::from_secs(3600)).unwrap();
        let writer = std::thread::spawn(move || run(file, feed, syncer));
        let e = hub.publish(EventKind::ContextChanged {
            source: Source::Http,
            context: "Text".into(),
        });
        let refused = hub.logged(e.seq).await.unwrap_err();
        assert!(
            refused.to_string().contains("No space left on device"),
            "{refused}"
        );
        let failure = hub.log_failure().expect("triggers are refused");
        assert!(
            failure
                .refusal()
                .starts_with("not triggered: the corpus log cannot be written")
        );
        hub.close_corpus();
        let end = writer.join().unwrap().unwrap_err();
        assert!(end.to_string().contains("corpus writes failed"), "{end}");
    }
}
