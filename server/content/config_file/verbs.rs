//! The `verbs:` section of `docent.yaml`: the site's own commands, each a new capitalised
//! name with its adapter, argument rule and description. Separate because a site verb is
//! checked against the built-in verbs and the other declarations, not just read.

use crate::DiagnosticCode;
use crate::acts_file::yaml::{Kind, Node};
use crate::config::{AdapterKind, ArgRule, SiteConfig, SiteVerb};
use crate::diagnostic::Diagnostic;
use crate::model::Verb;

use serde_json::{Value, json};

use super::Reader;
use super::section::{Field, Section, Shape};
use crate::schema::section_schema;

/// The settings of one site command under `verbs:`.
pub(super) const SITE_VERB: Section = Section {
    name: "the command",
    required: &[],
    fields: &[
        Field {
            key: "adapter",
            description: "Who carries the command out: `ws` (a program connected over the \
                          websocket, the default) or `log` (nobody: it is only written to the \
                          log).",
            shape: Shape::Choice(&["ws", "log"]),
        },
        Field {
            key: "argument",
            description: "Whether the command needs something after it: `required`, \
                          `optional` (the default) or `none`.",
            shape: Shape::Choice(&["required", "optional", "none"]),
        },
        Field {
            key: "description",
            description: "What the command does, in a few words for people.",
            shape: Shape::Words,
        },
    ],
};

/// The schema of `verbs:`: site commands by name, none of them a built-in one.
pub(crate) fn schema(description: &'static str) -> Value {
    let built_in: Vec<&str> = Verb::BUILT_IN.iter().map(Verb::as_str).collect();
    json!({
        "type": ["object", "null"],
        "description": description,
        "propertyNames": {
            "pattern": "^[A-Z][A-Z0-9_]*$",
            "not": { "enum": built_in },
            "description": "A command name: capital letters, digits and `_`, starting with a \
                            letter, and not one of the built-in commands.",
        },
        "additionalProperties": section_schema(&SITE_VERB, "One command of this site."),
    })
}

const VERBS_USAGE: &str = "`verbs` lists the site's own commands by name, e.g. \
                           `verbs: { LIGHTS: { adapter: ws } }`.";

/// Capital letters, digits and `_`, starting with a letter: the shape of every verb.
fn is_verb_name(name: &str) -> bool {
    name.starts_with(|c: char| c.is_ascii_uppercase())
        && name
            .chars()
            .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_')
}

impl Reader {
    pub(super) fn verbs(&mut self, node: &Node, config: &mut SiteConfig) {
        let entries = match &node.kind {
            Kind::Map(entries) => entries,
            Kind::Null => return,
            _ => return self.bad(node, VERBS_USAGE),
        };
        for (key, value) in entries {
            let name = key.as_text().unwrap_or_default();
            let problem = if !is_verb_name(name) {
                "A command name is written in capital letters, digits and `_`, starting with a \
                 letter, e.g. `LIGHTS_ON`."
            } else if Verb::built_in(name).is_some() {
                "This is already a built-in command; choose another name for the site's command."
            } else if config.verbs.contains_key(name) {
                let message = format!("The command `{name}` is declared twice. Keep one.");
                self.diagnostics.push(Diagnostic::error(
                    DiagnosticCode::DuplicateKey,
                    &key.pos,
                    message,
                ));
                continue;
            } else {
                let verb = self.site_verb(value);
                config.verbs.insert(name.to_owned(), verb);
                continue;
            };
            self.bad(key, problem);
        }
    }

    pub(super) fn site_verb(&mut self, node: &Node) -> SiteVerb {
        let mut verb = SiteVerb {
            adapter: AdapterKind::Ws,
            argument: ArgRule::Optional,
            description: None,
        };
        for (field, value) in self.entries(node, &SITE_VERB) {
            match field.key {
                "adapter" => {
                    let kinds = [AdapterKind::Ws, AdapterKind::Log];
                    verb.adapter = self
                        .pick(value, "command adapter", &field.shape, &kinds)
                        .unwrap_or(verb.adapter);
                }
                "argument" => {
                    let rules = [ArgRule::Required, ArgRule::Optional, ArgRule::None];
                    verb.argument = self
                        .pick(value, "argument rule", &field.shape, &rules)
                        .unwrap_or(verb.argument);
                }
                _ => {
                    let usage = "`description` is a short text for people.";
                    verb.description = self.setting(value, usage, |t| Some(t.to_owned()));
                }
            }
        }
        verb
    }
}
