//! What the dispatcher tells clients outside an answer, delivered: an `outcome` frame to the
//! client that triggered a command which was cancelled or failed (so a kiosk never waits for
//! speech that will not come), a `speaking` frame to every kiosk when speech starts or stops
//! (so a page can show it, and offer visitors a stop button for their own speech only), and a
//! `language` frame to the screens when the visitor's language changes. The dispatcher queues
//! [`Notice`]s in the order it decided them; this task sends them in that order, and greets a
//! kiosk that joined with who speaks, then what is being said.

use std::sync::Arc;

use tokio::sync::mpsc;
use tokio_util::sync::CancellationToken;

use crate::adapters::Outcome;
use crate::content::config::CaptionSettings;
use crate::dispatch::{Answer, Notice, Speaking};
use crate::events::ClientRole;
use crate::state::ClientLinks;
use crate::wire::outbox::Frame;
use crate::ws::Captions;
use crate::ws::protocol::{
    NotCarriedOut, OutcomeFrame, language_frame, outcome_frame, speaking_frame,
};

/// Delivers `notices` through `links` until `shutdown`; `captions` and `settings` (the live
/// bundle's `captions:`) greet a joining kiosk with the caption in force.
pub async fn deliver(
    mut notices: mpsc::UnboundedReceiver<Notice>,
    links: ClientLinks,
    captions: Arc<Captions>,
    settings: impl Fn() -> CaptionSettings,
    shutdown: CancellationToken,
) {
    // Who speaks, as the kiosks were last told: what a joining kiosk is told first.
    let mut speaking: Option<Speaking> = None;
    loop {
        let notice = tokio::select! {
            notice = notices.recv() => notice,
            () = shutdown.cancelled() => return,
        };
        let Some(notice) = notice else { return };
        match notice {
            Notice::NotCarriedOut {
                client,
                command,
                outcome,
                ended_by_visitor,
            } => {
                let (kind, reason) = match &outcome {
                    Outcome::Cancelled(reason) => (NotCarriedOut::Cancelled, reason),
                    Outcome::Failed(reason) => (NotCarriedOut::Failed, reason),
                    Outcome::Done => continue,
                };
                let frame = outcome_frame(&OutcomeFrame {
                    command: command.id,
                    trigger: command.act.trigger,
                    reference: command.act.reference.as_deref(),
                    label: &command.act.label,
                    verb: command.verb.as_str(),
                    outcome: kind,
                    reason,
                    ended_by_visitor,
                });
                // A client that has left learns nothing; the corpus has the outcome either
                // way. Not an answer: it rides along with the client's next frames (within
                // 2 ms).
                links.send_lingering_to(client, &Frame::from(frame));
            }
            Notice::Speaking(now) => {
                speaking = now;
                let frame = Frame::from(speaking_frame(now));
                links.send_to_role(ClientRole::Kiosk, &frame);
            }
            Notice::Language {
                language,
                seq,
                answer,
            } => {
                let frame = Frame::from(language_frame(None, &language));
                links.send_to_role(ClientRole::Kiosk, &frame);
                links.send_to_role(ClientRole::Projector, &frame);
                // Then the one who asked: its answer acknowledges the logged change.
                if let Some(Answer { client, reference }) = answer {
                    let frame = Frame::from(language_frame(reference.as_deref(), &language));
                    links.send_logged_to(client, frame, seq, reference);
                }
            }
            Notice::KioskJoined(client) => {
                // Sent when nothing speaks too: a shell that reconnects after a restart must
                // drop what it knew. Then what is being said: who speaks, then what.
                links.send_to(client, &Frame::from(speaking_frame(speaking)));
                captions.tell_joined(ClientRole::Kiosk, settings(), |frame| {
                    links.send_to(client, &frame);
                });
            }
        }
    }
}
