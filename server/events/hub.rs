//! The event hub: stamps events and fans them out. The corpus gets every event through an
//! unbounded channel (the log must not lose anything); websocket subscribers get them through a
//! bounded broadcast channel and handle lag themselves.

use std::collections::VecDeque;
use std::sync::{Arc, Mutex};
use std::time::{Instant, SystemTime};

use tokio::sync::{broadcast, mpsc};

use crate::events::{Event, EventKind};
use crate::sync::lock;

/// How many history events (acts triggered, proposals, marks) a console joining later gets.
pub const HISTORY_LEN: usize = 200;

/// How many events a slow websocket subscriber may fall behind before it lags.
pub const EVENT_CHANNEL_CAPACITY: usize = 4096;

/// What the hub sends the corpus writer.
#[derive(Debug)]
pub enum CorpusMsg {
    /// Log this event.
    Event(Arc<Event>),
    /// Flush, sync and stop.
    Close,
}

/// The one place events are published. Cheap to clone.
#[derive(Clone)]
pub struct Hub {
    inner: Arc<Inner>,
}

struct Inner {
    started: Instant,
    /// Holds the sequence counter; publishing under it keeps the corpus in sequence order.
    seq: Mutex<u64>,
    corpus: mpsc::UnboundedSender<CorpusMsg>,
    broadcast: broadcast::Sender<Arc<Event>>,
    /// The latest history events (see [`EventKind::is_history`]), oldest first.
    history: Mutex<VecDeque<Arc<Event>>>,
}

impl Hub {
    /// A hub and the receiving end for the corpus writer.
    pub fn new() -> (Hub, mpsc::UnboundedReceiver<CorpusMsg>) {
        let (corpus, corpus_rx) = mpsc::unbounded_channel();
        let (broadcast, _) = broadcast::channel(EVENT_CHANNEL_CAPACITY);
        let inner = Inner {
            started: Instant::now(),
            seq: Mutex::new(0),
            corpus,
            broadcast,
            history: Mutex::new(VecDeque::with_capacity(HISTORY_LEN)),
        };
        (
            Hub {
                inner: Arc::new(inner),
            },
            corpus_rx,
        )
    }

    /// Stamps and publishes an event; returns it.
    pub fn publish(&self, kind: EventKind) -> Arc<Event> {
        let mut seq = lock(&self.inner.seq);
        // Stamped under the lock so that sequence and monotonic time agree.
        let mono_us = self.inner.started.elapsed().as_micros() as u64;
        let time = SystemTime::now();
        *seq += 1;
        let event = Arc::new(Event::new(*seq, time, mono_us, kind));
        // A closed corpus channel means the writer has shut down; nothing is left to log to.
        let _ = self.inner.corpus.send(CorpusMsg::Event(Arc::clone(&event)));
        // No subscribers is fine.
        let _ = self.inner.broadcast.send(Arc::clone(&event));
        if event.kind.is_history() {
            let mut history = lock(&self.inner.history);
            if history.len() == HISTORY_LEN {
                history.pop_front();
            }
            history.push_back(Arc::clone(&event));
        }
        drop(seq);
        event
    }

    /// A receiver of every event from now on, and the recent history up to now: taken
    /// together, so no history event falls between them.
    pub fn subscribe_with_history(&self) -> (broadcast::Receiver<Arc<Event>>, Vec<Arc<Event>>) {
        let _seq = lock(&self.inner.seq);
        let rx = self.inner.broadcast.subscribe();
        let history = lock(&self.inner.history).iter().cloned().collect();
        (rx, history)
    }

    /// Tells the corpus writer to flush and stop after every event published so far.
    pub fn close_corpus(&self) {
        let _guard = lock(&self.inner.seq);
        let _ = self.inner.corpus.send(CorpusMsg::Close);
    }

    /// A receiver of every event published from now on.
    pub fn subscribe(&self) -> broadcast::Receiver<Arc<Event>> {
        self.inner.broadcast.subscribe()
    }

    /// Microseconds since the hub was made.
    pub fn mono_us(&self) -> u64 {
        self.inner.started.elapsed().as_micros() as u64
    }
}
