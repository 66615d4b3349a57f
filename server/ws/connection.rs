//! One websocket connection: the upgrade, the reader loop and how the connection ends. Each
//! frame read goes to the connection's [`Session`] (`session`), which routes it to its
//! handler. Every bad frame gets an `error` frame and the connection stays usable; only a
//! refused credential ends it, or a websocket protocol violation (closed with its RFC 6455
//! code, see `violation`), silence, a client too slow for what others send it (closed with
//! `1008` or `1013` and a reason, see `writer::WriterEnd`) or shutdown. A client that sends
//! faster than it reads its answers is not ended: the reader takes its next frame only once
//! its answers and its events have room (`backlog`).

use std::net::IpAddr;
use std::pin::pin;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use axum::Extension;
use axum::extract::State;
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade, close_code};
use axum::http::HeaderMap;
use axum::response::{IntoResponse, Response};
use futures_util::StreamExt;
use tokio::sync::oneshot;

use crate::access::ClientAddress;
use crate::events::{ClientRole, Ended};
use crate::http::ConnectionSlot;
use crate::http::auth::{Peer, same_origin};
use crate::state::AppState;
use crate::sync::lock;
use crate::wire::ErrorCode;
use crate::wire::outbox::Outbox;
use crate::ws::allowance::{self, Allowance, Verdict};
use crate::ws::client::Client;
use crate::ws::session::Session;
use crate::ws::violation::{Violation, client_closed, closed, violation};
use crate::ws::writer::{Link, PING_INTERVAL, WriterEnd, run_writer};

/// The per-connection read buffer (it grows for a larger frame).
const READ_BUFFER_BYTES: usize = 4 * 1024;
/// A client silent for this long (not even answering pings) is dropped.
const IDLE_TIMEOUT: Duration = Duration::from_secs(3 * PING_INTERVAL.as_secs());

/// Bytes of outgoing frames (pongs included) the websocket layer holds for a client that does
/// not read; beyond them it holds none, and the writer's next frame fails.
const MAX_WRITE_BUFFER_BYTES: usize = 256 * 1024;
/// Bytes the websocket layer gathers before writing them out.
const WRITE_BUFFER_BYTES: usize = 16 * 1024;

/// The `client.left` reason of a client whose outgoing queue overflowed.
const TOO_SLOW: &str = "too slow: its outgoing queue was full";

/// `GET /ws`: upgrades to a websocket connection.
pub async fn ws_upgrade(
    ws: WebSocketUpgrade,
    State(state): State<AppState>,
    Peer(client): Peer,
    slot: Option<Extension<ConnectionSlot>>,
    headers: HeaderMap,
) -> Response {
    // Browsers let any page open a websocket anywhere: only this server's own pages may.
    if let Err(refused) = same_origin(&headers) {
        return refused.into_response();
    }
    // Frames beyond `server: messages: max_size` end the connection at the websocket layer;
    // frames between `MAX_FRAME_BYTES` and it get an `error` frame and the connection stays.
    let max_message = state.limits.server.max_message_bytes;
    ws.max_message_size(max_message)
        .max_frame_size(max_message)
        // tungstenite reads into a 128 KiB buffer per connection by default; protocol frames
        // are small and a kiosk fleet is many idle connections.
        .read_buffer_size(READ_BUFFER_BYTES)
        // The pongs a client that pings and never reads makes the server owe stay bounded.
        .write_buffer_size(WRITE_BUFFER_BYTES)
        .max_write_buffer_size(MAX_WRITE_BUFFER_BYTES)
        .on_upgrade(move |socket| {
            // axum spawns this itself; tracking it lets shutdown wait for the client.left event.
            let tracker = state.life.tracker.clone();
            let serving = async move {
                serve(socket, state, client).await;
                // The websocket holds its connection's place among the open ones until it ends.
                drop(slot);
            };
            tracker.track_future(serving)
        })
}

async fn serve(socket: WebSocket, state: AppState, address: ClientAddress) {
    let id = state.next_client_id();
    let (sink, mut stream) = socket.split();
    let (outbox, queue) = Outbox::new(state.limits.server.queue_per_client);
    let (feed_tx, feed_rx) = oneshot::channel();
    let link = Link::default();
    let writer = state.life.tracker.spawn(run_writer(
        sink,
        queue,
        std::sync::Arc::clone(outbox.lingering()),
        feed_rx,
        state.clone(),
        link.clone(),
    ));
    let Link {
        stop,
        close_with,
        backlog,
    } = link;
    let peer = address.ip;
    let client = Client {
        id,
        address,
        state: state.clone(),
        outbox,
    };
    let mut session = Session::new(client, feed_tx);
    let shutdown = state.life.shutdown.clone();
    let kicked = session.kicked();
    // Made once for the connection, not per frame: each would register with its token (and
    // the timer) anew at every frame.
    let mut kicked = pin!(kicked.cancelled());
    let mut shutdown = pin!(shutdown.cancelled());
    let mut stopped = pin!(stop.cancelled());
    let mut idle = pin!(tokio::time::sleep(IDLE_TIMEOUT));
    let mut allowance = Allowance::new(Instant::now());
    let outbox = session.client().outbox.clone();
    // Set while the reader waits for room rather than for the client.
    let waiting = AtomicBool::new(false);
    let end = loop {
        // An adapter's reports make no answers to it, while commands others send fill its
        // queue: waiting to read them would only hold up the commands' outcomes.
        let paced = session.role() != Some(ClientRole::Adapter);
        let next = tokio::select! {
            // The client's frames first; the budget of tokio's cooperative scheduling still
            // lets the others be seen during a flood.
            biased;
            next = async {
                // A log falling behind slows every client down, at the socket; answers and
                // events a client has not read yet slow it down.
                waiting.store(true, Ordering::Relaxed);
                state.hub.room_to_log().await;
                if paced {
                    backlog.room(&outbox).await;
                }
                waiting.store(false, Ordering::Relaxed);
                stream.next().await
            } => next,
            () = &mut idle => {
                // Silent because Docent holds its frames back, not because it is idle.
                if waiting.load(Ordering::Relaxed) {
                    idle.as_mut().reset(tokio::time::Instant::now() + IDLE_TIMEOUT);
                    continue;
                }
                // Nothing heard, not even a pong: the peer vanished without a word.
                break EndedBy::Reader("idle timeout", Ended::Lost);
            }
            () = &mut kicked => {
                let words = "too slow: the outgoing queue was full";
                let Violation { reason, ended, close } =
                    closed(TOO_SLOW, close_code::POLICY, words);
                *lock(&close_with) = close;
                logged(&state, id, peer, reason);
                break EndedBy::Reader(reason, ended);
            }
            () = &mut shutdown => {
                let words = "server shutting down";
                *lock(&close_with) = closed(words, close_code::AWAY, words).close;
                break EndedBy::Reader(words, Ended::Server);
            }
            () = &mut stopped => break EndedBy::Writer,
        };
        // Extending a deadline does not touch the timer wheel until the old one passes.
        idle.as_mut()
            .reset(tokio::time::Instant::now() + IDLE_TIMEOUT);
        match next {
            // The stream ends without a close frame only after the closing handshake (an end of
            // stream without it is an error, below).
            None => break EndedBy::Reader("closed by client", Ended::Closed),
            Some(Ok(Message::Close(frame))) => {
                let (reason, ended) = client_closed(frame.as_ref());
                break EndedBy::Reader(reason, ended);
            }
            Some(Err(error)) => {
                // The writer answers with the violation's close code as it closes.
                let Violation {
                    reason,
                    ended,
                    close,
                } = violation(error);
                *lock(&close_with) = close;
                break EndedBy::Reader(reason, ended);
            }
            Some(Ok(Message::Ping(_) | Message::Pong(_))) => {
                if allowance.ping(session.role(), Instant::now()) == Verdict::Close {
                    let Violation {
                        reason,
                        ended,
                        close,
                    } = allowance::too_many_pings();
                    *lock(&close_with) = close;
                    logged(&state, id, peer, reason);
                    break EndedBy::Reader(reason, ended);
                }
            }
            Some(Ok(message)) => match allowance.frame(session.role(), Instant::now()) {
                Verdict::Take => match message {
                    Message::Text(text) => {
                        session.on_text(text.as_str());
                        if let Some(reason) = session.closing() {
                            break EndedBy::Reader(reason, Ended::Server);
                        }
                    }
                    _ => session.on_binary(),
                },
                Verdict::Drop(Some(wait)) => {
                    let message = allowance::dropped_message(wait);
                    (session.client()).reply_error(ErrorCode::RateLimited, &message, None, None);
                }
                Verdict::Drop(None) | Verdict::Close => {}
            },
        }
    };
    // The reader's copy of the sender: the writer sees the queue closed once the session's goes.
    drop(outbox);
    if session.closing().is_some() {
        // Dropping the only sender lets the writer send the queued error, then close.
        drop(session);
        let _ = writer.await;
        return;
    }
    let (reason, ended) = match end {
        EndedBy::Writer => {
            let end = writer.await.unwrap_or(WriterEnd::WriteFailed);
            if let Some(close) = end.close() {
                logged(&state, id, peer, &close.reason);
            }
            return session.leave(end.reason(), end.ended(), end.close().map(|c| c.code));
        }
        EndedBy::Reader(reason, ended) => (reason, ended),
    };
    // Leave first: a writer stuck on a client that stopped reading must not delay failing the
    // commands an adapter owes, or the client.left event, past shutdown.
    let code = lock(&close_with).as_ref().map(|c| c.code);
    session.leave(reason, ended, code);
    stop.cancel();
    let _ = writer.await;
}

/// Which side ended the connection.
enum EndedBy {
    /// The reader, for this `client.left` reason and ending (and the close frame in
    /// `CloseWith`, if any).
    Reader(&'static str, Ended),
    /// The writer, which has the reason.
    Writer,
}

/// Logs a connection closed for a limit, within the shared allowance of logged refusals (so
/// that many connections closed at once cannot flood the server log).
fn logged(state: &AppState, client: u64, peer: Option<IpAddr>, reason: &str) {
    if let Some(unlogged) = state.access.admit_refusal_log() {
        tracing::warn!(client, address = ?peer, unlogged, "websocket closed: {reason}");
    }
}
