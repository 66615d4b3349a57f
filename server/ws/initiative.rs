//! Mixed initiative and corpus marks. A dialog manager `propose`s an act; an operator
//! `accept`s it (the act is triggered on the operator's behalf) or `dismiss`es it. Operators
//! `mark` visitor sessions, the visitor group (which may set the context) and dialog
//! situations. Every outcome is an event, so the corpus tells who decided what.

use crate::dispatch::TriggerRequest;
use crate::events::{ClientRole, EventKind};
use crate::operator::{Proposal, VISITOR_GROUPS};
use crate::wire::ErrorCode;
use crate::ws::connection::Session;
use crate::ws::protocol::{
    MarkKind, dismissed_frame, marked_frame, proposed_frame, triggered_frame,
};

const OPERATOR: [ClientRole; 1] = [ClientRole::Operator];

impl Session {
    pub(super) fn propose(
        &self,
        label: String,
        context: Option<String>,
        reason: Option<String>,
        reference: Option<String>,
    ) {
        let reference = reference.as_deref();
        if self.allowed(&[ClientRole::Dm], reference).is_none() {
            return;
        }
        if let Err(e) = self.state.dispatcher.check(&label, context.as_deref()) {
            return self.reply_error(e.code(), &e.to_string(), reference, e.suggestion());
        }
        let hub = &self.state.hub;
        let announce = |p: &Proposal| {
            hub.publish(EventKind::ProposalMade {
                proposal: p.proposal,
                client: p.client,
                label: p.label.clone(),
                context: p.context.clone(),
                reason: p.reason.clone(),
            });
        };
        let made = (self.state.proposals).propose(self.client, label, context, reason, announce);
        match made {
            Ok(p) => self.send_logged(proposed_frame(reference, p.proposal), reference),
            Err(e) => self.reply_error(e.code(), &e.to_string(), reference, None),
        }
    }

    /// Withdraws the pending proposals of a dialog manager that left.
    pub(super) fn withdraw_proposals(&self) {
        for p in self.state.proposals.withdraw_from(self.client) {
            self.state.hub.publish(EventKind::ProposalWithdrawn {
                proposal: p.proposal,
                client: p.client,
                label: p.label,
                reason: "the dialog manager left".into(),
            });
        }
    }

    pub(super) fn accept(&self, id: u64, reference: Option<String>) {
        if self.allowed(&OPERATOR, reference.as_deref()).is_none()
            || !self.log_writable(reference.as_deref())
        {
            return;
        }
        let proposal = match self.state.proposals.settle(id) {
            Ok(p) => p,
            Err(e) => {
                return self.reply_error(e.code(), &e.to_string(), reference.as_deref(), None);
            }
        };
        let request = TriggerRequest {
            context: proposal.context.clone(),
            reference: reference.clone(),
            client: Some(self.client),
            ..TriggerRequest::new(proposal.label.clone(), ClientRole::Operator.source())
        };
        match self.state.dispatcher.trigger(request) {
            Ok(t) => {
                self.state.hub.publish(EventKind::ProposalAccepted {
                    proposal: id,
                    client: self.client,
                    label: proposal.label,
                    trigger: t.trigger,
                });
                // After the event, so that the acknowledgement waits for it in the log too.
                self.send_logged(triggered_frame(&t), reference.as_deref());
            }
            Err(e) => {
                // Still pending: another operator may dismiss it, or the bundle may change.
                self.state.proposals.restore(proposal);
                self.reply_error(
                    e.code(),
                    &e.to_string(),
                    reference.as_deref(),
                    e.suggestion(),
                );
            }
        }
    }

    pub(super) fn dismiss(&self, id: u64, reference: Option<String>) {
        let reference = reference.as_deref();
        if self.allowed(&OPERATOR, reference).is_none() {
            return;
        }
        match self.state.proposals.settle(id) {
            Ok(p) => {
                self.state.hub.publish(EventKind::ProposalDismissed {
                    proposal: id,
                    client: self.client,
                    label: p.label,
                });
                self.send_logged(dismissed_frame(reference, id), reference);
            }
            Err(e) => self.reply_error(e.code(), &e.to_string(), reference, None),
        }
    }

    pub(super) fn mark(&self, mark: MarkKind, value: Option<String>, reference: Option<String>) {
        let reference = reference.as_deref();
        let Some(role) = self.allowed(&OPERATOR, reference) else {
            return;
        };
        let (source, client) = (role.source(), self.client);
        let visits = &self.state.visits;
        let hub = &self.state.hub;
        let session = match mark {
            MarkKind::SessionStart => {
                let (ended, session) = visits.start();
                if let Some(ended) = ended {
                    hub.publish(EventKind::SessionEnded {
                        session: ended,
                        source,
                        client,
                    });
                }
                hub.publish(EventKind::SessionStarted {
                    session,
                    source,
                    client,
                });
                Some(session)
            }
            MarkKind::SessionEnd => {
                let Some(session) = visits.end() else {
                    let message = "no visitor session is running; start one first";
                    return self.reply_error(ErrorCode::NoSession, message, reference, None);
                };
                hub.publish(EventKind::SessionEnded {
                    session,
                    source,
                    client,
                });
                Some(session)
            }
            MarkKind::Group => {
                let Some(group) = self.known_value(value.as_deref(), &VISITOR_GROUPS, reference)
                else {
                    return;
                };
                let context = self.group_context(group);
                let session = visits.current();
                hub.publish(EventKind::VisitorGroup {
                    session,
                    group: group.to_owned(),
                    context: context.clone(),
                    source,
                    client,
                });
                if let Some(context) = context {
                    // Known to exist: the loader checked the site's mapping.
                    let _ = self.state.dispatcher.set_context(&context, source);
                }
                session
            }
            MarkKind::Situation => {
                let bundle = self.state.dispatcher.bundle();
                let names: Vec<&str> = (bundle.config.operator.situations.iter())
                    .map(String::as_str)
                    .collect();
                let Some(situation) = self.known_value(value.as_deref(), &names, reference) else {
                    return;
                };
                let session = visits.current();
                hub.publish(EventKind::SituationMarked {
                    session,
                    situation: situation.to_owned(),
                    source,
                    client,
                });
                session
            }
        };
        self.send_logged(
            marked_frame(reference, mark, value.as_deref(), session),
            reference,
        );
    }

    /// The context the site maps a visitor group to, if any.
    fn group_context(&self, group: &str) -> Option<String> {
        let bundle = self.state.dispatcher.bundle();
        bundle.config.operator.visitor_groups.get(group).cloned()
    }

    /// `value` if it is one of `known`; otherwise answers with an error listing them.
    fn known_value<'a>(
        &self,
        value: Option<&str>,
        known: &[&'a str],
        reference: Option<&str>,
    ) -> Option<&'a str> {
        let found = value.and_then(|v| known.iter().find(|k| **k == v).copied());
        if found.is_none() {
            let message = format!(
                "\"value\" must be one of: {} (got {})",
                known.join(", "),
                value.map_or_else(|| "nothing".to_owned(), |v| format!("{v:?}"))
            );
            self.reply_error(ErrorCode::BadMark, &message, reference, None);
        }
        found
    }
}
