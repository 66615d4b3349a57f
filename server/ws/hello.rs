//! `hello`: who a client is. Operator and dialog-manager clients must show their credential
//! (adapters too, unless they run on this machine); a refused one gets an `error` frame, the
//! refusal is logged without the credential, and the connection ends. An accepted client is
//! welcomed with the current state and gets its feed: display commands for kiosks and
//! projectors, the event stream (after the recent history) for operators and dialog managers.

use crate::access::{ClientAddress, Needed, Refusal};
use crate::events::{ClientRole, EventKind};
use crate::state::ClientInfo;
use crate::wire::ErrorCode;
use crate::wire::outbox::Frame;
use crate::ws::connection::Session;
use crate::ws::protocol::{event_frame, speaking_frame, welcome_frame};
use crate::ws::writer::Feed;

/// What a `hello` frame says.
pub(super) struct Hello {
    pub(super) role: ClientRole,
    pub(super) verbs: Vec<String>,
    pub(super) name: Option<String>,
    pub(super) token: Option<String>,
    pub(super) events: bool,
}

/// The credential a role needs from a client at `peer`, if any.
fn needed(role: ClientRole, local: bool) -> Option<Needed> {
    match role {
        ClientRole::Operator => Some(Needed::Operator),
        ClientRole::Dm => Some(Needed::Dm),
        // Device adapters normally run on the robot itself; one elsewhere is a machine
        // client like a dialog manager.
        ClientRole::Adapter if !local => Some(Needed::Dm),
        ClientRole::Adapter | ClientRole::Kiosk | ClientRole::Projector => None,
    }
}

impl Session {
    pub(super) fn hello(&mut self, hello: Hello) {
        let Hello {
            role,
            verbs,
            name,
            token,
            events,
        } = hello;
        if self.role.is_some() {
            return self.reply_error(
                ErrorCode::AlreadyIntroduced,
                "hello was already received on this connection",
                None,
                None,
            );
        }
        let address = ClientAddress {
            ip: self.peer,
            local: self.local,
        };
        if let Some(needed) = needed(role, self.local)
            && let Err(refusal) = self.state.access.check(address, needed, token.as_deref())
        {
            self.log_refusal(role, refusal);
            self.reply_error(refusal.code(), &refusal.message(needed), None, None);
            self.closing = Some("credential refused");
            return;
        }
        if role == ClientRole::Adapter && verbs.is_empty() {
            return self.reply_error(
                ErrorCode::NoVerbs,
                "an adapter must list the verbs it serves in \"verbs\"",
                None,
                None,
            );
        }
        self.role = Some(role);
        let state = &self.state;
        let (display, display_rx) = state.devices.display.join(role, self.client);
        // Subscribed before the state is read: an event (a refused save, a context change)
        // published in between then arrives after the welcome instead of falling between them.
        let events = match (role, &display_rx) {
            (ClientRole::Operator | ClientRole::Dm, None) if events => {
                Some(state.hub.subscribe_with_history())
            }
            _ => None,
        };
        let mut view = state.state_view();
        view.display = display;
        self.send(welcome_frame(self.client, role, &view));
        let feed = match (display_rx, events) {
            (Some(rx), _) => Some(Feed::Display(role, rx)),
            (None, Some((rx, history))) => {
                for event in history {
                    self.outbox.send(Frame::from(event_frame(&event)));
                }
                Some(Feed::Events(rx))
            }
            (None, None) => None,
        };
        if let (Some(feed), Some(tx)) = (feed, self.feed.take()) {
            let _ = tx.send(feed);
        }
        if role == ClientRole::Adapter {
            state
                .devices
                .external
                .connect(self.client, verbs.clone(), self.outbox.clone());
            self.warn_unrouted(&verbs);
        }
        let info = ClientInfo {
            role,
            name: name.clone(),
            verbs: verbs.clone(),
        };
        state.client_joined(self.client, info, self.outbox.clone());
        if role == ClientRole::Kiosk {
            // Joined first, so every later change reaches this kiosk on its own.
            state.dispatcher.tell_speaking_now(|now| {
                if now.is_some() {
                    self.outbox.send(Frame::from(speaking_frame(now)));
                }
            });
        }
        state.hub.publish(EventKind::ClientConnected {
            client: self.client,
            role,
            name,
            verbs,
        });
    }

    /// Logs a counted refusal, within the shared allowance; an address already waiting is
    /// refused quietly, so a flood of hellos cannot flood the log.
    fn log_refusal(&self, role: ClientRole, refusal: Refusal) {
        if matches!(refusal, Refusal::Locked(_)) {
            return;
        }
        let Some(unlogged) = self.state.access.admit_refusal_log() else {
            return;
        };
        let address = self.peer.map(|p| p.to_string());
        let code = refusal.code();
        tracing::warn!(
            ?role,
            address,
            code = code.as_str(),
            unlogged,
            "websocket credential refused"
        );
        self.state.hub.publish(EventKind::ClientRefused {
            role,
            code,
            address,
            unlogged,
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
        self.reply_error(ErrorCode::VerbNotRouted, &message, None, None);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_operators_dialog_managers_and_remote_adapters_need_a_credential() {
        assert_eq!(needed(ClientRole::Operator, true), Some(Needed::Operator));
        assert_eq!(needed(ClientRole::Dm, true), Some(Needed::Dm));
        assert_eq!(needed(ClientRole::Adapter, false), Some(Needed::Dm));
        assert_eq!(needed(ClientRole::Adapter, true), None);
        assert_eq!(needed(ClientRole::Kiosk, false), None);
        assert_eq!(needed(ClientRole::Projector, false), None);
    }
}
