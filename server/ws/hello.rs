//! `hello`: who a client is. Operator and dialog-manager clients must show their credential
//! (adapters too, unless they run on this machine); a refused one gets an `error` frame, the
//! refusal is logged without the credential, and the connection ends. An accepted client is
//! welcomed with the current state and gets its feed: display commands for kiosks and
//! projectors, the event stream (after the recent history) for operators and dialog managers.
//!
//! Three steps, so that the session can record what each decides in between, in the order the
//! client sees it: [`admit`] (the credential), [`welcome`] (the `welcome` frame and the feed
//! the session hands to the writer) and [`join`] (the server learns of the client).
//!
//! A kiosk that reconnects says which page it shows (`page`): the welcome's state keeps the
//! visitor there (`DisplayState::join_kiosk_showing`) unless the tour moved on meanwhile; a
//! page not of the bundle is refused with `unknown-page` and the kiosk follows the state. A
//! joining kiosk or projector is told the caption in force (`ws::captions`).

use crate::access::{Needed, Refusal};
use crate::content::{BundleArea, resolve_in_bundle};
use crate::events::{
    ClientConnected, ClientRefused, ClientRole, EventKind, robot_event_name_problem,
};
use crate::state::ClientInfo;
use crate::wire::ErrorCode;
use crate::wire::outbox::Frame;
use crate::ws::client::Client;
use crate::ws::protocol::{HelloFrame, event_frame, welcome_frame};
use crate::ws::writer::Feed;

/// What a `hello` frame says.
pub(super) struct Hello {
    pub(super) role: ClientRole,
    pub(super) verbs: Vec<String>,
    pub(super) robot_events: Vec<String>,
    pub(super) name: Option<String>,
    pub(super) credential: Credential,
    pub(super) events: bool,
    /// The page a reconnecting kiosk shows.
    pub(super) page: Option<String>,
    /// The language a reconnecting kiosk shows its pages in.
    pub(super) language: Option<String>,
}

impl From<HelloFrame> for Hello {
    /// A `hello` frame as sent: its credential, if any, travelled in `token`.
    fn from(frame: HelloFrame) -> Hello {
        Hello {
            role: frame.role,
            verbs: frame.verbs,
            robot_events: frame.robot_events,
            name: frame.name,
            credential: Credential::Token(frame.token),
            events: frame.events,
            page: frame.page,
            language: frame.language,
        }
    }
}

/// How a client proves its role.
pub(super) enum Credential {
    /// The credential itself (`hello.token`), checked by `Access::check`.
    Token(Option<String>),
    /// A signature made with the role's credential, verified by the transport that carried the
    /// frame (a fleet command over MQTT, `fleet::signed`): the credential never travelled.
    Signed,
}

/// A client whose `hello` was accepted: the session records its role.
pub(super) struct Admitted {
    pub(super) role: ClientRole,
    verbs: Vec<String>,
    /// The robot events an adapter may send.
    pub(super) robot_events: Vec<String>,
    name: Option<String>,
    /// Whether an operator or dialog manager asked for the event stream.
    events: bool,
    /// The page a kiosk said it shows, checked to be one of the bundle's.
    page: Option<String>,
    /// The language a kiosk said it shows its pages in, as written.
    language: Option<String>,
}

/// Why a `hello` was refused; the client was told already.
pub(super) enum Refused {
    /// The credential was missing or wrong: the connection ends after the `error` frame.
    Credential,
    /// An adapter listed no verbs nor robot events, or a bad robot event name: it may say
    /// `hello` again.
    NoVerbs,
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

/// Checks the credential the role needs and what the role must say; a refusal is answered
/// (and a refused credential logged) here.
pub(super) fn admit(client: &Client, hello: Hello) -> Result<Admitted, Refused> {
    let Hello {
        role,
        verbs,
        robot_events,
        name,
        credential,
        events,
        page,
        language,
    } = hello;
    let checked = |needed| match &credential {
        Credential::Token(token) => {
            (client.state.access).check(client.address, needed, token.as_deref())
        }
        Credential::Signed => Ok(()),
    };
    if let Some(needed) = needed(role, client.address.local)
        && let Err(refusal) = checked(needed)
    {
        log_refusal(client, role, refusal);
        client.reply_error(refusal.code(), &refusal.message(needed), None, None);
        return Err(Refused::Credential);
    }
    if role == ClientRole::Adapter && verbs.is_empty() && robot_events.is_empty() {
        client.reply_error(
            ErrorCode::NoVerbs,
            "an adapter must list the verbs it serves in \"verbs\" (or, a sensor, the robot \
             events it sends in \"robot_events\")",
            None,
            None,
        );
        return Err(Refused::NoVerbs);
    }
    if let Some(problem) = robot_events
        .iter()
        .find_map(|e| robot_event_name_problem(e))
    {
        client.reply_error(ErrorCode::BadFrame, &problem, None, None);
        return Err(Refused::NoVerbs);
    }
    let robot_events = if role == ClientRole::Adapter {
        robot_events
    } else {
        Vec::new()
    };
    let page = page.and_then(|page| shown_page(client, role, page));
    let language = language.filter(|_| kiosk_only(client, role, "language"));
    Ok(Admitted {
        role,
        verbs,
        robot_events,
        name,
        events,
        page,
        language,
    })
}

/// The page a kiosk's `hello` says it shows, if it is one of the bundle's; anything else is
/// answered with an error, and the kiosk is sent the server's page in its welcome.
fn shown_page(client: &Client, role: ClientRole, page: String) -> Option<String> {
    if !kiosk_only(client, role, "page") {
        return None;
    }
    let root = &client.state.dispatcher.bundle().root;
    if resolve_in_bundle(root, BundleArea::Pages, &page).is_err() {
        let message = format!(
            "{page:?} is not a page of this bundle: the kiosk is sent the page Docent shows"
        );
        client.reply_error(ErrorCode::UnknownPage, &message, None, None);
        return None;
    }
    Some(page)
}

/// Whether `role` may say `field` in its hello (only a kiosk says what it shows); another
/// role is told so with `bad-frame` and welcomed all the same.
fn kiosk_only(client: &Client, role: ClientRole, field: &str) -> bool {
    if role != ClientRole::Kiosk {
        let message = format!("only a kiosk says in its hello what it shows ({field:?})");
        client.reply_error(ErrorCode::BadFrame, &message, None, None);
    }
    role == ClientRole::Kiosk
}

/// Takes a reconnecting kiosk's language when nothing changed the language since this server
/// started (`Dispatcher::adopt_kiosk_language`); a language the bundle lacks is answered with
/// `unknown-language`, and the kiosk follows the welcome's language.
fn adopt_language(client: &Client, wanted: &str) {
    if let Err(refused) = client.state.dispatcher.adopt_kiosk_language(wanted) {
        client.reply_error(refused.code(), &refused.to_string(), None, None);
    }
}

/// Sends the `welcome` frame (and an operator's recent history); returns the feed the writer
/// is to follow from now on, if the role has one.
pub(super) fn welcome(client: &Client, admitted: &Admitted) -> Option<Feed> {
    let role = admitted.role;
    let state = &client.state;
    let (display, display_rx) = match &admitted.page {
        Some(page) if role == ClientRole::Kiosk => {
            let display = &state.devices.display;
            let (shown, rx, _) = display.join_kiosk_showing(client.id, page.clone());
            (shown, rx)
        }
        _ => state.devices.display.join(role, client.id),
    };
    // Subscribed before the state is read: an event (a refused save, a context change)
    // published in between then arrives after the welcome instead of falling between them.
    let events = match (role, &display_rx) {
        (ClientRole::Operator | ClientRole::Dm, None) if admitted.events => {
            Some(state.hub.subscribe_with_history())
        }
        _ => None,
    };
    if let Some(language) = &admitted.language {
        adopt_language(client, language);
    }
    let mut view = state.state_view();
    view.display = display;
    client.send(welcome_frame(client.id, role, &view));
    match (display_rx, events) {
        (Some(rx), _) => Some(Feed::Display(role, rx)),
        (None, Some((rx, history))) => {
            for event in history {
                client.outbox.send(Frame::from(event_frame(&event)));
            }
            Some(Feed::Events(rx))
        }
        (None, None) => None,
    }
}

/// Makes the welcomed client known: adapters get their verbs, everyone is listed among the
/// clients, a kiosk learns who speaks, and `client.connected` is published.
pub(super) fn join(client: &Client, admitted: Admitted) {
    let Admitted {
        role, verbs, name, ..
    } = admitted;
    let state = &client.state;
    if role == ClientRole::Adapter {
        state
            .devices
            .external
            .connect(client.id, verbs.clone(), client.outbox.clone());
        warn_unrouted(client, &verbs);
    }
    let info = ClientInfo {
        role,
        name: name.clone(),
        verbs: verbs.clone(),
    };
    state.client_joined(client.id, info, client.outbox.clone());
    if role == ClientRole::Kiosk {
        // Joined first, so every later change reaches this kiosk on its own; greeted among
        // the dispatcher's notices with who speaks, then what is being said (`ws::notices`).
        state.dispatcher.kiosk_joined(client.id);
    } else {
        let captions = state.dispatcher.bundle().config.captions;
        state.captions.tell_joined(role, captions, |frame| {
            client.outbox.send(frame);
        });
    }
    state
        .hub
        .publish(EventKind::ClientConnected(ClientConnected {
            client: client.id,
            role,
            name,
            verbs,
        }));
}

/// Logs a counted refusal, within the shared allowance; an address already waiting is
/// refused quietly, so a flood of hellos cannot flood the log.
fn log_refusal(client: &Client, role: ClientRole, refusal: Refusal) {
    if matches!(refusal, Refusal::Locked(_)) {
        return;
    }
    let Some(unlogged) = client.state.access.admit_refusal_log() else {
        return;
    };
    let address = client.address.ip.map(|p| p.to_string());
    let code = refusal.code();
    tracing::warn!(
        ?role,
        address,
        code = code.as_str(),
        unlogged,
        "websocket credential refused"
    );
    client
        .state
        .hub
        .publish(EventKind::ClientRefused(ClientRefused {
            role,
            code: code.into(),
            address,
            unlogged,
        }));
}

/// Tells an adapter, in one frame, which of its verbs this bundle sends elsewhere: it
/// will not get them.
fn warn_unrouted(client: &Client, verbs: &[String]) {
    let problems: Vec<String> = (verbs.iter())
        .filter_map(|verb| match client.state.dispatcher.adapter_for(verb) {
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
    client.reply_error(ErrorCode::VerbNotRouted, &message, None, None);
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
