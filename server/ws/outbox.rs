//! A connection's outgoing queue. Bounded: a client that stops reading is dropped (its
//! connection is "kicked") instead of slowing down everyone who sends to it.

use axum::extract::ws::Utf8Bytes;
use tokio::sync::mpsc;
use tokio_util::sync::CancellationToken;

/// A text frame, cheap to clone for many recipients.
pub type Frame = Utf8Bytes;

/// How many frames may wait for one client before it counts as too slow.
pub const OUTBOX_CAPACITY: usize = 1024;

/// The sending side of a connection's queue. Cheap to clone.
#[derive(Clone, Debug)]
pub struct Outbox {
    tx: mpsc::Sender<Frame>,
    kick: CancellationToken,
}

impl Outbox {
    /// A queue of `capacity` frames and its receiving end.
    pub fn new(capacity: usize) -> (Outbox, mpsc::Receiver<Frame>) {
        let (tx, rx) = mpsc::channel(capacity);
        (
            Outbox {
                tx,
                kick: CancellationToken::new(),
            },
            rx,
        )
    }

    /// Queues a text frame without waiting. False when the client is gone or too slow (it is
    /// then kicked).
    pub fn send(&self, frame: Frame) -> bool {
        match self.tx.try_send(frame) {
            Ok(()) => true,
            Err(mpsc::error::TrySendError::Full(_)) => {
                self.kick.cancel();
                false
            }
            Err(mpsc::error::TrySendError::Closed(_)) => false,
        }
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

    /// Cancelled when the client was too slow.
    pub fn kicked(&self) -> &CancellationToken {
        &self.kick
    }
}
