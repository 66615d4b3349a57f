//! Triggering and controlling: `trigger` (kiosks, operators, dialog managers), `stop` and
//! `context` (operators, dialog managers; a kiosk's `stop` ends only visitors' speech) and
//! `page` (kiosks; leaving a page ends the speech that kiosk started). A kiosk is a visitor's
//! touchscreen: it may trigger only the acts the bundle's pages offer (and the idle act), at
//! the rate its address is allowed ([`Access::kiosk_allowance`](crate::access::Access)); every
//! refusal is an `error` frame and a `trigger.refused` event, except that a run of
//! rate-limited ones is logged once. Whether the current run was logged is the session's to
//! remember: these handlers are told it and return what became of the run ([`RefusedRun`]).

use std::time::Instant;

use crate::access::KioskAllowance;
use crate::content::{Bundle, BundleArea, resolve_in_bundle};
use crate::dispatch::{Answer, TriggerRequest};
use crate::events::{ClientRole, EventKind, KioskCause, Touch, element_description};
use crate::wire::ErrorCode;
use crate::ws::client::Client;
use crate::ws::protocol::{
    TriggerFrame, context_frame, language_frame, stopped_frame, triggered_frame,
};

const TRIGGER_ROLES: [ClientRole; 3] = [ClientRole::Kiosk, ClientRole::Operator, ClientRole::Dm];
const CONTROL_ROLES: [ClientRole; 2] = [ClientRole::Operator, ClientRole::Dm];

/// What a frame did to the client's run of refused triggers, which is logged once (one
/// `trigger.refused` per run, so a flood cannot flood the corpus). The session records it.
#[derive(Debug, PartialEq, Eq)]
pub(super) enum RefusedRun {
    /// Nothing to record: no refusal was logged and the run, if any, goes on.
    Unchanged,
    /// A refusal was logged: later ones of the same run are not.
    Logged,
    /// The kiosk was within its allowance: the run (if any) is over.
    Over,
}

/// Triggers an act for the client, if its role and (for a kiosk) its allowance and the pages
/// allow; `run_logged` says whether the client's current run of refusals was logged already.
pub(super) fn trigger(
    client: &Client,
    role: Option<ClientRole>,
    trigger: TriggerFrame,
    run_logged: bool,
) -> RefusedRun {
    let TriggerFrame {
        label,
        context,
        interrupt,
        reference,
        via,
        element,
    } = trigger;
    let Some(allowed) = client.allowed(role, &TRIGGER_ROLES, reference.as_deref()) else {
        // Once per connection: a role does not change, repeating it says nothing new.
        let Some(role) = role else {
            return RefusedRun::Unchanged;
        };
        if run_logged {
            return RefusedRun::Unchanged;
        }
        let message = "this role may not trigger acts".into();
        log_refused(client, role, label, ErrorCode::Forbidden, message);
        return RefusedRun::Logged;
    };
    // One bundle for the whole request: its checks here and the trigger itself.
    let bundle = client.state.dispatcher.bundle();
    let mut run = RefusedRun::Unchanged;
    if allowed == ClientRole::Kiosk {
        if let Err(message) = kiosk_allowance(client, KioskAllowance::Visitor) {
            let code = ErrorCode::RateLimited;
            client.reply_error(code, &message, reference.as_deref(), None);
            if run_logged {
                return RefusedRun::Unchanged;
            }
            log_refused(client, allowed, label, code, message);
            return RefusedRun::Logged;
        }
        run = RefusedRun::Over;
        let touch = KioskCause::is_touch(via).then(|| Touched {
            element: element_description(element),
            act: Some(label.clone()),
            link: None,
        });
        if let Err(message) = offered(&bundle, &label) {
            let code = ErrorCode::NotOffered;
            client.reply_error(code, &message, reference.as_deref(), None);
            if let Some(touch) = touch {
                touch.log(client, None);
            }
            log_refused(client, allowed, label, code, message);
            return run;
        }
        if !client.log_writable(reference.as_deref()) {
            return run;
        }
        if let Some(touch) = touch {
            // Before the trigger's events, so that they are in the session it starts.
            let page = client.state.devices.display.snapshot().page;
            client
                .state
                .visits
                .touched(&bundle.config.corpus, client.id);
            touch.log(client, page);
        }
    } else if !client.log_writable(reference.as_deref()) {
        return run;
    }
    let request = TriggerRequest {
        label,
        context,
        interrupt,
        reference: reference.clone(),
        source: allowed.source(),
        client: Some(client.id),
    };
    match client.state.dispatcher.trigger_in(bundle, request) {
        Ok(t) => client.send_logged(triggered_frame(&t), reference.as_deref()),
        Err(e) => client.reply_error(
            e.code(),
            &e.to_string(),
            reference.as_deref(),
            e.suggestion(),
        ),
    }
    run
}

/// Whether a kiosk may trigger `label`: an act its pages offer, the idle act or an attract
/// loop's act.
fn offered(bundle: &Bundle, label: &str) -> Result<(), String> {
    let offered = bundle.page_acts.iter().any(|a| a == label)
        || bundle.config.kiosk_own_acts().any(|a| a == label);
    if !offered {
        return Err(format!(
            "no page of this bundle offers the act {label:?}, so a touchscreen may not \
             trigger it (add data-act=\"{label}\" to a page to offer it)"
        ));
    }
    Ok(())
}

/// Takes one from this kiosk address's `which` allowance (triggers and `page` reports); the
/// error is the `rate-limited` message.
pub(super) fn kiosk_allowance(client: &Client, which: KioskAllowance) -> Result<(), String> {
    let allowance = client
        .state
        .access
        .kiosk_allowance(client.address.ip, which, Instant::now());
    allowance.map_err(|wait| {
        format!(
            "too many requests from this touchscreen; the next is possible in {} ms",
            wait.as_millis().max(1)
        )
    })
}

/// Records a trigger this client may not make.
fn log_refused(client: &Client, role: ClientRole, label: String, code: ErrorCode, message: String) {
    client.state.hub.publish(EventKind::TriggerRefused {
        source: role.source(),
        client: Some(client.id),
        label,
        code: code.into(),
        message,
    });
}

/// Stops the robot for an operator or a dialog manager; a kiosk stops only visitors' speech.
pub(super) fn stop(client: &Client, role: Option<ClientRole>, reference: Option<String>) {
    // A visitor may stop the speech visitors started, never anyone else's.
    if role == Some(ClientRole::Kiosk) {
        // A visitor's tap, logged as a `stop`: from the visitor's allowance like any other.
        if let Err(message) = kiosk_allowance(client, KioskAllowance::Visitor) {
            let code = ErrorCode::RateLimited;
            return client.reply_error(code, &message, reference.as_deref(), None);
        }
        client.state.dispatcher.stop_visitor_speech(client.id);
        return client.send(stopped_frame(reference.as_deref()));
    }
    let Some(role) = client.allowed(role, &CONTROL_ROLES, reference.as_deref()) else {
        return;
    };
    // Never refused for the log: stopping the robot must always work.
    client.state.dispatcher.stop(role.source(), "stop request");
    client.send_logged(stopped_frame(reference.as_deref()), reference.as_deref());
}

/// Sets the context acts are chosen in.
pub(super) fn set_context(
    client: &Client,
    role: Option<ClientRole>,
    context: String,
    reference: Option<String>,
) {
    let Some(role) = client.allowed(role, &CONTROL_ROLES, reference.as_deref()) else {
        return;
    };
    match client.state.dispatcher.set_context(&context, role.source()) {
        Ok(()) => client.send_logged(
            context_frame(reference.as_deref(), &context),
            reference.as_deref(),
        ),
        Err(e) => client.reply_error(
            e.code(),
            &e.to_string(),
            reference.as_deref(),
            e.suggestion(),
        ),
    }
}

/// Sets the visitor's language: operators and dialog managers any of the bundle's, a kiosk
/// only one a button on the page it shows offers (as with `data-act`).
pub(super) fn set_language(
    client: &Client,
    role: Option<ClientRole>,
    language: &str,
    reference: Option<String>,
) {
    let Some(role) = client.allowed(role, &TRIGGER_ROLES, reference.as_deref()) else {
        return;
    };
    let page = client.state.devices.display.snapshot().page;
    if role == ClientRole::Kiosk {
        // A visitor's tap on a language button: from the visitor's allowance, and a touch
        // like any other, so that the session it starts holds the choice of language.
        if let Err(message) = kiosk_allowance(client, KioskAllowance::Visitor) {
            let code = ErrorCode::RateLimited;
            return client.reply_error(code, &message, reference.as_deref(), None);
        }
        let corpus = client.state.dispatcher.bundle().config.corpus;
        client.state.visits.touched(&corpus, client.id);
        let touch = Touched {
            element: Some(format!("the language button {language:?}")),
            act: None,
            link: None,
        };
        touch.log(client, page.clone());
    }
    let dispatcher = &client.state.dispatcher;
    // A kiosk is one of the screens every change is told to: it is answered among the
    // dispatcher's notices, after that notice (`ws::notices`). Others are answered here, before
    // the `language.changed` event in their event stream.
    let screen = role == ClientRole::Kiosk;
    let answer = screen.then(|| Answer {
        client: client.id,
        reference: reference.clone(),
    });
    match dispatcher.set_language(language, role.source(), page.as_deref(), answer) {
        Ok(_) if screen => {}
        Ok(language) => client.send_logged(
            language_frame(reference.as_deref(), &language),
            reference.as_deref(),
        ),
        Err(e) => client.reply_error(e.code(), &e.to_string(), reference.as_deref(), None),
    }
}

/// A kiosk reports a page it shows on its own, so the server's display state (what a
/// reconnecting kiosk is sent back to, what the log says) stays true. It takes from the same
/// allowance as triggers, so one within it ends a run of refused triggers.
pub(super) fn page_shown(
    client: &Client,
    role: Option<ClientRole>,
    page: String,
    via: Option<KioskCause>,
    element: Option<String>,
) -> RefusedRun {
    if client.allowed(role, &[ClientRole::Kiosk], None).is_none() {
        return RefusedRun::Unchanged;
    }
    // Before the allowance: leaving a page ends its speech even for a hasty visitor.
    client.state.dispatcher.page_left(client.id, &page);
    // The shell's own pages (attract loop, schedule, idle return) from the shell's allowance.
    let which = match via {
        Some(KioskCause::Attract | KioskCause::Schedule | KioskCause::Idle) => {
            KioskAllowance::Shell
        }
        _ => KioskAllowance::Visitor,
    };
    if let Err(message) = kiosk_allowance(client, which) {
        client.reply_error(ErrorCode::RateLimited, &message, None, None);
        return RefusedRun::Unchanged;
    }
    let root = &client.state.dispatcher.bundle().root;
    if resolve_in_bundle(root, BundleArea::Pages, &page).is_err() {
        let message = format!("{page:?} is not a page of this bundle");
        client.reply_error(ErrorCode::UnknownPage, &message, None, None);
        return RefusedRun::Over;
    }
    let display = &client.state.devices.display;
    if KioskCause::is_touch(via) {
        let touched = Touched {
            element: element_description(element),
            act: None,
            link: Some(page.clone()),
        };
        let from = display.snapshot().page;
        let corpus = client.state.dispatcher.bundle().config.corpus;
        client.state.visits.touched(&corpus, client.id);
        touched.log(client, from);
    }
    display.page_shown(page, &client.state.hub);
    RefusedRun::Over
}

/// A visitor's touch, logged as a `touch` before what it caused.
struct Touched {
    element: Option<String>,
    act: Option<String>,
    link: Option<String>,
}

impl Touched {
    /// Logs the touch on `page`, the page the server's display state has the kiosk on.
    fn log(self, client: &Client, page: Option<String>) {
        client.state.hub.publish(EventKind::Touch(Touch {
            client: client.id,
            page,
            element: self.element,
            act: self.act,
            link: self.link,
        }));
    }
}
