//! Commands over MQTT: a message on `docent/ID/cmd` is a websocket client frame (`trigger`,
//! `stop`, `context`, `mark`, `accept`, `dismiss`) with two more fields, `role` (`operator`,
//! the default, or `dm`) and `token`, the credential that role shows in a websocket `hello`.
//! Each answer frame is published on `docent/ID/reply`, carrying the command's `ref`.
//!
//! Why an embedded session rather than a second reading of the frames: the command is handed
//! to [`EmbeddedSession`] (`ws::embedded`), which runs the websocket's own `hello` (credential,
//! `Attempts` lockout, refusal logging as `client.refused`) and the websocket's own parsing and
//! handlers, so an MQTT command is checked exactly as a websocket frame is, gets the same
//! `error` codes and wording, and leaves the same events in the corpus (`client.connected`
//! and `client.left` named `mqtt` around what it did). What is MQTT's own is only the
//! envelope: who may send over a broker. A kiosk or projector role needs no credential on the
//! websocket (it is a touchscreen on the robot's own network); anyone who can publish to the
//! broker could claim it, so over MQTT only the roles with a credential are taken.
//!
//! The broker does not say who published a message, so failed credentials count against the
//! broker's address, as a reverse proxy's would without `trusted_proxies`: a flood of wrong
//! credentials through the broker makes every MQTT command wait, and nothing else.

use std::net::IpAddr;

use serde_json::{Map, Value};

use crate::access::ClientAddress;
use crate::events::ClientRole;
use crate::state::AppState;
use crate::wire::ErrorCode;
use crate::ws::EmbeddedSession;
use crate::ws::protocol::error_frame;

/// The name an MQTT command's session has in `client.connected` events.
pub const CLIENT_NAME: &str = "mqtt";

/// The answer frames to one command `payload` that came through the broker at `broker`, each
/// with the command's `ref` (when it had one).
pub async fn answer(state: &AppState, broker: IpAddr, payload: &[u8]) -> Vec<String> {
    // Never local: an `--open` server takes no commands from a broker anybody may reach.
    let address = ClientAddress {
        ip: Some(broker),
        local: false,
    };
    let Ok(text) = std::str::from_utf8(payload) else {
        let message = "a command is a JSON object in UTF-8 text";
        return vec![error_frame(ErrorCode::MalformedJson, message, None, None)];
    };
    let mut session = EmbeddedSession::open(state, address);
    let Ok(Value::Object(mut fields)) = serde_json::from_str::<Value>(text) else {
        // Not an object: the websocket's reading says what is wrong with it, in its words.
        session.frame(text);
        let frames = session.answers().await;
        session.leave("mqtt command answered");
        return frames;
    };
    let reference = fields.get("ref").and_then(Value::as_str).map(str::to_owned);
    let (role, token) = match envelope(&mut fields) {
        Ok(found) => found,
        Err((code, message)) => {
            tracing::warn!(code = code.as_str(), "MQTT command refused: {message}");
            return vec![error_frame(code, &message, reference.as_deref(), None)];
        }
    };
    let frames = if session.hello(role, token, CLIENT_NAME) {
        // The welcome is the websocket's business; the command's answers follow it.
        drop(session.answers().await);
        session.frame(&Value::Object(fields).to_string());
        let frames = session.answers().await;
        session.leave("mqtt command answered");
        frames
    } else {
        session.answers().await
    };
    frames
        .into_iter()
        .map(|frame| with_reference(frame, reference.as_deref()))
        .collect()
}

/// Takes `role` and `token` out of a command: the role, if one allowed over MQTT, and the
/// credential; otherwise the `error` code and message.
fn envelope(
    fields: &mut Map<String, Value>,
) -> Result<(ClientRole, Option<String>), (ErrorCode, String)> {
    let token = match fields.remove("token") {
        None | Some(Value::Null) => None,
        Some(Value::String(token)) => Some(token),
        // Not echoed: it may be a credential written wrong.
        Some(_) => {
            let message = "\"token\" is the operator's or dialog manager's credential, as text";
            return Err((ErrorCode::BadFrame, message.into()));
        }
    };
    let role = match fields.remove("role") {
        None => ClientRole::Operator,
        Some(role) => serde_json::from_value(role).map_err(|_| {
            let message = "\"role\" is operator (the default) or dm";
            (ErrorCode::BadFrame, message.to_owned())
        })?,
    };
    match role {
        ClientRole::Operator | ClientRole::Dm => Ok((role, token)),
        ClientRole::Kiosk | ClientRole::Projector | ClientRole::Adapter => {
            let message = format!(
                "a client with role {role:?} may not send commands over MQTT: only operator \
                 and dm, which show their credential in \"token\""
            )
            .to_lowercase();
            Err((ErrorCode::Forbidden, message))
        }
    }
}

/// `frame` with `"ref": reference` when it has none (a refused credential's `error` frame
/// does not on the websocket, where the connection says whose it is; a reply topic does not).
fn with_reference(frame: String, reference: Option<&str>) -> String {
    let Some(reference) = reference else {
        return frame;
    };
    match serde_json::from_str::<Value>(&frame) {
        Ok(Value::Object(mut fields)) if fields.get("ref").is_none_or(Value::is_null) => {
            fields.insert("ref".into(), Value::String(reference.to_owned()));
            Value::Object(fields).to_string()
        }
        _ => frame,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn fields(value: Value) -> Map<String, Value> {
        match value {
            Value::Object(fields) => fields,
            _ => unreachable!("an object"),
        }
    }

    #[test]
    fn the_envelope_takes_credentialed_roles_only() {
        let mut command = fields(json!({"type": "stop", "token": "t", "ref": "a"}));
        let (role, token) = envelope(&mut command).expect("operator by default");
        assert_eq!((role, token.as_deref()), (ClientRole::Operator, Some("t")));
        assert_eq!(command, fields(json!({"type": "stop", "ref": "a"})));
        let mut dm = fields(json!({"type": "stop", "role": "dm"}));
        assert_eq!(envelope(&mut dm).expect("dm").0, ClientRole::Dm);
        for role in ["kiosk", "projector", "adapter"] {
            let mut command = fields(json!({"type": "trigger", "label": "X", "role": role}));
            let (code, message) = envelope(&mut command).unwrap_err();
            assert_eq!(code, ErrorCode::Forbidden, "{role}");
            assert!(message.contains(role), "{message}");
        }
        let mut odd = fields(json!({"type": "stop", "role": "boss"}));
        assert_eq!(envelope(&mut odd).unwrap_err().0, ErrorCode::BadFrame);
        let mut number = fields(json!({"type": "stop", "token": 12345}));
        let (_, message) = envelope(&mut number).unwrap_err();
        assert!(!message.contains("12345"));
    }

    #[test]
    fn answers_carry_the_commands_ref() {
        let frame = r#"{"type":"error","code":"unauthorized","message":"m"}"#.to_owned();
        let with = with_reference(frame, Some("r1"));
        assert_eq!(
            serde_json::from_str::<Value>(&with).expect("json")["ref"],
            "r1"
        );
        let own = r#"{"type":"stopped","ref":"mine"}"#.to_owned();
        assert_eq!(with_reference(own.clone(), Some("r1")), own);
    }
}
