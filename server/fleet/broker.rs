//! Reaching the broker: its address (`mqtt://host[:port]`, `mqtts://` for TLS), the login,
//! the MQTT options both the robot's bridge and the fleet view connect with, the topic names
//! under `docent/ID/`, and the state of the link (up, down and why), which operators are shown.

use std::sync::{Arc, Mutex};
use std::time::Duration;

use rumqttc::{LastWill, MqttOptions, TlsConfiguration, Transport};

pub use docent_content::names::{BrokerUrl, robot_id_problem};
pub use docent_protocol::fleet_link::{LinkState, LinkView};

use super::link::{MAX_MESSAGE_BYTES, MAX_PACKET_BYTES};
use crate::access::Secret;
use crate::sync::lock;

/// How often an idle link is pinged; the broker gives up on a silent client after 1.5 times
/// this and publishes its last will.
pub const KEEP_ALIVE: Duration = Duration::from_secs(10);
/// The longest a reconnection waits after a failed attempt.
pub const MAX_RETRY: Duration = Duration::from_secs(2);
/// Topics are `docent/ROBOT/...`.
pub const TOPIC_ROOT: &str = "docent";

/// Where and as whom to connect.
#[derive(Clone, Debug)]
pub struct Broker {
    /// The broker.
    pub url: BrokerUrl,
    /// The MQTT user name, if the broker wants one.
    pub username: Option<String>,
    /// Its password: never printed, logged or published.
    pub password: Option<Secret>,
    /// For `mqtts://`: whom to trust (see `tls.rs`).
    pub tls: Option<Arc<rustls::ClientConfig>>,
}

impl Broker {
    /// The options to connect as `client_id`, leaving `will` if the link dies.
    pub fn options(&self, client_id: &str, will: Option<LastWill>) -> MqttOptions {
        let mut options = MqttOptions::new(client_id, self.url.host.clone(), self.url.port);
        options.set_keep_alive(KEEP_ALIVE);
        // A reconnecting client subscribes again itself; old sessions are not kept around.
        options.set_clean_session(true);
        // Any packet is read, so a message over the limit is dropped (`link`) rather than
        // breaking the connection; Docent's own stay within the message limit.
        options.set_max_packet_size(MAX_PACKET_BYTES, MAX_MESSAGE_BYTES);
        if let Some(username) = &self.username {
            let password = self.password.as_ref().map_or("", |p| p.expose());
            options.set_credentials(username.clone(), password);
        }
        if let Some(will) = will {
            options.set_last_will(will);
        }
        if let Some(config) = &self.tls {
            let tls = TlsConfiguration::Rustls(Arc::clone(config));
            options.set_transport(Transport::tls_with_config(tls));
        }
        options
    }
}

/// A robot's topic `docent/ROBOT/LEAF`.
pub fn topic(robot: &str, leaf: &str) -> String {
    format!("{TOPIC_ROOT}/{robot}/{leaf}")
}

/// The robot a topic `docent/ROBOT/LEAF` belongs to, and its leaf.
pub fn split_topic(topic: &str) -> Option<(&str, &str)> {
    let rest = topic.strip_prefix(TOPIC_ROOT)?.strip_prefix('/')?;
    rest.split_once('/')
}

/// A link's state, shared between its task and whoever shows it.
#[derive(Debug)]
pub struct LinkStatus(Mutex<LinkView>);

impl LinkStatus {
    /// A link to `broker`, connecting.
    pub fn new(broker: &BrokerUrl) -> Self {
        LinkStatus(Mutex::new(LinkView {
            broker: broker.to_string(),
            state: LinkState::Connecting,
            reason: None,
        }))
    }

    /// The link as it is now.
    pub fn view(&self) -> LinkView {
        lock(&self.0).clone()
    }

    /// Records a change; true when the state changed (a transition to announce).
    pub fn set(&self, state: LinkState, reason: Option<String>) -> bool {
        let mut view = lock(&self.0);
        let changed = view.state != state;
        view.state = state;
        view.reason = reason;
        changed
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn topics_split_into_robot_and_leaf() {
        assert_eq!(split_topic("docent/r1/state"), Some(("r1", "state")));
        assert_eq!(split_topic("other/r1/state"), None);
    }
}
