//! A connection's writer task: sends queued frames and, once the client has said hello, the
//! frames of its subscription (display commands or events), pinging an idle client. How far it
//! is behind the events it relays goes to the reader ([`Backlog`]), which slows the client
//! down; a client that falls behind all the same, or does not read for [`WRITE_TIMEOUT`], is
//! closed with a code and a reason ([`WriterEnd`]).

use std::sync::Arc;
use std::time::Duration;

use axum::extract::ws::{CloseFrame, Message, WebSocket, close_code};
use futures_util::SinkExt;
use futures_util::stream::SplitSink;
use tokio::sync::broadcast::error::{RecvError, TryRecvError};
use tokio::sync::{broadcast, mpsc, oneshot};
use tokio_util::sync::CancellationToken;

use crate::events::{ClientRole, Ended, Event, Hub, LogUnwritable};
use crate::state::AppState;
use crate::wire::linger::Lingering;
use crate::wire::outbox::{Frame, Queued};
use crate::ws::backlog::Backlog;
use crate::ws::protocol::{error_frame, event_frame, state_frame};

/// A client that cannot take a frame within this time is dropped.
pub const WRITE_TIMEOUT: Duration = Duration::from_secs(10);
// The close frame of `WriterEnd::NotReading` says it.
const _: () = assert!(WRITE_TIMEOUT.as_secs() == 10);
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
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WriterEnd {
    /// The connection is ending for a reason the reader knows (the client left, the server
    /// stops, a limit), or the queue closed.
    Closed,
    /// A write failed: the connection is lost.
    WriteFailed,
    /// The client took nothing for [`WRITE_TIMEOUT`] while frames waited for it, or so little
    /// that the websocket layer holds no more for it.
    NotReading,
    /// The client read the event stream slower than events came, and fell this many behind
    /// beyond what the channel holds.
    FellBehind(u64),
    /// The event stream closed: the server is shutting down.
    ServerClosing,
}

impl WriterEnd {
    /// The `client.left` reason.
    pub fn reason(self) -> &'static str {
        match self {
            WriterEnd::Closed => "closed",
            WriterEnd::WriteFailed => "connection lost",
            WriterEnd::NotReading => "too slow: did not read its frames",
            WriterEnd::FellBehind(_) => "too slow: fell behind the event stream",
            WriterEnd::ServerClosing => "server shutting down",
        }
    }

    /// Who ended the connection, as `client.left` gives it.
    pub fn ended(self) -> Ended {
        match self {
            WriterEnd::WriteFailed => Ended::Lost,
            WriterEnd::Closed => Ended::Closed,
            WriterEnd::NotReading | WriterEnd::FellBehind(_) | WriterEnd::ServerClosing => {
                Ended::Server
            }
        }
    }

    /// The close frame the client gets, when the server decided the end: `1008` for a client
    /// that stopped reading, `1013` (try again later) for one that fell behind, since a new
    /// connection starts from a fresh state.
    pub fn close(self) -> Option<CloseFrame> {
        let (code, words) = match self {
            WriterEnd::NotReading => (
                close_code::POLICY,
                "too slow: read nothing for 10 s while frames waited for it".to_owned(),
            ),
            WriterEnd::FellBehind(missed) => (
                close_code::AGAIN,
                format!(
                    "too slow: fell {missed} events behind the event stream; reconnect for a \
                     fresh state"
                ),
            ),
            WriterEnd::ServerClosing => (close_code::AWAY, "server shutting down".to_owned()),
            WriterEnd::Closed | WriterEnd::WriteFailed => return None,
        };
        Some(CloseFrame {
            code,
            reason: words.into(),
        })
    }
}

/// The close frame the writer ends with, when the reader found a protocol violation; a plain
/// close otherwise.
pub type CloseWith = Arc<std::sync::Mutex<Option<CloseFrame>>>;

/// What a connection's reader and writer share.
#[derive(Clone, Debug, Default)]
pub struct Link {
    /// Cancelled when either ends.
    pub stop: CancellationToken,
    /// The close frame the reader decided, if any.
    pub close_with: CloseWith,
    /// How far the writer is behind, which the reader waits on.
    pub backlog: Arc<Backlog>,
}

/// Writes until the queue closes, the client fails or falls behind, or `link.stop` is
/// cancelled; cancels it itself when it ends first.
pub async fn run_writer(
    mut sink: SplitSink<WebSocket, Message>,
    mut queue: mpsc::Receiver<Queued>,
    lingering: Arc<Lingering>,
    feed: oneshot::Receiver<Feed>,
    state: AppState,
    link: Link,
) -> WriterEnd {
    let Link {
        stop,
        close_with,
        backlog,
    } = link;
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
                    None => break WriterEnd::Closed,
                },
                None => break WriterEnd::Closed,
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
                if let Err(end) = write(&stop, sink.send(Message::Ping(Default::default()))).await { break end }
                continue;
            }
            () = stop.cancelled() => break WriterEnd::Closed,
        };
        if let Err(end) = write(&stop, sink.feed(Message::Text(frame))).await {
            break end;
        }
        // Send whatever else is ready, answers and fed frames alike, in one flush: one
        // system call per batch instead of one per frame.
        let mut batch = 0;
        while batch < MAX_BATCH {
            let frame = match queue.try_recv() {
                Ok(queued) => match release(queued, &state.hub, &stop).await {
                    Some(frame) => frame,
                    None => break 'writing WriterEnd::Closed,
                },
                Err(_) => match try_next_fed(&mut subscription, &state) {
                    Some(Ok(frame)) => frame,
                    Some(Err(end)) => break 'writing end,
                    None => break,
                },
            };
            if let Err(end) = write(&stop, sink.feed(Message::Text(frame))).await {
                break 'writing end;
            }
            batch += 1;
        }
        // Notices waiting for company ride along; after the queue's, which may hold older
        // ones the flusher moved there.
        let lingering_now = if queue.is_empty() {
            lingering.take()
        } else {
            Vec::new()
        };
        for frame in lingering_now {
            if let Err(end) = write(&stop, sink.feed(Message::Text(frame))).await {
                break 'writing end;
            }
        }
        if let Err(end) = write(&stop, sink.flush()).await {
            break end;
        }
        backlog.sent(match &subscription {
            Some(Feed::Events(rx)) => rx.len(),
            _ => 0,
        });
    };
    // Tell the reader loop, which may be waiting on a silent client.
    stop.cancel();
    let close = crate::sync::lock(&close_with)
        .take()
        .or_else(|| end.close());
    let closing = async {
        if let Some(frame) = close {
            sink.send(Message::Close(Some(frame))).await?;
        }
        sink.close().await
    };
    // A client that fell behind still reads: give it time to reach the close frame.
    let patience = match end {
        WriterEnd::FellBehind(_) => WRITE_TIMEOUT,
        _ => CLOSE_TIMEOUT,
    };
    let _ = tokio::time::timeout(patience, closing).await;
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
    /// This many were skipped.
    Lagged(u64),
    Closed,
}

impl<T> From<Result<T, RecvError>> for Got<T> {
    fn from(r: Result<T, RecvError>) -> Self {
        match r {
            Ok(item) => Got::Item(item),
            Err(RecvError::Lagged(missed)) => Got::Lagged(missed),
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
            Err(TryRecvError::Lagged(missed)) => Some(Got::Lagged(missed)),
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
        Got::Lagged(_) => {
            let (display, fresh) = state.devices.display.subscribe(role);
            if let Some(fresh) = fresh {
                *rx = fresh;
            }
            let mut view = state.state_view();
            view.display = display;
            Ok(Frame::from(state_frame(&view)))
        }
        Got::Closed => Err(WriterEnd::ServerClosing),
    }
}

fn event_frame_of(got: Got<Arc<Event>>) -> Result<Frame, WriterEnd> {
    match got {
        Got::Item(event) => Ok(Frame::from(event_frame(&event))),
        // An event stream with holes would mislead an operator: close, and they reconnect to
        // a fresh state and history.
        Got::Lagged(missed) => Err(WriterEnd::FellBehind(missed)),
        Got::Closed => Err(WriterEnd::ServerClosing),
    }
}

/// Runs one write with the write timeout, giving up at once when the connection is stopping.
async fn write<F>(stop: &CancellationToken, write: F) -> Result<(), WriterEnd>
where
    F: std::future::Future<Output = Result<(), axum::Error>>,
{
    tokio::select! {
        // The write first: when it is done at once (the usual case), the stop token is not
        // polled, so it is not registered with and unregistered from at every frame.
        biased;
        result = tokio::time::timeout(WRITE_TIMEOUT, write) => match result {
            Ok(Ok(())) => Ok(()),
            Ok(Err(e)) if write_buffer_full(&e) => Err(WriterEnd::NotReading),
            Ok(Err(_)) => Err(WriterEnd::WriteFailed),
            Err(_) => Err(WriterEnd::NotReading),
        },
        () = stop.cancelled() => Err(WriterEnd::Closed),
    }
}

/// Whether the websocket layer refused a frame because it holds no more for this client.
fn write_buffer_full(e: &axum::Error) -> bool {
    let inner = std::error::Error::source(e).and_then(|e| e.downcast_ref());
    matches!(inner, Some(tungstenite::Error::WriteBufferFull(_)))
}
