//! The limits under `server:` in `docent.yaml`: `connections`, `timeouts`, `messages` and
//! `queues`, each a small section of its own. Every value must carry its unit where it has one
//! (`30s`, `1 MiB`) and lie in the range `ServerLimits` gives; a value outside it is reported
//! where it is written, with the range and an example, and the default stays in force. A
//! `per_address` above `total` is a warning, not an error: the server still works (no address
//! can hold more than `total` anyway), but the file says something it does not do.

use std::ops::RangeInclusive;
use std::time::Duration;

use serde_json::{Value, json};

use crate::DiagnosticCode;
use crate::acts_file::yaml::Node;
use crate::config::ServerLimits;
use crate::diagnostic::Diagnostic;
use crate::duration::parse_duration;
use crate::size::parse_size;

use super::Reader;
use super::screens::AMOUNT_PATTERN;
use super::section::{Field, Section, Shape};

/// A count of connections, as the schema gives it.
const CONNECTION_COUNT: Shape = Shape::Integer {
    min: *ServerLimits::CONNECTIONS.start() as i64,
    max: *ServerLimits::CONNECTIONS.end() as i64,
};

/// The settings of `server: connections:`.
pub(crate) const CONNECTIONS: Section = Section {
    name: "connections",
    required: &[],
    fields: &[
        Field {
            key: "per_address",
            description: "Open connections (websockets included) one client address may hold, \
                          from 1 to 65536 (default 128); one more is answered `503 \
                          too-many-connections`. Raise it for many kiosks behind one router \
                          (NAT).",
            shape: CONNECTION_COUNT,
        },
        Field {
            key: "total",
            description: "Open connections in all, from 1 to 65536 (default 1024). Each is a \
                          file descriptor: give the process more (`LimitNOFILE=` in systemd) \
                          than this plus 64.",
            shape: CONNECTION_COUNT,
        },
    ],
};

/// The settings of `server: timeouts:`.
pub(crate) const TIMEOUTS: Section = Section {
    name: "timeouts",
    required: &[],
    fields: &[
        Field {
            key: "headers",
            description: "How long a request's headers may take to arrive, from 1s to 10m \
                          (default 30s); also how long an idle keep-alive connection stays \
                          open.",
            shape: Shape::Duration,
        },
        Field {
            key: "body",
            description: "How long a request's body may take to arrive after its headers, \
                          from 1s to 10m (default 30s); a recording chunk from a kiosk on slow \
                          Wi-Fi is the largest body.",
            shape: Shape::Duration,
        },
    ],
};

/// The settings of `server: messages:`.
pub(crate) const MESSAGES: Section = Section {
    name: "messages",
    required: &[],
    fields: &[Field {
        key: "max_size",
        description: "The largest websocket message a client may send, from 16 KiB to 64 MiB \
                      (default 1 MiB); a larger one closes its connection with code 1009.",
        shape: Shape::Custom(message_size_schema),
    }],
};

/// The settings of `server: queues:`.
pub(crate) const QUEUES: Section = Section {
    name: "queues",
    required: &[],
    fields: &[Field {
        key: "per_client",
        description: "How many frames may wait for one websocket client that reads slowly, \
                      from 256 to 65536 (default 1024).",
        shape: Shape::Integer {
            min: *ServerLimits::QUEUE_LENGTHS.start() as i64,
            max: *ServerLimits::QUEUE_LENGTHS.end() as i64,
        },
    }],
};

const PER_ADDRESS_USAGE: &str = "`connections: per_address` is how many connections one \
                                 client address may hold: a whole number from 1 to 65536, \
                                 e.g. `per_address: 256`.";
const TOTAL_USAGE: &str = "`connections: total` is how many connections the server holds in \
                           all: a whole number from 1 to 65536, e.g. `total: 2048`.";
const TIMEOUT_USAGE: &str = "is a length of time with its unit, from 1s to 10m, e.g. `30s` or \
                             `2m` (a bare number is refused).";
const MAX_SIZE_USAGE: &str = "`messages: max_size` is the largest websocket message a client \
                              may send: an amount with its unit from 16 KiB to 64 MiB, e.g. \
                              `max_size: 1 MiB` (a bare number is refused).";
const PER_CLIENT_USAGE: &str = "`queues: per_client` is how many frames may wait for one \
                                websocket client: a whole number from 256 to 65536, e.g. \
                                `per_client: 4096`.";

impl Reader {
    /// Reads `server: connections:`; warns when `per_address` says more than `total` allows.
    pub(super) fn connections(&mut self, node: &Node, limits: &mut ServerLimits) {
        let mut per_address = None;
        for (field, value) in self.entries(node, &CONNECTIONS) {
            if field.key == "per_address" {
                let read = self.count(value, PER_ADDRESS_USAGE, ServerLimits::CONNECTIONS);
                if let Some(count) = read {
                    limits.per_address = count;
                    per_address = Some(value);
                }
            } else if let Some(count) = self.count(value, TOTAL_USAGE, ServerLimits::CONNECTIONS) {
                limits.total = count;
            }
        }
        let Some(at) = per_address.filter(|_| limits.per_address > limits.total) else {
            return;
        };
        let (per_address, total) = (limits.per_address, limits.total);
        let message = format!(
            "`per_address: {per_address}` is more than `total: {total}`: one address can never \
             hold more than {total} connections, the whole server's. Lower `per_address`, or \
             raise `total` to at least {per_address}."
        );
        let code = DiagnosticCode::PerAddressOverTotal;
        (self.diagnostics).push(Diagnostic::warning(code, &at.pos, message));
    }

    /// Reads `server: timeouts:`.
    pub(super) fn timeouts(&mut self, node: &Node, limits: &mut ServerLimits) {
        for (field, value) in self.entries(node, &TIMEOUTS) {
            let usage = format!("`timeouts: {}` {TIMEOUT_USAGE}", field.key);
            let within = |d: &Duration| ServerLimits::TIMEOUTS.contains(d);
            let parse = |t: &str| parse_duration(t).filter(within);
            let Some(timeout) = self.setting(value, &usage, parse) else {
                continue;
            };
            match field.key {
                "headers" => limits.header_timeout = timeout,
                _ => limits.body_timeout = timeout,
            }
        }
    }

    /// Reads `server: messages:`.
    pub(super) fn messages(&mut self, node: &Node, limits: &mut ServerLimits) {
        for (_, value) in self.entries(node, &MESSAGES) {
            let parse = |t: &str| {
                let bytes = usize::try_from(parse_size(t)?).ok()?;
                ServerLimits::MESSAGE_SIZES
                    .contains(&bytes)
                    .then_some(bytes)
            };
            if let Some(bytes) = self.setting(value, MAX_SIZE_USAGE, parse) {
                limits.max_message_bytes = bytes;
            }
        }
    }

    /// Reads `server: queues:`.
    pub(super) fn queues(&mut self, node: &Node, limits: &mut ServerLimits) {
        for (_, value) in self.entries(node, &QUEUES) {
            let lengths = ServerLimits::QUEUE_LENGTHS;
            if let Some(frames) = self.count(value, PER_CLIENT_USAGE, lengths) {
                limits.queue_per_client = frames;
            }
        }
    }

    /// A whole number within `range`, or `None` after reporting `usage`.
    fn count(&mut self, node: &Node, usage: &str, range: RangeInclusive<usize>) -> Option<usize> {
        let parse = |t: &str| t.parse::<usize>().ok().filter(|n| range.contains(n));
        self.setting(node, usage, parse)
    }
}

/// An amount of storage with its unit, as `size.rs` parses it.
fn message_size_schema(description: &'static str) -> Value {
    json!({
        "type": "string",
        "pattern": AMOUNT_PATTERN,
        "description": format!("{description} An amount with its unit: `1 MiB`, `256 KiB`."),
        "examples": ["1 MiB", "4 MiB"],
    })
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use crate::config::ServerLimits;
    use crate::config_file::section::Section;
    use crate::config_file::test_support::{parse, problems};

    use super::{
        CONNECTIONS, MAX_SIZE_USAGE, MESSAGES, PER_ADDRESS_USAGE, PER_CLIENT_USAGE, QUEUES,
        TIMEOUT_USAGE, TIMEOUTS, TOTAL_USAGE,
    };

    /// `seconds` as the descriptions write it: `30s`, `10m`.
    fn time(duration: Duration) -> String {
        match duration.as_secs() {
            s if s % 60 == 0 => format!("{}m", s / 60),
            s => format!("{s}s"),
        }
    }

    /// `bytes` as the descriptions write it: `16 KiB`, `1 MiB`.
    fn size(bytes: usize) -> String {
        match bytes {
            b if b % (1024 * 1024) == 0 => format!("{} MiB", b / (1024 * 1024)),
            b => format!("{} KiB", b / 1024),
        }
    }

    /// The description of `key` in `section`.
    fn described(section: &'static Section, key: &str) -> &'static str {
        section.field(key).expect("a field").description
    }

    /// The descriptions and usages are `const` text: they must write the figures the code
    /// holds, the ranges and the defaults.
    #[test]
    fn descriptions_and_usages_name_the_figures_the_code_holds() {
        let defaults = ServerLimits::default();
        let (low, high) = ServerLimits::CONNECTIONS.into_inner();
        let range = format!("from {low} to {high}");
        for (key, usage, default) in [
            ("per_address", PER_ADDRESS_USAGE, defaults.per_address),
            ("total", TOTAL_USAGE, defaults.total),
        ] {
            let description = described(&CONNECTIONS, key);
            assert!(description.contains(&range), "{description}");
            assert!(description.contains(&format!("(default {default})")));
            assert!(usage.contains(&range.replace("from ", "")), "{usage}");
        }
        let (low, high) = ServerLimits::TIMEOUTS.into_inner();
        let range = format!("from {} to {}", time(low), time(high));
        assert!(TIMEOUT_USAGE.contains(&range), "{TIMEOUT_USAGE}");
        for (key, default) in [
            ("headers", defaults.header_timeout),
            ("body", defaults.body_timeout),
        ] {
            let description = described(&TIMEOUTS, key);
            assert!(description.contains(&range), "{description}");
            assert!(description.contains(&format!("(default {})", time(default))));
        }
        let (low, high) = ServerLimits::MESSAGE_SIZES.into_inner();
        let range = format!("from {} to {}", size(low), size(high));
        let description = described(&MESSAGES, "max_size");
        assert!(description.contains(&range), "{description}");
        let default = size(defaults.max_message_bytes);
        assert!(description.contains(&format!("(default {default})")));
        assert!(MAX_SIZE_USAGE.contains(&range), "{MAX_SIZE_USAGE}");
        let (low, high) = ServerLimits::QUEUE_LENGTHS.into_inner();
        let range = format!("from {low} to {high}");
        let description = described(&QUEUES, "per_client");
        assert!(description.contains(&range), "{description}");
        let default = defaults.queue_per_client;
        assert!(description.contains(&format!("(default {default})")));
        assert!(PER_CLIENT_USAGE.contains(&range), "{PER_CLIENT_USAGE}");
    }

    #[test]
    fn a_file_that_says_nothing_keeps_the_defaults() {
        let file = parse("server:\n  trusted_proxies: [127.0.0.1]\n");
        assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
        assert_eq!(file.config.server.limits, ServerLimits::default());
    }

    #[test]
    fn each_limit_is_read_with_its_unit() {
        let file = parse(
            "server:\n  connections: {per_address: 512, total: 4096}\n  timeouts: {headers: \
             10s, body: 2m}\n  messages: {max_size: 4 MiB}\n  queues: {per_client: 2048}\n",
        );
        assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
        let limits = file.config.server.limits;
        assert_eq!(
            limits,
            ServerLimits {
                per_address: 512,
                total: 4096,
                header_timeout: Duration::from_secs(10),
                body_timeout: Duration::from_secs(120),
                max_message_bytes: 4 * 1024 * 1024,
                queue_per_client: 2048,
            }
        );
    }

    #[test]
    fn zero_negative_absurd_and_unitless_limits_are_located_and_the_defaults_kept() {
        let found = problems(
            "server:\n  connections:\n    per_address: 0\n    total: -5\n  timeouts:\n    \
             headers: 30\n    body: 2h\n  messages:\n    max_size: 1048576\n  queues:\n    \
             per_client: 100000\n",
        );
        let located: Vec<_> = (found.iter())
            .map(|(code, line, column, _)| (*code, *line, *column))
            .collect();
        assert_eq!(
            located,
            [
                ("config-bad-value", 3, 18),
                ("config-bad-value", 4, 12),
                ("config-bad-value", 6, 14),
                ("config-bad-value", 7, 11),
                ("config-bad-value", 9, 15),
                ("config-bad-value", 11, 17),
            ]
        );
        let says = |i: usize, words: &str| {
            let message = &found[i].3;
            assert!(message.contains(words), "{message:?} says {words:?}");
        };
        says(0, "from 1 to 65536");
        says(0, "Found: `0`");
        says(1, "Found: `-5`");
        says(2, "`timeouts: headers` is a length of time with its unit");
        says(3, "from 1s to 10m");
        says(4, "a bare number is refused");
        says(5, "from 256 to 65536");
        let file =
            parse("server:\n  connections: {per_address: 0}\n  messages: {max_size: 1 TB}\n");
        assert_eq!(file.config.server.limits, ServerLimits::default());
    }

    #[test]
    fn a_per_address_over_the_total_is_a_warning_at_per_address() {
        let found = problems("server:\n  connections: {total: 100, per_address: 200}\n");
        assert_eq!(found.len(), 1, "{found:?}");
        let (code, line, column, message) = &found[0];
        assert_eq!((*code, *line, *column), ("per-address-over-total", 2, 42));
        assert!(
            message.contains("raise `total` to at least 200"),
            "{message}"
        );
        let file = parse("server:\n  connections: {per_address: 2000}\n");
        assert_eq!(file.diagnostics.len(), 1, "over the default total too");
        assert_eq!(file.config.server.limits.per_address, 2000);
        // Only a lowered total: the default per-address cap is simply never reached.
        assert!(
            parse("server:\n  connections: {total: 64}\n")
                .diagnostics
                .is_empty()
        );
    }

    #[test]
    fn a_misspelt_limit_is_an_unknown_key_with_a_suggestion() {
        let found =
            problems("server:\n  connections: {per_adress: 5}\n  queue: {per_client: 300}\n");
        let codes: Vec<_> = found.iter().map(|(c, l, col, _)| (*c, *l, *col)).collect();
        assert_eq!(
            codes,
            [("config-unknown-key", 3, 3), ("config-unknown-key", 2, 17)]
        );
        assert!(found[0].3.contains("queues"), "{}", found[0].3);
        assert!(found[1].3.contains("per_address"), "{}", found[1].3);
    }
}
