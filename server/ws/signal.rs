//! WebRTC signalling relay: the operator console and the kiosk device exchange offers,
//! answers and candidates through the server; the media itself flows between the browsers
//! and never passes through Docent. An operator may signal any kiosk; a kiosk may answer only
//! an operator that signalled it first, so a visitor's screen cannot reach consoles unasked.
//! Each client relays at a bounded rate, only the kinds of data a call uses, and a receiver
//! that falls behind loses relayed frames instead of its connection.

use std::time::Instant;

use serde_json::json;

use crate::events::ClientRole;
use crate::wire::ErrorCode;
use crate::wire::outbox::Frame;
use crate::ws::connection::Session;
use crate::ws::protocol::signal_frame;

/// The `data.kind` values a call uses (see `static/camera-kiosk.js`).
const KINDS: [&str; 5] = ["offer", "answer", "candidate", "hangup", "error"];

impl Session {
    pub(super) fn signal(&mut self, to: u64, data: &serde_json::Value) {
        let Some(role) = self.allowed(&[ClientRole::Operator, ClientRole::Kiosk], None) else {
            return;
        };
        if !(data["kind"].as_str()).is_some_and(|k| KINDS.contains(&k)) {
            let message = format!("signal data needs a \"kind\": one of {}", KINDS.join(", "));
            return self.reply_error(ErrorCode::BadSignal, &message, None, None);
        }
        if let Err(wait) = self.signals.take(Instant::now()) {
            let message = format!(
                "too many signalling frames; the next is possible in {} ms",
                wait.as_millis().max(1)
            );
            return self.reply_error(ErrorCode::RateLimited, &message, None, None);
        }
        let permitted = match role {
            ClientRole::Kiosk => self.state.was_signalled_by(self.client, to),
            _ => (self.state.role_of(to)).is_none_or(|r| r == ClientRole::Kiosk),
        };
        if !permitted {
            let message = match role {
                ClientRole::Kiosk => "a kiosk may signal only an operator that signalled it",
                _ => "an operator may signal only kiosks",
            };
            return self.reply_error(ErrorCode::Forbidden, message, None, None);
        }
        // The kiosk remembers the operator that called it (so it may answer); not the reverse.
        let caller = (role == ClientRole::Operator).then_some(self.client);
        let Some(outbox) = self.state.signal_route(to, caller) else {
            let message = format!("client {to} is not connected");
            return self.reply_error(ErrorCode::UnknownClient, &message, None, None);
        };
        outbox.send_if_room(Frame::from(signal_frame(self.client, role, data)));
    }

    /// Ends the calls of an operator that left (a closed or crashed console), so kiosks free
    /// their camera at once instead of waiting for WebRTC to notice.
    pub(super) fn hang_up_calls(&self) {
        let data = json!({"kind": "hangup", "reason": "the operator left"});
        let frame = signal_frame(self.client, ClientRole::Operator, &data);
        for outbox in self.state.signaller_left(self.client) {
            outbox.send_if_room(Frame::from(frame.clone()));
        }
    }
}
