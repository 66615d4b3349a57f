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

use crate::events::Event;
use crate::state::AppState;
use crate::ws::outbox::Frame;
use crate::ws::protocol::{event_frame, state_frame};

/// A client that cannot take a frame within this time is dropped.
const WRITE_TIMEOUT: Duration = Duration::from_secs(10);
/// How often an otherwise quiet connection is pinged.
pub const PING_INTERVAL: Duration = Duration::from_secs(20);

/// What a client receives besides direct answers.
pub enum Feed {
    /// Display command frames (kiosk, projector).
    Display(broadcast::Receiver<Frame>),
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
                if send(&mut sink, Message::Ping(Default::default())).await.is_err() { break "write failed" }
                continue;
            }
            () = stop.cancelled() => break "closed",
        };
        if feed_only(&mut sink, Message::Text(frame)).await.is_err() {
            break "write failed or timed out";
        }
        // Send whatever else is ready in one flush.
        while let Ok(frame) = queue.try_recv() {
            if feed_only(&mut sink, Message::Text(frame)).await.is_err() {
                break 'writing "write failed or timed out";
            }
        }
        if flush(&mut sink).await.is_err() {
            break "write failed or timed out";
        }
    };
    // Tell the reader loop, which may be waiting on a silent client.
    stop.cancel();
    let _ = tokio::time::timeout(WRITE_TIMEOUT, sink.close()).await;
    end
}

async fn next_fed(subscription: &mut Option<Feed>, state: &AppState) -> Result<Frame, WriterEnd> {
    match subscription {
        Some(Feed::Display(rx)) => match rx.recv().await {
            Ok(frame) => Ok(frame),
            // Fell behind: a fresh snapshot says where things are now.
            Err(RecvError::Lagged(_)) => Ok(Frame::from(state_frame(&state.state_view()))),
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

async fn send(sink: &mut SplitSink<WebSocket, Message>, msg: Message) -> Result<(), ()> {
    match tokio::time::timeout(WRITE_TIMEOUT, sink.send(msg)).await {
        Ok(Ok(())) => Ok(()),
        _ => Err(()),
    }
}

async fn feed_only(sink: &mut SplitSink<WebSocket, Message>, msg: Message) -> Result<(), ()> {
    match tokio::time::timeout(WRITE_TIMEOUT, sink.feed(msg)).await {
        Ok(Ok(())) => Ok(()),
        _ => Err(()),
    }
}

async fn flush(sink: &mut SplitSink<WebSocket, Message>) -> Result<(), ()> {
    match tokio::time::timeout(WRITE_TIMEOUT, sink.flush()).await {
        Ok(Ok(())) => Ok(()),
        _ => Err(()),
    }
}
