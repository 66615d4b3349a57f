//! WebRTC signalling relay: the operator console and the kiosk device exchange offers,
//! answers and candidates through the server; the media itself flows between the browsers
//! and never passes through Docent. An operator may signal any kiosk; a kiosk may answer only
//! an operator that signalled it first, so a visitor's screen cannot reach consoles unasked.

use crate::events::ClientRole;
use crate::ws::connection::Session;
use crate::ws::outbox::Frame;
use crate::ws::protocol::signal_frame;

/// What a kiosk is told on behalf of an operator that left without hanging up.
const HANGUP: &str = r#"{"kind":"hangup","reason":"the operator left"}"#;

impl Session {
    pub(super) fn signal(&self, to: u64, data: &serde_json::Value) {
        let Some(role) = self.allowed(&[ClientRole::Operator, ClientRole::Kiosk], None) else {
            return;
        };
        let permitted = match role {
            ClientRole::Kiosk => self.state.was_signalled_by(self.client, to),
            _ => self
                .state
                .clients()
                .get(&to)
                .is_none_or(|c| c.role == ClientRole::Kiosk),
        };
        if !permitted {
            let message = match role {
                ClientRole::Kiosk => "a kiosk may signal only an operator that signalled it",
                _ => "an operator may signal only kiosks",
            };
            return self.reply_error("forbidden", message, None, None);
        }
        let Some((_, outbox)) = self.state.signal_route(to, self.client) else {
            let message = format!("client {to} is not connected");
            return self.reply_error("unknown-client", &message, None, None);
        };
        outbox.send(Frame::from(signal_frame(self.client, role, data)));
    }

    /// Ends the calls of an operator that left (a closed or crashed console), so kiosks free
    /// their camera at once instead of waiting for WebRTC to notice.
    pub(super) fn hang_up_calls(&self) {
        let data: serde_json::Value = serde_json::from_str(HANGUP).unwrap_or_default();
        let frame = signal_frame(self.client, ClientRole::Operator, &data);
        for outbox in self.state.signaller_left(self.client) {
            outbox.send(Frame::from(frame.clone()));
        }
    }
}
