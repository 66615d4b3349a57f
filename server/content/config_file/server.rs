//! The `server:` section of `docent.yaml`: how Docent itself is reached. The reverse proxies
//! whose `X-Forwarded-For` is believed (`trusted_proxies`); every other peer's header is
//! ignored, so that a client cannot choose the address its wrong credentials count against.
//! And the server's limits (`connections`, `timeouts`, `messages`, `queues`), read by
//! `server_limits.rs`.

use std::net::IpAddr;

use crate::acts_file::yaml::{Kind, Node};
use crate::config::ServerSettings;

use serde_json::{Value, json};

use super::Reader;
use super::section::{Field, Section, Shape};
use super::server_limits;

/// The settings of `server:`.
pub(crate) const SECTION: Section = Section {
    name: "server",
    required: &[],
    fields: &[
        Field {
            key: "trusted_proxies",
            description: "The reverse proxies in front of Docent whose X-Forwarded-For header \
                          is believed, e.g. `[127.0.0.1]`; every other client's header is \
                          ignored.",
            shape: Shape::Custom(proxies_schema),
        },
        Field {
            key: "connections",
            description: "How many connections one client address and all clients together \
                          may hold (in force from start-up).",
            shape: Shape::Nested(&server_limits::CONNECTIONS),
        },
        Field {
            key: "timeouts",
            description: "How long a request may take to arrive (in force from start-up).",
            shape: Shape::Nested(&server_limits::TIMEOUTS),
        },
        Field {
            key: "messages",
            description: "The largest websocket message (in force from start-up).",
            shape: Shape::Nested(&server_limits::MESSAGES),
        },
        Field {
            key: "queues",
            description: "How many frames may wait for one slow websocket client (in force \
                          from start-up).",
            shape: Shape::Nested(&server_limits::QUEUES),
        },
    ],
};
const PROXIES_USAGE: &str = "`trusted_proxies` lists the IP addresses of the reverse proxies \
                             in front of Docent, e.g. `trusted_proxies: [127.0.0.1]` for a \
                             proxy on this machine or `[10.0.0.2, \"fd00::2\"]`; only these \
                             may name the client in `X-Forwarded-For`.";

impl Reader {
    /// Reads `server:` into `server`.
    pub(super) fn server(&mut self, node: &Node, server: &mut ServerSettings) {
        for (field, value) in self.entries(node, &SECTION) {
            let limits = &mut server.limits;
            match field.key {
                "connections" => self.connections(value, limits),
                "timeouts" => self.timeouts(value, limits),
                "messages" => self.messages(value, limits),
                "queues" => self.queues(value, limits),
                _ => server.trusted_proxies = self.proxies(value),
            }
        }
    }

    /// One address or a list of them; a repeat is reported, a bad one reported and left out.
    fn proxies(&mut self, node: &Node) -> Vec<IpAddr> {
        let items: Vec<&Node> = match &node.kind {
            Kind::Seq(items) => items.iter().collect(),
            Kind::Null => Vec::new(),
            _ => vec![node],
        };
        let mut proxies: Vec<IpAddr> = Vec::new();
        for item in items {
            let parse = |text: &str| text.parse::<IpAddr>().ok();
            let Some(address) = self.setting(item, PROXIES_USAGE, parse) else {
                continue;
            };
            if proxies.contains(&address) {
                self.bad(item, "This proxy is listed twice.");
            } else {
                proxies.push(address);
            }
        }
        proxies
    }
}

/// One address or a list of them.
fn proxies_schema(description: &'static str) -> Value {
    let address = json!({
        "type": "string",
        "description": "The IP address of a reverse proxy, e.g. `127.0.0.1` or `fd00::2`.",
    });
    json!({
        "description": description,
        "anyOf": [
            { "type": "null" },
            address,
            { "type": "array", "items": address, "uniqueItems": true },
        ],
    })
}

#[cfg(test)]
mod tests {
    use crate::config_file::test_support::parse;

    #[test]
    fn trusted_proxies_are_read_as_addresses() {
        let file = parse("server:\n  trusted_proxies: [127.0.0.1, \"fd00::2\"]\n");
        assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
        let proxies = &file.config.server.trusted_proxies;
        assert_eq!(
            proxies,
            &[
                "127.0.0.1".parse::<std::net::IpAddr>().unwrap(),
                "fd00::2".parse().unwrap()
            ]
        );
        let single = parse("server:\n  trusted_proxies: 10.0.0.2\n");
        assert_eq!(single.config.server.trusted_proxies.len(), 1);
        assert!(parse("server:\n").config.server.trusted_proxies.is_empty());
    }

    #[test]
    fn a_bad_or_repeated_proxy_is_located_and_left_out() {
        let file = parse(
            "server:\n  trusted_proxies:\n    - 10.0.0.2\n    - proxy.local\n    - 10.0.0.2\n  \
             trusted_proxy: x\n",
        );
        let found: Vec<_> = (file.diagnostics.iter())
            .map(|d| (d.code.as_str(), d.line, d.column))
            .collect();
        assert_eq!(
            found,
            [
                ("config-unknown-key", 6, 3),
                ("config-bad-value", 4, 7),
                ("config-bad-value", 5, 7),
            ]
        );
        assert!(file.diagnostics[1].message.contains("IP addresses"));
        assert!(file.diagnostics[2].message.contains("listed twice"));
        assert_eq!(file.config.server.trusted_proxies.len(), 1);
    }
}
