//! Triggering and controlling: `trigger` (kiosks, operators, dialog managers), `stop` and
//! `context` (operators, dialog managers; a kiosk's `stop` ends only visitors' speech) and
//! `page` (kiosks; leaving a page ends the speech that kiosk started). A kiosk is a visitor's
//! touchscreen: it may trigger only the acts the bundle's pages offer (and the idle act), at
//! the rate its address is allowed ([`Access::kiosk_allowance`](crate::access::Access)); every
//! refusal is an `error` frame and a `trigger.refused` event, except that a run of
//! rate-limited ones is logged once.

use std::time::Instant;

use crate::content::{BundleArea, resolve_in_bundle};
use crate::dispatch::TriggerRequest;
use crate::events::{ClientRole, EventKind, LogUnwritable};
use crate::wire::ErrorCode;
use crate::wire::outbox::Frame;
use crate::ws::connection::Session;
use crate::ws::protocol::{context_frame, stopped_frame, triggered_frame};

const TRIGGER_ROLES: [ClientRole; 3] = [ClientRole::Kiosk, ClientRole::Operator, ClientRole::Dm];
const CONTROL_ROLES: [ClientRole; 2] = [ClientRole::Operator, ClientRole::Dm];

impl Session {
    pub(super) fn trigger(
        &mut self,
        label: String,
        context: Option<String>,
        interrupt: bool,
        reference: Option<String>,
    ) {
        let Some(role) = self.allowed(&TRIGGER_ROLES, reference.as_deref()) else {
            // Once per connection: a role does not change, repeating it says nothing new.
            if self.role.is_none() || std::mem::replace(&mut self.limited_logged, true) {
                return;
            }
            return self.log_refused(
                label,
                ErrorCode::Forbidden,
                "this role may not trigger acts".into(),
            );
        };
        if role == ClientRole::Kiosk
            && let Err((code, message)) = self.kiosk_may_trigger(&label)
        {
            self.reply_error(code, &message, reference.as_deref(), None);
            if code == ErrorCode::RateLimited {
                if self.limited_logged {
                    return;
                }
                self.limited_logged = true;
            }
            return self.log_refused(label, code, message);
        }
        if !self.log_writable(reference.as_deref()) {
            return;
        }
        let request = TriggerRequest {
            label,
            context,
            interrupt,
            reference: reference.clone(),
            source: role.source(),
            client: Some(self.client),
        };
        match self.state.dispatcher.trigger(request) {
            Ok(t) => self.send_logged(triggered_frame(&t), reference.as_deref()),
            Err(e) => self.reply_error(
                e.code(),
                &e.to_string(),
                reference.as_deref(),
                e.suggestion(),
            ),
        }
    }

    /// Sends an acknowledgement once the corpus log holds every event published so far, which
    /// includes those of the action it acknowledges (see `docs/CORPUS.md`, "Guarantees").
    pub(super) fn send_logged(&self, frame: String, reference: Option<&str>) {
        let logged = self.state.hub.published_seq();
        let reference = reference.map(str::to_owned);
        self.outbox
            .send_logged(Frame::from(frame), logged, reference);
    }

    /// False, after telling the client, while the corpus log cannot be written: a trigger
    /// could not be acknowledged truthfully then.
    pub(super) fn log_writable(&self, reference: Option<&str>) -> bool {
        let Some(failure) = self.state.hub.log_failure() else {
            return true;
        };
        self.reply_error(LogUnwritable::CODE, &failure.refusal(), reference, None);
        false
    }

    /// Whether a kiosk may trigger `label` now: within its allowance, an act its pages offer.
    fn kiosk_may_trigger(&mut self, label: &str) -> Result<(), (ErrorCode, String)> {
        self.kiosk_allowance()?;
        let bundle = self.state.dispatcher.bundle();
        let offered = bundle.page_acts.iter().any(|a| a == label)
            || bundle.config.kiosk.idle_act.as_deref() == Some(label);
        if !offered {
            let message = format!(
                "no page of this bundle offers the act {label:?}, so a touchscreen may not \
                 trigger it (add data-act=\"{label}\" to a page to offer it)"
            );
            return Err((ErrorCode::NotOffered, message));
        }
        Ok(())
    }

    /// Takes one from this kiosk address's allowance (triggers and `page` reports alike).
    fn kiosk_allowance(&mut self) -> Result<(), (ErrorCode, String)> {
        if let Err(wait) = self.state.access.kiosk_allowance(self.peer, Instant::now()) {
            let message = format!(
                "too many requests from this touchscreen; the next is possible in {} ms",
                wait.as_millis().max(1)
            );
            return Err((ErrorCode::RateLimited, message));
        }
        self.limited_logged = false;
        Ok(())
    }

    /// Records a trigger this client may not make.
    fn log_refused(&self, label: String, code: ErrorCode, message: String) {
        let Some(role) = self.role else { return };
        self.state.hub.publish(EventKind::TriggerRefused {
            source: role.source(),
            client: Some(self.client),
            label,
            code,
            message,
        });
    }

    pub(super) fn stop(&self, reference: Option<String>) {
        // A visitor may stop the speech visitors started, never anyone else's.
        if self.role == Some(ClientRole::Kiosk) {
            self.state.dispatcher.stop_visitor_speech(self.client);
            return self.send(stopped_frame(reference.as_deref()));
        }
        let Some(role) = self.allowed(&CONTROL_ROLES, reference.as_deref()) else {
            return;
        };
        // Never refused for the log: stopping the robot must always work.
        self.state.dispatcher.stop(role.source(), "stop request");
        self.send_logged(stopped_frame(reference.as_deref()), reference.as_deref());
    }

    pub(super) fn set_context(&self, context: String, reference: Option<String>) {
        let Some(role) = self.allowed(&CONTROL_ROLES, reference.as_deref()) else {
            return;
        };
        match self.state.dispatcher.set_context(&context, role.source()) {
            Ok(()) => self.send_logged(
                context_frame(reference.as_deref(), &context),
                reference.as_deref(),
            ),
            Err(e) => self.reply_error(
                e.code(),
                &e.to_string(),
                reference.as_deref(),
                e.suggestion(),
            ),
        }
    }

    /// A kiosk reports a page it shows on its own, so the server's display state (what a
    /// reconnecting kiosk is sent back to, what the log says) stays true.
    pub(super) fn page_shown(&mut self, page: String) {
        if self.allowed(&[ClientRole::Kiosk], None).is_none() {
            return;
        }
        // Before the allowance: leaving a page ends its speech even for a hasty visitor.
        self.state.dispatcher.page_left(self.client, &page);
        if let Err((code, message)) = self.kiosk_allowance() {
            return self.reply_error(code, &message, None, None);
        }
        let root = &self.state.dispatcher.bundle().root;
        if resolve_in_bundle(root, BundleArea::Pages, &page).is_err() {
            let message = format!("{page:?} is not a page of this bundle");
            return self.reply_error(ErrorCode::UnknownPage, &message, None, None);
        }
        self.state.devices.display.page_shown(page, &self.state.hub);
    }
}
