//! `attract` frames: a kiosk tells that its attract loop began or ended. Both are logged
//! (`attract.started`, `attract.ended`) and so reach the operators' consoles; the touch that
//! ends a loop is a visitor's first touch and is handled as one (a `touch` event, a session
//! started when none runs), while the loop's own pages and act never start a session.

use crate::access::KioskAllowance;
use crate::events::{
    AttractEnd, AttractEnded, AttractStarted, AttractState, ClientRole, EventKind, Touch,
};
use crate::wire::ErrorCode;
use crate::ws::client::Client;
use crate::ws::triggers::kiosk_allowance;

/// The element a touch that ends the loop is described as, in the `touch` event.
const ENDING_TOUCH: &str = "the attract loop";

/// Logs a kiosk's attract loop report; other roles are refused.
pub(super) fn reported(
    client: &Client,
    role: Option<ClientRole>,
    state: AttractState,
    by: Option<AttractEnd>,
) {
    if client.allowed(role, &[ClientRole::Kiosk], None).is_none() {
        return;
    }
    // From the kiosk's allowance for the shell's own doing: a faulty kiosk cannot flood the
    // log, and a loop that cycled fast cannot spend the taps of the visitor who ends it.
    if let Err(message) = kiosk_allowance(client, KioskAllowance::Shell) {
        return client.reply_error(ErrorCode::RateLimited, &message, None, None);
    }
    let hub = &client.state.hub;
    let by = match (state, by) {
        (AttractState::Started, _) => {
            hub.publish(EventKind::AttractStarted(AttractStarted {
                client: client.id,
            }));
            return;
        }
        (AttractState::Ended, Some(by)) => by,
        (AttractState::Ended, None) => {
            let message = "an attract frame with state \"ended\" says what ended the loop: \
                           \"by\": \"touch\", \"robot\" or \"schedule\"";
            return client.reply_error(ErrorCode::BadFrame, message, None, None);
        }
    };
    hub.publish(EventKind::AttractEnded(AttractEnded {
        client: client.id,
        by,
    }));
    if by == AttractEnd::Touch {
        let corpus = client.state.dispatcher.bundle().config.corpus;
        client.state.visits.touched(&corpus, client.id);
        hub.publish(EventKind::Touch(Touch {
            client: client.id,
            page: client.state.devices.display.snapshot().page,
            element: Some(ENDING_TOUCH.to_owned()),
            act: None,
            link: None,
        }));
    }
}
