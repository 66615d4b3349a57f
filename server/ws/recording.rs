//! A kiosk's frames about recording (`docs/PROTOCOL.md`, "Recording"): `clock`, answered at
//! once with the hub's clock so the kiosk can place its recordings' first samples on it, and
//! its reports on the recordings it was asked for (`recording-started`, `-stopped`,
//! `-failed`), handed to [`crate::recording::Recordings`]. The reports that are logged and
//! shown on every console (`recording-started`, `recording-failed`) take from the kiosk
//! address's recording allowance; `recording-stopped` only ever closes the kiosk's own open
//! recording, so it is never refused.

use crate::access::KioskAllowance;
use crate::events::{ClientRole, FailureCode};
use crate::recording::clock_frame;
use crate::wire::ErrorCode;
use crate::ws::client::Client;
use crate::ws::triggers::kiosk_allowance;

const KIOSK: [ClientRole; 1] = [ClientRole::Kiosk];

/// `clock`: answered at once, not through the log (nothing is acknowledged).
pub(super) fn clock(client: &Client, role: Option<ClientRole>, t0: f64) {
    if client.allowed(role, &KIOSK, None).is_some() {
        client.send(clock_frame(t0, client.state.hub.mono_us()));
    }
}

/// `recording-started`: `recording.started` places the recording on the session clock.
pub(super) fn started(
    client: &Client,
    role: Option<ClientRole>,
    recording: u64,
    mime: &str,
    mono_us: u64,
    clock_error_us: u64,
) {
    if !allowed(client, role) {
        return;
    }
    let recordings = &client.state.recordings;
    if !recordings.started(client.id, recording, mime, mono_us, clock_error_us) {
        // Stopped or withdrawn meanwhile: the kiosk learns it from its next upload (410).
        tracing::debug!(recording, "a kiosk reported a recording that is not open");
    }
}

/// `recording-stopped`: the last chunk is uploaded; `recording.stopped` says what it holds.
pub(super) fn stopped(client: &Client, role: Option<ClientRole>, recording: u64) {
    if client.allowed(role, &KIOSK, None).is_some() {
        client.state.recordings.kiosk_stopped(client.id, recording);
    }
}

/// `recording-failed`: logged, and told to operators at once.
pub(super) fn failed(
    client: &Client,
    role: Option<ClientRole>,
    recording: Option<u64>,
    code: FailureCode,
    message: &str,
) {
    if allowed(client, role) {
        let message = if message.is_empty() {
            "the kiosk gave no details"
        } else {
            message
        };
        client
            .state
            .recordings
            .failed(client.id, recording, code, message);
    }
}

/// Whether a kiosk may send a logged recording report now: its role, then its address's
/// recording allowance (`rate-limited` beyond it).
fn allowed(client: &Client, role: Option<ClientRole>) -> bool {
    if client.allowed(role, &KIOSK, None).is_none() {
        return false;
    }
    match kiosk_allowance(client, KioskAllowance::Recording) {
        Ok(()) => true,
        Err(message) => {
            client.reply_error(ErrorCode::RateLimited, &message, None, None);
            false
        }
    }
}
