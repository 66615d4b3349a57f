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
pub(crate) mod server;
mod verbs;

use codebook::Codebook;
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
    /// The acts `reactions:` trigger, with their places (checked later).
    pub reaction_acts: Vec<Located<String>>,
    /// The pages and acts the attract loops and the schedule name, with their places
    /// (checked later, `attract::check_screen_refs`).
    pub screen_refs: attract::ScreenRefs,
    /// Problems found.
    pub diagnostics: Vec<Diagnostic>,
}

pub(crate) const TOP_KEYS: &[&str] = &[
    "home",
    "contexts",
    "languages",
    "speech",
    "display",
    "drive",
    "adapters",
    "kiosk",
    "projector",
    "corpus",
    "verbs",
    "access",
    "operator",
    "server",
    "channels",
    "priorities",
    "codebook",
    "reactions",
    "mqtt",
    "rosbridge",
    "schedule",
    "captions",
];
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
    };
    let mut out = ConfigFile::default();
    if let Some(root) = &parsed.root {
        reader.top_level(root, &mut out);
    }
    out.diagnostics = reader.diagnostics;
    out.screen_refs = reader.screen_refs;
    out
}

impl Reader {
    fn top_level(&mut self, root: &Node, out: &mut ConfigFile) {
        // Read after the loop: a site command's channel needs `verbs:`, wherever it is written.
        let mut channels = None;
        let mut codebook = None;
        let mut drive = None;
        let mut languages = Vec::new();
        let mut voices = Vec::new();
        let mut voice_written = false;
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
                "languages" => languages = self.languages(value),
                "speech" => {
                    voice_written = matches!(&value.kind, Kind::Map(entries)
                        if entries.iter().any(|(k, _)| k.as_text() == Some("voice")));
                    voices = self.speech(value, config);
                }
                "display" => {
                    for (_, value) in self.entries(value, &["adapter"], "display") {
                        let kinds = [("display", AdapterKind::Display), ("ws", AdapterKind::Ws)];
                        if let Some(kind) = self.choice(value, "display adapter", &kinds) {
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
