//! What the dispatcher tells clients outside an answer: an `outcome` frame to the client that
//! triggered a command which was cancelled or failed (so a kiosk never waits for speech that
//! will not come), and a `speaking` frame to every kiosk when speech starts or stops (so a
//! page can show it, and offer visitors a stop button for their own speech only).

use crate::adapters::{Command, Outcome};
use crate::dispatch::{Notifier, Speaking};
use crate::events::ClientRole;
use crate::state::ClientLinks;
use crate::wire::outbox::Frame;
use crate::ws::protocol::{
    NotCarriedOut, OutcomeFrame, language_frame, outcome_frame, speaking_frame,
};

/// The websocket side of the dispatcher's [`Notifier`].
pub struct ClientNotices {
    links: ClientLinks,
}

impl ClientNotices {
    /// Notices sent through `links`.
    pub fn new(links: ClientLinks) -> Self {
        ClientNotices { links }
    }
}

impl Notifier for ClientNotices {
    fn outcome(&self, client: u64, command: &Command, outcome: &Outcome, ended_by_visitor: bool) {
        let (kind, reason) = match outcome {
            Outcome::Cancelled(reason) => (NotCarriedOut::Cancelled, reason),
            Outcome::Failed(reason) => (NotCarriedOut::Failed, reason),
            Outcome::Done => return,
        };
        let frame = Frame::from(outcome_frame(&OutcomeFrame {
            command: command.id,
            trigger: command.act.trigger,
            reference: command.act.reference.as_deref(),
            label: &command.act.label,
            verb: command.verb.as_str(),
            outcome: kind,
            reason,
            ended_by_visitor,
        }));
        // A client that has left learns nothing; the corpus has the outcome either way. Not
        // an answer: it rides along with the client's next frames (within 2 ms).
        self.links.send_lingering_to(client, &frame);
    }

    fn speaking(&self, now: Option<Speaking>) {
        let frame = Frame::from(speaking_frame(now));
        self.links.send_to_role(ClientRole::Kiosk, &frame);
    }

    fn language(&self, language: &crate::content::Language) {
        let frame = Frame::from(language_frame(None, language));
        self.links.send_to_role(ClientRole::Kiosk, &frame);
        self.links.send_to_role(ClientRole::Projector, &frame);
    }
}
