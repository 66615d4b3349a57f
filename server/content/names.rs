//! Names and addresses a site writes in `docent.yaml` that become parts of messages: robot
//! event names (in the log, in `reactions:`, for dialog managers), robot ids (a level of the
//! fleet's MQTT topics) and the broker's address. Their grammar is here, below the runtime,
//! so that `docent check` and the running server refuse the same names with the same words.

/// The longest robot event name, in characters.
pub const ROBOT_EVENT_NAME_CHARS: usize = 64;

/// The MQTT port when the address names none.
pub const DEFAULT_PORT: u16 = 1883;
/// The MQTT-over-TLS port when an `mqtts://` address names none.
pub const DEFAULT_TLS_PORT: u16 = 8883;
/// Why `name` cannot be a robot event's name, if it cannot: 1 to 64 characters, lower-case
/// letters, digits, `.`, `_` and `-`, starting with a letter, so that it reads the same in
/// `docent.yaml`, the log and a dialog manager's code.
pub fn robot_event_name_problem(name: &str) -> Option<String> {
    let first_is_letter = name.chars().next().is_some_and(|c| c.is_ascii_lowercase());
    let allowed = |c: char| c.is_ascii_lowercase() || c.is_ascii_digit() || ".-_".contains(c);
    if name.is_empty() || name.chars().count() > ROBOT_EVENT_NAME_CHARS {
        return Some(format!(
            "a robot event's name has 1 to {ROBOT_EVENT_NAME_CHARS} characters (got {name:?})"
        ));
    }
    if !first_is_letter || !name.chars().all(allowed) {
        return Some(format!(
            "a robot event's name starts with a lower-case letter and has only lower-case \
             letters, digits, '.', '_' and '-' (got {name:?}, e.g. \"person.near\")"
        ));
    }
    None
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_short_lower_case_words_with_dots() {
        for good in [
            "person.near",
            "bumper",
            "battery_low",
            "asr.text-final",
            "a1",
        ] {
            assert_eq!(robot_event_name_problem(good), None, "{good}");
        }
        for bad in [
            "",
            "Person.near",
            "1person",
            "person near",
            "é",
            &"a".repeat(65),
        ] {
            assert!(robot_event_name_problem(bad).is_some(), "{bad:?}");
        }
    }

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
    }
}
