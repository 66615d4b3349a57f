//! A session with no websocket under it: how another transport (the MQTT bridge,
//! `fleet::commands`) hands Docent a client's frame so that it is parsed, checked and handled
//! by exactly the code that handles the websocket's (`session` and its handlers), with the same
//! roles, corpus events and `error` frames.
//! There is no second copy of the protocol's validation anywhere.
//!
//! A transport opens one [`EmbeddedSession`] per request, introduces it with
//! [`EmbeddedSession::hello_signed`] (the role's signature verified by the transport; the
//! rest of the `hello` as a websocket's), hands it one
//! frame ([`EmbeddedSession::frame`]) and takes the frames the session answered with
//! ([`EmbeddedSession::answers`]; an acknowledgement only once the corpus log holds what it
//! acknowledges, as the websocket writer sends it), then [`EmbeddedSession::leave`]s. Frames
//! that only make sense on a live connection (a kiosk's page reports, an adapter's replies,
//! signalling, a dialog manager's proposals, which are withdrawn when it leaves) are refused
//! with an `error` frame: the match below is exhaustive, so a new frame type must be placed.

use tokio::sync::{mpsc, oneshot};
use tokio_util::sync::CancellationToken;

use crate::access::ClientAddress;
use crate::events::ClientRole;
use crate::state::AppState;
use crate::wire::ErrorCode;
use crate::wire::outbox::{Outbox, Queued};
use crate::ws::client::Client;
use crate::ws::hello::{Credential, Hello};
use crate::ws::protocol::ClientFrame;
use crate::ws::session::Session;
use crate::ws::writer::release;

/// One request's session, not on a websocket.
pub struct EmbeddedSession {
    session: Session,
    queue: mpsc::Receiver<Queued>,
    /// Never cancelled while the session lives: an acknowledgement waits for the log.
    stop: CancellationToken,
}

impl EmbeddedSession {
    /// A session for a client at `address` that has not said `hello` yet.
    pub fn open(state: &AppState, address: ClientAddress) -> Self {
        let (outbox, queue) = Outbox::new(state.limits.server.queue_per_client);
        let client = Client {
            id: state.next_client_id(),
            address,
            state: state.clone(),
            outbox,
        };
        // No feed: an embedded client asks for no event stream and is no screen.
        let (feed, _) = oneshot::channel();
        EmbeddedSession {
            session: Session::new(client, feed),
            queue,
            stop: CancellationToken::new(),
        }
    }

    /// Says `hello` as `role`, without the event stream, for a command the transport has
    /// verified to be signed with `role`'s credential (`fleet::signed`): no credential is
    /// checked here, since none travelled. True when admitted; otherwise the refusal (an
    /// `error` frame) waits in [`EmbeddedSession::answers`].
    pub fn hello_signed(&mut self, role: ClientRole, name: &str) -> bool {
        self.session.hello(Hello {
            role,
            verbs: Vec::new(),
            robot_events: Vec::new(),
            name: Some(name.to_owned()),
            credential: Credential::Signed,
            events: false,
            page: None,
            language: None,
        });
        self.session.role().is_some()
    }

    /// Handles one text frame as the websocket would, refusing those that need a live
    /// connection.
    pub fn frame(&mut self, text: &str) {
        let Some(frame) = self.session.parse(text) else {
            return;
        };
        match needs_connection(&frame) {
            None => self.session.on_frame(frame),
            Some(why) => {
                let reference = reference_of(&frame);
                let client = self.session.client();
                client.reply_error(ErrorCode::Forbidden, why, reference, None);
            }
        }
    }

    /// The frames answered so far, in order; each acknowledgement once the corpus log holds
    /// what it acknowledges (or the `error` frame saying it could not be logged).
    pub async fn answers(&mut self) -> Vec<String> {
        let hub = self.session.client().state.hub.clone();
        let mut frames = Vec::new();
        while let Ok(queued) = self.queue.try_recv() {
            if let Some(frame) = release(queued, &hub, &self.stop).await {
                frames.push(frame.as_str().to_owned());
            }
        }
        frames
    }

    /// Ends the session for `reason` (`client.left`, as a websocket client's, ended by the
    /// server: it answered what it was asked).
    pub fn leave(self, reason: &str) {
        self.session
            .leave(reason, crate::events::Ended::Server, None);
    }
}

/// Why `frame` cannot come from a client that is not connected, if it cannot.
fn needs_connection(frame: &ClientFrame) -> Option<&'static str> {
    match frame {
        ClientFrame::Trigger(_)
        | ClientFrame::Stop { .. }
        | ClientFrame::Context { .. }
        | ClientFrame::Language { .. }
        | ClientFrame::Accept { .. }
        | ClientFrame::Dismiss { .. }
        | ClientFrame::Mark { .. } => None,
        ClientFrame::Hello(_) => {
            Some("a command says who sends it in its signed envelope's role; send no hello frame")
        }
        ClientFrame::Propose { .. } => Some(
            "a proposal lives as long as its dialog manager's connection: propose over the \
             websocket",
        ),
        ClientFrame::Page { .. }
        | ClientFrame::Attract { .. }
        | ClientFrame::Signal { .. }
        | ClientFrame::Started { .. }
        | ClientFrame::Done { .. }
        | ClientFrame::Failed { .. }
        | ClientFrame::Robot { .. }
        | ClientFrame::Clock { .. }
        | ClientFrame::RecordingStarted { .. }
        | ClientFrame::RecordingStopped { .. }
        | ClientFrame::RecordingFailed { .. } => Some(
            "this frame comes from a kiosk, projector or adapter connected over the websocket; \
             it cannot be sent as a command",
        ),
    }
}

/// The `ref` a refused frame carried, to echo.
fn reference_of(frame: &ClientFrame) -> Option<&str> {
    match frame {
        ClientFrame::Propose { reference, .. } => reference.as_deref(),
        _ => None,
    }
}
