//! Bookkeeping shared by senders and subscribers: the outstanding triggers, the latency of every
//! delivered command, and what went missing. Latencies are kept whole (one u64 per delivery)
//! and percentiles are taken by sorting, so no histogram rounding enters the figures.

use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard, PoisonError};
use std::time::{Duration, Instant};

use tokio::sync::oneshot;

/// The state of one run, shared by every thread of it.
pub struct Tally {
    /// Command frames each trigger should produce in all (subscribers × commands).
    per_trigger: u64,
    next_ref: AtomicU64,
    inner: Mutex<Inner>,
}

#[derive(Default)]
struct Inner {
    pending: HashMap<u64, Pending>,
    /// Measured triggers sent, and the command frames they should and did produce.
    sent: u64,
    expected: u64,
    received: u64,
    /// Command frames whose ref was not outstanding (late after a closed-loop timeout, or extra).
    unexpected: u64,
    /// `error` frames from the server, and the first one's message.
    errors: u64,
    first_error: Option<String>,
    last_delivery: Option<Instant>,
    /// Due time → read by a subscriber, per measured command frame, in ns.
    latency_ns: Vec<u64>,
    /// Due time → handed to the socket, per measured trigger, in ns: how late the client was.
    send_lag_ns: Vec<u64>,
}

struct Pending {
    due: Instant,
    remaining: u64,
    measured: bool,
    all_arrived: Option<oneshot::Sender<()>>,
}

/// What a run ended with.
#[derive(Debug)]
pub struct Summary {
    pub sent: u64,
    pub expected: u64,
    pub received: u64,
    /// Measured triggers at least one of whose command frames never arrived.
    pub lost_triggers: u64,
    pub unexpected: u64,
    pub errors: u64,
    pub first_error: Option<String>,
    pub last_delivery: Option<Instant>,
    /// Sorted.
    pub latency_ns: Vec<u64>,
    /// Sorted.
    pub send_lag_ns: Vec<u64>,
}

fn ns(d: Duration) -> u64 {
    d.as_nanos().try_into().unwrap_or(u64::MAX)
}

impl Tally {
    /// A tally for triggers that each produce `per_trigger` command frames in all.
    pub fn new(per_trigger: u64) -> Self {
        Tally {
            per_trigger,
            next_ref: AtomicU64::new(0),
            inner: Mutex::new(Inner::default()),
        }
    }

    fn lock(&self) -> MutexGuard<'_, Inner> {
        // A panicking thread cannot leave the counters half-updated in a way that matters here.
        self.inner.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Records a trigger about to be sent that was due at `due`; returns its ref number.
    /// `all_arrived` fires once every expected command frame for it has been read.
    pub fn register(
        &self,
        due: Instant,
        measured: bool,
        all_arrived: Option<oneshot::Sender<()>>,
    ) -> u64 {
        let number = self.next_ref.fetch_add(1, Ordering::Relaxed);
        let lag = Instant::now().saturating_duration_since(due);
        let mut inner = self.lock();
        if measured {
            inner.sent += 1;
            inner.expected += self.per_trigger;
            inner.send_lag_ns.push(ns(lag));
        }
        let pending = Pending {
            due,
            remaining: self.per_trigger,
            measured,
            all_arrived,
        };
        inner.pending.insert(number, pending);
        number
    }

    /// Records a command frame for trigger `number`, read at `at`.
    pub fn deliver(&self, number: u64, at: Instant) {
        let mut guard = self.lock();
        let inner = &mut *guard;
        let Some(pending) = inner.pending.get_mut(&number) else {
            inner.unexpected += 1;
            return;
        };
        if pending.measured {
            inner.received += 1;
            inner
                .latency_ns
                .push(ns(at.saturating_duration_since(pending.due)));
            inner.last_delivery = Some(at);
        }
        pending.remaining = pending.remaining.saturating_sub(1);
        if pending.remaining == 0
            && let Some(done) = inner.pending.remove(&number).and_then(|p| p.all_arrived)
        {
            let _ = done.send(());
        }
    }

    /// Records an `error` frame from the server.
    pub fn error(&self, message: &str) {
        let mut inner = self.lock();
        inner.errors += 1;
        if inner.first_error.is_none() {
            inner.first_error = Some(message.to_owned());
        }
    }

    /// Measured command frames still to arrive.
    pub fn outstanding(&self) -> u64 {
        let inner = self.lock();
        inner.expected.saturating_sub(inner.received)
    }

    /// The figures so far.
    pub fn summary(&self) -> Summary {
        let inner = self.lock();
        let mut latency_ns = inner.latency_ns.clone();
        let mut send_lag_ns = inner.send_lag_ns.clone();
        latency_ns.sort_unstable();
        send_lag_ns.sort_unstable();
        Summary {
            sent: inner.sent,
            expected: inner.expected,
            received: inner.received,
            lost_triggers: inner.pending.values().filter(|p| p.measured).count() as u64,
            unexpected: inner.unexpected,
            errors: inner.errors,
            first_error: inner.first_error.clone(),
            last_delivery: inner.last_delivery,
            latency_ns,
            send_lag_ns,
        }
    }
}

/// The `q` quantile (0..=1) of sorted samples, in µs with one decimal; `None` when empty.
pub fn quantile_us(sorted_ns: &[u64], q: f64) -> Option<f64> {
    if sorted_ns.is_empty() {
        return None;
    }
    let rank = (q * sorted_ns.len() as f64).ceil() as usize;
    let ns = sorted_ns[rank.clamp(1, sorted_ns.len()) - 1];
    Some((ns as f64 / 100.0).round() / 10.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_pick_the_nearest_rank() {
        let samples: Vec<u64> = (1..=100).map(|n| n * 1000).collect();
        assert_eq!(quantile_us(&samples, 0.5), Some(50.0));
        assert_eq!(quantile_us(&samples, 0.99), Some(99.0));
        assert_eq!(quantile_us(&samples, 1.0), Some(100.0));
        assert_eq!(quantile_us(&samples, 0.0), Some(1.0));
        assert_eq!(quantile_us(&[], 0.5), None);
    }

    #[test]
    fn a_trigger_is_lost_until_every_frame_arrived() {
        let tally = Tally::new(2);
        let now = Instant::now();
        let a = tally.register(now, true, None);
        let b = tally.register(now, true, None);
        tally.deliver(a, now);
        tally.deliver(a, now);
        tally.deliver(b, now);
        tally.deliver(99, now);
        let s = tally.summary();
        assert_eq!((s.sent, s.expected, s.received), (2, 4, 3));
        assert_eq!((s.lost_triggers, s.unexpected), (1, 1));
        assert_eq!(tally.outstanding(), 1);
    }
}
