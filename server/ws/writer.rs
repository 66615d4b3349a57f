//! A connection's writer task: sends queued frames and, once the client has said hello, the
//! frames of its subscription (display commands or events), pinging an idle client.

use std::sync::Arc;
use std::time::Duration;

use axum::extract::ws::{CloseFrame, Message, WebSocket};
use futures_util::SinkExt;
use futures_util::stream::SplitSink;
use tokio::sync::broadcast::error::{RecvError, TryRecvError};
use tokio::sync::{broadcast, mpsc, oneshot};
use tokio_util::sync::CancellationToken;

use crate::events::{ClientRole, Event, Hub, LogUnwritable};
use crate::state::AppState;
use crate::wire::linger::Lingering;
use crate::wire::outbox::{Frame, Queued};
use crate::ws::protocol::{error_frame, event_frame, state_frame};

/// A client that cannot take a frame within this time is dropped.
const WRITE_TIMEOUT: Duration = Duration::from_secs(10);
/// Most frames written before one flush.
const MAX_BATCH: usize = 64;
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

/// The close frame the writer ends with, when the reader found a protocol violation; a plain
/// close otherwise.
pub type CloseWith = Arc<std::sync::Mutex<Option<CloseFrame>>>;

/// Writes until the queue closes, the client fails or falls behind, or `stop` is cancelled;
/// cancels `stop` itself when it ends first.
pub async fn run_writer(
    mut sink: SplitSink<WebSocket, Message>,
    mut queue: mpsc::Receiver<Queued>,
    lingering: Arc<Lingering>,
    feed: oneshot::Receiver<Feed>,
    state: AppState,
    stop: CancellationToken,
    close_with: CloseWith,
) -> WriterEnd {
    let mut feed = Some(feed);
    let mut subscription: Option<Feed> = None;
    let mut ping = tokio::time::interval(PING_INTERVAL);
    ping.tick().await;
    let end = 'writing: loop {
        // Biased: direct answers (and `welcome` before anything fed) go out first.
        let frame = tokio::select! {
            biased;
            queued = queue.recv() => match queued {
                Some(queued) => match release(queued, &state.hub, &stop).await {
                    Some(frame) => frame,
                    None => break "closed",
                },
                None => break "closed",
            },
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
        // Send whatever else is ready, answers and fed frames alike, in one flush: one
        // system call per batch instead of one per frame.
        let mut batch = 0;
        while batch < MAX_BATCH {
            let frame = match queue.try_recv() {
                Ok(queued) => match release(queued, &state.hub, &stop).await {
                    Some(frame) => frame,
                    None => break 'writing "closed",
                },
                Err(_) => match try_next_fed(&mut subscription, &state) {
                    Some(Ok(frame)) => frame,
                    Some(Err(end)) => break 'writing end,
                    None => break,
                },
            };
            if write(&stop, sink.feed(Message::Text(frame))).await.is_err() {
                break 'writing "write failed or timed out";
            }
            batch += 1;
        }
        // Notices waiting for company ride along.
        for frame in lingering.take() {
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
    let close = crate::sync::lock(&close_with).take();
    let closing = async {
        if let Some(frame) = close {
            sink.send(Message::Close(Some(frame))).await?;
        }
        sink.close().await
    };
    let _ = tokio::time::timeout(CLOSE_TIMEOUT, closing).await;
    end
}

/// The frame to send for `queued`: an acknowledgement once the corpus log holds what it
/// acknowledges, or an `error` frame saying it could not be logged. `None` when the connection
/// stops meanwhile.
pub(super) async fn release(queued: Queued, hub: &Hub, stop: &CancellationToken) -> Option<Frame> {
    let Some(ack) = queued.ack else {
        return Some(queued.frame);
    };
    if !hub.is_logged(ack.logged) {
        // Let the frames this request woke (commands to kiosks and adapters) go out first:
        // the acknowledgement may have to write the log itself.
        tokio::task::yield_now().await;
    }
    let logged = tokio::select! {
        logged = hub.logged(ack.logged) => logged,
        () = stop.cancelled() => return None,
    };
    Some(match logged {
        Ok(()) => queued.frame,
        Err(unwritable) => Frame::from(error_frame(
            LogUnwritable::CODE,
            &unwritable.after_the_fact(),
            ack.reference.as_deref(),
            None,
        )),
    })
}

/// What a subscription's receiver gave.
enum Got<T> {
    Item(T),
    Lagged,
    Closed,
}

impl<T> From<Result<T, RecvError>> for Got<T> {
    fn from(r: Result<T, RecvError>) -> Self {
        match r {
            Ok(item) => Got::Item(item),
            Err(RecvError::Lagged(_)) => Got::Lagged,
            Err(RecvError::Closed) => Got::Closed,
        }
    }
}

/// The next frame of the subscription, waiting for it.
async fn next_fed(subscription: &mut Option<Feed>, state: &AppState) -> Result<Frame, WriterEnd> {
    match subscription {
        Some(Feed::Display(role, rx)) => {
            let got = rx.recv().await.into();
            display_frame(*role, rx, state, got)
        }
        Some(Feed::Events(rx)) => event_frame_of(rx.recv().await.into()),
        None => std::future::pending().await,
    }
}

/// The next frame of the subscription if one is ready.
fn try_next_fed(
    subscription: &mut Option<Feed>,
    state: &AppState,
) -> Option<Result<Frame, WriterEnd>> {
    fn got<T>(r: Result<T, TryRecvError>) -> Option<Got<T>> {
        match r {
            Ok(item) => Some(Got::Item(item)),
            Err(TryRecvError::Empty) => None,
            Err(TryRecvError::Lagged(_)) => Some(Got::Lagged),
            Err(TryRecvError::Closed) => Some(Got::Closed),
        }
    }
    match subscription {
        Some(Feed::Display(role, rx)) => {
            let next = got(rx.try_recv())?;
            Some(display_frame(*role, rx, state, next))
        }
        Some(Feed::Events(rx)) => Some(event_frame_of(got(rx.try_recv())?)),
        None => None,
    }
}

fn display_frame(
    role: ClientRole,
    rx: &mut broadcast::Receiver<Frame>,
    state: &AppState,
    got: Got<Frame>,
) -> Result<Frame, WriterEnd> {
    match got {
        Got::Item(frame) => Ok(frame),
        // Fell behind: start over from a fresh snapshot and subscription (taken together, so
        // nothing is missed or replayed), instead of replaying stale pages.
        Got::Lagged => {
            let (display, fresh) = state.devices.display.subscribe(role);
            if let Some(fresh) = fresh {
                *rx = fresh;
            }
            let mut view = state.state_view();
            view.display = display;
            Ok(Frame::from(state_frame(&view)))
        }
        Got::Closed => Err("server closing"),
    }
}

fn event_frame_of(got: Got<Arc<Event>>) -> Result<Frame, WriterEnd> {
    match got {
        Got::Item(event) => Ok(Frame::from(event_frame(&event))),
        // An event stream with holes would mislead an operator: drop them; they reconnect.
        Got::Lagged => Err("too slow: fell behind the event stream"),
        Got::Closed => Err("server closing"),
    }
}

/// Runs one write with the write timeout, giving up at once when the connection is stopping.
async fn write<F>(stop: &CancellationToken, write: F) -> Result<(), ()>
where
    F: std::future::Future<Output = Result<(), axum::Error>>,
{
    tokio::select! {
        // The write first: when it is done at once (the usual case), the stop token is not
        // polled, so it is not registered with and unregistered from at every frame.
        biased;
        result = tokio::time::timeout(WRITE_TIMEOUT, write) => match result {
            Ok(Ok(())) => Ok(()),
            _ => Err(()),
        },
        () = stop.cancelled() => Err(()),
    }
}
