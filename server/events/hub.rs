//! The event hub: stamps events and fans them out. The corpus writer gets every event (the log
//! must not lose anything) by taking, in one swap, all events published since its last batch;
//! websocket subscribers get them through a bounded broadcast channel and handle lag
//! themselves; the components that carry out a decision (recordings)
//! follow the few kinds they act on without loss ([`Hub::follow`]). The writer reports how far the log is written through a `watch`, so that an
//! acknowledgement can wait until its event is in the file ([`Hub::logged`]).

use std::collections::VecDeque;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, OnceLock};
use std::thread::Thread;
use std::time::{Duration, Instant, SystemTime};

use tokio::sync::{broadcast, mpsc, watch};

use crate::events::logged::check_logged;
use crate::events::{Event, EventKind, LogUnwritable, Logged};
use crate::sync::lock;
use docent_corpus::{Committer, Feed};

/// An acknowledgement that finds the log written by another one less than this time ago waits
/// this long before it writes: under load one write then serves the acknowledgements of a whole
/// moment, and their answers leave together (measured under the shared bench's closed loop:
/// Docent's CPU per trigger 143 → 124 µs, the client's 154 → 130 µs, as its sender threads
/// are woken once per batch); on a quiet log an acknowledgement writes at once.
const GATHER: Duration = Duration::from_millis(1);

/// How many history events (acts triggered, proposals, marks) a console joining later gets.
pub const HISTORY_LEN: usize = 200;

/// How many events a slow websocket subscriber may fall behind before it lags.
pub const EVENT_CHANNEL_CAPACITY: usize = 4096;

/// How long an acknowledgement waits for the corpus writer before giving up.
pub const LOG_WAIT_TIMEOUT: Duration = Duration::from_secs(10);

/// The one place events are published. Cheap to clone.
#[derive(Clone)]
pub struct Hub {
    inner: Arc<Inner>,
}

struct Inner {
    started: Instant,
    /// The sequence counter and the events the writer has not taken; publishing under it keeps
    /// the corpus in sequence order.
    queue: Mutex<Queue>,
    /// The `seq` of the latest event published (read without the lock by acknowledgements).
    published: AtomicU64,
    broadcast: broadcast::Sender<Arc<Event>>,
    /// Lossless followers of a few kinds of events ([`Hub::follow`]).
    followers: Mutex<Vec<Follower>>,
    /// The latest history events (see [`EventKind::is_history`]), oldest first.
    history: Mutex<VecDeque<Arc<Event>>>,
    /// The writer thread, woken by a publish while it sleeps with nothing to do, or by an
    /// acknowledgement that waits.
    writer: OnceLock<Thread>,
    /// An acknowledgement asked the writer to write now (cleared by the writer when it wakes):
    /// many waiting acknowledgements wake it once.
    wake_asked: AtomicBool,
    logged: watch::Sender<Logged>,
    /// Writes the log on an acknowledgement's own thread while the writer runs.
    committer: Mutex<Option<Arc<dyn Committer>>>,
    /// When an acknowledgement last wrote the log itself (on tokio's clock, which tests pause).
    acknowledged_write: Mutex<Option<tokio::time::Instant>>,
}

/// Which events a lossless follower takes.
pub type Interest = fn(&EventKind) -> bool;

struct Follower {
    interest: Interest,
    events: mpsc::UnboundedSender<Arc<Event>>,
}

#[derive(Default)]
struct Queue {
    seq: u64,
    pending: Vec<Arc<Event>>,
    /// The writer sleeps until the next publish.
    writer_idle: bool,
    /// Close asked for: the writer writes what is pending and stops.
    closed: bool,
    /// No writer will take events (its [`CorpusFeed`] was dropped): publish keeps none.
    detached: bool,
}

/// The corpus writer's end of the hub: takes published events in batches.
pub struct CorpusFeed {
    inner: Arc<Inner>,
}

/// How many published events may wait to be written before readers wait ([`Hub::room_to_log`]):
/// a few MB at most, and far more than a second of any real site's events.
pub const UNLOGGED_ROOM: u64 = 4096;

impl Hub {
    /// A hub and the corpus writer's end of it.
    pub fn new() -> (Hub, CorpusFeed) {
        let (broadcast, _) = broadcast::channel(EVENT_CHANNEL_CAPACITY);
        let inner = Arc::new(Inner {
            started: Instant::now(),
            queue: Mutex::new(Queue::default()),
            published: AtomicU64::new(0),
            broadcast,
            followers: Mutex::default(),
            history: Mutex::new(VecDeque::with_capacity(HISTORY_LEN)),
            writer: OnceLock::new(),
            wake_asked: AtomicBool::new(false),
            logged: watch::Sender::new(Logged::default()),
            committer: Mutex::new(None),
            acknowledged_write: Mutex::new(None),
        });
        let feed = CorpusFeed {
            inner: Arc::clone(&inner),
        };
        (Hub { inner }, feed)
    }

    /// Stamps and publishes an event; returns it.
    pub fn publish(&self, kind: EventKind) -> Arc<Event> {
        let mut queue = lock(&self.inner.queue);
        // Stamped under the lock so that sequence and monotonic time agree.
        let mono_us = self.inner.started.elapsed().as_micros() as u64;
        let time = SystemTime::now();
        queue.seq += 1;
        let event = Arc::new(Event::new(queue.seq, time, mono_us, kind));
        if !queue.detached {
            queue.pending.push(Arc::clone(&event));
        }
        self.inner.published.store(queue.seq, Ordering::Release);
        let wake = std::mem::take(&mut queue.writer_idle);
        // No subscribers is fine.
        let _ = self.inner.broadcast.send(Arc::clone(&event));
        {
            let mut followers = lock(&self.inner.followers);
            // Under the queue's lock: each follower gets its events in `seq` order.
            followers.retain(|f| {
                !(f.interest)(&event.kind) || f.events.send(Arc::clone(&event)).is_ok()
            });
        }
        if event.kind.is_history() {
            let mut history = lock(&self.inner.history);
            if history.len() == HISTORY_LEN {
                history.pop_front();
            }
            history.push_back(Arc::clone(&event));
        }
        drop(queue);
        if wake {
            self.inner.wake_writer();
        }
        event
    }

    /// Waits while the log is more than [`UNLOGGED_ROOM`] events behind what was published:
    /// connection readers call it before taking a client's next frame, so that a flood waits
    /// in the sockets (TCP back-pressure on the clients) instead of piling events up in memory.
    /// Returns at once when the log cannot be written (requests are refused then anyway).
    pub async fn room_to_log(&self) {
        let behind = self.published_seq().saturating_sub(UNLOGGED_ROOM);
        if !self.is_logged(behind) {
            let _ = self.logged(behind).await;
        }
    }

    /// The `seq` of the latest event published so far: an acknowledgement given after an
    /// action waits for this ([`Hub::logged`]), which covers the action's own events.
    pub fn published_seq(&self) -> u64 {
        self.inner.published.load(Ordering::Acquire)
    }

    /// Whether every event up to `seq` is written to the operating system already.
    pub fn is_logged(&self, seq: u64) -> bool {
        self.inner.logged.borrow().holds(seq)
    }

    /// Waits until every event up to `seq` is written to the operating system, so that an
    /// acknowledgement sent afterwards never claims an event a crash could lose. Fails at once
    /// when the log cannot be written or its writer has stopped, and after
    /// [`LOG_WAIT_TIMEOUT`] without an answer (a stalled disk).
    pub async fn logged(&self, seq: u64) -> Result<(), LogUnwritable> {
        let mut rx = self.inner.logged.subscribe();
        if rx.borrow().through >= seq {
            return check_logged(&rx.borrow(), seq);
        }
        if self.inner.wrote_a_moment_ago() {
            // Under load: wait for company, so that one write serves every acknowledgement
            // of the next moment, and their answers leave together.
            tokio::time::sleep(GATHER).await;
            if rx.borrow().through >= seq {
                return check_logged(&rx.borrow(), seq);
            }
        }
        if self.inner.try_commit() && rx.borrow().through >= seq {
            return check_logged(&rx.borrow(), seq);
        }
        self.inner.ask_write();
        let waited = rx.wait_for(|l| l.through >= seq || l.failure.is_some() || l.ended);
        match tokio::time::timeout(LOG_WAIT_TIMEOUT, waited).await {
            Ok(Ok(logged)) => check_logged(&logged, seq),
            Ok(Err(_)) => Err(LogUnwritable("the corpus writer has stopped".into())),
            Err(_) => Err(LogUnwritable(
                format!(
                    "the corpus writer did not confirm within {} s",
                    LOG_WAIT_TIMEOUT.as_secs()
                )
                .into(),
            )),
        }
    }

    /// Why the corpus log cannot be written now, if it cannot: new triggers are refused then
    /// (see `docs/CORPUS.md`).
    pub fn log_failure(&self) -> Option<LogUnwritable> {
        let logged = self.inner.logged.borrow();
        if let Some(failure) = &logged.failure {
            return Some(LogUnwritable(Arc::clone(failure)));
        }
        logged
            .ended
            .then(|| LogUnwritable("the corpus writer has stopped".into()))
    }

    /// Follows the corpus writer's progress (for tests and status displays).
    pub fn logged_progress(&self) -> watch::Receiver<Logged> {
        self.inner.logged.subscribe()
    }

    /// A receiver of every event from now on, and the recent history up to now: taken
    /// together, so no history event falls between them.
    pub fn subscribe_with_history(&self) -> (broadcast::Receiver<Arc<Event>>, Vec<Arc<Event>>) {
        let _queue = lock(&self.inner.queue);
        let rx = self.inner.broadcast.subscribe();
        let history = lock(&self.inner.history).iter().cloned().collect();
        (rx, history)
    }

    /// Tells the corpus writer to write everything published so far, sync and stop.
    pub fn close_corpus(&self) {
        lock(&self.inner.queue).closed = true;
        self.inner.wake_writer();
    }

    /// Every event from now on that `interest` takes, none ever skipped: for a component that
    /// carries out a decision (a consent, a session's end), which must not miss one however
    /// busy the hub is. The channel is unbounded, so `interest` must take only kinds that
    /// come at human pace (sessions, consents, clients joining), never triggers or commands.
    pub fn follow(&self, interest: Interest) -> mpsc::UnboundedReceiver<Arc<Event>> {
        let (events, rx) = mpsc::unbounded_channel();
        lock(&self.inner.followers).push(Follower { interest, events });
        rx
    }

    /// A receiver of every event published from now on (it lags, skipping events, when it
    /// falls more than [`EVENT_CHANNEL_CAPACITY`] behind).
    pub fn subscribe(&self) -> broadcast::Receiver<Arc<Event>> {
        self.inner.broadcast.subscribe()
    }

    /// Microseconds since the hub was made.
    pub fn mono_us(&self) -> u64 {
        self.inner.started.elapsed().as_micros() as u64
    }
}

impl Inner {
    fn wake_writer(&self) {
        if let Some(writer) = self.writer.get() {
            writer.unpark();
        }
    }

    /// Writes the pending events on this thread if the log is free.
    fn try_commit(&self) -> bool {
        let committer = lock(&self.committer).clone();
        let wrote = committer.is_some_and(|c| c.try_commit());
        if wrote {
            *lock(&self.acknowledged_write) = Some(tokio::time::Instant::now());
        }
        wrote
    }

    /// Whether an acknowledgement wrote the log less than [`GATHER`] ago.
    fn wrote_a_moment_ago(&self) -> bool {
        lock(&self.acknowledged_write).is_some_and(|at| at.elapsed() < GATHER)
    }

    /// Wakes the writer for an acknowledgement, once however many wait.
    fn ask_write(&self) {
        if !self.wake_asked.swap(true, Ordering::AcqRel) {
            self.wake_writer();
        }
    }
}

impl Feed for CorpusFeed {
    /// Makes the calling thread the writer that publishes wake. Call once, from that thread.
    fn attach_current_thread(&self) {
        let _ = self.inner.writer.set(std::thread::current());
    }

    /// Sleeps for up to `tick`, or until an acknowledgement asks for a write or the hub closes.
    /// Publishing does not wake the writer (that would cost a wake-up per event on the hot
    /// path), so events nobody waits for are taken on the next tick.
    fn wait(&self, tick: Duration) {
        if !self.inner.wake_asked.load(Ordering::Acquire) {
            std::thread::park_timeout(tick);
        }
        self.inner.wake_asked.store(false, Ordering::Release);
    }

    /// Moves every pending event into `batch` (which should be empty), without waiting.
    fn take_now(&self, batch: &mut Vec<Arc<Event>>) {
        std::mem::swap(&mut lock(&self.inner.queue).pending, batch);
    }

    /// Whether the hub asked the writer to stop.
    fn closed(&self) -> bool {
        lock(&self.inner.queue).closed
    }

    /// Lets acknowledgements write the log themselves through `committer` (`None`: no more).
    fn set_committer(&self, committer: Option<Arc<dyn Committer>>) {
        *lock(&self.inner.committer) = committer;
    }

    /// After a quiet spell: sleeps until the next publish (which then wakes the writer, once),
    /// an acknowledgement or a close, so that an idle server's writer does not tick.
    fn sleep_until_published(&self) {
        loop {
            let mut queue = lock(&self.inner.queue);
            if !queue.pending.is_empty() || queue.closed {
                queue.writer_idle = false;
                return;
            }
            if self.inner.wake_asked.load(Ordering::Acquire) {
                return;
            }
            queue.writer_idle = true;
            drop(queue);
            std::thread::park();
        }
    }

    /// Reports how far the log is written.
    fn report(&self, logged: Logged) {
        self.inner.logged.send_replace(logged);
    }

    /// Publishes the writer's own news (`corpus.*`) like any event.
    fn publish(&self, kind: EventKind) {
        let inner = Arc::clone(&self.inner);
        Hub { inner }.publish(kind);
    }
}

impl Drop for CorpusFeed {
    fn drop(&mut self) {
        lock(&self.inner.queue).detached = true;
        self.inner.logged.send_modify(|l| l.ended = true);
    }
}

#[cfg(test)]
mod tests {
    use std::pin::pin;
    use std::task::Poll;

    use super::*;
    use crate::events::{EventKind, Source};

    fn publish(hub: &Hub, n: u64) {
        for _ in 0..n {
            hub.publish(EventKind::ContextChanged {
                source: Source::Http,
                context: "Text".into(),
            });
        }
    }

    /// Whether `future` is ready at its first poll.
    async fn ready_at_once(future: impl std::future::Future<Output = ()>) -> bool {
        let mut future = pin!(future);
        std::future::poll_fn(|cx| Poll::Ready(future.as_mut().poll(cx).is_ready())).await
    }

    #[tokio::test]
    async fn readers_wait_while_the_log_is_too_far_behind_and_go_on_once_it_catches_up() {
        let (hub, feed) = Hub::new();
        publish(&hub, UNLOGGED_ROOM);
        assert!(ready_at_once(hub.room_to_log()).await, "within the room");
        publish(&hub, 10);
        let mut waiting = pin!(hub.room_to_log());
        let first = std::future::poll_fn(|cx| Poll::Ready(waiting.as_mut().poll(cx))).await;
        assert!(
            first.is_pending(),
            "10 events beyond the room: readers wait"
        );
        feed.report(Logged {
            through: 10,
            ..Logged::default()
        });
        let then = std::future::poll_fn(|cx| Poll::Ready(waiting.as_mut().poll(cx))).await;
        assert!(then.is_ready(), "the log caught up: readers go on");
    }

    #[tokio::test]
    async fn a_follower_gets_every_event_it_takes_in_order_however_many_are_published() {
        let (hub, _feed) = Hub::new();
        let mut lagging = hub.subscribe();
        let mut ends = hub.follow(|kind| matches!(kind, EventKind::ServerStopping));
        for _ in 0..3 {
            publish(&hub, 2 * EVENT_CHANNEL_CAPACITY as u64);
            hub.publish(EventKind::ServerStopping);
        }
        let mut seqs = Vec::new();
        while let Ok(event) = ends.try_recv() {
            assert!(matches!(event.kind, EventKind::ServerStopping));
            seqs.push(event.seq);
        }
        let every = 2 * EVENT_CHANNEL_CAPACITY as u64 + 1;
        assert_eq!(seqs, [every, 2 * every, 3 * every]);
        assert!(
            matches!(
                lagging.try_recv(),
                Err(broadcast::error::TryRecvError::Lagged(_))
            ),
            "a broadcast subscriber skips what it missed"
        );
        drop(ends);
        publish(&hub, 1);
        hub.publish(EventKind::ServerStopping);
        assert!(
            lock(&hub.inner.followers).is_empty(),
            "a follower gone is dropped"
        );
    }
}
