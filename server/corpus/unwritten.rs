//! The lines handed to the writer and not yet written, in order, and how far the log is
//! written. A write that fails keeps what the kernel did not take; a file found removed after
//! its lines were written to it gets them again in a new file, so that no acknowledged line is
//! only in a file nobody can read; events that would take more than [`MAX_UNWRITTEN`] while
//! the log cannot be written are dropped as one counted range (a gap), never some here and
//! some there.

use std::collections::VecDeque;
use std::io;
use std::path::PathBuf;
use std::sync::Arc;

use crate::files::Sink;
use crate::manifest::SessionManifest;
use crate::route::Place;
use crate::writer::Logged;
use docent_protocol::events::Event;

/// While the log cannot be written, at most this many bytes of events wait for it; events
/// beyond are dropped until everything kept is written (then a `corpus.gap` says which).
pub(super) const MAX_UNWRITTEN: usize = 64 * 1024 * 1024;

/// How often in a row a file is made again because it was removed again, before the write
/// counts as failed (and is retried at the failures' pace).
const MAX_REMADE: usize = 3;

/// Lines not written yet, one segment per run of lines for the same file.
pub(super) struct Unwritten {
    segments: VecDeque<Segment>,
    /// At most this many bytes wait ([`MAX_UNWRITTEN`] but in tests).
    limit: usize,
    /// Bytes in all segments.
    bytes: usize,
    /// Every line up to this `seq` is written.
    pub(super) through: u64,
    /// Lines written.
    pub(super) lines: u64,
    /// Lines in the segments.
    pub(super) waiting: u64,
    /// Events dropped since the buffer filled up, not yet told: `(first seq, last seq,
    /// count)`. While it is set every event is dropped, so the gap is one range.
    pub(super) dropped: Option<(u64, u64, u64)>,
    /// Files found removed under the writer and made again, not yet told.
    pub(super) remade: Vec<PathBuf>,
    /// The ranges dropped and told, reported in every [`Logged`].
    pub(super) lost: Vec<(u64, u64)>,
}

/// Lines for one file.
struct Segment {
    file: PathBuf,
    bytes: Vec<u8>,
    /// How many of `bytes` the current file took.
    done: usize,
    /// The `seq` of its last line.
    last_seq: u64,
    lines: u64,
    /// A session's manifest as its lines leave it, written once they are.
    manifest: Option<(PathBuf, SessionManifest)>,
}

impl Unwritten {
    /// Nothing waiting; at most `limit` bytes will.
    pub(super) fn new(limit: usize) -> Self {
        Unwritten {
            segments: VecDeque::new(),
            limit,
            bytes: 0,
            through: 0,
            lines: 0,
            waiting: 0,
            dropped: None,
            remade: Vec::new(),
            lost: Vec::new(),
        }
    }

    pub(super) fn is_empty(&self) -> bool {
        self.segments.is_empty()
    }

    /// Adds `event`'s line for the file `place` names; drops it (counted in [`Self::dropped`])
    /// when too much waits already, or when dropping began and what was kept is not written.
    pub(super) fn push(&mut self, event: &Event, place: Place) {
        let json = event.json();
        if self.dropped.is_some() || self.bytes + json.len() >= self.limit {
            let (from, _, count) = self.dropped.unwrap_or((event.seq, event.seq, 0));
            self.dropped = Some((from, event.seq, count + 1));
            return;
        }
        let same_file = self.segments.back().is_some_and(|s| s.file == place.file);
        if !same_file {
            self.segments.push_back(Segment {
                file: place.file,
                bytes: Vec::new(),
                done: 0,
                last_seq: 0,
                lines: 0,
                manifest: None,
            });
        }
        let Some(segment) = self.segments.back_mut() else {
            return;
        };
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
    pub(super) fn write_to(&mut self, sink: &mut impl Sink) -> io::Result<()> {
        while let Some(segment) = self.segments.front_mut() {
            let mut remade = 0;
            loop {
                let written = write_segment(segment, sink);
                self.remade.extend(sink.take_remade());
                written?;
                // Lines written into a file that was removed meanwhile are in no file anyone
                // can read: the whole segment goes into a new one.
                if !sink.removed()? {
                    break;
                }
                remade += 1;
                if remade > MAX_REMADE {
                    return Err(io::Error::other("the corpus log keeps being removed"));
                }
                sink.forget();
                segment.done = 0;
                self.remade.push(segment.file.clone());
            }
            if let Some((dir, manifest)) = &segment.manifest {
                std::fs::create_dir_all(dir)?;
                manifest.write_to(dir)?;
                if manifest.ended.is_some() {
                    // A finished session's log is synced and closed (its lock released) now,
                    // not when the next event goes elsewhere.
                    sink.close()?;
                }
            }
            self.bytes -= segment.bytes.len();
            self.through = segment.last_seq;
            self.lines += segment.lines;
            self.waiting -= segment.lines;
            self.segments.pop_front();
        }
        Ok(())
    }

    /// How far the log is written, with the failure that stops it (and the operator's words).
    pub(super) fn logged(&self, failure: Option<(Arc<str>, Arc<str>)>) -> Logged {
        let (failure, alert) = failure.unzip();
        Logged {
            through: self.through,
            failure,
            alert,
            ended: false,
            lost: self.lost.clone(),
        }
    }
}

/// Writes what of `segment` its file has not taken yet.
fn write_segment(segment: &mut Segment, sink: &mut impl Sink) -> io::Result<()> {
    let file = sink.file_for(&segment.file)?;
    let start = segment.done;
    let result = loop {
        if segment.done == segment.bytes.len() {
            break Ok(());
        }
        match file.write(&segment.bytes[segment.done..]) {
            Ok(0) => break Err(io::Error::from(io::ErrorKind::WriteZero)),
            Ok(n) => segment.done += n,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(e) => break Err(e),
        }
    };
    // What was taken is not written again: the rest follows right after it.
    if segment.done > start {
        sink.written();
    }
    result
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use super::*;
    use crate::files::Files;
    use docent_protocol::events::{EventKind, Source};

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

    fn at(file: &std::path::Path) -> Place {
        Place {
            file: file.to_owned(),
            session_start_us: None,
            manifest: None,
        }
    }

    #[test]
    fn lines_written_into_a_log_removed_meanwhile_are_written_again_into_a_new_one() {
        let corpus = tempfile::tempdir().unwrap();
        let log = corpus.path().join("days/2026-11-29/09-00-00Z.jsonl");
        let mut files = Files::new(Duration::from_secs(3600));
        let mut out = Unwritten::new(MAX_UNWRITTEN);
        out.push(&event(1), at(&log));
        out.write_to(&mut files).unwrap();
        std::fs::remove_dir_all(corpus.path().join("days")).unwrap();

        out.push(&event(2), at(&log));
        out.write_to(&mut files).unwrap();
        assert_eq!(out.remade, std::slice::from_ref(&log), "said once");
        let text = std::fs::read_to_string(&log).expect("made again");
        assert_eq!(text, format!("{}\n", event(2).json()));
        assert_eq!((out.through, out.lines), (2, 2));
    }

    #[test]
    fn a_closed_log_found_removed_when_it_is_opened_again_is_said_to_be_made_again() {
        let corpus = tempfile::tempdir().unwrap();
        let day = corpus.path().join("days/2026-11-29/09-00-00Z.jsonl");
        let session = corpus
            .path()
            .join("sessions/2026-11-29T09-00-01Z/events.jsonl");
        let mut files = Files::new(Duration::from_secs(3600));
        let mut out = Unwritten::new(MAX_UNWRITTEN);
        out.push(&event(1), at(&day));
        out.push(&event(2), at(&session));
        out.write_to(&mut files).unwrap();
        assert!(out.remade.is_empty());
        std::fs::remove_dir_all(corpus.path().join("days")).unwrap();

        out.push(&event(3), at(&day));
        out.write_to(&mut files).unwrap();
        assert_eq!(out.remade, std::slice::from_ref(&day));
        let text = std::fs::read_to_string(&day).expect("made again");
        assert_eq!(text, format!("{}\n", event(3).json()));
    }

    #[test]
    fn events_beyond_the_limit_are_dropped_as_one_range_until_what_was_kept_is_written() {
        let (first, second) = (event(1), event(2));
        let mut out = Unwritten::new(first.json().len() + 10);
        let log = std::path::Path::new("days/x.jsonl");
        out.push(&first, at(log));
        out.push(&second, at(log));
        // Would fit beside the first, but the range stays one.
        out.push(&event(3), at(log));
        assert_eq!(out.dropped, Some((2, 3, 2)));
        assert_eq!(out.waiting, 1);
    }
}
