//! A fleet over MQTT (docs/FLEET.md): many robots' Docents point at one broker (mosquitto, or a
//! clustered one such as EMQX); nothing in Docent knows the others.
//!
//! - `broker`: the broker's address, the login, topic names (`docent/ID/...`), the link's
//!   state ([`LinkStatus`]).
//! - `link`: the task polling one connection (rumqttc reconnects) and telling its owner.
//! - `bridge`: the robot's side: retained `status` (with the last will) and `state`, every
//!   event on `events`, commands from `cmd` answered on `reply`.
//! - `robot_state`: the `state` document, and the battery level read from robot events.
//! - `signed`: the signed envelopes of commands and replies (HMAC-SHA256 keyed by the role's
//!   credential), and the memory of references taken (no replay).
//! - `commands`: a verified command handed to the websocket's own session code
//!   (`ws::embedded`).
//! - `view`: the fleet view's model: every robot's state heard, and Stop.
//! - `http`: `/fleet`, `/api/fleet...`, on a Docent and on `docent fleet`.
//! - `setup`: flags over `docent.yaml`'s `mqtt:`; starting the bridge and the view.
//! - `tls`: `mqtts://` with rustls (ring), trusting a site's CA file or the system's.
//! - `standalone`: `docent fleet --mqtt URL`, a server of the fleet view only (its command
//!   line is the root crate's `cli::fleet`).

mod bridge;
mod broker;
mod commands;
mod http;
mod link;
mod robot_state;
mod setup;
mod signed;
mod standalone;
mod tls;
mod view;

use std::sync::{Arc, OnceLock};

pub use bridge::{BridgeSettings, STATE_INTERVAL, start_bridge};
pub use broker::{Broker, BrokerUrl, LinkState, LinkStatus, LinkView, robot_id_problem};
pub use http::{FleetHttp, FleetPage, routes};
pub use link::MAX_MESSAGE_BYTES;
pub use robot_state::{Battery, Identity};
pub use setup::{FleetFlags, MQTT_PASSWORD_ENV, decide_bridge, join_fleet, tls_for};
pub use standalone::{FleetOptions, serve_fleet};
pub use view::{FleetView, StopFailed};

/// What a server has of the fleet: set once at start-up when it has a broker.
#[derive(Debug, Default)]
pub struct FleetHandles {
    robot: OnceLock<(String, Arc<LinkStatus>)>,
    view: OnceLock<Arc<FleetView>>,
}

impl FleetHandles {
    /// Records this robot's bridge (its id and link).
    pub fn set_bridge(&self, robot: String, link: Arc<LinkStatus>) {
        let _ = self.robot.set((robot, link));
    }

    /// Records the fleet view this server shows at `/fleet`.
    pub fn set_view(&self, view: Arc<FleetView>) {
        let _ = self.view.set(view);
    }

    /// The fleet view, if this server follows a fleet.
    pub fn view(&self) -> Option<Arc<FleetView>> {
        self.view.get().cloned()
    }

    /// `/api/state`'s `fleet`: this robot's id and broker link, or null without a broker.
    pub fn state_json(&self) -> serde_json::Value {
        match self.robot.get() {
            Some((robot, link)) => serde_json::json!({ "robot": robot, "link": link.view() }),
            None => serde_json::Value::Null,
        }
    }
}

impl std::fmt::Debug for FleetView {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FleetView")
            .field("link", &self.link())
            .finish()
    }
}
