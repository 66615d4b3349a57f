//! The writer's own tests: commits, failures and recovery, gaps and removed files, on a
//! disk the tests control.

use std::io::Write;

use super::*;
use crate::route::Place;
use docent_protocol::events::Source;

fn event(seq: u64) -> Event {
    let kind = EventKind::ContextChanged {
        source: Source::Http,
        context: format!("T{seq}"),
    };
    Event::new(
        seq,
        std::time::UNIX_EPOCH + Duration::from_secs(1_795_000_000),
        seq,
        kind,
    )
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

    fn removed(&mut self) -> io::Result<bool> {
        Ok(false)
    }

    fn forget(&mut self) {}

    fn take_remade(&mut self) -> Option<std::path::PathBuf> {
        None
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

    fn removed(&mut self) -> io::Result<bool> {
        Ok(false)
    }

    fn forget(&mut self) {}

    fn take_remade(&mut self) -> Option<std::path::PathBuf> {
        None
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
    let mut out = Unwritten::new(MAX_UNWRITTEN);
    let mut disk = Disk {
        data: Vec::new(),
        room: 30,
    };
    let (first, second) = (event(1), event(2));
    out.push(&first, place());
    out.push(&second, place());
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
    published: Mutex<Vec<EventKind>>,
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
    fn publish(&self, kind: EventKind) {
        lock(&self.published).push(kind);
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

#[test]
fn a_full_disk_is_told_once_and_its_recovery_after_the_events_it_had_to_drop() {
    let feed = Arc::new(TestFeed::default());
    let corpus = std::path::PathBuf::from("/srv/corpus");
    let mut log = Log {
        route: Route::new(corpus),
        files: Disk {
            data: Vec::new(),
            room: 0,
        },
        batch: Vec::new(),
        out: Unwritten::new(event(1).json().len() + 10),
        failures: Failures::default(),
    };
    lock(&feed.pending).extend([1, 2].map(|seq| Arc::new(event(seq))));
    log.commit(&feed);
    log.failures.retry_now();
    log.commit(&feed);
    let failing = lock(&feed.reports).last().cloned().expect("reported");
    assert_eq!(failing.through, 0);
    let alert = failing.alert.expect("the operator's words");
    assert!(
        alert.starts_with("The corpus disk is full (/srv/corpus)"),
        "{alert}"
    );

    lock(&feed.pending).push(Arc::new(event(3)));
    log.files.room = usize::MAX;
    log.failures.retry_now();
    log.commit(&feed);
    let written = lock(&feed.reports).last().cloned().expect("reported");
    assert_eq!((written.through, written.failure), (1, None));
    assert_eq!(
        String::from_utf8(log.files.data.clone()).unwrap(),
        format!("{}\n", event(1).json())
    );
    let told: Vec<String> = lock(&feed.published)
        .iter()
        .map(|k| serde_json::to_string(k).unwrap())
        .collect();
    assert_eq!(told.len(), 3, "{told:?}");
    assert!(
        told[0].contains(r#""type":"corpus.unwritable","fault":"disk-full""#),
        "{}",
        told[0]
    );
    assert!(
        told[1].contains(r#""type":"corpus.gap","from":2,"to":3,"count":2"#),
        "{}",
        told[1]
    );
    assert!(
        told[2].contains(r#""type":"corpus.writable""#),
        "{}",
        told[2]
    );
    assert!(
        told[2].contains("2 events published while it could not be were lost (seq 2 to 3)"),
        "{}",
        told[2]
    );
    assert_eq!(log.failures.lost, 2);
}

#[test]
fn events_dropped_while_the_log_could_be_written_are_told_and_the_next_ones_kept() {
    let feed = Arc::new(TestFeed::default());
    let mut log = Log {
        route: Route::new("/srv/corpus".into()),
        files: Disk {
            data: Vec::new(),
            room: usize::MAX,
        },
        batch: Vec::new(),
        out: Unwritten::new(event(1).json().len() + 10),
        failures: Failures::default(),
    };
    lock(&feed.pending).extend([1, 2, 3].map(|seq| Arc::new(event(seq))));
    log.commit(&feed);
    lock(&feed.pending).push(Arc::new(event(4)));
    log.commit(&feed);
    let expected = format!("{}\n{}\n", event(1).json(), event(4).json());
    assert_eq!(String::from_utf8(log.files.data.clone()).unwrap(), expected);
    let told = lock(&feed.published);
    let [EventKind::CorpusGap(gap)] = told.as_slice() else {
        panic!("one gap: {told:?}");
    };
    assert_eq!((gap.from, gap.to, gap.count, gap.fault), (2, 3, 2, None));
    // Every report that passes the dropped events says they are not in the log, so an
    // acknowledgement waiting for one is refused.
    for logged in lock(&feed.reports).iter().filter(|l| l.through >= 2) {
        assert!(!logged.holds(2) && !logged.holds(3), "{logged:?}");
    }
    let last = lock(&feed.reports).last().cloned().expect("reported");
    assert!(last.holds(1) && last.holds(4), "{last:?}");
}
