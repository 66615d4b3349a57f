//! A connection's writer task: sends queued frames and, once the client has said hello, the
//! frames of its subscription (display commands or events), pinging an idle client.

use std::sync::Arc;
use std::time::Duration;

use axum::extract::ws::{Message, WebSocket};
use futures_util::SinkExt;
use futures_util::stream::SplitSink;
use tokio::sync::broadcast::error::RecvError;
use tokio::sync::{broadcast, mpsc, oneshot};
use tokio_util::sync::CancellationToken;

use crate::events::{ClientRole, Event};
use crate::state::AppState;
use crate::ws::outbox::Frame;
use crate::ws::protocol::{event_frame, state_frame};

/// A client that cannot take a frame within this time is dropped.
const WRITE_TIMEOUT: Duration = Duration::from_secs(10);
/// How long a closing handshake may take.
const CLOSE_TIMEOUT: Duration = Duration::from_secs(1);
/// How often an otherwise quiet connection is pinged.
pub const PING_INTERVAL: Duration = Duration::from_secs(20);

/// What a client receives besides direct answers.
pub enum Feed {
    /// Display command frames (kiosk, projector).
    Display(ClientRole, broadcast::Receiver<Frame>),
    /// Every event (operator, dialog manager).
    Events(broadcast::Receiver<Arc<Event>>),
}

/// Why the writer ended.
pub type WriterEnd = &'static str;

/// Writes until the queue closes, the client fails or falls behind, or `stop` is cancelled;
/// cancels `stop` itself when it ends first.
pub async fn run_writer(
    mut sink: SplitSink<WebSocket, Message>,
    mut queue: mpsc::Receiver<Frame>,
    feed: oneshot::Receiver<Feed>,
    state: AppState,
    stop: CancellationToken,
) -> WriterEnd {
    let mut feed = Some(feed);
    let mut subscription: Option<Feed> = None;
    let mut ping = tokio::time::interval(PING_INTERVAL);
    ping.tick().await;
    let end = 'writing: loop {
        // Biased: direct answers (and `welcome` before anything fed) go out first.
        let frame = tokio::select! {
            biased;
            frame = queue.recv() => match frame { Some(f) => f, None => break "closed" },
            f = async {
                match feed.as_mut() {
                    Some(f) => f.await,
                    None => std::future::pending().await,
                }
            }, if feed.is_some() => {
                feed = None;
                subscription = f.ok();
                continue;
            }
            next = next_fed(&mut subscription, &state), if subscription.is_some() => match next {
                Ok(frame) => frame,
                Err(end) => break end,
            },
            _ = ping.tick() => {
                if write(&stop, sink.send(Message::Ping(Default::default()))).await.is_err() { break "write failed" }
                continue;
            }
            () = stop.cancelled() => break "closed",
        };
        if write(&stop, sink.feed(Message::Text(frame))).await.is_err() {
            break "write failed or timed out";
        }
        // Send whatever else is ready in one flush.
        while let Ok(frame) = queue.try_recv() {
            if write(&stop, sink.feed(Message::Text(frame))).await.is_err() {
                break 'writing "write failed or timed out";
            }
        }
        if write(&stop, sink.flush()).await.is_err() {
            break "write failed or timed out";
        }
    };
    // Tell the reader loop, which may be waiting on a silent client.
    stop.cancel();
    let _ = tokio::time::timeout(CLOSE_TIMEOUT, sink.close()).await;
    end
}

async fn next_fed(subscription: &mut Option<Feed>, state: &AppState) -> Result<Frame, WriterEnd> {
    match subscription {
        Some(Feed::Display(role, rx)) => match rx.recv().await {
            Ok(frame) => Ok(frame),
            // Fell behind: start over from a fresh snapshot and subscription (taken together,
            // so nothing is missed or replayed), instead of replaying stale pages.
            Err(RecvError::Lagged(_)) => {
                let (display, fresh) = state.devices.display.subscribe(*role);
                if let Some(fresh) = fresh {
                    *rx = fresh;
                }
                let mut view = state.state_view();
                view.display = display;
                Ok(Frame::from(state_frame(&view)))
            }
            Err(RecvError::Closed) => Err("server closing"),
        },
        Some(Feed::Events(rx)) => match rx.recv().await {
            Ok(event) => Ok(Frame::from(event_frame(&event))),
            // An event stream with holes would mislead an operator: drop them; they reconnect.
            Err(RecvError::Lagged(_)) => Err("too slow: fell behind the event stream"),
            Err(RecvError::Closed) => Err("server closing"),
        },
        None => std::future::pending().await,
    }
}

/// Runs one write with the write timeout, giving up at once when the connection is stopping.
async fn write<F>(stop: &CancellationToken, write: F) -> Result<(), ()>
where
    F: std::future::Future<Output = Result<(), axum::Error>>,
{
    tokio::select! {
        result = tokio::time::timeout(WRITE_TIMEOUT, write) => match result {
            Ok(Ok(())) => Ok(()),
            _ => Err(()),
        },
        () = stop.cancelled() => Err(()),
    }
}
