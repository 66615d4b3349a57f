//! `robot` frames: an adapter process on the robot tells of something its sensors noticed
//! (a person close by, a bumper, a battery), by a name it declared in its `hello`. The event
//! is logged and reaches operators and dialog managers; one the site lists in
//! `corpus: session_start_events` first starts a visitor session when none runs, so that a
//! robot that notices its visitors before they touch anything records them from the start.

use crate::events::ClientRole;
use crate::robot::{RobotNotice, RobotOrigin};
use crate::wire::ErrorCode;
use crate::ws::client::Client;

/// The most bytes of `data` a robot event may carry, as JSON: a sensor's reading, not a
/// recording.
pub const ROBOT_DATA_BYTES: usize = 4096;

/// Logs robot event `event` from an adapter that declared it in `declared`; anything else is
/// answered with an `error` frame saying why.
pub(super) fn noticed(
    client: &Client,
    role: Option<ClientRole>,
    declared: &[String],
    event: String,
    data: serde_json::Value,
) {
    if client.allowed(role, &[ClientRole::Adapter], None).is_none() {
        return;
    }
    if !declared.contains(&event) {
        let message = format!(
            "robot event {event:?} was not declared: list it in this adapter's hello \
             \"robot_events\" (declared: {})",
            if declared.is_empty() {
                "none".to_owned()
            } else {
                declared.join(", ")
            }
        );
        return client.reply_error(ErrorCode::BadFrame, &message, None, None);
    }
    let size = serde_json::to_vec(&data).map_or(usize::MAX, |d| d.len());
    if size > ROBOT_DATA_BYTES {
        let message = format!(
            "a robot event's \"data\" may have at most {ROBOT_DATA_BYTES} bytes of JSON \
             (this one has {size}): send a reading, not a recording"
        );
        return client.reply_error(ErrorCode::BadFrame, &message, None, None);
    }
    if !client.log_writable(None) {
        return;
    }
    let notice = RobotNotice {
        event,
        data,
        origin: RobotOrigin::Adapter { client: client.id },
    };
    crate::robot::notice(&client.state, notice);
}
