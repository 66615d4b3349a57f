//! What a connection's writer has yet to send, which its reader waits on: a client's requests
//! make answers and events that go back to it, so when it reads them slower than it sends,
//! taking its next frame later is what slows it down (the websocket's own back-pressure),
//! instead of its queue overflowing or its falling behind the event stream and being closed.
//! The reader takes a frame only while the connection's queue is at most half full and the
//! writer at most [`HIGH_WATER`] events behind; the writer reports after every batch it sent.
//! Adapters are not paced: their reports make no answers, and their queue is filled by the
//! commands others trigger.

use std::sync::atomic::{AtomicUsize, Ordering};

use tokio::sync::Notify;

use crate::events::EVENT_CHANNEL_CAPACITY;
use crate::wire::outbox::Outbox;

/// Events a writer may be behind before its reader stops taking frames: half of what it may
/// be behind before it lags, so a client's own events never make it lag.
pub const HIGH_WATER: usize = EVENT_CHANNEL_CAPACITY / 2;

/// A writer's progress, shared with its reader.
#[derive(Debug, Default)]
pub struct Backlog {
    /// Events the writer has yet to send.
    behind: AtomicUsize,
    sent: Notify,
}

impl Backlog {
    /// The writer sent a batch and has `behind` events yet to send.
    pub fn sent(&self, behind: usize) {
        self.behind.store(behind, Ordering::Release);
        self.sent.notify_waiters();
    }

    /// Waits until the client's `outbox` is at most half full and its writer at most
    /// [`HIGH_WATER`] events behind (or the client is gone).
    pub async fn room(&self, outbox: &Outbox) {
        loop {
            // Made before the check: `notify_waiters` wakes it from then on.
            let sent = self.sent.notified();
            if self.has_room(outbox) || outbox.is_closed() {
                return;
            }
            sent.await;
        }
    }

    fn has_room(&self, outbox: &Outbox) -> bool {
        self.behind.load(Ordering::Acquire) <= HIGH_WATER && outbox.half_free()
    }
}

#[cfg(test)]
mod tests {
    use std::future::Future;
    use std::pin::pin;
    use std::task::Poll;

    use super::*;
    use crate::wire::outbox::Frame;

    #[tokio::test]
    async fn the_reader_waits_while_its_answers_or_events_are_far_behind() {
        let backlog = Backlog::default();
        let (outbox, mut queue) = Outbox::new(8);
        backlog.sent(HIGH_WATER);
        backlog.room(&outbox).await;
        for _ in 0..5 {
            outbox.send(Frame::from("answer"));
        }
        {
            let mut waiting = pin!(backlog.room(&outbox));
            let mut ready = async || {
                std::future::poll_fn(|cx| Poll::Ready(waiting.as_mut().poll(cx).is_ready())).await
            };
            assert!(!ready().await, "5 of 8 answers unsent: the reader waits");
            queue.recv().await;
            assert!(!ready().await, "taken but not sent yet");
            backlog.sent(0);
            assert!(ready().await, "half the queue free: the reader goes on");
        }
        backlog.sent(HIGH_WATER + 1);
        let mut waiting = pin!(backlog.room(&outbox));
        let mut ready = async || {
            std::future::poll_fn(|cx| Poll::Ready(waiting.as_mut().poll(cx).is_ready())).await
        };
        assert!(!ready().await, "far behind the events: the reader waits");
        backlog.sent(HIGH_WATER);
        assert!(ready().await, "caught up: the reader goes on");
    }
}
