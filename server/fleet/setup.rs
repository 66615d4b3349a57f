//! Deciding at start-up whether and how a Docent joins a fleet: the command line
//! (`--mqtt URL --robot-id ID`) over `docent.yaml`'s `mqtt:`, the password from
//! `DOCENT_MQTT_PASSWORD` over the file's; then starting the robot's bridge and the fleet view
//! its `/fleet` page shows.

use std::net::SocketAddr;
use std::path::PathBuf;

use super::bridge::{BridgeSettings, start_bridge};
use super::broker::{Broker, BrokerUrl, robot_id_problem};
use super::robot_state::Identity;
use super::view::FleetView;
use crate::access::Secret;
use crate::content::config::MqttSettings;
use crate::state::AppState;

/// The environment variable holding the broker password (over `mqtt: password`).
pub const MQTT_PASSWORD_ENV: &str = "DOCENT_MQTT_PASSWORD";

/// What the command line said about the fleet.
#[derive(Clone, Debug, Default)]
pub struct FleetFlags {
    /// `--mqtt URL`.
    pub url: Option<String>,
    /// `--robot-id ID`.
    pub robot_id: Option<String>,
    /// `--mqtt-ca FILE`: the CA certificates an `mqtts://` broker is checked against.
    pub ca_file: Option<PathBuf>,
}

/// The bridge to start, if the flags or the file name a broker; a reason otherwise.
pub fn decide_bridge(
    flags: &FleetFlags,
    file: &MqttSettings,
    password_env: Option<String>,
    listen: SocketAddr,
) -> Result<Option<BridgeSettings>, String> {
    let url = match &flags.url {
        Some(text) => Some(BrokerUrl::parse(text).map_err(|why| format!("--mqtt: {why}"))?),
        None => file.url.clone(),
    };
    let robot = flags.robot_id.clone().or_else(|| file.robot_id.clone());
    let (url, robot) = match (url, robot) {
        (None, None) => return Ok(None),
        (Some(url), Some(robot)) => (url, robot),
        (Some(_), None) => {
            return Err(
                "a fleet needs this robot's id: add --robot-id ID (or mqtt: robot_id: \
                        in docent.yaml)"
                    .into(),
            );
        }
        (None, Some(_)) => {
            return Err(
                "a robot id was given but no broker: add --mqtt mqtt://HOST[:PORT] (or \
                        mqtt: url: in docent.yaml)"
                    .into(),
            );
        }
    };
    if let Some(problem) = robot_id_problem(&robot) {
        return Err(format!("--robot-id: {problem}"));
    }
    let password = password_env
        .filter(|p| !p.is_empty())
        .or_else(|| file.password.as_ref().map(|p| p.expose().to_owned()))
        .map(Secret::new);
    let console = file
        .console_url
        .clone()
        .unwrap_or_else(|| console_url(listen));
    let ca_file = flags.ca_file.clone().or_else(|| file.ca_file.clone());
    let tls = tls_for(&url, ca_file.as_deref())?;
    Ok(Some(BridgeSettings {
        broker: Broker {
            url,
            username: file.username.clone(),
            password,
            tls,
        },
        identity: Identity { robot, console },
    }))
}

/// The TLS set-up an `mqtts://` broker needs (`ca_file`'s CA, or the system's); none for
/// `mqtt://`, where a CA file is a mistake worth saying.
pub fn tls_for(
    url: &BrokerUrl,
    ca_file: Option<&std::path::Path>,
) -> Result<Option<std::sync::Arc<rustls::ClientConfig>>, String> {
    match (url.tls, ca_file) {
        (true, ca_file) => super::tls::client_config(ca_file).map(Some),
        (false, None) => Ok(None),
        (false, Some(_)) => Err(format!(
            "a CA file was given for {url}, which is not TLS: use mqtts:// (or leave the CA out)"
        )),
    }
}

/// This robot's console at the address it listens on; the machine's name for a wildcard one.
fn console_url(listen: SocketAddr) -> String {
    let host = if listen.ip().is_unspecified() {
        std::fs::read_to_string("/proc/sys/kernel/hostname")
            .map(|h| h.trim().to_owned())
            .ok()
            .filter(|h| !h.is_empty())
            .unwrap_or_else(|| "localhost".into())
    } else if listen.is_ipv6() {
        format!("[{}]", listen.ip())
    } else {
        listen.ip().to_string()
    };
    format!("http://{host}:{}/operator", listen.port())
}

/// Starts this robot's bridge and the fleet view of its `/fleet` page (which stops robots
/// with `operator_token`, this server's operator credential; `None` on `--open`).
pub fn join_fleet(state: &AppState, settings: BridgeSettings, operator_token: Option<Secret>) {
    let robot = settings.identity.robot.clone();
    let broker = settings.broker.clone();
    let link = start_bridge(state, settings);
    state.fleet.set_bridge(robot.clone(), link);
    let view = FleetView::start(
        &broker,
        &format!("docent-{robot}-view"),
        operator_token,
        &state.life,
    );
    state.fleet.set_view(view);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn listen() -> SocketAddr {
        "127.0.0.1:8080".parse().expect("an address")
    }

    #[test]
    fn flags_win_over_the_file_and_both_halves_are_needed() {
        let file = MqttSettings {
            url: BrokerUrl::parse("mqtt://file-broker").ok(),
            robot_id: Some("from-file".into()),
            ..MqttSettings::default()
        };
        let none = decide_bridge(
            &FleetFlags::default(),
            &MqttSettings::default(),
            None,
            listen(),
        );
        assert!(none.expect("no fleet").is_none());
        let from_file = decide_bridge(&FleetFlags::default(), &file, None, listen())
            .expect("valid")
            .expect("a bridge");
        assert_eq!(from_file.identity.robot, "from-file");
        assert_eq!(from_file.identity.console, "http://127.0.0.1:8080/operator");
        let flags = FleetFlags {
            url: Some("mqtt://flag-broker:1884".into()),
            robot_id: Some("from-flag".into()),
            ca_file: None,
        };
        let both = decide_bridge(&flags, &file, Some("pw".into()), listen())
            .expect("valid")
            .expect("a bridge");
        assert_eq!(both.broker.url.host, "flag-broker");
        assert_eq!(both.identity.robot, "from-flag");
        assert_eq!(
            both.broker.password.as_ref().map(Secret::expose),
            Some("pw")
        );
        let half = FleetFlags {
            url: Some("mqtt://b".into()),
            ..FleetFlags::default()
        };
        let err = decide_bridge(&half, &MqttSettings::default(), None, listen()).unwrap_err();
        assert!(err.contains("--robot-id"), "{err}");
        let bad = FleetFlags {
            url: Some("mqtt://b".into()),
            robot_id: Some("a/b".into()),
            ca_file: None,
        };
        assert!(decide_bridge(&bad, &file, None, listen()).is_err());
        let plain_with_ca = FleetFlags {
            ca_file: Some("/etc/ca.pem".into()),
            ..flags
        };
        let err = decide_bridge(&plain_with_ca, &file, None, listen()).unwrap_err();
        assert!(err.contains("use mqtts://"), "{err}");
    }
}
