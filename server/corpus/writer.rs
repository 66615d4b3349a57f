//! The writer thread's loop: group commit. Each batch of events becomes one buffer of whole
//! JSON lines per file it goes to (`route.rs` decides: a session's log or the day log), each
//! handed to the operating system with one `write(2)` (more only if the kernel takes part of
//! it); only when that returned does the hub learn the batch is logged. A failed write
//! (a full disk) keeps the bytes not written, in order, and retries them, so the file never
//! gets a line with a gap in it; meanwhile acknowledgements are refused, and events wait in
//! memory up to [`MAX_UNWRITTEN`].

use std::collections::VecDeque;
use std::io;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use crate::failures::Failures;
use crate::files::{Files, Sink};
use crate::manifest::SessionManifest;
use crate::route::{Place, Route};
use docent_protocol::events::Event;

use crate::lock;

/// How far the corpus log is written, as the writer last reported it.
#[derive(Clone, Debug, Default)]
pub struct Logged {
    /// Every event up to this `seq` has been handed to the operating system (`write(2)`
    /// returned), so it survives a crash or `kill -9` of Docent.
    pub through: u64,
    /// Why the log cannot be written now (a full disk, an I/O error); `None` while it can.
    pub failure: Option<Arc<str>>,
    /// The writer has stopped: nothing published later will be written.
    pub ended: bool,
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

/// While the log cannot be written, at most this many bytes of events wait for it; events
/// beyond are lost (counted, and the run ends with an error).
const MAX_UNWRITTEN: usize = 64 * 1024 * 1024;

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
            out: Unwritten::default(),
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
            self.out.push(&event, place, &mut self.failures);
        }
        if self.out.is_empty() || !self.failures.may_retry() {
            return took;
        }
        match self.out.write_to(&mut self.files) {
            Ok(()) => {
                self.failures.recovered();
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
    fn finish(&mut self, feed: &impl Feed) -> io::Result<u64> {
        if !self.out.is_empty()
            && let Err(error) = self.out.write_to(&mut self.files)
        {
            self.failures.note(&error);
            // What is still unwritten now never will be.
            self.failures.lost += self.out.waiting;
        }
        feed.report(self.out.logged(self.failures.current.clone()));
        let synced = self.files.close();
        match self.failures.count + self.failures.lost {
            0 => synced.map(|()| self.out.lines),
            _ => Err(io::Error::other(self.failures.summary())),
        }
    }
}

/// Lines handed to the writer and not yet written, in order, one segment per run of lines
/// for the same file; and how far the log is written.
#[derive(Default)]
struct Unwritten {
    segments: VecDeque<Segment>,
    /// Bytes in all segments.
    bytes: usize,
    /// Every line up to this `seq` is written.
    through: u64,
    /// Lines written.
    lines: u64,
    /// Lines in the segments.
    waiting: u64,
}

/// Lines for one file.
struct Segment {
    file: PathBuf,
    bytes: Vec<u8>,
    /// The `seq` of its last line.
    last_seq: u64,
    lines: u64,
    /// A session's manifest as its lines leave it, written once they are.
    manifest: Option<(PathBuf, SessionManifest)>,
}

impl Unwritten {
    fn is_empty(&self) -> bool {
        self.segments.is_empty()
    }

    fn push(&mut self, event: &Event, place: Place, failures: &mut Failures) {
        let json = event.json();
        if self.bytes + json.len() >= MAX_UNWRITTEN {
            failures.lost += 1;
            return;
        }
        let same_file = self.segments.back().is_some_and(|s| s.file == place.file);
        if !same_file {
            self.segments.push_back(Segment {
                file: place.file,
                bytes: Vec::new(),
                last_seq: 0,
                lines: 0,
                manifest: None,
            });
        }
        let segment = self.segments.back_mut().expect("pushed above");
        let before = segment.bytes.len();
        event.write_line(&mut segment.bytes, place.session_start_us);
        self.bytes += segment.bytes.len() - before;
        segment.last_seq = event.seq;
        segment.lines += 1;
        if place.manifest.is_some() {
            segment.manifest = place.manifest;
        }
        self.waiting += 1;
    }

    /// Writes every waiting segment to its file, in order, and the manifests they carry;
    /// keeps what the kernel did not take when a write fails.
    fn write_to(&mut self, sink: &mut impl Sink) -> io::Result<()> {
        while let Some(segment) = self.segments.front_mut() {
            let file = sink.file_for(&segment.file)?;
            let mut done = 0;
            let result = loop {
                if done == segment.bytes.len() {
                    break Ok(());
                }
                match file.write(&segment.bytes[done..]) {
                    Ok(0) => break Err(io::Error::from(io::ErrorKind::WriteZero)),
                    Ok(n) => done += n,
                    Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                    Err(e) => break Err(e),
                }
            };
            // What was taken is not written again: the rest follows right after it.
            segment.bytes.drain(..done);
            self.bytes -= done;
            if done > 0 {
                sink.written();
            }
            result?;
            if let Some((dir, manifest)) = &segment.manifest {
                manifest.write_to(dir)?;
                if manifest.ended.is_some() {
                    // A finished session's log is synced and closed (its lock released) now,
                    // not when the next event goes elsewhere.
                    sink.close()?;
                }
            }
            self.through = segment.last_seq;
            self.lines += segment.lines;
            self.waiting -= segment.lines;
            self.segments.pop_front();
        }
        Ok(())
    }

    fn logged(&self, failure: Option<Arc<str>>) -> Logged {
        Logged {
            through: self.through,
            failure,
            ended: false,
        }
    }
}

#[cfg(test)]
mod tests {
    use std::io::Write;

    use super::*;
    use docent_protocol::events::{EventKind, Source};

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

    impl Sink for Disk {
        fn file_for(&mut self, _: &std::path::Path) -> io::Result<&mut dyn Write> {
            Ok(self)
        }

        fn written(&mut self) {}

        fn close(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    /// Every file is `/dev/full`.
    struct FullDisk(std::fs::File);

    impl Sink for FullDisk {
        fn file_for(&mut self, _: &std::path::Path) -> io::Result<&mut dyn Write> {
            Ok(&mut self.0)
        }

        fn written(&mut self) {}

        fn close(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    fn place() -> Place {
        Place {
            file: "days/2026-11-24/09-00-00Z.jsonl".into(),
            session_start_us: None,
            manifest: None,
        }
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
        out.push(&first, place(), &mut failures);
        out.push(&second, place(), &mut failures);
        assert!(out.write_to(&mut disk).is_err());
        assert_eq!(out.logged(None).through, 0, "nothing confirmed");
        disk.room = usize::MAX;
        out.write_to(&mut disk).unwrap();
        let expected = format!("{}\n{}\n", first.json(), second.json());
        assert_eq!(String::from_utf8(disk.data).unwrap(), expected);
        assert_eq!((out.logged(None).through, out.lines), (2, 2));
    }

    /// A feed of the events given, recording every report, closed once they are taken.
    #[derive(Default)]
    struct TestFeed {
        pending: Mutex<Vec<Arc<Event>>>,
        reports: Mutex<Vec<Logged>>,
    }

    impl Feed for Arc<TestFeed> {
        fn attach_current_thread(&self) {}
        fn wait(&self, _: Duration) {}
        fn take_now(&self, batch: &mut Vec<Arc<Event>>) {
            std::mem::swap(&mut *lock(&self.pending), batch);
        }
        fn closed(&self) -> bool {
            lock(&self.pending).is_empty()
        }
        fn set_committer(&self, _: Option<Arc<dyn Committer>>) {}
        fn sleep_until_published(&self) {}
        fn report(&self, logged: Logged) {
            lock(&self.reports).push(logged);
        }
    }

    #[test]
    fn a_full_disk_is_reported_and_ends_the_run_with_an_error() {
        let file = std::fs::File::options()
            .append(true)
            .open("/dev/full")
            .unwrap();
        let feed = Arc::new(TestFeed::default());
        lock(&feed.pending).push(Arc::new(event(1)));
        let corpus = tempfile::tempdir().unwrap().path().to_owned();
        let end = run_into(FullDisk(file), Route::new(corpus), Arc::clone(&feed)).unwrap_err();
        assert!(end.to_string().contains("corpus writes failed"), "{end}");
        let reports = lock(&feed.reports);
        let failure = reports
            .iter()
            .find_map(|r| r.failure.clone())
            .expect("the failure is reported");
        assert!(failure.contains("No space left on device"), "{failure}");
        assert!(reports.iter().all(|r| r.through == 0), "nothing confirmed");
    }
}
