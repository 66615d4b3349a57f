//! Reading a bundle's `docent.yaml` into [`SiteConfig`]. Every key is optional and lower
//! case; unknown keys are errors (a misspelt setting silently ignored is worse than none).
//! A bad value is reported at its place and its default is kept, so the acts can still be
//! checked against the rest of the settings.

use std::sync::Arc;
use std::time::Duration;

use crate::content::acts_file::yaml::{self, Kind, Node, Recovery};
use crate::content::config::{AdapterKind, ArgRule, Bounds, SiteConfig, SiteVerb};
use crate::content::diagnostic::Diagnostic;
use crate::content::duration::parse_duration;
use crate::content::model::{Located, Pos, Verb};
use crate::content::suggest::closest;

/// What `docent.yaml` gave, beyond the settings themselves.
pub(crate) struct ConfigFile {
    /// The settings, defaults where absent or wrong.
    pub config: SiteConfig,
    /// The home page when set explicitly, with its place (a missing one is then an error).
    pub home: Option<Located<String>>,
    /// Problems found.
    pub diagnostics: Vec<Diagnostic>,
}

/// Parses the content of `docent.yaml`.
pub(crate) fn parse_config(file: &Arc<str>, bytes: &[u8]) -> ConfigFile {
    let parsed = yaml::parse(file, bytes, "config-syntax", Recovery::None);
    let mut reader = Reader {
        diagnostics: parsed.diagnostics,
    };
    let mut out = ConfigFile {
        config: SiteConfig::default(),
        home: None,
        diagnostics: Vec::new(),
    };
    if let Some(root) = &parsed.root {
        reader.top_level(root, &mut out);
    }
    out.diagnostics = reader.diagnostics;
    out
}

struct Reader {
    diagnostics: Vec<Diagnostic>,
}

impl Reader {
    fn top_level(&mut self, root: &Node, out: &mut ConfigFile) {
        const KEYS: &[&str] = &[
            "home", "contexts", "speech", "display", "drive", "adapters", "verbs",
        ];
        let config = &mut out.config;
        for (key, value) in self.entries(root, KEYS, "docent.yaml") {
            match key {
                "home" => {
                    if let Some(home) = self.text(
                        value,
                        "`home` must name a page under pages/, e.g. `home: index.html`.",
                    ) {
                        config.home = home.clone();
                        out.home = Some(Located {
                            value: home,
                            pos: value.pos.clone(),
                        });
                    }
                }
                "contexts" => config.contexts = self.contexts(value),
                "speech" => {
                    for (key, value) in self.entries(value, &["adapter", "voice", "rate"], "speech")
                    {
                        match key {
                            "adapter" => {
                                let kinds = [
                                    ("espeak", AdapterKind::Espeak),
                                    ("log", AdapterKind::Log),
                                    ("ws", AdapterKind::Ws),
                                ];
                                config.speech.adapter = self
                                    .choice(value, "speech adapter", &kinds)
                                    .or(config.speech.adapter);
                            }
                            "voice" => {
                                config.speech.voice =
                                    self.voice(value).unwrap_or(config.speech.voice.clone())
                            }
                            _ => {
                                config.speech.rate_wpm =
                                    self.rate(value).unwrap_or(config.speech.rate_wpm)
                            }
                        }
                    }
                }
                "display" => {
                    for (_, value) in self.entries(value, &["adapter"], "display") {
                        let kinds = [("display", AdapterKind::Display), ("ws", AdapterKind::Ws)];
                        config.display.adapter = self
                            .choice(value, "display adapter", &kinds)
                            .unwrap_or(config.display.adapter);
                    }
                }
                "drive" => self.drive(value, config),
                "adapters" => {
                    for (_, value) in self.entries(value, &["timeout"], "adapters") {
                        config.adapter_timeout =
                            self.timeout(value).unwrap_or(config.adapter_timeout);
                    }
                }
                _ => self.verbs(value, config),
            }
        }
    }

    fn drive(&mut self, node: &Node, config: &mut SiteConfig) {
        for (key, value) in
            self.entries(node, &["adapter", "speed", "pose_rate", "bounds"], "drive")
        {
            let drive = &mut config.drive;
            match key {
                "adapter" => {
                    let kinds = [("sim", AdapterKind::DriveSim), ("ws", AdapterKind::Ws)];
                    drive.adapter = self
                        .choice(value, "drive adapter", &kinds)
                        .unwrap_or(drive.adapter);
                }
                "speed" => {
                    let ok = self.number(value).filter(|&s| s > 0.0);
                    drive.speed = ok.unwrap_or_else(|| self.bad(value, "`speed` is the simulated speed in metres per second: a number above 0, e.g. `speed: 0.5`.", drive.speed));
                }
                "pose_rate" => {
                    let ok = self.number(value).filter(|&r| r > 0.0 && r <= 50.0);
                    drive.pose_hz = ok.unwrap_or_else(|| self.bad(value, "`pose_rate` is how many position updates per second the simulated drive sends: a number above 0 and at most 50, e.g. `pose_rate: 5`.", drive.pose_hz));
                }
                _ => drive.bounds = self.bounds(value).or(drive.bounds),
            }
        }
    }

    fn bounds(&mut self, node: &Node) -> Option<Bounds> {
        const KEYS: &[&str] = &["min_x", "min_y", "max_x", "max_y"];
        let usage = "`bounds` needs four numbers in metres, each min below its max, e.g. \
                     `bounds: { min_x: 0, min_y: 0, max_x: 20, max_y: 12 }`.";
        let mut values = [None; 4];
        let mut all_numbers = true;
        for (key, value) in self.entries(node, KEYS, "bounds") {
            let Some(index) = KEYS.iter().position(|k| *k == key) else {
                continue;
            };
            values[index] = self.number(value);
            if values[index].is_none() {
                all_numbers = false;
                self.bad(value, usage, ());
            }
        }
        let [Some(min_x), Some(min_y), Some(max_x), Some(max_y)] = values else {
            // A key left out (a wrong value or a wrong shape was reported already).
            if all_numbers && matches!(node.kind, Kind::Map(_)) {
                self.bad(node, usage, ());
            }
            return None;
        };
        if min_x >= max_x || min_y >= max_y {
            return self.bad(node, usage, None);
        }
        Some(Bounds {
            min_x,
            min_y,
            max_x,
            max_y,
        })
    }

    fn verbs(&mut self, node: &Node, config: &mut SiteConfig) {
        let Kind::Map(entries) = &node.kind else {
            if !matches!(node.kind, Kind::Null) {
                self.bad(node, "`verbs` lists new commands by name, e.g.\n  verbs:\n    LIGHTS:\n      adapter: ws", ());
            }
            return;
        };
        for (key, value) in entries {
            let Some(name) = key.as_text() else { continue };
            if !is_verb_name(name) {
                self.bad(key, &format!("`{name}` cannot be a command name: use capital letters, digits and `_`, starting with a letter, e.g. `LIGHTS_ON`."), ());
                continue;
            }
            if Verb::built_in(name).is_some() {
                self.bad(key, &format!("`{name}` is already a built-in command; choose another name for the site's command."), ());
                continue;
            }
            if config.verbs.contains_key(name) {
                self.diagnostics.push(Diagnostic::error(
                    "duplicate-key",
                    &key.pos,
                    format!("The command `{name}` is declared twice. Keep one."),
                ));
                continue;
            }
            let verb = self.site_verb(value);
            config.verbs.insert(name.to_owned(), verb);
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
                    verb.description = self.text(value, "`description` is a short text for people.")
                }
            }
        }
        verb
    }

    fn contexts(&mut self, node: &Node) -> Vec<String> {
        let items: Vec<&Node> = match &node.kind {
            Kind::Seq(items) => items.iter().collect(),
            Kind::Null => Vec::new(),
            _ => vec![node],
        };
        let mut contexts: Vec<String> = Vec::new();
        for item in items {
            let usage = "A context is the name of a text variant key starting with `Text`, e.g. `TextGroup` or `TextChild`.";
            match item.as_text() {
                Some(name)
                    if name.len() > 4
                        && name.starts_with("Text")
                        && !contexts.iter().any(|c| c == name) =>
                {
                    contexts.push(name.to_owned())
                }
                Some(name) if contexts.iter().any(|c| c == name) => {
                    self.bad(item, &format!("`{name}` is listed twice."), ())
                }
                _ => self.bad(item, usage, ()),
            }
        }
        contexts
    }

    fn voice(&mut self, node: &Node) -> Option<String> {
        // The voice is handed to espeak-ng as an argument: letters, digits and - + _ / only,
        // never starting with `-` (it would be read as an option).
        let ok = node.as_text().filter(|v| {
            !v.is_empty()
                && !v.starts_with('-')
                && v.chars()
                    .all(|c| c.is_ascii_alphanumeric() || "-+_/".contains(c))
        });
        match ok {
            Some(voice) => Some(voice.to_owned()),
            None => self.bad(
                node,
                "`voice` is an espeak-ng voice name such as `en`, `en-us` or `de`.",
                None,
            ),
        }
    }

    fn rate(&mut self, node: &Node) -> Option<u32> {
        let ok = node
            .as_text()
            .and_then(|t| t.trim().parse::<u32>().ok())
            .filter(|r| (40..=600).contains(r));
        ok.or_else(|| self.bad(node, "`rate` is the speaking speed in words per minute: a whole number from 40 to 600, e.g. `rate: 160`.", None))
    }

    fn timeout(&mut self, node: &Node) -> Option<Duration> {
        let ok = node
            .as_text()
            .and_then(parse_duration)
            .filter(|d| !d.is_zero());
        ok.or_else(|| self.bad(node, "`timeout` is a length of time with its unit, e.g. `timeout: 30s` or `timeout: 2m`.", None))
    }

    fn number(&self, node: &Node) -> Option<f64> {
        node.as_text()
            .and_then(|t| t.trim().parse::<f64>().ok())
            .filter(|n| n.is_finite())
    }

    fn text(&mut self, node: &Node, usage: &str) -> Option<String> {
        match node.as_text().map(str::trim) {
            Some(text) if !text.is_empty() => Some(text.to_owned()),
            _ => self.bad(node, usage, None),
        }
    }

    fn choice<T: Copy>(&mut self, node: &Node, what: &str, options: &[(&str, T)]) -> Option<T> {
        let written = node.as_text().unwrap_or_default();
        if let Some((_, value)) = options.iter().find(|(name, _)| *name == written) {
            return Some(*value);
        }
        let names: Vec<&str> = options.iter().map(|(name, _)| *name).collect();
        let hint = closest(written, names.iter().copied())
            .map_or_else(String::new, |s| format!(" Did you mean `{s}`?"));
        self.bad(
            node,
            &format!("The {what} must be one of: {}.{hint}", names.join(", ")),
            None,
        )
    }

    /// Reports a `config-bad-value` at `node` and returns `fallback`.
    fn bad<T>(&mut self, node: &Node, message: &str, fallback: T) -> T {
        let found = node.as_text().map_or_else(
            || format!("found {}", node.describe()),
            |t| format!("found `{t}`"),
        );
        self.diagnostics.push(Diagnostic::error(
            "config-bad-value",
            &node.pos,
            format!("{message} ({found})"),
        ));
        fallback
    }

    /// The entries of a settings mapping, reporting unknown, duplicate and non-text keys.
    /// A null section (`speech:` alone) has no entries.
    fn entries<'n>(
        &mut self,
        node: &'n Node,
        known: &'static [&'static str],
        section: &str,
    ) -> Vec<(&'static str, &'n Node)> {
        let entries = match &node.kind {
            Kind::Map(entries) => entries,
            Kind::Null => return Vec::new(),
            _ => {
                let keys = known.join(", ");
                return self.bad(
                    node,
                    &format!("`{section}` must be a set of settings ({keys})."),
                    Vec::new(),
                );
            }
        };
        let mut seen: Vec<(&str, &Pos)> = Vec::new();
        let mut out = Vec::new();
        for (key, value) in entries {
            let name = key.as_text().unwrap_or_default();
            if let Some((_, first)) = seen.iter().find(|(k, _)| *k == name) {
                let message = format!(
                    "`{name}` is set twice here (first on line {}). Keep one.",
                    first.line
                );
                self.diagnostics
                    .push(Diagnostic::error("duplicate-key", &key.pos, message));
                continue;
            }
            seen.push((name, &key.pos));
            match known.iter().find(|k| **k == name) {
                Some(k) => out.push((*k, value)),
                None => {
                    let hint = closest(name, known.iter().copied())
                        .map_or_else(String::new, |s| format!(" Did you mean `{s}`?"));
                    let message = format!(
                        "`{name}` is not a setting Docent knows in `{section}`.{hint} Known settings here: {}.",
                        known.join(", ")
                    );
                    self.diagnostics.push(Diagnostic::error(
                        "config-unknown-key",
                        &key.pos,
                        message,
                    ));
                }
            }
        }
        out
    }
}

/// Capital letters, digits and `_`, starting with a letter: the shape of every verb.
pub(crate) fn is_verb_name(name: &str) -> bool {
    name.starts_with(|c: char| c.is_ascii_uppercase())
        && name
            .chars()
            .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_')
}
