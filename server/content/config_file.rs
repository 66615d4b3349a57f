//! Reading a bundle's `docent.yaml` into [`SiteConfig`]. Every key is optional and lower
//! case; unknown keys are errors (a misspelt setting silently ignored is worse than none).
//! A bad value is reported at its place and its default is kept, so the acts can still be
//! checked against the rest of the settings.

use std::sync::Arc;

use crate::content::acts_file::yaml::{self, Kind, Node, Recovery};
use crate::content::config::{AdapterKind, ArgRule, Bounds, SiteConfig, SiteVerb};
use crate::content::diagnostic::Diagnostic;
use crate::content::duration::parse_duration;
use crate::content::model::{Located, Verb};

mod access;
pub(crate) mod operator;
pub(crate) mod policy;
mod reader;
mod screens;
pub(crate) mod server;

use reader::Reader;

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
    /// Problems found.
    pub diagnostics: Vec<Diagnostic>,
}

pub(crate) const TOP_KEYS: &[&str] = &[
    "home",
    "contexts",
    "speech",
    "display",
    "drive",
    "adapters",
    "kiosk",
    "projector",
    "verbs",
    "access",
    "operator",
    "server",
    "channels",
    "priorities",
];
const HOME_USAGE: &str = "`home` names the page under pages/ the kiosk starts on, e.g. \
                          `home: index.html`.";
const CONTEXT_USAGE: &str = "A context is the name of a text variant key: `Text` followed by \
                             a name, e.g. `TextGroup` or `TextChild`.";
const VOICE_USAGE: &str = "`voice` is an espeak-ng voice name such as `en`, `en-us` or `de`.";
const MAX_SECONDS_USAGE: &str = "`max_seconds` is the longest a single text may take to say, \
                                 in seconds: a whole number from 1 to 3600, e.g. \
                                 `max_seconds: 45`.";
const RATE_USAGE: &str = "`rate` is the speaking speed in words per minute: a whole number \
                          from 40 to 600, e.g. `rate: 160`.";
const SPEED_USAGE: &str = "`speed` is the simulated driving speed in metres per second: a \
                           number above 0, e.g. `speed: 0.5`.";
const POSE_RATE_USAGE: &str = "`pose_rate` is how many position updates per second the \
                               simulated drive sends: above 0 and at most 50, e.g. `pose_rate: 5`.";
const BOUNDS_USAGE: &str = "`bounds` needs four numbers in metres, each min below its max, \
                            e.g. `bounds: { min_x: 0, min_y: 0, max_x: 20, max_y: 12 }`.";
const TIMEOUT_USAGE: &str = "`timeout` is a length of time with its unit, e.g. `timeout: 30s` \
                             or `timeout: 2m`.";
const VERBS_USAGE: &str = "`verbs` lists the site's own commands by name, e.g. \
                           `verbs: { LIGHTS: { adapter: ws } }`.";

/// Parses the content of `docent.yaml`.
pub(crate) fn parse_config(file: &Arc<str>, bytes: &[u8]) -> ConfigFile {
    let parsed = yaml::parse(file, bytes, "config-syntax", Recovery::None);
    let mut reader = Reader {
        diagnostics: parsed.diagnostics,
    };
    let mut out = ConfigFile::default();
    if let Some(root) = &parsed.root {
        reader.top_level(root, &mut out);
    }
    out.diagnostics = reader.diagnostics;
    out
}

/// Capital letters, digits and `_`, starting with a letter: the shape of every verb.
fn is_verb_name(name: &str) -> bool {
    name.starts_with(|c: char| c.is_ascii_uppercase())
        && name
            .chars()
            .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_')
}

/// An espeak-ng voice is passed as a process argument: a plain name, never an option.
fn is_voice_name(name: &str) -> bool {
    !name.is_empty()
        && !name.starts_with('-')
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "-+_/".contains(c))
}

fn positive(text: &str) -> Option<f64> {
    text.parse::<f64>()
        .ok()
        .filter(|n| n.is_finite() && *n > 0.0)
}

impl Reader {
    fn top_level(&mut self, root: &Node, out: &mut ConfigFile) {
        // Read after the loop: a site command's channel needs `verbs:`, wherever it is written.
        let mut channels = None;
        for (key, value) in self.entries(root, TOP_KEYS, "docent.yaml") {
            let config = &mut out.config;
            match key {
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
                "speech" => self.speech(value, config),
                "display" => {
                    for (_, value) in self.entries(value, &["adapter"], "display") {
                        let kinds = [("display", AdapterKind::Display), ("ws", AdapterKind::Ws)];
                        if let Some(kind) = self.choice(value, "display adapter", &kinds) {
                            config.display.adapter = kind;
                        }
                    }
                }
                "drive" => self.drive(value, config),
                "kiosk" => out.idle_act = self.kiosk(value, config),
                "projector" => self.projector(value, config),
                "adapters" => {
                    for (_, value) in self.entries(value, &["timeout"], "adapters") {
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
                "priorities" => self.priorities(value, config),
                _ => self.verbs(value, config),
            }
        }
        if let Some(channels) = channels {
            self.channels(channels, &mut out.config);
        }
    }

    fn speech(&mut self, node: &Node, config: &mut SiteConfig) {
        let speech = &mut config.speech;
        const KEYS: [&str; 4] = ["adapter", "voice", "rate", "max_seconds"];
        for (key, value) in self.entries(node, &KEYS, "speech") {
            match key {
                "adapter" => {
                    let kinds = [
                        ("espeak", AdapterKind::Espeak),
                        ("log", AdapterKind::Log),
                        ("ws", AdapterKind::Ws),
                        ("browser", AdapterKind::Browser),
                    ];
                    speech.adapter = self
                        .choice(value, "speech adapter", &kinds)
                        .or(speech.adapter);
                }
                "voice" => {
                    let parse = |t: &str| is_voice_name(t).then(|| t.to_owned());
                    if let Some(voice) = self.setting(value, VOICE_USAGE, parse) {
                        speech.voice = voice;
                    }
                }
                "max_seconds" => {
                    let parse = |t: &str| t.parse::<u32>().ok().filter(|s| (1..=3600).contains(s));
                    if let Some(seconds) = self.setting(value, MAX_SECONDS_USAGE, parse) {
                        speech.max_seconds = seconds;
                    }
                }
                _ => {
                    let parse = |t: &str| t.parse::<u32>().ok().filter(|r| (40..=600).contains(r));
                    if let Some(rate) = self.setting(value, RATE_USAGE, parse) {
                        speech.rate_wpm = rate;
                    }
                }
            }
        }
    }

    fn drive(&mut self, node: &Node, config: &mut SiteConfig) {
        let drive = &mut config.drive;
        for (key, value) in
            self.entries(node, &["adapter", "speed", "pose_rate", "bounds"], "drive")
        {
            match key {
                "adapter" => {
                    let kinds = [("sim", AdapterKind::DriveSim), ("ws", AdapterKind::Ws)];
                    if let Some(kind) = self.choice(value, "drive adapter", &kinds) {
                        drive.adapter = kind;
                    }
                }
                "speed" => {
                    if let Some(speed) = self.setting(value, SPEED_USAGE, positive) {
                        drive.speed = speed;
                    }
                }
                "pose_rate" => {
                    let parse = |t: &str| positive(t).filter(|r| *r <= 50.0);
                    if let Some(rate) = self.setting(value, POSE_RATE_USAGE, parse) {
                        drive.pose_hz = rate;
                    }
                }
                _ => drive.bounds = self.bounds(value).or(drive.bounds),
            }
        }
    }

    fn bounds(&mut self, node: &Node) -> Option<Bounds> {
        const KEYS: &[&str] = &["min_x", "min_y", "max_x", "max_y"];
        let mut values = [None; 4];
        let mut all_numbers = true;
        for (key, value) in self.entries(node, KEYS, "bounds") {
            let index = KEYS.iter().position(|k| *k == key)?;
            values[index] = self.setting(value, BOUNDS_USAGE, |t| {
                t.parse::<f64>().ok().filter(|n| n.is_finite())
            });
            all_numbers &= values[index].is_some();
        }
        let [Some(min_x), Some(min_y), Some(max_x), Some(max_y)] = values else {
            // A key left out; wrong values and wrong shapes were reported already.
            if all_numbers && matches!(node.kind, Kind::Map(_)) {
                self.bad(node, BOUNDS_USAGE);
            }
            return None;
        };
        if min_x >= max_x || min_y >= max_y {
            self.bad(node, BOUNDS_USAGE);
            return None;
        }
        Some(Bounds {
            min_x,
            min_y,
            max_x,
            max_y,
        })
    }

    fn verbs(&mut self, node: &Node, config: &mut SiteConfig) {
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
                self.diagnostics
                    .push(Diagnostic::error("duplicate-key", &key.pos, message));
                continue;
            } else {
                let verb = self.site_verb(value);
                config.verbs.insert(name.to_owned(), verb);
                continue;
            };
            self.bad(key, problem);
        }
    }

    fn site_verb(&mut self, node: &Node) -> SiteVerb {
        let mut verb = SiteVerb {
            adapter: AdapterKind::Ws,
            argument: ArgRule::Optional,
            description: None,
        };
        for (key, value) in
            self.entries(node, &["adapter", "argument", "description"], "the command")
        {
            match key {
                "adapter" => {
                    let kinds = [("ws", AdapterKind::Ws), ("log", AdapterKind::Log)];
                    verb.adapter = self
                        .choice(value, "command adapter", &kinds)
                        .unwrap_or(verb.adapter);
                }
                "argument" => {
                    let rules = [
                        ("required", ArgRule::Required),
                        ("optional", ArgRule::Optional),
                        ("none", ArgRule::None),
                    ];
                    verb.argument = self
                        .choice(value, "argument rule", &rules)
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
            .map(|d| (d.code, d.line, d.column, d.message))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use super::*;

    use super::test_support::{parse, problems};

    #[test]
    fn the_documented_example_maps_onto_site_config() {
        let text = "home: start.html\ncontexts: [TextGroup, TextFormally, TextChild]\n\
            speech:\n  adapter: espeak\n  voice: en-us\n  rate: 160\ndisplay:\n  adapter: ws\n\
            drive:\n  adapter: sim\n  speed: 0.5\n  pose_rate: 5\n  \
            bounds: { min_x: 0, min_y: 0, max_x: 20, max_y: 12 }\nadapters:\n  timeout: 45s\n\
            verbs:\n  LIGHTS:\n    adapter: ws\n    argument: required\n    \
            description: Switch the showcase lights\n  BELL:\n";
        let file = parse(text);
        assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
        let config = file.config;
        assert_eq!(config.home, "start.html");
        assert_eq!(file.home.map(|h| (h.pos.line, h.pos.column)), Some((1, 7)));
        assert_eq!(config.contexts, ["TextGroup", "TextFormally", "TextChild"]);
        assert_eq!(config.speech.adapter, Some(AdapterKind::Espeak));
        assert_eq!(
            (config.speech.voice.as_str(), config.speech.rate_wpm),
            ("en-us", 160)
        );
        assert_eq!(config.display.adapter, AdapterKind::Ws);
        assert_eq!(
            (
                config.drive.adapter,
                config.drive.speed,
                config.drive.pose_hz
            ),
            (AdapterKind::DriveSim, 0.5, 5.0)
        );
        assert_eq!(
            config.drive.bounds,
            Some(Bounds {
                min_x: 0.0,
                min_y: 0.0,
                max_x: 20.0,
                max_y: 12.0
            })
        );
        assert_eq!(config.adapter_timeout, Duration::from_secs(45));
        let lights = &config.verbs["LIGHTS"];
        assert_eq!(
            (lights.adapter, lights.argument),
            (AdapterKind::Ws, ArgRule::Required)
        );
        assert_eq!(
            lights.description.as_deref(),
            Some("Switch the showcase lights")
        );
        assert_eq!(
            (config.verbs["BELL"].adapter, config.verbs["BELL"].argument),
            (AdapterKind::Ws, ArgRule::Optional)
        );
    }

    #[test]
    fn an_empty_file_gives_the_defaults() {
        let file = parse("# nothing set yet\n");
        assert!(file.diagnostics.is_empty());
        assert_eq!(file.config, SiteConfig::default());
        assert!(file.home.is_none());
    }

    #[test]
    fn unknown_keys_are_located_with_a_suggestion() {
        let found = problems("hoem: x.html\nspeech:\n  volume: 3\n  rat: 100\n");
        let located: Vec<_> = found.iter().map(|(c, l, col, _)| (*c, *l, *col)).collect();
        assert_eq!(
            located,
            [
                ("config-unknown-key", 1, 1),
                ("config-unknown-key", 3, 3),
                ("config-unknown-key", 4, 3)
            ]
        );
        assert!(found[0].3.contains("Did you mean `home`?"));
        assert!(!found[1].3.contains("Did you mean"));
        assert!(found[2].3.contains("Did you mean `rate`?"));
    }

    #[test]
    fn bad_values_are_located_and_defaults_kept() {
        let text = [
            "speech:",
            "  adapter: espeek",
            "  voice: \"-x\"",
            "  rate: 1000",
            "drive:",
            "  speed: -1",
            "  pose_rate: 100",
            "  bounds: { min_x: 5, min_y: 0, max_x: 1, max_y: 2 }",
            "adapters:",
            "  timeout: 30",
            "contexts: [TextGroup, Group, TextGroup]",
        ];
        let file = parse(&text.join("\n"));
        let located: Vec<_> = file
            .diagnostics
            .iter()
            .map(|d| (d.code, d.line, d.column))
            .collect();
        assert_eq!(
            located,
            [
                ("config-bad-value", 2, 12),
                ("config-bad-value", 3, 10),
                ("config-bad-value", 4, 9),
                ("config-bad-value", 6, 10),
                ("config-bad-value", 7, 14),
                ("config-bad-value", 8, 11),
                ("config-bad-value", 10, 12),
                ("config-bad-value", 11, 23),
                ("config-bad-value", 11, 30),
            ]
        );
        assert!(
            file.diagnostics[0]
                .message
                .contains("Did you mean `espeak`?")
        );
        assert_eq!(file.config.speech, SiteConfig::default().speech);
        assert_eq!(file.config.drive, SiteConfig::default().drive);
        assert_eq!(file.config.contexts, ["TextGroup"]);
    }

    #[test]
    fn site_verbs_must_be_capitalised_and_new() {
        let found = problems("verbs:\n  SAY: {}\n  lights: {}\n  FOG:\n    argument: sometimes\n");
        let located: Vec<_> = found.iter().map(|(c, l, col, _)| (*c, *l, *col)).collect();
        assert_eq!(
            located,
            [
                ("config-bad-value", 2, 3),
                ("config-bad-value", 3, 3),
                ("config-bad-value", 5, 15)
            ]
        );
    }

    #[test]
    fn syntax_errors_and_duplicates_are_reported() {
        assert_eq!(problems("home: [x\n")[0].0, "config-syntax");
        let found = problems("home: a.html\nhome: b.html\n");
        assert_eq!(
            (found[0].0, found[0].1, found[0].2),
            ("duplicate-key", 2, 1)
        );
    }
}
