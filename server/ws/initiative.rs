//! Mixed initiative and corpus marks. A dialog manager `propose`s an act; an operator
//! `accept`s it (the act is triggered on the operator's behalf) or `dismiss`es it. Operators
//! `mark` visitor sessions, the visitor group (which may set the context) and dialog
//! situations. Every outcome is an event, so the corpus tells who decided what. Nothing here
//! changes the session: each handler answers the [`Client`] it is lent.

use crate::dispatch::TriggerRequest;
use crate::events::{
    ClientRole, Consent, EventKind, NoteWritten, ProposalAccepted, ProposalDismissed, ProposalMade,
    ProposalWithdrawn, SessionEnd, SituationMarked, VisitorGroup,
};
use crate::operator::{Confirmation, ConsentRefused, Proposal, VISITOR_GROUPS};
use crate::wire::ErrorCode;
use crate::ws::client::Client;
use crate::ws::protocol::{
    MarkKind, dismissed_frame, marked_frame, proposed_frame, triggered_frame,
};

const OPERATOR: [ClientRole; 1] = [ClientRole::Operator];
const SESSION_MARKERS: [ClientRole; 2] = [ClientRole::Operator, ClientRole::Dm];

/// A dialog manager proposes an act for an operator to accept or dismiss.
pub(super) fn propose(
    client: &Client,
    role: Option<ClientRole>,
    label: String,
    context: Option<String>,
    reason: Option<String>,
    reference: Option<String>,
) {
    let reference = reference.as_deref();
    if client.allowed(role, &[ClientRole::Dm], reference).is_none() {
        return;
    }
    if let Err(e) = client.state.dispatcher.check(&label, context.as_deref()) {
        return client.reply_error(e.code(), &e.to_string(), reference, e.suggestion());
    }
    let hub = &client.state.hub;
    let announce = |p: &Proposal| {
        hub.publish(EventKind::ProposalMade(ProposalMade {
            proposal: p.proposal,
            client: p.client,
            label: p.label.clone(),
            context: p.context.clone(),
            reason: p.reason.clone(),
        }));
    };
    let made = (client.state.proposals).propose(client.id, label, context, reason, announce);
    match made {
        Ok(p) => client.send_logged(proposed_frame(reference, p.proposal), reference),
        Err(e) => client.reply_error(e.code(), &e.to_string(), reference, None),
    }
}

/// Withdraws the pending proposals of a dialog manager that left.
pub(super) fn withdraw_proposals(client: &Client) {
    for p in client.state.proposals.withdraw_from(client.id) {
        client
            .state
            .hub
            .publish(EventKind::ProposalWithdrawn(ProposalWithdrawn {
                proposal: p.proposal,
                client: p.client,
                label: p.label,
                reason: "the dialog manager left".into(),
            }));
    }
}

/// An operator accepts a proposal: its act is triggered on the operator's behalf.
pub(super) fn accept(
    client: &Client,
    role: Option<ClientRole>,
    id: u64,
    reference: Option<String>,
) {
    if client
        .allowed(role, &OPERATOR, reference.as_deref())
        .is_none()
        || !client.log_writable(reference.as_deref())
    {
        return;
    }
    let proposal = match client.state.proposals.settle(id) {
        Ok(p) => p,
        Err(e) => {
            return client.reply_error(e.code(), &e.to_string(), reference.as_deref(), None);
        }
    };
    let request = TriggerRequest {
        context: proposal.context.clone(),
        reference: reference.clone(),
        client: Some(client.id),
        ..TriggerRequest::new(proposal.label.clone(), ClientRole::Operator.source())
    };
    match client.state.dispatcher.trigger(request) {
        Ok(t) => {
            client
                .state
                .hub
                .publish(EventKind::ProposalAccepted(ProposalAccepted {
                    proposal: id,
                    client: client.id,
                    label: proposal.label,
                    trigger: t.trigger,
                }));
            // After the event, so that the acknowledgement waits for it in the log too.
            client.send_logged(triggered_frame(&t), reference.as_deref());
        }
        Err(e) => {
            // Still pending: another operator may dismiss it, or the bundle may change.
            client.state.proposals.restore(proposal);
            client.reply_error(
                e.code(),
                &e.to_string(),
                reference.as_deref(),
                e.suggestion(),
            );
        }
    }
}

/// An operator dismisses a proposal.
pub(super) fn dismiss(
    client: &Client,
    role: Option<ClientRole>,
    id: u64,
    reference: Option<String>,
) {
    let reference = reference.as_deref();
    if client.allowed(role, &OPERATOR, reference).is_none() {
        return;
    }
    match client.state.proposals.settle(id) {
        Ok(p) => {
            client
                .state
                .hub
                .publish(EventKind::ProposalDismissed(ProposalDismissed {
                    proposal: id,
                    client: client.id,
                    label: p.label,
                }));
            client.send_logged(dismissed_frame(reference, id), reference);
        }
        Err(e) => client.reply_error(e.code(), &e.to_string(), reference, None),
    }
}

/// An operator marks a visitor session, the visitor group or a dialog situation; a dialog
/// manager may mark sessions.
/// `confirmed` matters only to a consent that deletes recordings (the frame's `confirm`).
pub(super) fn mark(
    client: &Client,
    role: Option<ClientRole>,
    mark: MarkKind,
    value: Option<String>,
    confirmed: Confirmation,
    reference: Option<String>,
) {
    let reference = reference.as_deref();
    // A dialog manager may cut sessions (it knows when visitors come and go); what the
    // visitors are and what happened stays the operator's to say.
    let roles: &[ClientRole] = match mark {
        MarkKind::SessionStart | MarkKind::SessionEnd => &SESSION_MARKERS,
        MarkKind::Group | MarkKind::Situation | MarkKind::Consent | MarkKind::Note => &OPERATOR,
    };
    let Some(role) = client.allowed(role, roles, reference) else {
        return;
    };
    let (source, id) = (role.source(), client.id);
    let visits = &client.state.visits;
    let hub = &client.state.hub;
    let session = match mark {
        MarkKind::SessionStart => {
            let corpus = client.state.dispatcher.bundle().config.corpus;
            Some(visits.start(&corpus, source, Some(id)))
        }
        MarkKind::Consent => {
            let words =
                [Consent::Recorded, Consent::Declined, Consent::Withdrawn].map(Consent::as_str);
            let Some(word) = known_value(client, value.as_deref(), &words, reference) else {
                return;
            };
            let consent = Consent::from_word(word).expect("one of the words above");
            let recordings = &client.state.recordings;
            match recordings.note_consent(consent, confirmed, source, id) {
                Ok(session) => Some(session),
                Err(refused) => {
                    let code = match refused {
                        ConsentRefused::NoSession => ErrorCode::NoSession,
                        ConsentRefused::Withdrawn => ErrorCode::BadMark,
                        ConsentRefused::Unconfirmed => ErrorCode::ConfirmationRequired,
                    };
                    return client.reply_error(code, &refused.to_string(), reference, None);
                }
            }
        }
        MarkKind::SessionEnd => {
            let Some(session) = visits.end(source, Some(id), SessionEnd::Marked) else {
                let message = "no visitor session is running; start one first";
                return client.reply_error(ErrorCode::NoSession, message, reference, None);
            };
            Some(session)
        }
        MarkKind::Group => {
            let Some(group) = known_value(client, value.as_deref(), &VISITOR_GROUPS, reference)
            else {
                return;
            };
            let context = group_context(client, group);
            let session = visits.current();
            hub.publish(EventKind::VisitorGroup(VisitorGroup {
                session,
                group: group.to_owned(),
                context: context.clone(),
                source,
                client: id,
            }));
            if let Some(context) = context {
                // Known to exist: the loader checked the site's mapping.
                let _ = client.state.dispatcher.set_context(&context, source);
            }
            session
        }
        MarkKind::Situation => {
            let bundle = client.state.dispatcher.bundle();
            let names: Vec<&str> = (bundle.config.operator.situations.iter())
                .map(String::as_str)
                .collect();
            let Some(situation) = known_value(client, value.as_deref(), &names, reference) else {
                return;
            };
            let session = visits.current();
            hub.publish(EventKind::SituationMarked(SituationMarked {
                session,
                situation: situation.to_owned(),
                source,
                client: id,
            }));
            session
        }
        MarkKind::Note => {
            let Some(text) = note_text(client, value.as_deref(), reference) else {
                return;
            };
            let session = visits.current();
            hub.publish(EventKind::NoteWritten(NoteWritten {
                session,
                text: text.to_owned(),
                source,
                client: id,
            }));
            session
        }
    };
    client.send_logged(
        marked_frame(reference, mark, value.as_deref(), session),
        reference,
    );
}

/// The longest note an operator may write, in characters.
pub const NOTE_CHARS: usize = 500;

/// A note's text, trimmed, if it has 1 to [`NOTE_CHARS`] characters; otherwise answers with an
/// error saying what is wrong.
fn note_text<'a>(
    client: &Client,
    value: Option<&'a str>,
    reference: Option<&str>,
) -> Option<&'a str> {
    let text = value.map(str::trim).unwrap_or_default();
    let count = text.chars().count();
    let problem = if count == 0 {
        "a note needs its text in \"value\"".to_owned()
    } else if count > NOTE_CHARS {
        format!("a note may have at most {NOTE_CHARS} characters (this one has {count}): split it")
    } else {
        return Some(text);
    };
    client.reply_error(ErrorCode::BadMark, &problem, reference, None);
    None
}

/// The context the site maps a visitor group to, if any.
fn group_context(client: &Client, group: &str) -> Option<String> {
    let bundle = client.state.dispatcher.bundle();
    bundle.config.operator.visitor_groups.get(group).cloned()
}

/// `value` if it is one of `known`; otherwise answers with an error listing them.
fn known_value<'a>(
    client: &Client,
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
        client.reply_error(ErrorCode::BadMark, &message, reference, None);
    }
    found
}
