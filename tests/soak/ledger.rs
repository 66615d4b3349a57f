//! What the clients saw, kept in one place: every trigger sent and its answer (the
//! acknowledgement the corpus must hold), its latency, refusals by code, recording chunks
//! acknowledged, and anything unexpected, in words.

use std::collections::{BTreeMap, HashMap};
use std::sync::Mutex;
use std::time::Instant;

/// Who triggered.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Role {
    /// A touchscreen a visitor taps.
    Kiosk,
    /// The operator's console.
    Operator,
    /// The dialog manager.
    Dm,
}

impl Role {
    /// Its name in reports.
    pub fn name(self) -> &'static str {
        match self {
            Role::Kiosk => "kiosk",
            Role::Operator => "operator",
            Role::Dm => "dm",
        }
    }

    /// Every role, in report order.
    pub const ALL: [Role; 3] = [Role::Kiosk, Role::Operator, Role::Dm];
}

/// One answered trigger's latency: sent `at` seconds into the run, answered after `ms`.
#[derive(Clone, Copy, Debug)]
pub struct Latency {
    pub at: f64,
    pub role: Role,
    pub ms: f64,
}

/// Everything recorded; read once the load has ended.
#[derive(Default, Debug)]
pub struct Book {
    pending: HashMap<String, (Role, Instant)>,
    /// The refs of every trigger answered `triggered`, in order of answer.
    pub acked: Vec<String>,
    pub latencies: Vec<Latency>,
    /// Triggers refused, by role and error code.
    pub refused: BTreeMap<(Role, String), u64>,
    /// Triggers whose connection a storm dropped before they were answered (not acknowledged).
    pub unanswered_at_drop: u64,
    /// Recording chunks acknowledged (`200`), and the largest `acked` length per recording.
    pub chunks: u64,
    pub recordings: HashMap<u64, u64>,
    /// Kiosk connections opened (reconnections included).
    pub connections: u64,
    /// What went wrong, in words; the verdict fails on any.
    pub unexpected: Vec<String>,
}

/// The shared, locked [`Book`].
pub struct Ledger {
    book: Mutex<Book>,
    start: Instant,
}

impl Ledger {
    /// A ledger whose latencies are placed on a run that began at `start`.
    pub fn new(start: Instant) -> Ledger {
        Ledger {
            book: Mutex::default(),
            start,
        }
    }

    fn book(&self) -> std::sync::MutexGuard<'_, Book> {
        self.book.lock().expect("ledger")
    }

    /// A trigger with `reference` is about to be sent.
    pub fn sent(&self, reference: &str, role: Role) {
        self.book()
            .pending
            .insert(reference.to_owned(), (role, Instant::now()));
    }

    /// `triggered` arrived for `reference`.
    pub fn answered(&self, reference: &str) {
        let now = Instant::now();
        let start = self.start;
        let mut book = self.book();
        match book.pending.remove(reference) {
            Some((role, sent)) => {
                book.acked.push(reference.to_owned());
                book.latencies.push(Latency {
                    at: sent.duration_since(start).as_secs_f64(),
                    role,
                    ms: now.duration_since(sent).as_secs_f64() * 1000.0,
                });
            }
            None => book.unexpected.push(format!(
                "an answer to {reference}, which is not waiting for one"
            )),
        }
    }

    /// `error` with `code` arrived for `reference`.
    pub fn refused(&self, reference: &str, code: &str) {
        let mut book = self.book();
        match book.pending.remove(reference) {
            Some((role, _)) => *book.refused.entry((role, code.to_owned())).or_default() += 1,
            None => book.unexpected.push(format!(
                "a refusal ({code}) of {reference}, which is not waiting"
            )),
        }
    }

    /// A kiosk's connection ended: its triggers still waiting (refs starting `prefix`) will
    /// never be answered on it.
    pub fn dropped(&self, prefix: &str) {
        let mut book = self.book();
        let before = book.pending.len();
        book.pending.retain(|r, _| !r.starts_with(prefix));
        book.unanswered_at_drop += (before - book.pending.len()) as u64;
    }

    /// Triggers still waiting for an answer.
    pub fn waiting(&self) -> Vec<String> {
        self.book().pending.keys().cloned().collect()
    }

    /// Chunk stored: recording `recording` now holds `acked` bytes.
    pub fn chunk(&self, recording: u64, acked: u64) {
        let mut book = self.book();
        book.chunks += 1;
        let held = book.recordings.entry(recording).or_default();
        *held = (*held).max(acked);
    }

    /// A kiosk connection was opened.
    pub fn connected(&self) {
        self.book().connections += 1;
    }

    /// Something went wrong.
    pub fn unexpected(&self, what: String) {
        self.book().unexpected.push(what);
    }

    /// How many triggers were acknowledged so far.
    pub fn acked(&self) -> usize {
        self.book().acked.len()
    }

    /// The book, once the load has ended.
    pub fn take(&self) -> Book {
        std::mem::take(&mut *self.book())
    }
}
