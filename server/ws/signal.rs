//! WebRTC signalling relay: the operator console and the kiosk device exchange offers,
//! answers and candidates through the server; the media itself flows between the browsers
//! and never passes through Docent. An operator may signal any kiosk; a kiosk may answer only
//! an operator that signalled it first, so a visitor's screen cannot reach consoles unasked.
//! Each client relays at a bounded rate, only the kinds of data a call uses, and a receiver
//! that falls behind loses relayed frames instead of its connection. The allowance is the
//! connection's own, kept and taken from by the session between [`signalling_role`] and
//! [`relay`].

use std::time::Duration;

use serde_json::json;

use crate::events::ClientRole;
use crate::wire::ErrorCode;
use crate::wire::outbox::Frame;
use crate::ws::client::Client;
use crate::ws::protocol::signal_frame;

/// The `data.kind` values a call uses (see `static/camera-kiosk.js`).
const KINDS: [&str; 5] = ["offer", "answer", "candidate", "hangup", "error"];

/// The client's role if it may signal at all and `data` is of a kind a call uses; otherwise
/// answers with an error. Checked before the session takes from the client's signalling
/// allowance, so a frame refused here costs none of it.
pub(super) fn signalling_role(
    client: &Client,
    role: Option<ClientRole>,
    data: &serde_json::Value,
) -> Option<ClientRole> {
    let role = client.allowed(role, &[ClientRole::Operator, ClientRole::Kiosk], None)?;
    if !(data["kind"].as_str()).is_some_and(|k| KINDS.contains(&k)) {
        let message = format!("signal data needs a \"kind\": one of {}", KINDS.join(", "));
        client.reply_error(ErrorCode::BadSignal, &message, None, None);
        return None;
    }
    Some(role)
}

/// Answers a signalling frame beyond the client's allowance; the next is possible in `wait`.
pub(super) fn refuse_too_many(client: &Client, wait: Duration) {
    let message = format!(
        "too many signalling frames; the next is possible in {} ms",
        wait.as_millis().max(1)
    );
    client.reply_error(ErrorCode::RateLimited, &message, None, None);
}

/// Relays `data` to client `to`, if `role` may reach it: an operator any kiosk, a kiosk only an
/// operator that signalled it.
pub(super) fn relay(client: &Client, role: ClientRole, to: u64, data: &serde_json::Value) {
    let permitted = match role {
        ClientRole::Kiosk => client.state.was_signalled_by(client.id, to),
        _ => (client.state.role_of(to)).is_none_or(|r| r == ClientRole::Kiosk),
    };
    if !permitted {
        let message = match role {
            ClientRole::Kiosk => "a kiosk may signal only an operator that signalled it",
            _ => "an operator may signal only kiosks",
        };
        return client.reply_error(ErrorCode::Forbidden, message, None, None);
    }
    // The kiosk remembers the operator that called it (so it may answer); not the reverse.
    let calling_operator = (role == ClientRole::Operator).then_some(client.id);
    let Some(outbox) = client.state.signal_route(to, calling_operator) else {
        let message = format!("client {to} is not connected");
        return client.reply_error(ErrorCode::UnknownClient, &message, None, None);
    };
    outbox.send_if_room(Frame::from(signal_frame(client.id, role, data)));
}

/// Ends the calls of an operator that left (a closed or crashed console), so kiosks free
/// their camera at once instead of waiting for WebRTC to notice.
pub(super) fn hang_up_calls(client: &Client) {
    let data = json!({"kind": "hangup", "reason": "the operator left"});
    let frame = signal_frame(client.id, ClientRole::Operator, &data);
    for outbox in client.state.signaller_left(client.id) {
        outbox.send_if_room(Frame::from(frame.clone()));
    }
}
