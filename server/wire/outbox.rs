//! A connection's outgoing queue. Bounded: the connection's reader takes the client's next
//! frame only while the queue is at most half full ([`Outbox::half_free`]), so a client that sends
//! faster than it reads is slowed down at its socket, never cut off for its own answers. What
//! others queue for it (notices, relayed frames) does not wait: a client that stops reading is
//! dropped (its connection is "kicked") instead of slowing down everyone who sends to it. An
//! acknowledgement waits in the queue until the corpus log holds what it acknowledges
//! ([`Outbox::send_logged`]), and the frames queued after it wait behind it, so a client sees
//! its answers in order. Notices that may wait a moment linger beside the queue (`linger.rs`).

use std::sync::Arc;

use axum::extract::ws::Utf8Bytes;
use tokio::sync::mpsc;
use tokio_util::sync::CancellationToken;

use crate::wire::linger::Lingering;

/// A text frame, cheap to clone for many recipients.
pub type Frame = Utf8Bytes;

/// A frame in the queue.
#[derive(Debug)]
pub struct Queued {
    /// The frame.
    pub frame: Frame,
    /// Set for an acknowledgement: what it waits for. Boxed, since most frames have none.
    pub ack: Option<Box<Ack>>,
}

/// What an acknowledgement waits for before it may go out.
#[derive(Debug)]
pub struct Ack {
    /// The corpus log must be written through this `seq`.
    pub logged: u64,
    /// The `ref` of the request acknowledged, for the `error` frame sent instead when the log
    /// cannot be written.
    pub reference: Option<String>,
}

/// The sending side of a connection's queue. Cheap to clone.
#[derive(Clone, Debug)]
pub struct Outbox {
    tx: mpsc::Sender<Queued>,
    kick: CancellationToken,
    lingering: Arc<Lingering>,
}

impl Outbox {
    /// A queue of `capacity` frames and its receiving end.
    pub fn new(capacity: usize) -> (Outbox, mpsc::Receiver<Queued>) {
        let (tx, rx) = mpsc::channel(capacity);
        (
            Outbox {
                tx,
                kick: CancellationToken::new(),
                lingering: Arc::default(),
            },
            rx,
        )
    }

    /// Queues a text frame without waiting. False when the client is gone or too slow (it is
    /// then kicked).
    pub fn send(&self, frame: Frame) -> bool {
        self.queue(Queued { frame, ack: None })
    }

    /// Queues an acknowledgement, to be sent once the corpus log is written through `logged`
    /// (or an `error` frame with `reference` in its place if it cannot be). As [`Outbox::send`]
    /// otherwise.
    pub fn send_logged(&self, frame: Frame, logged: u64, reference: Option<String>) -> bool {
        let ack = Some(Box::new(Ack { logged, reference }));
        self.queue(Queued { frame, ack })
    }

    fn queue(&self, queued: Queued) -> bool {
        match self.tx.try_send(queued) {
            Ok(()) => true,
            Err(mpsc::error::TrySendError::Full(_)) => {
                self.kick.cancel();
                false
            }
            Err(mpsc::error::TrySendError::Closed(_)) => false,
        }
    }

    /// Whether at most half the queue is taken: the reader takes the client's next frame only
    /// then (`ws::backlog`), so the other half is room for what its requests owe it later (a
    /// command's failure) and for notices.
    pub fn half_free(&self) -> bool {
        let max = self.tx.max_capacity();
        let waiting = max - self.tx.capacity() + self.lingering.len();
        waiting <= max / 2
    }

    /// Queues a frame that may be lost (relayed from another client): dropped when the queue
    /// is three quarters full, so another client's flood cannot get this one kicked. False
    /// when dropped.
    pub fn send_if_room(&self, frame: Frame) -> bool {
        if self.tx.capacity() < self.tx.max_capacity() / 4 {
            return false;
        }
        self.send(frame)
    }

    /// The frames lingering for this client, which its writer takes with every batch.
    pub fn lingering(&self) -> &Arc<Lingering> {
        &self.lingering
    }

    /// Queues the frames that lingered long enough.
    /// Queues the frames that lingered long enough, as many as there is room for: the rest
    /// go with the writer's next batch (a full queue keeps it busy). They are the outcomes of
    /// commands, the client's own among them, so they never get it kicked while the writer can
    /// take them; only more than [`Lingering::MOST`] times the queue does.
    pub(crate) fn flush_lingering(&self) {
        if self.lingering.flush_into(&self.tx) {
            self.kick();
        }
    }

    /// Counts the client as too slow: its connection is closed.
    pub(crate) fn kick(&self) {
        self.kick.cancel();
    }

    /// How many frames the queue holds at most.
    pub(crate) fn max_capacity(&self) -> usize {
        self.tx.max_capacity()
    }

    /// Whether the client is gone (its writer ended).
    pub fn is_closed(&self) -> bool {
        self.tx.is_closed()
    }

    /// Cancelled when the client was too slow.
    pub fn kicked(&self) -> &CancellationToken {
        &self.kick
    }
}
