//! Reading a bundle's `docent.yaml` into [`SiteConfig`]. Every key is optional and lower
//! case; unknown keys are errors (a misspelt setting silently ignored is worse than none).
//! A bad value is reported at its place and its default is kept, so the acts can still be
//! checked against the rest of the settings.

use std::sync::Arc;

use crate::DiagnosticCode;
use crate::acts_file::yaml::{self, Kind, Node, Recovery};
use crate::config::{AdapterKind, SiteConfig};
use crate::diagnostic::Diagnostic;
use crate::duration::parse_duration;
use crate::model::Located;
use crate::schedule::CalendarDate;

mod access;
pub(crate) mod attract;
pub(crate) mod captions;
pub(crate) mod codebook;
mod devices;
mod languages;
pub(crate) mod mqtt;
pub(crate) mod operator;
pub(crate) mod policy;
pub(crate) mod reactions;
mod reader;
pub(crate) mod rosbridge;
pub(crate) mod schedule;
pub(crate) mod screens;
pub(crate) mod section;
pub(crate) mod server;
mod server_limits;
pub(crate) mod shell_strings;
mod verbs;

use codebook::Codebook;
use reader::Reader;
use section::{Field, Section, Shape};
use serde_json::{Value, json};

/// What `docent.yaml` gave, beyond the settings themselves.
#[derive(Default)]
pub(crate) struct ConfigFile {
    /// The settings, defaults where absent or wrong.
    pub config: SiteConfig,
    /// The home page when set explicitly, with its place (a missing one is then an error).
    pub home: Option<Located<String>>,
    /// The act to trigger when the kiosk goes idle, with its place (checked to exist later).
    pub idle_act: Option<Located<String>>,
    /// The operator console's map as written (`pages/...`), with its place (checked later).
    pub map: Option<Located<String>>,
    /// Visitor groups given a context explicitly, with the context's place (checked later
    /// against the bundle's contexts, which also decide the defaults).
    pub visitor_groups: Vec<(&'static str, Located<String>)>,
    /// The acts `reactions:` trigger, with their places (checked later).
    pub reaction_acts: Vec<Located<String>>,
    /// The pages and acts the attract loops and the schedule name, with their places
    /// (checked later, `attract::check_screen_refs`).
    pub screen_refs: attract::ScreenRefs,
    /// Each `schedule: special_days:` date with its place (checked against today later,
    /// `check_past_special_days`).
    pub special_dates: Vec<Located<CalendarDate>>,
    /// Problems found.
    pub diagnostics: Vec<Diagnostic>,
}

/// The top level of `docent.yaml`: every section, in the order unknown-key messages list them.
pub(crate) const SECTION: Section = Section {
    name: "docent.yaml",
    required: &[],
    fields: &[
        Field {
            key: "home",
            description: "The page under pages/ the touchscreen starts on, e.g. `index.html`.",
            shape: Shape::Words,
        },
        Field {
            key: "contexts",
            description: "The text variants this bundle uses as contexts, e.g. `[TextGroup, \
                          TextChild]`. Listing them lets `docent check` catch a misspelt \
                          variant key.",
            shape: Shape::Custom(contexts_schema),
        },
        Field {
            key: "languages",
            description: "The bundle's languages, the default first, e.g. `[en, de]`. Texts \
                          in another language are written `Text@de:` beside `Text:`, pages in \
                          `pages/de/`. Without it the bundle has one language: that of \
                          `speech: voice`, else `en`.",
            shape: Shape::Custom(languages::schema),
        },
        Field {
            key: "speech",
            description: "How the robot speaks.",
            shape: Shape::Nested(&devices::SPEECH),
        },
        Field {
            key: "display",
            description: "The touchscreen and the projector.",
            shape: Shape::Nested(&DISPLAY),
        },
        Field {
            key: "drive",
            description: "The robot's driving base.",
            shape: Shape::Nested(&devices::DRIVE),
        },
        Field {
            key: "adapters",
            description: "Settings shared by all devices.",
            shape: Shape::Nested(&ADAPTERS),
        },
        Field {
            key: "kiosk",
            description: "How the touchscreen behaves.",
            shape: Shape::Nested(&screens::KIOSK),
        },
        Field {
            key: "projector",
            description: "How the projector behaves.",
            shape: Shape::Nested(&screens::PROJECTOR),
        },
        Field {
            key: "corpus",
            description: "How the corpus is cut into visitor sessions.",
            shape: Shape::Nested(&screens::CORPUS),
        },
        Field {
            key: "verbs",
            description: "This site's own commands, by name, e.g. `verbs: { LIGHTS: { adapter: \
                          ws, argument: required } }`.",
            shape: Shape::Custom(verbs::schema),
        },
        Field {
            key: "access",
            description: "Credentials the operator console and a dialog manager show to \
                          connect. Better kept out of the bundle: set DOCENT_OPERATOR_TOKEN \
                          and DOCENT_DM_TOKEN instead.",
            shape: Shape::Nested(&access::SECTION),
        },
        Field {
            key: "operator",
            description: "What the operator console shows.",
            shape: Shape::Nested(&operator::SECTION),
        },
        Field {
            key: "server",
            description: "How Docent itself is reached.",
            shape: Shape::Nested(&server::SECTION),
        },
        Field {
            key: "channels",
            description: "What each output channel (speech, touchscreen, projector, drive or a \
                          command under `verbs`) does with a command that arrives while \
                          another runs.",
            shape: Shape::Custom(policy::channels_schema),
        },
        Field {
            key: "priorities",
            description: "Which trigger source wins when several ask for the same channel \
                          (defaults: operator 3, http 3, dm 2, kiosk 1).",
            shape: Shape::Nested(&policy::PRIORITIES),
        },
        Field {
            key: "codebook",
            description: "The annotation tiers researchers code recorded sessions with on the \
                          /sessions page, e.g. `{situation: {question: q, laughter: l}}`. \
                          Without it: one `situation` tier of `operator.situations`, keyed 1 \
                          to 9.",
            shape: Shape::Custom(codebook::schema),
        },
        Field {
            key: "reactions",
            description: "Robot events mapped to acts, each with an optional condition and a \
                          cool-down, e.g. `- {event: person.near, if: distance < 1.5, act: \
                          GREETING, cooldown: 2m}`.",
            shape: Shape::Custom(reactions::schema),
        },
        Field {
            key: "mqtt",
            description: "The fleet's MQTT broker and this robot's id in it (docs/FLEET.md); \
                          `docent serve --mqtt URL --robot-id ID` overrides both.",
            shape: Shape::Nested(&mqtt::SECTION),
        },
        Field {
            key: "rosbridge",
            description: "The link to a ROS 2 robot through a rosbridge v2 server \
                          (docs/ROBOT.md): where goals go, where the pose comes from, how the \
                          robot is stopped, which topics become robot events. Needs `url`.",
            shape: Shape::Nested(&rosbridge::SECTION),
        },
        Field {
            key: "schedule",
            description: "Opening hours, evaluated by the kiosk's own clock: outside them the \
                          kiosk shows the `closed` page.",
            shape: Shape::Nested(&schedule::SECTION),
        },
        Field {
            key: "captions",
            description: "Captions of the robot's speech: on the touchscreen by default (a \
                          page may opt out with <meta name=\"docent-captions\" \
                          content=\"off\">), on the projector when asked.",
            shape: Shape::Nested(&captions::SECTION),
        },
    ],
};

/// `display:`: who shows pages and pictures.
const DISPLAY: Section = Section {
    name: "display",
    required: &[],
    fields: &[Field {
        key: "adapter",
        description: "Who shows pages and pictures: `display` (Docent's own touchscreen and \
                      projector pages, the default) or `ws` (a program connected over the \
                      websocket).",
        shape: Shape::Choice(&["display", "ws"]),
    }],
};

/// `adapters:`: settings shared by all devices.
const ADAPTERS: Section = Section {
    name: "adapters",
    required: &[],
    fields: &[Field {
        key: "timeout",
        description: "How long a device (a websocket adapter, the touchscreen or projector \
                      page) may take to report a command before Docent reports it failed, \
                      e.g. `30s`; a film only until it plays. Not zero.",
        shape: Shape::Duration,
    }],
};

/// The schema of `contexts:`: one name or a list of names, each `Text` and more.
fn contexts_schema(description: &'static str) -> Value {
    let context = json!({
        "type": "string",
        "pattern": "^Text.",
        "description": "A context: the name of a text variant key, e.g. `TextChild`.",
    });
    json!({
        "description": description,
        "anyOf": [
            { "type": "null" },
            context,
            { "type": "array", "items": context, "uniqueItems": true },
        ],
    })
}

const HOME_USAGE: &str = "`home` names the page under pages/ the kiosk starts on, e.g. \
                          `home: index.html`.";
const CONTEXT_USAGE: &str = "A context is the name of a text variant key: `Text` followed by \
                             a name, e.g. `TextGroup` or `TextChild`.";
const TIMEOUT_USAGE: &str = "`timeout` is a length of time with its unit, e.g. `timeout: 30s` \
                             or `timeout: 2m`.";

/// Parses the content of `docent.yaml`.
pub(crate) fn parse_config(file: &Arc<str>, bytes: &[u8]) -> ConfigFile {
    let parsed = yaml::parse(file, bytes, DiagnosticCode::ConfigSyntax, Recovery::None);
    let mut reader = Reader {
        diagnostics: parsed.diagnostics,
        screen_refs: attract::ScreenRefs::default(),
        special_dates: Vec::new(),
    };
    let mut out = ConfigFile::default();
    if let Some(root) = &parsed.root {
        reader.top_level(root, &mut out);
    }
    out.diagnostics = reader.diagnostics;
    out.screen_refs = reader.screen_refs;
    out.special_dates = reader.special_dates;
    out
}

impl Reader {
    fn top_level(&mut self, root: &Node, out: &mut ConfigFile) {
        // Read after the loop: a site command's channel needs `verbs:`, wherever it is written.
        let mut channels = None;
        let mut priorities = None;
        let mut codebook = None;
        let mut drive = None;
        let mut languages = Vec::new();
        let mut voices = Vec::new();
        let mut voice_written = false;
        for (field, value) in self.entries(root, &SECTION) {
            let config = &mut out.config;
            match field.key {
                "home" => {
                    if let Some(home) = self.setting(value, HOME_USAGE, |t| Some(t.to_owned())) {
                        config.home.clone_from(&home);
                        out.home = Some(Located {
                            value: home,
                            pos: value.pos.clone(),
                        });
                    }
                }
                "contexts" => config.contexts = self.contexts(value),
                "languages" => languages = self.languages(value),
                "speech" => {
                    voice_written = matches!(&value.kind, Kind::Map(entries)
                        if entries.iter().any(|(k, _)| k.as_text() == Some("voice")));
                    voices = self.speech(value, config);
                }
                "display" => {
                    for (field, value) in self.entries(value, &DISPLAY) {
                        let kinds = [AdapterKind::Display, AdapterKind::Ws];
                        if let Some(kind) =
                            self.pick(value, "display adapter", &field.shape, &kinds)
                        {
                            config.display.adapter = kind;
                        }
                    }
                }
                "drive" => {
                    drive = Some(value);
                    self.drive(value, config);
                }
                "rosbridge" => self.rosbridge(value, config),
                "kiosk" => out.idle_act = self.kiosk(value, config),
                "projector" => self.projector(value, config),
                "corpus" => self.corpus(value, config),
                "adapters" => {
                    for (_, value) in self.entries(value, &ADAPTERS) {
                        let parse = |t: &str| parse_duration(t).filter(|d| !d.is_zero());
                        if let Some(timeout) = self.setting(value, TIMEOUT_USAGE, parse) {
                            config.adapter_timeout = timeout;
                        }
                    }
                }
                "access" => self.access(value, &mut config.access),
                "operator" => self.operator(value, out),
                "server" => self.server(value, &mut config.server),
                "channels" => channels = Some(value),
                "priorities" => {
                    priorities = Some(value);
                    self.priorities(value, config);
                }
                "codebook" => codebook = Some(self.codebook(value)),
                "reactions" => (config.reactions, out.reaction_acts) = self.reactions(value),
                "mqtt" => self.mqtt(value, &mut config.mqtt),
                "schedule" => config.schedule = self.schedule(value),
                "captions" => self.captions(value, config),
                _ => self.verbs(value, config),
            }
        }
        self.settle_languages(languages, voices, voice_written, &mut out.config);
        self.rosbridge_drive_needs_url(drive, &out.config);
        if let Some(channels) = channels {
            self.channels(channels, &mut out.config);
        }
        // After `channels:`: whether visitors cut the operator off depends on speech's policy.
        if let Some(priorities) = priorities {
            self.visitors_over_operator(priorities, &out.config);
        }
        // Read last: without a `codebook:`, the operator's situations are its one tier.
        out.config.codebook =
            codebook.unwrap_or_else(|| Codebook::from_situations(&out.config.operator.situations));
    }

    /// A single name or a list of names, each `Text` followed by something, no repeats.
    fn contexts(&mut self, node: &Node) -> Vec<String> {
        let items: Vec<&Node> = match &node.kind {
            Kind::Seq(items) => items.iter().collect(),
            Kind::Null => Vec::new(),
            _ => vec![node],
        };
        let mut contexts: Vec<String> = Vec::new();
        for item in items {
            match item.as_text() {
                Some(name) if contexts.iter().any(|c| c == name) => {
                    self.bad(item, "This context is listed twice.");
                }
                Some(name) if name.len() > 4 && name.starts_with("Text") => {
                    contexts.push(name.to_owned());
                }
                _ => self.bad(item, CONTEXT_USAGE),
            }
        }
        contexts
    }
}

/// What the section readers' tests share: `docent.yaml` text in, settings and problems out.
#[cfg(test)]
pub(crate) mod test_support {
    use std::sync::Arc;

    use super::{ConfigFile, parse_config};

    /// The settings read from `text`, as if it were `docent.yaml`.
    pub(crate) fn parse(text: &str) -> ConfigFile {
        parse_config(&Arc::from("docent.yaml"), text.as_bytes())
    }

    /// The problems found in `text`: code, line, column and message.
    pub(crate) fn problems(text: &str) -> Vec<(&'static str, u32, u32, String)> {
        let file = parse(text);
        file.diagnostics
            .into_iter()
            .map(|d| (d.code.as_str(), d.line, d.column, d.message))
            .collect()
    }
}

#[cfg(test)]
mod tests;
