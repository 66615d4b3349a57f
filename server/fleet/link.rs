//! The task that keeps one broker connection going: it polls rumqttc's event loop (which
//! reconnects by itself at the next poll), waits a growing moment after each failed attempt,
//! records the link's state, and tells its owner what matters ([`LinkNote`]): the link is up
//! (subscribe again and re-publish retained state: the broker forgot a clean session), it is
//! down and why, a message arrived. The owner publishes through the `AsyncClient`; keeping the
//! polling in its own task means a publish waiting for room never stops the link.
//!
//! A message over [`MAX_MESSAGE_BYTES`] is dropped, with one warning (then at most one a
//! minute, saying how many more were dropped), and the link stays up. rumqttc cannot skip a
//! packet it refuses to read: the connection would fail, and a retained message would come
//! again at every reconnection, for ever. So the packet limit rumqttc reads with is MQTT's
//! own maximum ([`MAX_PACKET_BYTES`]) and the message limit is kept here; a site bounds the
//! memory a message may take with its broker's `message_size_limit` (docs/FLEET.md).

use std::pin::pin;
use std::sync::Arc;
use std::time::Duration;

use tokio::time::Instant;

use rumqttc::{ConnectionError, Event, EventLoop, Incoming, Outgoing};
use tokio::sync::mpsc;
use tokio_util::sync::CancellationToken;

use super::broker::{LinkState, LinkStatus, MAX_RETRY};

/// What the link tells its owner.
#[derive(Debug)]
pub enum LinkNote {
    /// The broker accepted the connection (again).
    Up,
    /// The connection was lost or refused; rumqttc tries again.
    Down(String),
    /// A message on a subscribed topic.
    Message {
        /// Its topic.
        topic: String,
        /// Its payload.
        payload: Vec<u8>,
    },
}

/// The largest message taken from the broker; a larger one is dropped with a warning. The
/// largest Docent publishes (a state, an event, a reply) is far smaller.
pub const MAX_MESSAGE_BYTES: usize = 256 * 1024;
/// The largest packet read from the broker: MQTT's own maximum (its remaining length is at
/// most 268,435,455 bytes), so that no message breaks the connection.
pub const MAX_PACKET_BYTES: usize = 268_435_455;
/// After a warning about a dropped message, the next comes no sooner than this.
const WARN_AGAIN_AFTER: Duration = Duration::from_secs(60);

/// The first wait after a failed attempt; doubled up to [`MAX_RETRY`].
const FIRST_RETRY: Duration = Duration::from_millis(100);

/// Polls `events` until the owner's disconnect has gone out, or `stop` (after which the
/// owner has `grace` to say goodbye). Notes go to `notes`; a full queue drops messages, with a
/// warning, never the link.
pub async fn run_link(
    mut events: EventLoop,
    link: Arc<LinkStatus>,
    notes: mpsc::Sender<LinkNote>,
    stop: CancellationToken,
    grace: Duration,
) {
    let mut retry = FIRST_RETRY;
    let mut deadline = None;
    let mut stopping = pin!(stop.cancelled());
    let mut oversized = Oversized::default();
    loop {
        // A poll is never dropped half-way for the stop (it may be writing a packet, and a
        // packet cut short breaks the connection before the owner's goodbye): the same poll is
        // awaited on after the stop, until the goodbye's deadline.
        let mut poll = pin!(events.poll());
        let polled = loop {
            tokio::select! {
                polled = &mut poll => break polled,
                () = &mut stopping, if deadline.is_none() => {
                    // Keep polling a little so the owner's last publishes and disconnect go out.
                    deadline = Some(tokio::time::Instant::now() + grace);
                }
                () = sleep_until(deadline) => return,
            }
        };
        match polled {
            Ok(Event::Incoming(Incoming::ConnAck(_))) => {
                retry = FIRST_RETRY;
                link.set(LinkState::Up, None);
                let _ = notes.send(LinkNote::Up).await;
            }
            Ok(Event::Incoming(Incoming::Publish(message)))
                if message.payload.len() > MAX_MESSAGE_BYTES =>
            {
                let size = message.payload.len();
                if let Some(unwarned) = oversized.warn(Instant::now()) {
                    tracing::warn!(
                        topic = message.topic,
                        size,
                        more_dropped = unwarned,
                        "an MQTT message over {MAX_MESSAGE_BYTES} bytes was dropped"
                    );
                }
            }
            Ok(Event::Incoming(Incoming::Publish(message))) => {
                let note = LinkNote::Message {
                    topic: message.topic,
                    payload: message.payload.to_vec(),
                };
                if notes.try_send(note).is_err() {
                    tracing::warn!("an MQTT message was dropped: its handler is behind");
                }
            }
            // Not gone yet: closing a socket that holds unread data (the broker's last acks)
            // resets it, and the broker may drop the goodbye it has not read. The broker closes
            // the connection after the disconnect; that error ends the task below.
            Ok(Event::Outgoing(Outgoing::Disconnect)) => {
                deadline.get_or_insert_with(|| tokio::time::Instant::now() + grace);
            }
            Ok(_) => {}
            Err(error) => {
                if deadline.is_some() {
                    return;
                }
                let reason = describe(&error);
                if link.set(LinkState::Down, Some(reason.clone())) {
                    tracing::warn!(reason, "the MQTT broker link is down; reconnecting");
                    let _ = notes.send(LinkNote::Down(reason)).await;
                }
                tokio::select! {
                    () = tokio::time::sleep(retry) => {}
                    () = stop.cancelled() => return,
                }
                retry = (retry * 2).min(MAX_RETRY);
            }
        }
    }
}

/// The warnings about messages dropped for their size: the first at once, then at most one
/// in [`WARN_AGAIN_AFTER`], with the number dropped meanwhile.
#[derive(Debug, Default)]
struct Oversized {
    warned: Option<Instant>,
    unwarned: u64,
}

impl Oversized {
    /// One more dropped at `now`: `Some(n)` to warn now, `n` the ones dropped unwarned since
    /// the last warning; `None` to count it silently.
    fn warn(&mut self, now: Instant) -> Option<u64> {
        if self.warned.is_some_and(|at| now < at + WARN_AGAIN_AFTER) {
            self.unwarned += 1;
            return None;
        }
        self.warned = Some(now);
        Some(std::mem::take(&mut self.unwarned))
    }
}

async fn sleep_until(deadline: Option<tokio::time::Instant>) {
    match deadline {
        Some(at) => tokio::time::sleep_until(at).await,
        None => std::future::pending().await,
    }
}

/// A connection error in words an operator can act on (never the login).
fn describe(error: &ConnectionError) -> String {
    match error {
        ConnectionError::ConnectionRefused(code) => format!(
            "the broker refused the connection ({code:?}): check the user name and password \
             (docent.yaml mqtt:, DOCENT_MQTT_PASSWORD) and the broker's access rules"
        ),
        ConnectionError::Io(io) => format!("cannot reach the broker: {io}"),
        ConnectionError::NetworkTimeout => "the broker did not answer in time".into(),
        other => format!("the broker link failed: {other}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_of_oversized_messages_is_warned_about_once_a_minute_with_the_count() {
        let start = Instant::now();
        let mut oversized = Oversized::default();
        assert_eq!(oversized.warn(start), Some(0));
        for n in 1..=296 {
            assert_eq!(oversized.warn(start + Duration::from_millis(n)), None);
        }
        assert_eq!(oversized.warn(start + WARN_AGAIN_AFTER), Some(296));
        assert_eq!(oversized.warn(start + WARN_AGAIN_AFTER), None);
    }
}
