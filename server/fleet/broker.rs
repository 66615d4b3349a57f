//! Reaching the broker: its address (`mqtt://host[:port]`, `mqtts://` for TLS), the login,
//! the MQTT options both the robot's bridge and the fleet view connect with, the topic names
//! under `docent/ID/`, and the state of the link (up, down and why), which operators are shown.

use std::sync::{Arc, Mutex};
use std::time::Duration;

use rumqttc::{LastWill, MqttOptions, TlsConfiguration, Transport};
use serde::Serialize;

use super::link::{MAX_MESSAGE_BYTES, MAX_PACKET_BYTES};
use crate::access::Secret;
use crate::sync::lock;

/// The MQTT port when the address names none.
pub const DEFAULT_PORT: u16 = 1883;
/// The MQTT-over-TLS port when an `mqtts://` address names none.
pub const DEFAULT_TLS_PORT: u16 = 8883;
/// How often an idle link is pinged; the broker gives up on a silent client after 1.5 times
/// this and publishes its last will.
pub const KEEP_ALIVE: Duration = Duration::from_secs(10);
/// The longest a reconnection waits after a failed attempt.
pub const MAX_RETRY: Duration = Duration::from_secs(2);
/// Topics are `docent/ROBOT/...`.
pub const TOPIC_ROOT: &str = "docent";

/// A broker's address, from `mqtt://host[:port]` or `mqtts://host[:port]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BrokerUrl {
    /// Host name or address.
    pub host: String,
    /// TCP port.
    pub port: u16,
    /// Whether the link is TLS (`mqtts://`).
    pub tls: bool,
}

impl BrokerUrl {
    /// Parses `mqtt://host[:port]` or `mqtts://host[:port]`; the reason, in words an operator
    /// can act on, otherwise. A login in the address is refused: it would be printed and
    /// logged with it.
    pub fn parse(text: &str) -> Result<BrokerUrl, String> {
        let (rest, tls) = if let Some(rest) = text.strip_prefix("mqtt://") {
            (rest, false)
        } else if let Some(rest) = text.strip_prefix("mqtts://") {
            (rest, true)
        } else {
            return Err(
                "a broker address starts with mqtt:// (or mqtts:// for TLS), e.g. \
                        mqtt://broker.local:1883"
                    .into(),
            );
        };
        let rest = rest.strip_suffix('/').unwrap_or(rest);
        if rest.contains('@') {
            return Err(
                "put the broker's user name and password in docent.yaml's mqtt: section \
                 (or DOCENT_MQTT_PASSWORD), not in its address"
                    .into(),
            );
        }
        if rest.contains(['/', '?', '#']) {
            return Err(
                "a broker address is mqtt://host[:port] (or mqtts://), with no path".into(),
            );
        }
        let (host, port) = match rest.rsplit_once(':') {
            // An IPv6 address is written in brackets: [::1]:1883.
            Some((host, port)) if !host.ends_with(':') && !port.contains(']') => {
                let port = port
                    .parse::<u16>()
                    .ok()
                    .filter(|p| *p > 0)
                    .ok_or_else(|| format!("`{port}` is not a port number (1 to 65535)"))?;
                (host, port)
            }
            _ if tls => (rest, DEFAULT_TLS_PORT),
            _ => (rest, DEFAULT_PORT),
        };
        let host = host.trim_start_matches('[').trim_end_matches(']');
        if host.is_empty() {
            return Err("the broker address names no host, e.g. mqtt://broker.local".into());
        }
        Ok(BrokerUrl {
            host: host.to_owned(),
            port,
            tls,
        })
    }
}

impl std::fmt::Display for BrokerUrl {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let scheme = if self.tls { "mqtts" } else { "mqtt" };
        if self.host.contains(':') {
            write!(f, "{scheme}://[{}]:{}", self.host, self.port)
        } else {
            write!(f, "{scheme}://{}:{}", self.host, self.port)
        }
    }
}

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

/// Whether `id` can name a robot in a topic: 1 to 64 letters, digits, `-` and `_` (no MQTT
/// wildcard, no level separator).
pub fn robot_id_problem(id: &str) -> Option<String> {
    let ok = !id.is_empty()
        && id.len() <= 64
        && id
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_');
    (!ok).then(|| {
        "a robot id is 1 to 64 letters, digits, - and _ (it becomes a topic level: \
         docent/ID/state), e.g. robot-1"
            .to_owned()
    })
}

/// Whether the link to the broker is up, as operators are shown it.
#[derive(Clone, Debug, Serialize, PartialEq, Eq)]
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
#[derive(Clone, Copy, Debug, Serialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum LinkState {
    /// Not connected yet.
    Connecting,
    /// Connected (the broker acknowledged).
    Up,
    /// Lost or refused; reconnecting.
    Down,
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
    fn broker_addresses_are_read_or_refused_with_a_reason() {
        let url = BrokerUrl::parse("mqtt://broker.local").expect("parses");
        assert_eq!((url.host.as_str(), url.port), ("broker.local", 1883));
        let url = BrokerUrl::parse("mqtt://127.0.0.1:18830/").expect("parses");
        assert_eq!((url.host.as_str(), url.port), ("127.0.0.1", 18830));
        let url = BrokerUrl::parse("mqtt://[::1]:1884").expect("parses");
        assert_eq!((url.host.as_str(), url.port), ("::1", 1884));
        assert_eq!(url.to_string(), "mqtt://[::1]:1884");
        let login = BrokerUrl::parse("mqtt://user:hunter2@broker").unwrap_err();
        assert!(login.contains("not in its address") && !login.contains("hunter2"));
        assert!(
            BrokerUrl::parse("http://broker")
                .unwrap_err()
                .contains("mqtt://")
        );
        let tls = BrokerUrl::parse("mqtts://broker").expect("TLS");
        assert_eq!((tls.port, tls.tls), (8883, true));
        assert_eq!(tls.to_string(), "mqtts://broker:8883");
        assert!(
            BrokerUrl::parse("mqtt://broker:0")
                .unwrap_err()
                .contains("port")
        );
        assert!(BrokerUrl::parse("mqtt://").unwrap_err().contains("no host"));
    }

    #[test]
    fn robot_ids_are_one_topic_level() {
        assert_eq!(robot_id_problem("robot-1_a"), None);
        for bad in ["", "a/b", "a+", "#", "ünï", &"x".repeat(65)] {
            assert!(robot_id_problem(bad).is_some(), "{bad}");
        }
        assert_eq!(split_topic("docent/r1/state"), Some(("r1", "state")));
        assert_eq!(split_topic("other/r1/state"), None);
    }
}
