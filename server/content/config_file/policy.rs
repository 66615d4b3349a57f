//! The `channels:` and `priorities:` sections of `docent.yaml`: what each output channel does
//! with a command that arrives while another runs, and which trigger source wins. Read after
//! `verbs:`, so a site verb's channel can be checked to exist wherever it is written.

use crate::DiagnosticCode;
use crate::acts_file::yaml::{Kind, Node};
use crate::config::{
    Channel, ChannelPolicy, MAX_PRIORITY, MAX_QUEUE_LIMIT, Priorities, SiteConfig, WhenBusy,
};
use crate::diagnostic::Diagnostic;
use crate::suggest::did_you_mean;

use serde_json::{Value, json};

use super::Reader;
use super::section::{Field, Section, Shape};
use crate::schema::section_schema;

/// The settings of one channel's policy.
pub(super) const CHANNEL: Section = Section {
    name: "the channel",
    required: &[],
    fields: &[
        Field {
            key: "when_busy",
            description: "What a command arriving while another of the same priority runs \
                          does: `queue` (waits its turn), `replace` (stops what runs) or \
                          `drop` (is not carried out).",
            shape: Shape::Choice(&["queue", "replace", "drop"]),
        },
        Field {
            key: "queue_limit",
            description: "How many commands may wait on this channel, 1 to 20.",
            shape: Shape::Integer {
                min: 1,
                max: MAX_QUEUE_LIMIT as i64,
            },
        },
    ],
};

/// A trigger source's priority.
const PRIORITY: Shape = Shape::Integer {
    min: 1,
    max: MAX_PRIORITY as i64,
};

/// The settings of `priorities:`: one per trigger source.
pub(crate) const PRIORITIES: Section = Section {
    name: "priorities",
    required: &[],
    fields: &[
        Field {
            key: "operator",
            description: "The priority of `operator` triggers, 1 (lowest) to 9: a lower priority \
                          never interrupts a higher one.",
            shape: PRIORITY,
        },
        Field {
            key: "http",
            description: "The priority of `http` triggers, 1 (lowest) to 9: a lower priority \
                          never interrupts a higher one.",
            shape: PRIORITY,
        },
        Field {
            key: "dm",
            description: "The priority of `dm` triggers, 1 (lowest) to 9: a lower priority \
                          never interrupts a higher one.",
            shape: PRIORITY,
        },
        Field {
            key: "kiosk",
            description: "The priority of `kiosk` triggers, 1 (lowest) to 9: a lower priority \
                          never interrupts a higher one.",
            shape: PRIORITY,
        },
    ],
};

/// The schema of `channels:`: a policy by channel name, built-in or a site command's.
pub(crate) fn channels_schema(description: &'static str) -> Value {
    json!({
        "type": ["object", "null"],
        "description": description,
        "propertyNames": {
            "pattern": format!("^({}|[A-Z][A-Z0-9_]*)$", Channel::BUILT_IN.join("|")),
            "description": "A built-in channel or a site command's name.",
        },
        "additionalProperties": section_schema(&CHANNEL, "One output channel's policy."),
    })
}

const CHANNELS_USAGE: &str = "`channels` gives output channels a policy by name: `speech`, \
                              `touchscreen`, `projector`, `drive` or a command declared under \
                              `verbs`, e.g. `channels: { speech: { when_busy: replace } }`.";
const QUEUE_LIMIT_USAGE: &str = "`queue_limit` is how many commands may wait on this channel: \
                                 a whole number from 1 to 20, e.g. `queue_limit: 2`.";
const PRIORITY_USAGE: &str = "A priority is a whole number from 1 (lowest) to 9, e.g. \
                              `kiosk: 1`; a higher one is never interrupted by a lower one.";

impl Reader {
    /// Reads `channels:`; site verbs must already be in `config.verbs`.
    pub(super) fn channels(&mut self, node: &Node, config: &mut SiteConfig) {
        let entries = match &node.kind {
            Kind::Map(entries) => entries,
            Kind::Null => return,
            _ => return self.bad(node, CHANNELS_USAGE),
        };
        let mut seen: Vec<&str> = Vec::new();
        for (key, value) in entries {
            let name = key.as_text().unwrap_or_default();
            if seen.contains(&name) {
                self.bad(key, "This channel is given a policy twice here; keep one.");
                continue;
            }
            seen.push(name);
            let known_site = config.verbs.contains_key(name);
            let start = match config.channels.built_in_mut(name) {
                Some(policy) => *policy,
                None if known_site => config.channels.of(&Channel::Site(name.to_owned())),
                None => {
                    let names = Channel::BUILT_IN
                        .iter()
                        .copied()
                        .chain(config.verbs.keys().map(String::as_str));
                    let hint = did_you_mean(name, names);
                    let message = format!(
                        "There is no output channel `{name}`.{hint} {CHANNELS_USAGE} A site \
                         command's channel is named like the command, which must be declared \
                         under `verbs`."
                    );
                    self.bad(key, &message);
                    continue;
                }
            };
            let policy = self.channel_policy(value, start);
            match config.channels.built_in_mut(name) {
                Some(slot) => *slot = policy,
                None => {
                    config.channels.site.insert(name.to_owned(), policy);
                }
            }
        }
    }

    fn channel_policy(&mut self, node: &Node, mut policy: ChannelPolicy) -> ChannelPolicy {
        for (field, value) in self.entries(node, &CHANNEL) {
            if field.key == "when_busy" {
                let options = [WhenBusy::Queue, WhenBusy::Replace, WhenBusy::Drop];
                let what = "channel's `when_busy`";
                if let Some(when) = self.pick(value, what, &field.shape, &options) {
                    policy.when_busy = when;
                }
                continue;
            }
            let parse =
                |t: &str| (t.parse::<usize>().ok()).filter(|n| (1..=MAX_QUEUE_LIMIT).contains(n));
            if let Some(limit) = self.setting(value, QUEUE_LIMIT_USAGE, parse) {
                policy.queue_limit = limit;
            }
        }
        policy
    }

    /// Reads `priorities:`.
    pub(super) fn priorities(&mut self, node: &Node, config: &mut SiteConfig) {
        for (field, value) in self.entries(node, &PRIORITIES) {
            let key = field.key;
            let parse = |t: &str| {
                t.parse::<u8>()
                    .ok()
                    .filter(|p| (1..=MAX_PRIORITY).contains(p))
            };
            if let Some(priority) = self.setting(value, PRIORITY_USAGE, parse)
                && let Some(slot) = config.priorities.by_name_mut(key)
            {
                *slot = priority;
            }
        }
    }
}

impl Reader {
    /// Warns where `priorities:` lets visitors' taps cut the operator off: the kiosk above the
    /// operator (a higher priority takes every channel over), or level with it while speech is
    /// `when_busy: replace` (the latest utterance wins). Level with `queue`, the default, is
    /// left alone: a visitor's speech then waits for the operator's. Reported at `kiosk:`, else
    /// at `operator:` (whichever was written made the two meet).
    pub(super) fn visitors_over_operator(&mut self, node: &Node, config: &SiteConfig) {
        let Priorities {
            operator, kiosk, ..
        } = config.priorities;
        let speech_replaces = config.channels.speech.when_busy == WhenBusy::Replace;
        let message = if kiosk > operator {
            format!(
                "Visitors' taps (`kiosk: {kiosk}`) outrank the operator (`operator: \
                 {operator}`): a visitor touching the screen cuts off what the operator has the \
                 robot say, show or drive to, and the operator cannot take over. Give the kiosk \
                 a lower number than the operator, e.g. `priorities: {{ operator: 3, kiosk: 1 }}` \
                 (the defaults)."
            )
        } else if kiosk == operator && speech_replaces {
            format!(
                "Visitors' taps have the operator's priority ({kiosk}) and speech is \
                 `when_busy: replace` under `channels:`: a visitor's tap cuts the operator's \
                 speech off mid-sentence. Give the kiosk a lower number than the operator (e.g. \
                 `kiosk: 1`), or let speech wait its turn with `speech: {{ when_busy: queue }}`."
            )
        } else {
            return;
        };
        let Kind::Map(entries) = &node.kind else {
            return;
        };
        let written = |name: &str| {
            (entries.iter())
                .find(|(key, _)| key.as_text() == Some(name))
                .map(|(_, value)| value)
        };
        if let Some(at) = written("kiosk").or_else(|| written("operator")) {
            let code = DiagnosticCode::KioskOverOperator;
            (self.diagnostics).push(Diagnostic::warning(code, &at.pos, message));
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::config_file::test_support::{parse, problems};

    use crate::config::{Channel, ChannelPolicy, Priorities, WhenBusy};

    #[test]
    fn channel_policies_and_priorities_are_read() {
        let file = parse(
            "channels:\n  speech: { when_busy: replace }\n  LIGHTS: { when_busy: drop }\n  \
             drive: { when_busy: queue, queue_limit: 3 }\npriorities: { kiosk: 2, dm: 5 }\n\
             verbs:\n  LIGHTS: { adapter: log }\n",
        );
        assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
        let channels = &file.config.channels;
        assert_eq!(channels.speech.when_busy, WhenBusy::Replace);
        assert_eq!(channels.drive, ChannelPolicy::queue(3));
        let lights = channels.of(&Channel::Site("LIGHTS".into()));
        assert_eq!(lights.when_busy, WhenBusy::Drop);
        let expected = Priorities {
            kiosk: 2,
            dm: 5,
            ..Priorities::default()
        };
        assert_eq!(file.config.priorities, expected);
    }

    #[test]
    fn an_unknown_channel_is_located_with_a_suggestion() {
        let found = problems("channels:\n  speach: { when_busy: drop }\n");
        assert_eq!(found.len(), 1, "{found:?}");
        let (code, line, col, message) = &found[0];
        assert_eq!((*code, *line, *col), ("config-bad-value", 2, 3));
        assert!(message.contains("`speech`"), "{message}");
    }

    #[test]
    fn bad_policies_and_priorities_are_located_and_defaults_kept() {
        let text = "channels:\n  speech: { when_busy: shout, queue_limit: 500 }\n\
                    priorities: { kiosk: 0, robot: 3 }\n";
        let found: Vec<(&str, u32, u32)> = problems(text)
            .into_iter()
            .map(|(code, line, col, _)| (code, line, col))
            .collect();
        assert_eq!(
            found,
            // `channels:` is read last, after `verbs:`.
            [
                ("config-unknown-key", 3, 25),
                ("config-bad-value", 3, 22),
                ("config-bad-value", 2, 24),
                ("config-bad-value", 2, 44),
            ]
        );
        let file = parse(text);
        assert_eq!(file.config.channels.speech, ChannelPolicy::queue(2));
        assert_eq!(file.config.priorities, Priorities::default());
    }

    #[test]
    fn visitors_who_can_cut_the_operator_off_are_warned_at_the_kiosk() {
        let located = |text: &str| -> Vec<(&str, u32, u32)> {
            (problems(text).into_iter())
                .map(|(code, line, col, _)| (code, line, col))
                .collect()
        };
        // Above the operator: whatever the channels do.
        let above = "home: a.html\npriorities:\n  operator: 2\n  kiosk: 4\n";
        assert_eq!(located(above), [("kiosk-over-operator", 4, 10)]);
        // Level, with speech replacing (channels written after priorities): the same warning.
        let level = "priorities: { kiosk: 3 }\nchannels:\n  speech: { when_busy: replace }\n";
        assert_eq!(located(level), [("kiosk-over-operator", 1, 22)]);
        // Only `operator:` written, lowered to the kiosk's default 1.
        let lowered = "channels: { speech: { when_busy: replace } }\npriorities: { operator: 1 }\n";
        assert_eq!(located(lowered), [("kiosk-over-operator", 2, 25)]);
        // Level with speech queueing (the default), or below: visitors wait their turn.
        assert!(located("priorities: { kiosk: 3 }\n").is_empty());
        assert!(located("priorities: { kiosk: 2, dm: 5 }\n").is_empty());
        let found = problems(above);
        assert!(found[0].3.contains("`kiosk: 4`"), "{found:?}");
    }
}
