//! `Client`: one connected client as the frame handlers see it, the facts fixed when it
//! connected (its id, its address, the server) and the way back to it (its outbox). The
//! session (`session`) owns it and lends it to a handler by shared reference, so a handler can
//! answer the client and act on the server but never changes the session: what the session
//! must remember, a handler returns.

use crate::access::ClientAddress;
use crate::events::{ClientRole, LogUnwritable};
use crate::state::AppState;
use crate::wire::ErrorCode;
use crate::wire::outbox::{Frame, Outbox};
use crate::ws::protocol::error_frame;

/// One connected client, fixed for the connection's life.
pub(super) struct Client {
    /// The connection's id.
    pub(super) id: u64,
    /// The client's address: the connection's peer, or the client a trusted proxy names
    /// (see [`ClientAddress`]).
    pub(super) address: ClientAddress,
    /// The server.
    pub(super) state: AppState,
    /// Frames to this client.
    pub(super) outbox: Outbox,
}

impl Client {
    /// Queues `frame` for this client.
    pub(super) fn send(&self, frame: String) {
        self.outbox.send(Frame::from(frame));
    }

    /// Answers this client with an `error` frame.
    pub(super) fn reply_error(
        &self,
        code: ErrorCode,
        message: &str,
        reference: Option<&str>,
        suggestion: Option<&str>,
    ) {
        self.send(error_frame(code, message, reference, suggestion));
    }

    /// Sends an acknowledgement once the corpus log holds every event published so far, which
    /// includes those of the action it acknowledges (see `docs/CORPUS.md`, "Guarantees").
    pub(super) fn send_logged(&self, frame: String, reference: Option<&str>) {
        let logged = self.state.hub.published_seq();
        let reference = reference.map(str::to_owned);
        self.outbox
            .send_logged(Frame::from(frame), logged, reference);
    }

    /// False, after telling the client, while the corpus log cannot be written: an action
    /// could not be acknowledged truthfully then.
    pub(super) fn log_writable(&self, reference: Option<&str>) -> bool {
        let Some(failure) = self.state.hub.log_failure() else {
            return true;
        };
        self.reply_error(LogUnwritable::CODE, &failure.refusal(), reference, None);
        false
    }

    /// `role` (the client's, once `hello` was accepted) if it is one of `roles`; otherwise
    /// answers with an error.
    pub(super) fn allowed(
        &self,
        role: Option<ClientRole>,
        roles: &[ClientRole],
        reference: Option<&str>,
    ) -> Option<ClientRole> {
        match role {
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
}
