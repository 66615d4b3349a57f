//! The `mqtt:` section of `docent.yaml`: the fleet's broker (`url`), this robot's id in the
//! topics (`robot_id`), the broker login (`username`, `password`) and the address of this
//! robot's console as the fleet view links to it (`console_url`). `docent serve --mqtt URL
//! --robot-id ID` overrides the first two, `DOCENT_MQTT_PASSWORD` the password. The password
//! is never repeated in a message, nor is a broker address (it might carry a login).

use std::fmt;

use crate::DiagnosticCode;
use crate::acts_file::yaml::Node;
use crate::diagnostic::Diagnostic;
use crate::names::{BrokerUrl, robot_id_problem};

use super::Reader;
use super::section::{Field, Section, Shape};

/// The settings of `mqtt:`.
pub(crate) const SECTION: Section = Section {
    name: "mqtt",
    required: &[],
    fields: &[
        Field {
            key: "url",
            description: "The fleet's MQTT broker, e.g. `mqtt://broker.local:1883` (port 1883 \
                          when left out). No user name or password in it.",
            shape: Shape::Pattern("^mqtt://[^@/?#]+/?$"),
        },
        Field {
            key: "robot_id",
            description: "This robot's id in the topics (`docent/ID/state`): 1 to 64 letters, \
                          digits, - and _, e.g. `robot-1`.",
            shape: Shape::Pattern("^[A-Za-z0-9_-]{1,64}$"),
        },
        Field {
            key: "username",
            description: "The broker's user name for this robot.",
            shape: Shape::Text,
        },
        Field {
            key: "password",
            description: "The broker's password for `username`. Better kept out of the \
                          bundle: set DOCENT_MQTT_PASSWORD instead.",
            shape: Shape::Text,
        },
        Field {
            key: "ca_file",
            description: "For an mqtts:// broker: the absolute path of the PEM file with the \
                          CA certificates it is checked against (the system's without one).",
            shape: Shape::Pattern("^/"),
        },
        Field {
            key: "console_url",
            description: "This robot's console as the fleet view links to it, e.g. \
                          `http://robot-1.local:8080/operator` (by default the --listen \
                          address's).",
            shape: Shape::Pattern("^https?://"),
        },
    ],
};

/// What `mqtt:` says (all optional: the command line may give the rest).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MqttSettings {
    /// The broker, `mqtt://host[:port]`.
    pub url: Option<BrokerUrl>,
    /// This robot's id: `docent/ID/...`.
    pub robot_id: Option<String>,
    /// The broker's user name for this robot.
    pub username: Option<String>,
    /// Its password.
    pub password: Option<MqttPassword>,
    /// This robot's console as the fleet view links to it (`http://robot-1.local:8080/operator`).
    pub console_url: Option<String>,
    /// For `mqtts://`: the CA certificates (PEM) the broker is checked against, an absolute
    /// path on the robot (read when serving, never by `docent check`); the system's otherwise.
    pub ca_file: Option<std::path::PathBuf>,
}

/// The broker password: never printed by `Debug`.
#[derive(Clone, PartialEq, Eq)]
pub struct MqttPassword(String);

impl MqttPassword {
    /// The password, for the broker's login only.
    pub fn expose(&self) -> &str {
        &self.0
    }
}

impl fmt::Debug for MqttPassword {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("MqttPassword(***)")
    }
}

impl Reader {
    /// Reads `mqtt:` into `mqtt`.
    pub(super) fn mqtt(&mut self, node: &Node, mqtt: &mut MqttSettings) {
        for (field, value) in self.entries(node, &SECTION) {
            match field.key {
                "url" => mqtt.url = self.broker_url(value),
                "robot_id" => {
                    let usage = robot_id_problem("").unwrap_or_default();
                    let usage = format!("`robot_id`: {usage}.");
                    mqtt.robot_id = self.setting(value, &usage, |t| {
                        robot_id_problem(t).is_none().then(|| t.to_owned())
                    });
                }
                "username" => {
                    let usage = "`username` is the broker's user name for this robot, e.g. \
                                 `username: robot-1`.";
                    mqtt.username = self.setting(value, usage, |t| Some(t.to_owned()));
                }
                "password" => mqtt.password = self.mqtt_password(value),
                "ca_file" => {
                    let usage = "`ca_file` is the absolute path of the PEM file with the CA \
                                 certificates an mqtts:// broker is checked against, e.g. \
                                 `ca_file: /etc/docent/fleet-ca.pem`.";
                    mqtt.ca_file = self.setting(value, usage, |t| {
                        let path = std::path::Path::new(t);
                        path.is_absolute().then(|| path.to_path_buf())
                    });
                }
                _ => {
                    let usage = "`console_url` is this robot's console as the fleet view links \
                                 to it, e.g. `console_url: http://robot-1.local:8080/operator`.";
                    mqtt.console_url = self.setting(value, usage, |t| {
                        let web = t.starts_with("http://") || t.starts_with("https://");
                        web.then(|| t.to_owned())
                    });
                }
            }
        }
    }

    /// The broker's address; a problem says why, without repeating the address.
    fn broker_url(&mut self, node: &Node) -> Option<BrokerUrl> {
        let parsed = match node.as_text().map(str::trim) {
            Some(text) => BrokerUrl::parse(text),
            None => Err(format!("it is {} here", node.describe())),
        };
        match parsed {
            Ok(url) => Some(url),
            Err(why) => {
                let message = format!(
                    "`url` is the fleet's MQTT broker, e.g. `url: mqtt://broker.local:1883`: \
                     {why}."
                );
                self.diagnostics.push(Diagnostic::error(
                    DiagnosticCode::ConfigBadValue,
                    &node.pos,
                    message,
                ));
                None
            }
        }
    }

    /// The password as text; a problem never repeats it.
    fn mqtt_password(&mut self, node: &Node) -> Option<MqttPassword> {
        match node.as_text() {
            Some(text) if !text.is_empty() => Some(MqttPassword(text.to_owned())),
            _ => {
                let message = format!(
                    "`password` is the broker's password for `username`, as text, and it is {} \
                     here. Or leave it out here and set DOCENT_MQTT_PASSWORD when starting \
                     Docent.",
                    node.describe()
                );
                self.diagnostics.push(Diagnostic::error(
                    DiagnosticCode::ConfigBadValue,
                    &node.pos,
                    message,
                ));
                None
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::config_file::test_support::{parse, problems};

    #[test]
    fn the_mqtt_section_is_read_and_keeps_its_password_out_of_debug_output() {
        let file = parse(
            "mqtt:\n  url: mqtt://broker.local:1884\n  robot_id: robot-1\n  username: r1\n  \
             password: s3cret-pass\n  console_url: http://robot-1.local:8080/operator\n",
        );
        assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
        let mqtt = &file.config.mqtt;
        let url = mqtt.url.as_ref().expect("a url");
        assert_eq!((url.host.as_str(), url.port), ("broker.local", 1884));
        assert_eq!(mqtt.robot_id.as_deref(), Some("robot-1"));
        assert_eq!(
            mqtt.password.as_ref().map(|p| p.expose()),
            Some("s3cret-pass")
        );
        assert!(!format!("{:?}", file.config).contains("s3cret"));
    }

    #[test]
    fn a_login_in_the_broker_url_is_refused_at_its_place_without_repeating_it() {
        let found = problems("mqtt:\n  url: mqtt://r1:hunter2@broker\n");
        assert_eq!(found.len(), 1, "{found:?}");
        let (code, line, column, message) = &found[0];
        assert_eq!((*code, *line, *column), ("config-bad-value", 2, 8));
        assert!(message.contains("DOCENT_MQTT_PASSWORD"), "{message}");
        assert!(!message.contains("hunter2"), "{message}");
    }

    #[test]
    fn a_robot_id_that_is_not_one_topic_level_is_refused_at_its_place() {
        let found = problems("mqtt:\n  robot_id: hall/1\n");
        assert_eq!(found.len(), 1, "{found:?}");
        let (code, line, column, message) = &found[0];
        assert_eq!((*code, *line, *column), ("config-bad-value", 2, 13));
        assert!(message.contains("letters, digits"), "{message}");
    }

    #[test]
    fn a_ca_file_must_be_an_absolute_path() {
        let file = parse("mqtt:\n  ca_file: /etc/docent/ca.pem\n");
        assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
        let found = problems("mqtt:\n  ca_file: certs/ca.pem\n");
        let codes: Vec<_> = found.iter().map(|(c, l, col, _)| (*c, *l, *col)).collect();
        assert_eq!(codes, [("config-bad-value", 2, 12)]);
        assert!(found[0].3.contains("absolute path"), "{}", found[0].3);
    }

    #[test]
    fn a_password_that_is_not_text_is_refused_without_repeating_it() {
        let found = problems("mqtt:\n  password: [a, b]\n  console_url: robot-1:8080\n");
        let codes: Vec<_> = found.iter().map(|(c, l, col, _)| (*c, *l, *col)).collect();
        assert_eq!(
            codes,
            [("config-bad-value", 2, 13), ("config-bad-value", 3, 16)]
        );
        assert!(found[0].3.contains("DOCENT_MQTT_PASSWORD"));
    }
}
