//! Frames that may wait a moment: a notice that is not an answer (an `outcome` frame: a
//! command will not be carried out) lingers beside its client's queue instead of waking the
//! client's writer on its own. It goes out with the next frame that client gets anyway, or
//! within [`LINGER`] when none comes (as many as its queue has room for; the writer takes the
//! rest with its next batch).
//!
//! Why: a trigger that replaces another's page tells that other sender so. Under load that is
//! one notice per trigger, to a different client than the one answered, and written alone
//! each would cost a writer wake-up and a system call (and wake the client) per trigger;
//! riding along costs neither. 2 ms is far below what a visitor or an operator notices.

use std::mem;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use tokio::sync::{Notify, mpsc};

use crate::lifecycle::Lifecycle;
use crate::sync::lock;
use crate::wire::outbox::{Frame, Outbox, Queued};

/// The longest a lingering frame waits for company.
pub const LINGER: Duration = Duration::from_millis(2);

/// One client's lingering frames, shared by its outbox (which adds) and its writer (which
/// takes them with every batch it writes).
#[derive(Debug, Default)]
pub struct Lingering(Mutex<Vec<Frame>>);

impl Lingering {
    /// How many times its queue's capacity a client may have lingering before it counts as
    /// too slow: its writer takes them all with every batch, so only a client that does not
    /// read lets them pile up.
    pub const MOST: usize = 4;

    /// Takes every lingering frame, oldest first.
    pub fn take(&self) -> Vec<Frame> {
        mem::take(&mut *lock(&self.0))
    }

    /// How many frames linger.
    pub fn len(&self) -> usize {
        lock(&self.0).len()
    }

    /// Whether none lingers.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Moves the oldest frames into `queue` while it has room; true when more than
    /// [`Lingering::MOST`] times its capacity are left (the client is too slow).
    pub(crate) fn flush_into(&self, queue: &mpsc::Sender<Queued>) -> bool {
        let mut frames = lock(&self.0);
        let mut sent = 0;
        for frame in frames.iter() {
            let queued = Queued {
                frame: frame.clone(),
                ack: None,
            };
            match queue.try_send(queued) {
                Ok(()) => sent += 1,
                Err(mpsc::error::TrySendError::Full(_)) => break,
                Err(mpsc::error::TrySendError::Closed(_)) => {
                    frames.clear();
                    return false;
                }
            }
        }
        frames.drain(..sent);
        frames.len() > Self::MOST * queue.max_capacity()
    }
}

/// The server's one flusher: sends the frames that found no company within [`LINGER`].
pub struct Linger {
    /// Outboxes that got a lingering frame since the last flush.
    due: Mutex<Vec<Outbox>>,
    wake: Notify,
}

impl Linger {
    /// Starts the flusher; it ends with the server.
    pub fn start(life: &Lifecycle) -> Arc<Linger> {
        let linger = Arc::new(Linger {
            due: Mutex::default(),
            wake: Notify::new(),
        });
        let flusher = Arc::clone(&linger);
        let shutdown = life.shutdown.clone();
        life.spawn(async move {
            loop {
                tokio::select! {
                    () = flusher.wake.notified() => {}
                    () = shutdown.cancelled() => return,
                }
                tokio::time::sleep(LINGER).await;
                let due = mem::take(&mut *lock(&flusher.due));
                for outbox in due {
                    outbox.flush_lingering();
                }
            }
        });
        linger
    }

    /// Queues `frame` for `outbox` to linger. False when the client is gone or too slow (more
    /// than [`Lingering::MOST`] times its queue linger: it is kicked).
    pub fn send(&self, outbox: &Outbox, frame: Frame) -> bool {
        if outbox.is_closed() {
            return false;
        }
        let mut frames = lock(&outbox.lingering().0);
        if frames.len() >= Lingering::MOST * outbox.max_capacity() {
            // It reads nothing while they pile up (the writer takes them with every batch).
            drop(frames);
            outbox.kick();
            return false;
        }
        frames.push(frame);
        // The first frame makes the outbox due; later ones find it due already (or being
        // flushed: the flusher takes the frames after it took the list).
        if frames.len() == 1 {
            let mut due = lock(&self.due);
            due.push(outbox.clone());
            if due.len() == 1 {
                self.wake.notify_one();
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[tokio::test(start_paused = true)]
    async fn a_lingering_frame_goes_out_alone_after_the_linger() {
        let life = Lifecycle::new();
        let linger = Linger::start(&life);
        let (outbox, mut queue) = Outbox::new(8);
        assert!(linger.send(&outbox, Frame::from("a")));
        assert!(linger.send(&outbox, Frame::from("b")));
        let started = tokio::time::Instant::now();
        let first = queue.recv().await.expect("flushed");
        let second = queue.recv().await.expect("flushed");
        assert_eq!((first.frame.as_str(), second.frame.as_str()), ("a", "b"));
        assert_eq!(started.elapsed(), LINGER);
        assert!(outbox.lingering().take().is_empty());
    }

    #[tokio::test(start_paused = true)]
    async fn frames_beyond_the_queues_room_keep_lingering_in_order_and_only_a_pile_kicks() {
        let life = Lifecycle::new();
        let linger = Linger::start(&life);
        let (outbox, mut queue) = Outbox::new(2);
        for name in ["a", "b", "c"] {
            linger.send(&outbox, Frame::from(name));
        }
        let first = queue.recv().await.expect("flushed");
        assert_eq!(first.frame.as_str(), "a");
        assert_eq!(queue.recv().await.expect("flushed").frame.as_str(), "b");
        let left: Vec<_> = outbox.lingering().take();
        assert_eq!(left, [Frame::from("c")], "left for the writer's next batch");
        assert!(!outbox.kicked().is_cancelled());
        // A client that reads nothing while far more than its queue piles up is too slow.
        for _ in 0..2 + Lingering::MOST * 2 + 1 {
            linger.send(&outbox, Frame::from("x"));
        }
        outbox.kicked().cancelled().await;
    }

    #[tokio::test(start_paused = true)]
    async fn a_frame_taken_with_a_batch_is_not_sent_twice() {
        let life = Lifecycle::new();
        let linger = Linger::start(&life);
        let (outbox, mut queue) = Outbox::new(8);
        linger.send(&outbox, Frame::from("a"));
        let taken = outbox.lingering().take();
        assert_eq!(taken.len(), 1);
        tokio::time::sleep(LINGER * 2).await;
        assert!(queue.try_recv().is_err(), "the writer had it already");
        // The next one makes the outbox due again.
        linger.send(&outbox, Frame::from("b"));
        let flushed = queue.recv().await.expect("flushed");
        assert_eq!(flushed.frame.as_str(), "b");
    }
}
