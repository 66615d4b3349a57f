//! The `reactions:` section of `docent.yaml`: robot events mapped to acts, each with an
//! optional condition on the event's data and a cool-down (`content::reaction`).
//!
//! ```yaml
//! reactions:
//!   - event: person.near
//!     if: distance < 1.5
//!     act: GREETING
//!     cooldown: 2m
//! ```

use crate::DiagnosticCode;
use crate::acts_file::yaml::{Kind, Node};
use crate::diagnostic::Diagnostic;
use crate::duration::parse_duration;
use crate::model::{Located, Pos};
use crate::names::robot_event_name_problem;
use crate::reaction::{Condition, DEFAULT_COOLDOWN, Reaction};

use serde_json::{Value, json};

use super::Reader;
use super::section::{Field, Section, Shape};
use crate::schema::section_schema;

/// The settings of one reaction.
const REACTION: Section = Section {
    name: "a reaction",
    required: &["event", "act"],
    fields: &[
        Field {
            key: "event",
            description: "The robot event that sets it off, e.g. `person.near`.",
            shape: Shape::Pattern("^[a-z][a-z0-9._-]{0,63}$"),
        },
        Field {
            key: "if",
            description: "A condition on the event's data: comparisons (<, <=, >, >=, ==, !=) \
                          of a field with a number, \"quoted text\", true or false, joined by \
                          `and`, e.g. `distance < 1.5`.",
            shape: Shape::Words,
        },
        Field {
            key: "act",
            description: "The label of the act it triggers.",
            shape: Shape::Words,
        },
        Field {
            key: "cooldown",
            description: "The least time between two of its triggers (default 30s).",
            shape: Shape::Duration,
        },
    ],
};

/// The schema of `reactions:`: a list of reactions.
pub(crate) fn schema(description: &'static str) -> Value {
    let reaction = section_schema(
        &REACTION,
        "A reaction: when the robot notices `event` and its data passes `if`, trigger `act`.",
    );
    json!({
        "description": description,
        "anyOf": [{ "type": "null" }, { "type": "array", "items": reaction }],
    })
}

const REACTIONS_USAGE: &str = "`reactions` is a list; each item names a robot `event`, the \
                               `act` it triggers and, if wanted, a condition `if` and a \
                               `cooldown`, e.g. `- {event: person.near, if: distance < 1.5, \
                               act: GREETING, cooldown: 2m}`.";
const EVENT_USAGE: &str = "`event` is the name of a robot event, as the robot's adapter or \
                           `rosbridge: events` names it, e.g. `event: person.near`.";
const ACT_USAGE: &str = "`act` is the label of the act to trigger, e.g. `act: GREETING`.";
const COOLDOWN_USAGE: &str = "`cooldown` is the least time between two triggers of this \
                              reaction, with its unit, e.g. `cooldown: 30s` or `cooldown: 5m`.";

impl Reader {
    /// Reads `reactions:`; returns the reactions and, for each, where its act is named (the
    /// acts are checked once the bundle's acts are known).
    pub(super) fn reactions(&mut self, node: &Node) -> (Vec<Reaction>, Vec<Located<String>>) {
        let items = match &node.kind {
            Kind::Seq(items) => items.as_slice(),
            Kind::Null => &[],
            _ => {
                self.bad(node, REACTIONS_USAGE);
                return (Vec::new(), Vec::new());
            }
        };
        let mut reactions = Vec::new();
        let mut acts = Vec::new();
        for item in items {
            let (reaction, act) = self.reaction(item);
            reactions.extend(reaction);
            acts.extend(act);
        }
        (reactions, acts)
    }

    fn reaction(&mut self, item: &Node) -> (Option<Reaction>, Option<Located<String>>) {
        if !matches!(item.kind, Kind::Map(_)) {
            self.bad(item, REACTIONS_USAGE);
            return (None, None);
        }
        let (mut event, mut condition, mut act) = (None, None, None);
        let mut cooldown = Some(DEFAULT_COOLDOWN);
        let mut complete = true;
        for (field, value) in self.entries(item, &REACTION) {
            match field.key {
                "event" => {
                    let name = value.as_text().map(str::trim).unwrap_or_default();
                    event = match robot_event_name_problem(name) {
                        None => Some(name.to_owned()),
                        Some(problem) => {
                            self.bad(value, &format!("{EVENT_USAGE} Here: {problem}."));
                            complete = false;
                            None
                        }
                    };
                }
                "if" => {
                    condition = self.condition(value);
                    complete &= condition.is_some();
                }
                "act" => {
                    let label = self.setting(value, ACT_USAGE, |t| Some(t.to_owned()));
                    act = label.map(|label| Located {
                        value: label,
                        pos: value.pos.clone(),
                    });
                    complete &= act.is_some();
                }
                _ => {
                    cooldown = self.setting(value, COOLDOWN_USAGE, parse_duration);
                    complete &= cooldown.is_some();
                }
            }
        }
        let (Some(event), Some(act), Some(cooldown)) = (event, act.clone(), cooldown) else {
            if complete {
                // Nothing was wrong in what is there: a key is missing.
                self.bad(item, REACTIONS_USAGE);
            }
            return (None, act);
        };
        let reaction = Reaction {
            event,
            condition,
            act: act.value.clone(),
            cooldown,
        };
        // A reaction with a wrong part is left out whole: a half-read one would fire wrongly.
        // Its act is still checked, so that every mistake is told in one go.
        (complete.then_some(reaction), Some(act))
    }

    /// Reads `if:`, placing a mistake at the character it concerns when the text stands in
    /// the file as written.
    fn condition(&mut self, node: &Node) -> Option<Condition> {
        let Some(text) = node.as_text() else {
            self.bad(
                node,
                "`if` is a condition on the event's data, e.g. `if: distance < 1.5`.",
            );
            return None;
        };
        let problem = match Condition::parse(text) {
            Ok(condition) => return Some(condition),
            Err(problem) => problem,
        };
        let verbatim_at = match &node.kind {
            Kind::Str { verbatim_at, .. } => *verbatim_at,
            _ => Some(0),
        };
        let pos = match verbatim_at {
            Some(start) => {
                let before = text.get(..problem.offset).unwrap_or(text).chars().count();
                let shift = start + u32::try_from(before).unwrap_or(0);
                Pos {
                    column: node.pos.column + shift,
                    ..node.pos.clone()
                }
            }
            None => node.pos.clone(),
        };
        let message = format!(
            "This reaction's condition cannot be read: {}. A condition compares a field of \
             the event's data with a number, \"quoted text\", true or false, joined by `and`, \
             e.g. `if: distance < 1.5 and zone == \"entrance\"`.",
            problem.message
        );
        self.diagnostics.push(Diagnostic::error(
            DiagnosticCode::ReactionBadCondition,
            &pos,
            message,
        ));
        None
    }
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use crate::config_file::{ConfigFile, parse_config};

    fn parse(text: &str) -> ConfigFile {
        parse_config(&"docent.yaml".into(), text.as_bytes())
    }

    fn located(text: &str) -> Vec<(&'static str, u32, u32)> {
        (parse(text).diagnostics.iter())
            .map(|d| (d.code.as_str(), d.line, d.column))
            .collect()
    }

    #[test]
    fn the_documented_example_is_read() {
        let file = parse(
            "reactions:\n  - event: person.near\n    if: distance < 1.5\n    act: GREETING\n    \
             cooldown: 2m\n  - {event: bumper, act: SORRY}\n",
        );
        assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
        let [near, bumper] = file.config.reactions.as_slice() else {
            panic!("{:?}", file.config.reactions);
        };
        assert_eq!(
            (near.event.as_str(), near.act.as_str(), near.cooldown),
            ("person.near", "GREETING", Duration::from_secs(120))
        );
        assert_eq!(
            near.condition.as_ref().unwrap().to_string(),
            "distance < 1.5"
        );
        assert_eq!(
            (bumper.condition.as_ref(), bumper.cooldown),
            (None, Duration::from_secs(30))
        );
        let acts: Vec<(&str, u32)> = (file.reaction_acts.iter())
            .map(|a| (a.value.as_str(), a.pos.line))
            .collect();
        assert_eq!(acts, [("GREETING", 4), ("SORRY", 6)]);
    }

    #[test]
    fn a_condition_mistake_is_placed_at_its_character() {
        // Plain: the column of `near` itself; quoted: one further for the quote.
        let plain = "reactions:\n  - {event: person.near, if: distance < near, act: HI}\n";
        assert_eq!(located(plain), [("reaction-bad-condition", 2, 41)]);
        let quoted = "reactions:\n  - {event: person.near, if: \"distance 1\", act: HI}\n";
        assert_eq!(located(quoted), [("reaction-bad-condition", 2, 40)]);
        let file = parse(plain);
        assert!(file.config.reactions.is_empty(), "left out whole");
        let acts: Vec<&str> = file
            .reaction_acts
            .iter()
            .map(|a| a.value.as_str())
            .collect();
        assert_eq!(acts, ["HI"], "its act is checked all the same");
    }

    #[test]
    fn bad_parts_and_missing_keys_are_reported_where_written() {
        let cases = [
            (
                "reactions:\n  - {event: Person Near, act: HI}\n",
                ("config-bad-value", 2, 13),
            ),
            (
                "reactions:\n  - {event: a, act: HI, cooldown: 5}\n",
                ("config-bad-value", 2, 35),
            ),
            ("reactions:\n  - {event: a}\n", ("config-bad-value", 2, 5)),
            (
                "reactions:\n  - {event: a, act: HI, when: x}\n",
                ("config-unknown-key", 2, 25),
            ),
            ("reactions: {event: a}\n", ("config-bad-value", 1, 12)),
        ];
        for (text, want) in cases {
            assert_eq!(located(text), [want], "{text}");
        }
    }
}
