//! One websocket connection: the upgrade, the reader loop and what each client frame does.
//! Every bad frame gets an `error` frame and the connection stays usable.

use std::time::Duration;

use axum::extract::State;
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::response::Response;
use futures_util::StreamExt;
use tokio::sync::oneshot;
use tokio_util::sync::CancellationToken;

use crate::adapters::Outcome;
use crate::content::{BundleArea, resolve_in_bundle};
use crate::dispatch::TriggerRequest;
use crate::events::{ClientRole, EventKind};
use crate::state::{AppState, ClientInfo};
use crate::ws::diagnose::diagnose;
use crate::ws::outbox::{Frame, OUTBOX_CAPACITY, Outbox};
use crate::ws::protocol::{
    ClientFrame, MAX_FRAME_BYTES, context_frame, error_frame, stopped_frame, triggered_frame,
    welcome_frame,
};
use crate::ws::writer::{Feed, PING_INTERVAL, run_writer};

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
pub async fn ws_upgrade(ws: WebSocketUpgrade, State(state): State<AppState>) -> Response {
    ws.max_message_size(MAX_MESSAGE_BYTES)
        .max_frame_size(MAX_MESSAGE_BYTES)
        // tungstenite reads into a 128 KiB buffer per connection by default; protocol frames
        // are small and a kiosk fleet is many idle connections.
        .read_buffer_size(READ_BUFFER_BYTES)
        .on_upgrade(move |socket| {
            // axum spawns this itself; tracking it lets shutdown wait for the client.left event.
            let tracker = state.life.tracker.clone();
            tracker.track_future(serve(socket, state))
        })
}

/// What a `hello` frame says.
struct Hello {
    role: ClientRole,
    verbs: Vec<String>,
    name: Option<String>,
    events: bool,
}

struct Session {
    client: u64,
    role: Option<ClientRole>,
    outbox: Outbox,
    feed: Option<oneshot::Sender<Feed>>,
    state: AppState,
}

async fn serve(socket: WebSocket, state: AppState) {
    let client = state.next_client_id();
    let (sink, mut stream) = socket.split();
    let (outbox, queue) = Outbox::new(OUTBOX_CAPACITY);
    let (feed_tx, feed_rx) = oneshot::channel();
    let stop = CancellationToken::new();
    let writer = state.life.tracker.spawn(run_writer(
        sink,
        queue,
        feed_rx,
        state.clone(),
        stop.clone(),
    ));
    let mut session = Session {
        client,
        role: None,
        outbox,
        feed: Some(feed_tx),
        state: state.clone(),
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
            Ok(Some(Err(_))) => break "protocol error",
            Ok(Some(Ok(Message::Text(text)))) => session.on_text(text.as_str()),
            Ok(Some(Ok(Message::Binary(_)))) => {
                session.reply_error(
                    "binary-frame",
                    "send JSON text frames, not binary ones",
                    None,
                    None,
                );
            }
            Ok(Some(Ok(_))) => {} // pings and pongs
        }
    };
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
    fn send(&self, frame: String) {
        self.outbox.send(Frame::from(frame));
    }

    fn reply_error(
        &self,
        code: &str,
        message: &str,
        reference: Option<&str>,
        suggestion: Option<&str>,
    ) {
        self.send(error_frame(code, message, reference, suggestion));
    }

    fn on_text(&mut self, text: &str) {
        if text.len() > MAX_FRAME_BYTES {
            let message = format!("frames are limited to {MAX_FRAME_BYTES} bytes");
            return self.reply_error("frame-too-large", &message, None, None);
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
                token: _,
                events,
            } => self.hello(Hello {
                role,
                verbs,
                name,
                events,
            }),
            ClientFrame::Trigger {
                label,
                context,
                interrupt,
                reference,
            } => {
                let Some(role) = self.allowed(
                    &[ClientRole::Kiosk, ClientRole::Operator, ClientRole::Dm],
                    reference.as_deref(),
                ) else {
                    return self.log_refused(label);
                };
                let request = TriggerRequest {
                    label,
                    context,
                    interrupt,
                    reference: reference.clone(),
                    source: role.source(),
                    client: Some(self.client),
                };
                match self.state.dispatcher.trigger(request) {
                    Ok(t) => self.send(triggered_frame(&t)),
                    Err(e) => self.reply_error(
                        e.code(),
                        &e.to_string(),
                        reference.as_deref(),
                        e.suggestion(),
                    ),
                }
            }
            ClientFrame::Stop { reference } => {
                let Some(role) = self.allowed(
                    &[ClientRole::Operator, ClientRole::Dm],
                    reference.as_deref(),
                ) else {
                    return;
                };
                self.state.dispatcher.stop(role.source(), "stop request");
                self.send(stopped_frame(reference.as_deref()));
            }
            ClientFrame::Context { context, reference } => {
                let Some(role) = self.allowed(
                    &[ClientRole::Operator, ClientRole::Dm],
                    reference.as_deref(),
                ) else {
                    return;
                };
                match self.state.dispatcher.set_context(&context, role.source()) {
                    Ok(()) => self.send(context_frame(reference.as_deref(), &context)),
                    Err(e) => self.reply_error(
                        e.code(),
                        &e.to_string(),
                        reference.as_deref(),
                        e.suggestion(),
                    ),
                }
            }
            ClientFrame::Page { page } => self.page_shown(page),
            ClientFrame::Started { id } => self.answer(id, None),
            ClientFrame::Done { id } => self.answer(id, Some(Outcome::Done)),
            ClientFrame::Failed { id, reason } => {
                let reason = reason.unwrap_or_else(|| "the adapter reported a failure".into());
                self.answer(id, Some(Outcome::Failed(reason)));
            }
        }
    }

    /// The client's role if it is one of `roles`; otherwise answers with an error.
    fn allowed(&self, roles: &[ClientRole], reference: Option<&str>) -> Option<ClientRole> {
        match self.role {
            None => {
                self.reply_error(
                    "hello-first",
                    "say hello (with your role) before anything else",
                    reference,
                    None,
                );
                None
            }
            Some(role) if roles.contains(&role) => Some(role),
            Some(role) => {
                let message = format!("a client with role {role:?} may not do this").to_lowercase();
                self.reply_error("forbidden", &message, reference, None);
                None
            }
        }
    }

    /// A kiosk reports a page it shows on its own, so the server's display state (what a
    /// reconnecting kiosk is sent back to, what the log says) stays true.
    fn page_shown(&self, page: String) {
        if self.allowed(&[ClientRole::Kiosk], None).is_none() {
            return;
        }
        let root = &self.state.dispatcher.bundle().root;
        if resolve_in_bundle(root, BundleArea::Pages, &page).is_err() {
            let message = format!("{page:?} is not a page of this bundle");
            return self.reply_error("unknown-page", &message, None, None);
        }
        self.state.devices.display.page_shown(page, &self.state.hub);
    }

    /// Records a trigger this client's role may not make.
    fn log_refused(&self, label: String) {
        let Some(role) = self.role else { return };
        self.state.hub.publish(EventKind::TriggerRefused {
            source: role.source(),
            client: Some(self.client),
            label,
            code: "forbidden",
            message: format!("a client with role {role:?} may not trigger acts").to_lowercase(),
        });
    }

    fn hello(&mut self, hello: Hello) {
        let Hello {
            role,
            verbs,
            name,
            events,
        } = hello;
        if self.role.is_some() {
            return self.reply_error(
                "already-introduced",
                "hello was already received on this connection",
                None,
                None,
            );
        }
        if role == ClientRole::Adapter && verbs.is_empty() {
            return self.reply_error(
                "no-verbs",
                "an adapter must list the verbs it serves in \"verbs\"",
                None,
                None,
            );
        }
        self.role = Some(role);
        let state = &self.state;
        let (display, display_rx) = state.devices.display.subscribe(role);
        if role == ClientRole::Projector {
            state.devices.display.projector_joined(self.client);
        }
        let mut view = state.state_view();
        view.display = display;
        self.send(welcome_frame(self.client, role, &view));
        let feed = match (role, display_rx) {
            (_, Some(rx)) => Some(Feed::Display(role, rx)),
            (ClientRole::Operator | ClientRole::Dm, None) if events => {
                Some(Feed::Events(state.hub.subscribe()))
            }
            _ => None,
        };
        if let (Some(feed), Some(tx)) = (feed, self.feed.take()) {
            let _ = tx.send(feed);
        }
        if role == ClientRole::Adapter {
            state
                .devices
                .ws
                .connect(self.client, verbs.clone(), self.outbox.clone());
            self.warn_unrouted(&verbs);
        }
        state.client_joined(
            self.client,
            ClientInfo {
                role,
                name: name.clone(),
                verbs: verbs.clone(),
            },
        );
        state.hub.publish(EventKind::ClientConnected {
            client: self.client,
            role,
            name,
            verbs,
        });
    }

    /// Tells an adapter, in one frame, which of its verbs this bundle sends elsewhere: it
    /// will not get them.
    fn warn_unrouted(&self, verbs: &[String]) {
        let problems: Vec<String> = (verbs.iter())
            .filter_map(|verb| match self.state.dispatcher.adapter_for(verb) {
                Some("ws") => None,
                Some(other) => Some(format!("{verb} goes to the {other} adapter")),
                None => Some(format!("{verb} is not a verb of this bundle")),
            })
            .collect();
        if problems.is_empty() {
            return;
        }
        let message = format!(
            "{}; route built-in verbs to ws and declare site verbs under verbs: in docent.yaml \
             to receive them here",
            problems.join("; ")
        );
        self.reply_error("verb-not-routed", &message, None, None);
    }

    fn answer(&self, id: u64, outcome: Option<Outcome>) {
        let roles = [ClientRole::Adapter, ClientRole::Projector];
        if self.allowed(&roles, None) == Some(ClientRole::Projector) {
            // A projector answers for the videos it plays; `started` adds nothing there.
            if let Some(outcome) = outcome {
                self.state.devices.display.answer(self.client, id, outcome);
            }
            return;
        }
        if self.role != Some(ClientRole::Adapter) {
            return;
        }
        let ws = &self.state.devices.ws;
        let result = match outcome {
            None => ws.started(self.client, id),
            Some(outcome) => ws.answer(self.client, id, outcome),
        };
        if let Err(e) = result {
            self.reply_error("unknown-command", &e.to_string(), None, None);
        }
    }

    fn leave(self, reason: &str) {
        let Some(role) = self.role else { return };
        if role == ClientRole::Adapter {
            self.state.devices.ws.disconnect(self.client);
        }
        if role == ClientRole::Projector {
            self.state.devices.display.projector_left(self.client);
        }
        self.state.client_left(self.client);
        let reason = reason.to_owned();
        self.state.hub.publish(EventKind::ClientLeft {
            client: self.client,
            role,
            reason,
        });
    }
}
