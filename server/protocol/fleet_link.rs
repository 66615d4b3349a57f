//! Whether a robot's link to the fleet's MQTT broker is up, as the `fleet.link` event and
//! operators show it.

use serde::{Deserialize, Serialize};

/// Whether the link to the broker is up, as operators are shown it.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Eq)]
pub struct LinkView {
    /// The broker, without any login.
    pub broker: String,
    /// `connecting`, `up` or `down`.
    pub state: LinkState,
    /// Why it is down.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
}

/// The state of a broker link.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum LinkState {
    /// Not connected yet.
    Connecting,
    /// Connected (the broker acknowledged).
    Up,
    /// Lost or refused; reconnecting.
    Down,
}
