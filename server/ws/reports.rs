//! A device's report on a command it was sent (`started`, `done`, `failed`): kiosks and
//! projectors report on what they were sent to show, external adapters on the commands they
//! serve. The report goes to whoever waits for it; an adapter answering a command it does not
//! owe is told so.

use crate::adapters::{Outcome, ScreenReport};
use crate::events::ClientRole;
use crate::wire::ErrorCode;
use crate::ws::client::Client;

/// The roles that are sent commands, so the only ones that report on them.
const REPORTING_ROLES: [ClientRole; 3] = [
    ClientRole::Adapter,
    ClientRole::Projector,
    ClientRole::Kiosk,
];

/// Passes the client's report on command `id` to the display or the external adapters.
pub(super) fn report(client: &Client, role: Option<ClientRole>, id: u64, report: ScreenReport) {
    let Some(role) = client.allowed(role, &REPORTING_ROLES, None) else {
        return;
    };
    let state = &client.state;
    if role != ClientRole::Adapter {
        // Kiosks and projectors report on what they were sent to show.
        return state.devices.display.report(role, client.id, id, report);
    }
    let external = &state.devices.external;
    let result = match report {
        ScreenReport::Started => external.started(client.id, id),
        ScreenReport::Done { .. } => external.answer(client.id, id, Outcome::Done),
        ScreenReport::Failed(reason) => external.answer(client.id, id, Outcome::Failed(reason)),
    };
    if let Err(e) = result {
        client.reply_error(ErrorCode::UnknownCommand, &e.to_string(), None, None);
    }
}
