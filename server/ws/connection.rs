//! One websocket connection: the upgrade, the reader loop and the routing of each client frame
//! to its handler (`hello`, `triggers`, `initiative`, `signal` and answers here). Every bad
//! frame gets an `error` frame and the connection stays usable; only a refused credential
//! ends it, or a websocket protocol violation (closed with its RFC 6455 code, see
//! `violation`).

use std::net::IpAddr;
use std::time::{Duration, Instant};

use axum::Extension;
use axum::extract::State;
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::http::HeaderMap;
use axum::response::{IntoResponse, Response};
use futures_util::StreamExt;
use tokio::sync::oneshot;
use tokio_util::sync::CancellationToken;

use crate::access::{ClientAddress, TokenBucket};
use crate::adapters::{Outcome, ScreenReport};
use crate::events::{ClientRole, EventKind};
use crate::http::ConnectionSlot;
use crate::http::auth::{Peer, same_origin};
use crate::state::AppState;
use crate::sync::lock;
use crate::wire::ErrorCode;
use crate::wire::outbox::{Frame, OUTBOX_CAPACITY, Outbox};
use crate::ws::diagnose::diagnose;
use crate::ws::hello::Hello;
use crate::ws::protocol::{ClientFrame, MAX_FRAME_BYTES, error_frame};
use crate::ws::violation::{Violation, violation};
use crate::ws::writer::{CloseWith, Feed, PING_INTERVAL, run_writer};

/// Frames beyond this size end the connection at the websocket layer; frames between
/// [`MAX_FRAME_BYTES`] and this get an `error` frame and the connection stays.
const MAX_MESSAGE_BYTES: usize = 1024 * 1024;
/// The per-connection read buffer (it grows for a larger frame).
const READ_BUFFER_BYTES: usize = 4 * 1024;
/// A client silent for this long (not even answering pings) is dropped.
const IDLE_TIMEOUT: Duration = Duration::from_secs(3 * PING_INTERVAL.as_secs());

/// The reader's reason when the writer ended first (the writer then has the real reason).
const WRITER_ENDED: &str = "writer ended";

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
    ws.max_message_size(MAX_MESSAGE_BYTES)
        .max_frame_size(MAX_MESSAGE_BYTES)
        // tungstenite reads into a 128 KiB buffer per connection by default; protocol frames
        // are small and a kiosk fleet is many idle connections.
        .read_buffer_size(READ_BUFFER_BYTES)
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

/// One connection's state, shared by the frame handlers in the sibling files.
pub(super) struct Session {
    /// The connection's id.
    pub(super) client: u64,
    /// The client's address (`None` when unknown): the connection's peer, or the client a
    /// trusted proxy names.
    pub(super) peer: Option<IpAddr>,
    /// Whether the client is on this machine (see [`ClientAddress::local`]).
    pub(super) local: bool,
    /// The role, once `hello` was accepted.
    pub(super) role: Option<ClientRole>,
    /// Frames to this client.
    pub(super) outbox: Outbox,
    /// Hands the writer its subscription after `hello`.
    pub(super) feed: Option<oneshot::Sender<Feed>>,
    /// The server.
    pub(super) state: AppState,
    /// Set when the connection must end after the frames queued so far (a refused hello).
    pub(super) closing: Option<&'static str>,
    /// Whether this client's current run of refused triggers (rate-limited, or forbidden for
    /// its role) was logged already: one `trigger.refused` per run, so a flood cannot flood
    /// the corpus.
    pub(super) limited_logged: bool,
    /// This client's allowance for relayed signalling frames.
    pub(super) signals: TokenBucket,
}

async fn serve(socket: WebSocket, state: AppState, address: ClientAddress) {
    let client = state.next_client_id();
    let (sink, mut stream) = socket.split();
    let (outbox, queue) = Outbox::new(OUTBOX_CAPACITY);
    let (feed_tx, feed_rx) = oneshot::channel();
    let stop = CancellationToken::new();
    let close_with = CloseWith::default();
    let writer = state.life.tracker.spawn(run_writer(
        sink,
        queue,
        std::sync::Arc::clone(outbox.lingering()),
        feed_rx,
        state.clone(),
        stop.clone(),
        close_with.clone(),
    ));
    let mut session = Session {
        client,
        peer: address.ip,
        local: address.local,
        role: None,
        outbox,
        feed: Some(feed_tx),
        state: state.clone(),
        closing: None,
        limited_logged: false,
        signals: TokenBucket::signalling(Instant::now()),
    };
    let shutdown = state.life.shutdown.clone();
    let kicked = session.outbox.kicked().clone();
    let reason = loop {
        let next = tokio::select! {
            next = tokio::time::timeout(IDLE_TIMEOUT, stream.next()) => next,
            () = kicked.cancelled() => break "too slow: its outgoing queue was full",
            () = shutdown.cancelled() => break "server shutting down",
            () = stop.cancelled() => break WRITER_ENDED,
        };
        match next {
            Err(_) => break "idle timeout",
            Ok(None) | Ok(Some(Ok(Message::Close(_)))) => break "closed by client",
            Ok(Some(Err(error))) => {
                // The writer answers with the violation's close code as it closes.
                let Violation { reason, close } = violation(error);
                *lock(&close_with) = close;
                break reason;
            }
            Ok(Some(Ok(Message::Text(text)))) => {
                session.on_text(text.as_str());
                if let Some(reason) = session.closing {
                    break reason;
                }
            }
            Ok(Some(Ok(Message::Binary(_)))) => {
                session.reply_error(
                    ErrorCode::BinaryFrame,
                    "send JSON text frames, not binary ones",
                    None,
                    None,
                );
            }
            Ok(Some(Ok(_))) => {} // pings and pongs
        }
    };
    if session.closing.is_some() {
        // Dropping the only sender lets the writer send the queued error, then close.
        drop(session);
        let _ = writer.await;
        return;
    }
    if reason == WRITER_ENDED {
        let writer_end = writer.await.unwrap_or("writer failed");
        return session.leave(writer_end);
    }
    // Leave first: a writer stuck on a client that stopped reading must not delay failing the
    // commands an adapter owes, or the client.left event, past shutdown.
    session.leave(reason);
    stop.cancel();
    let _ = writer.await;
}

impl Session {
    pub(super) fn send(&self, frame: String) {
        self.outbox.send(Frame::from(frame));
    }

    pub(super) fn reply_error(
        &self,
        code: ErrorCode,
        message: &str,
        reference: Option<&str>,
        suggestion: Option<&str>,
    ) {
        self.send(error_frame(code, message, reference, suggestion));
    }

    fn on_text(&mut self, text: &str) {
        if text.len() > MAX_FRAME_BYTES {
            let message = format!("frames are limited to {MAX_FRAME_BYTES} bytes");
            return self.reply_error(ErrorCode::FrameTooLarge, &message, None, None);
        }
        match serde_json::from_str::<ClientFrame>(text) {
            Ok(frame) => self.on_frame(frame),
            Err(e) => {
                let (code, message, reference) = diagnose(text, &e);
                self.reply_error(code, &message, reference.as_deref(), None);
            }
        }
    }

    fn on_frame(&mut self, frame: ClientFrame) {
        match frame {
            ClientFrame::Hello {
                role,
                verbs,
                name,
                token,
                events,
            } => self.hello(Hello {
                role,
                verbs,
                name,
                token,
                events,
            }),
            ClientFrame::Trigger {
                label,
                context,
                interrupt,
                reference,
            } => self.trigger(label, context, interrupt, reference),
            ClientFrame::Stop { reference } => self.stop(reference),
            ClientFrame::Context { context, reference } => self.set_context(context, reference),
            ClientFrame::Page { page } => self.page_shown(page),
            ClientFrame::Propose {
                label,
                context,
                reason,
                reference,
            } => self.propose(label, context, reason, reference),
            ClientFrame::Accept {
                proposal,
                reference,
            } => self.accept(proposal, reference),
            ClientFrame::Dismiss {
                proposal,
                reference,
            } => self.dismiss(proposal, reference),
            ClientFrame::Mark {
                mark,
                value,
                reference,
            } => self.mark(mark, value, reference),
            ClientFrame::Signal { to, data } => self.signal(to, &data),
            ClientFrame::Started { id } => self.answer(id, ScreenReport::Started),
            ClientFrame::Done { id, held } => self.answer(id, ScreenReport::Done { held }),
            ClientFrame::Failed { id, reason } => {
                let reason = reason.unwrap_or_else(|| "the adapter reported a failure".into());
                self.answer(id, ScreenReport::Failed(reason));
            }
        }
    }

    /// The client's role if it is one of `roles`; otherwise answers with an error.
    pub(super) fn allowed(
        &self,
        roles: &[ClientRole],
        reference: Option<&str>,
    ) -> Option<ClientRole> {
        match self.role {
            None => {
                self.reply_error(
                    ErrorCode::HelloFirst,
                    "say hello (with your role) before anything else",
                    reference,
                    None,
                );
                None
            }
            Some(role) if roles.contains(&role) => Some(role),
            Some(role) => {
                let message = format!("a client with role {role:?} may not do this").to_lowercase();
                self.reply_error(ErrorCode::Forbidden, &message, reference, None);
                None
            }
        }
    }

    fn answer(&self, id: u64, report: ScreenReport) {
        let roles = [
            ClientRole::Adapter,
            ClientRole::Projector,
            ClientRole::Kiosk,
        ];
        let Some(role) = self.allowed(&roles, None) else {
            return;
        };
        if role != ClientRole::Adapter {
            // Kiosks and projectors report on what they were sent to show.
            return self
                .state
                .devices
                .display
                .report(role, self.client, id, report);
        }
        let external = &self.state.devices.external;
        let result = match report {
            ScreenReport::Started => external.started(self.client, id),
            ScreenReport::Done { .. } => external.answer(self.client, id, Outcome::Done),
            ScreenReport::Failed(reason) => {
                external.answer(self.client, id, Outcome::Failed(reason))
            }
        };
        if let Err(e) = result {
            self.reply_error(ErrorCode::UnknownCommand, &e.to_string(), None, None);
        }
    }

    fn leave(self, reason: &str) {
        let Some(role) = self.role else { return };
        if role == ClientRole::Adapter {
            self.state.devices.external.disconnect(self.client);
        }
        self.state.devices.display.left(role, self.client);
        self.state.client_left(self.client);
        if role == ClientRole::Operator {
            self.hang_up_calls();
        }
        if role == ClientRole::Dm {
            self.withdraw_proposals();
        }
        let reason = reason.to_owned();
        self.state.hub.publish(EventKind::ClientLeft {
            client: self.client,
            role,
            reason,
        });
    }
}
