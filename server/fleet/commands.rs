//! Commands over MQTT: a message on `docent/ID/cmd` is a signed envelope (`signed`) around a
//! websocket client frame (`trigger`, `stop`, `context`, `mark`, `accept`, `dismiss`), signed
//! with the credential of its `role` (`operator` or `dm`). Each answer frame is published on
//! `docent/ID/reply` in a signed reply envelope carrying the command's `ref`.
//!
//! Before anything runs, the robot checks the envelope: its MAC (with the role's credential),
//! that it names this robot, that its `ts` is within [`signed::FRESHNESS`] of this robot's
//! clock and that its `ref` was not taken already (a command read off the broker and
//! published again is refused). A command carrying a raw `token`, as the first fleet commands
//! did, is refused with `unsigned-command` and never compared: whoever reads the broker has
//! seen that credential, and the site should change it.
//!
//! Why an embedded session rather than a second reading of the frames: the verified frame is
//! handed to [`EmbeddedSession`] (`ws::embedded`), which runs the websocket's own parsing and
//! handlers, so an MQTT command gets the same `error` codes and wording as a websocket frame,
//! and leaves the same events in the corpus (`client.connected` and `client.left` named
//! `mqtt` around what it did). A kiosk or projector role needs no credential on the websocket
//! (it is a touchscreen on the robot's own network); anyone who can publish to the broker
//! could claim it, so over MQTT only the roles with a credential are taken.
//!
//! The broker does not say who published a message, and it may run on this machine: bad
//! signatures are counted under their own key (`Counted::Mqtt`), never the broker's address,
//! so a flood of them through the broker never makes a local console or HTTP client wait, and
//! a rightly signed command is always taken, whatever came before it.

use std::net::IpAddr;

use serde_json::{Map, Value};

use super::signed::{self, Replays, SignedCommand, SignedReply, Unfresh};
use crate::access::{ClientAddress, Counted, Needed, Refusal, Secret, whole_seconds};
use crate::events::{ClientRefused, ClientRole, EventKind};
use crate::state::AppState;
use crate::wire::ErrorCode;
use crate::ws::EmbeddedSession;
use crate::ws::protocol::error_frame;

/// The name an MQTT command's session has in `client.connected` events.
pub const CLIENT_NAME: &str = "mqtt";

/// A command refused before it ran: answered without a MAC.
#[derive(Debug)]
struct Refused {
    reference: Option<String>,
    code: ErrorCode,
    message: String,
}

/// A command whose envelope checked out, to run.
pub struct Verified {
    role: ClientRole,
    key: Secret,
    reference: String,
    frame: String,
}

/// Checks a command `payload` for robot `robot`, which came through the broker at `broker`
/// (its address or host name, for the log): the command to run, or the reply envelope (JSON
/// text, unsigned) refusing it. Quick and never waiting, so that the bridge checks every
/// command as it arrives and only verified ones queue to run: a flood of bad commands through
/// the broker cannot crowd a rightly signed Stop out of the queue.
pub fn check(
    state: &AppState,
    (broker, robot): (&str, &str),
    replays: &mut Replays,
    payload: &[u8],
) -> Result<Verified, String> {
    verify(state, (broker, robot), replays, payload).map_err(|refused| {
        let frame = error_frame(refused.code, &refused.message, None, None);
        json_text(&SignedReply {
            robot: robot.to_owned(),
            reference: refused.reference,
            frame,
            mac: None,
        })
    })
}

/// Runs a verified `command` for robot `robot` through the websocket's own session code;
/// the reply envelopes (JSON text), each signed with the command's credential.
pub async fn run(
    state: &AppState,
    (broker, robot): (IpAddr, &str),
    command: Verified,
) -> Vec<String> {
    // Never local: an `--open` server takes no commands from a broker anybody may reach.
    let address = ClientAddress {
        ip: Some(broker),
        local: false,
    };
    let mut session = EmbeddedSession::open(state, address);
    let frames = if session.hello_signed(command.role, CLIENT_NAME) {
        // The welcome is the websocket's business; the command's answers follow it.
        drop(session.answers().await);
        session.frame(&command.frame);
        let frames = session.answers().await;
        session.leave("mqtt command answered");
        frames
    } else {
        session.answers().await
    };
    (frames.into_iter())
        .map(|frame| signed_reply(robot, &command, frame))
        .collect()
}

/// The reply to a verified `command` that was not run because `waiting` commands wait to run
/// already (signed, as its answers would be): the sender learns at once, instead of waiting
/// for an answer that will not come.
pub fn busy(robot: &str, command: &Verified, waiting: usize) -> String {
    let message = format!(
        "not run: {waiting} commands wait to run on this robot already; send it again in a \
         moment"
    );
    let frame = error_frame(
        ErrorCode::RateLimited,
        &message,
        Some(&command.reference),
        None,
    );
    signed_reply(robot, command, frame)
}

/// A reply envelope for `command` carrying `frame`, signed with the command's credential.
fn signed_reply(robot: &str, command: &Verified, frame: String) -> String {
    let text = signed::reply_text(robot, &command.reference, &frame);
    json_text(&SignedReply {
        robot: robot.to_owned(),
        reference: Some(command.reference.clone()),
        mac: Some(signed::mac(&command.key, &text)),
        frame,
    })
}

fn json_text(reply: &SignedReply) -> String {
    serde_json::to_string(reply).unwrap_or_else(|_| unreachable!("strings serialize"))
}

/// Reads and checks a command's envelope.
fn verify(
    state: &AppState,
    (broker, robot): (&str, &str),
    replays: &mut Replays,
    payload: &[u8],
) -> Result<Verified, Refused> {
    let fields = match serde_json::from_slice::<Value>(payload) {
        Ok(Value::Object(fields)) => fields,
        _ => {
            let message = "a command is a signed envelope, a JSON object (docs/FLEET.md)";
            return Err(refused(None, ErrorCode::MalformedJson, message));
        }
    };
    let reference = (fields.get("ref").and_then(Value::as_str))
        .filter(|r| signed::reference_problem(r).is_none())
        .map(str::to_owned);
    let command = envelope(fields).map_err(|(code, message)| {
        // Within the shared allowance: anyone who can publish could flood the log.
        if let Some(unlogged) = state.access.admit_refusal_log() {
            tracing::warn!(
                code = code.as_str(),
                unlogged,
                "MQTT command refused: {message}"
            );
        }
        refused(reference.clone(), code, &message)
    })?;
    let role = role_of(&command.role).map_err(|(c, m)| refused(reference.clone(), c, &m))?;
    let needed = match role {
        ClientRole::Dm => Needed::Dm,
        _ => Needed::Operator,
    };
    let Some(key) = state.access.credential(needed).cloned() else {
        let message = "an --open server takes no commands over MQTT: start it with credentials";
        return Err(refused(reference, ErrorCode::Unauthorized, message));
    };
    let text = signed::command_text(
        &command.robot,
        &command.role,
        &command.reference,
        command.ts,
        &command.frame,
    );
    if !signed::verifies(&key, &text, &command.mac) {
        let refusal = state.access.failed(Counted::Mqtt, Refusal::Wrong);
        log_refusal(state, broker, role, refusal);
        return Err(bad_signature(reference, refusal, needed));
    }
    if command.robot != robot {
        let message = format!(
            "this command was signed for robot {:?}, not {robot:?}: it is not run here",
            command.robot
        );
        return Err(refused(reference, ErrorCode::BadSignature, &message));
    }
    if let Err(unfresh) = replays.take(&command.reference, command.ts, signed::now_ms()) {
        return Err(unfresh_refusal(reference, unfresh));
    }
    Ok(Verified {
        role,
        key,
        reference: command.reference,
        frame: command.frame,
    })
}

fn refused(reference: Option<String>, code: ErrorCode, message: &str) -> Refused {
    Refused {
        reference,
        code,
        message: message.to_owned(),
    }
}

/// The envelope's fields, or why they are not one.
fn envelope(mut fields: Map<String, Value>) -> Result<SignedCommand, (ErrorCode, String)> {
    if fields.remove("token").is_some() {
        // Never compared nor echoed: whoever reads the broker has it already.
        let message = "a command never carries a credential (\"token\"): everyone who reads \
                       the broker sees it. This one was not run; change that credential, and \
                       sign commands with HMAC-SHA256 instead (docs/FLEET.md, Signed commands)";
        return Err((ErrorCode::UnsignedCommand, message.into()));
    }
    if !fields.contains_key("mac") {
        let message = "a command is signed: {robot, role, ref, ts, frame, mac} with an \
                       HMAC-SHA256 keyed by the role's credential (docs/FLEET.md, Signed \
                       commands); this one was not run";
        return Err((ErrorCode::UnsignedCommand, message.into()));
    }
    let command: SignedCommand = serde_json::from_value(Value::Object(fields)).map_err(|e| {
        let message = format!(
            "a signed command is {{robot, role, ref, ts, frame, mac}}, ts in milliseconds and \
             frame the command frame as JSON text (docs/FLEET.md): {e}"
        );
        (ErrorCode::BadFrame, message)
    })?;
    if let Some(problem) = signed::reference_problem(&command.reference) {
        return Err((ErrorCode::BadFrame, problem));
    }
    Ok(command)
}

/// The role a command is signed for, if one allowed over MQTT.
fn role_of(role: &str) -> Result<ClientRole, (ErrorCode, String)> {
    let role: ClientRole =
        serde_json::from_value(Value::String(role.to_owned())).map_err(|_| {
            let message = "\"role\" is operator or dm";
            (ErrorCode::BadFrame, message.to_owned())
        })?;
    match role {
        ClientRole::Operator | ClientRole::Dm => Ok(role),
        ClientRole::Kiosk | ClientRole::Projector | ClientRole::Adapter => {
            let message = format!(
                "a client with role {role:?} may not send commands over MQTT: only operator \
                 and dm, which sign them with their credential"
            )
            .to_lowercase();
            Err((ErrorCode::Forbidden, message))
        }
    }
}

fn bad_signature(reference: Option<String>, refusal: Refusal, needed: Needed) -> Refused {
    let which = match needed {
        Needed::Dm => "the dialog-manager credential (DOCENT_DM_TOKEN)",
        _ => "the operator credential (DOCENT_OPERATOR_TOKEN)",
    };
    match refusal {
        Refusal::TooManyAttempts(wait) | Refusal::Locked(wait) => {
            let message = format!(
                "too many badly signed commands over MQTT; try again in {} s (a rightly signed \
                 command is always taken)",
                whole_seconds(wait)
            );
            refused(reference, ErrorCode::TooManyAttempts, &message)
        }
        Refusal::Wrong | Refusal::Missing => {
            let message = format!("the command's mac is not signed with {which}");
            refused(reference, ErrorCode::BadSignature, &message)
        }
    }
}

fn unfresh_refusal(reference: Option<String>, unfresh: Unfresh) -> Refused {
    let seconds = signed::FRESHNESS.as_secs();
    let (code, message) = match unfresh {
        Unfresh::Stale => (
            ErrorCode::StaleCommand,
            format!(
                "the command's ts is more than {seconds} s from this robot's clock: sign each \
                 command as it is sent, and keep the clocks set (NTP)"
            ),
        ),
        Unfresh::Replayed => (
            ErrorCode::ReplayedCommand,
            "a command with this ref was taken already: each command needs a fresh random ref"
                .to_owned(),
        ),
        Unfresh::TooMany => (
            ErrorCode::RateLimited,
            format!("too many commands within {seconds} s: try again shortly"),
        ),
    };
    refused(reference, code, &message)
}

/// Logs a counted bad signature, within the shared allowance of logged refusals; one that
/// only waits (`Locked`) is not logged again, so a flood cannot flood the log.
fn log_refusal(state: &AppState, broker: &str, role: ClientRole, refusal: Refusal) {
    if matches!(refusal, Refusal::Locked(_)) {
        return;
    }
    let Some(unlogged) = state.access.admit_refusal_log() else {
        return;
    };
    let code = match refusal {
        Refusal::Wrong | Refusal::Missing => ErrorCode::BadSignature,
        _ => ErrorCode::TooManyAttempts,
    };
    let address = Some(format!("mqtt via {broker}"));
    tracing::warn!(
        ?role,
        address,
        code = code.as_str(),
        unlogged,
        "MQTT command refused"
    );
    state.hub.publish(EventKind::ClientRefused(ClientRefused {
        role,
        code: code.into(),
        address,
        unlogged,
    }));
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
    fn a_raw_credential_is_refused_unread() {
        let command = fields(json!({"type": "stop", "token": "secret-secret-1", "ref": "a"}));
        let (code, message) = envelope(command).unwrap_err();
        assert_eq!(code, ErrorCode::UnsignedCommand);
        assert!(!message.contains("secret-secret-1"), "{message}");
        let unsigned = fields(json!({"type": "stop"}));
        assert_eq!(
            envelope(unsigned).unwrap_err().0,
            ErrorCode::UnsignedCommand
        );
        let short = fields(
            json!({"robot": "r", "role": "operator", "ref": "1", "ts": 1,
            "frame": "{}", "mac": "00"}),
        );
        assert_eq!(envelope(short).unwrap_err().0, ErrorCode::BadFrame);
    }

    #[test]
    fn only_credentialed_roles_may_send_commands() {
        assert_eq!(role_of("operator").ok(), Some(ClientRole::Operator));
        assert_eq!(role_of("dm").ok(), Some(ClientRole::Dm));
        for role in ["kiosk", "projector", "adapter"] {
            let (code, message) = role_of(role).unwrap_err();
            assert_eq!(code, ErrorCode::Forbidden, "{role}");
            assert!(message.contains(role), "{message}");
        }
        assert_eq!(role_of("boss").unwrap_err().0, ErrorCode::BadFrame);
    }
}
