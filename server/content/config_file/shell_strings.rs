//! `kiosk: strings:` in `docent.yaml`: the site's own words for the kiosk shell, by language,
//! over the built-in table (`crate::shell_strings`): how a site adds a language the shell does
//! not know, or words it prefers.
//!
//! ```yaml
//! kiosk:
//!   strings:
//!     sv: { stop: Sluta tala, cannot_say: Roboten kan inte säga det nu. }
//! ```

use serde_json::{Value, json};

use crate::DiagnosticCode;
use crate::acts_file::yaml::{Kind, Node};
use crate::diagnostic::Diagnostic;
use crate::shell_strings::{ShellString, SiteStrings};
use crate::suggest::did_you_mean;

use super::Reader;
use super::languages::LANGUAGE_PATTERN;

/// What `kiosk: strings:` is, for the author and the schema.
pub(crate) const DESCRIPTION: &str = "The kiosk shell's own words (its Stop button and \
                                      notices) by language, over the built-in ones (en, de, \
                                      fr, es, it, nl), e.g. `strings: {sv: {stop: Sluta \
                                      tala}}`.";

const USAGE: &str = "`strings` gives the kiosk shell's words by language, each a text, e.g. \
                     `strings: {sv: {stop: Sluta tala, cannot_say: Roboten kan inte säga det \
                     nu.}}`.";

/// The schema of `kiosk: strings:`: language tags, each a map of the known keys to texts.
pub(crate) fn schema(description: &'static str) -> Value {
    let words: serde_json::Map<String, Value> = (ShellString::ALL.into_iter())
        .map(|s| {
            (
                s.key().to_owned(),
                json!({ "type": "string", "minLength": 1, "description": s.shown() }),
            )
        })
        .collect();
    json!({
        "description": description,
        "type": "object",
        "propertyNames": { "pattern": LANGUAGE_PATTERN },
        "additionalProperties": {
            "type": "object",
            "properties": words,
            "additionalProperties": false,
        },
    })
}

impl Reader {
    /// Reads `kiosk: strings:`; every problem located, the rest kept.
    pub(super) fn shell_strings(&mut self, node: &Node) -> SiteStrings {
        let mut out = SiteStrings::new();
        let languages = match &node.kind {
            Kind::Map(languages) => languages,
            Kind::Null => return out,
            _ => {
                self.bad(node, USAGE);
                return out;
            }
        };
        for (tag, words) in languages {
            let Some(language) = self.language(tag) else {
                continue;
            };
            let Kind::Map(entries) = &words.kind else {
                self.bad(words, USAGE);
                continue;
            };
            for (key, text) in entries {
                let name = key.as_text().unwrap_or_default();
                let Some(string) = ShellString::from_key(name) else {
                    self.unknown_string(key, name);
                    continue;
                };
                match text.as_text().map(str::trim).filter(|t| !t.is_empty()) {
                    Some(words) => {
                        (out.entry(language.clone()).or_default()).insert(string, words.to_owned());
                    }
                    None => self.bad(text, USAGE),
                }
            }
        }
        out
    }

    fn unknown_string(&mut self, key: &Node, name: &str) {
        let known: Vec<&str> = ShellString::ALL.into_iter().map(ShellString::key).collect();
        let hint = did_you_mean(name, known.iter().copied());
        let message = format!(
            "`{name}` is not one of the kiosk shell's words.{hint} Known words: {}.",
            known.join(", ")
        );
        self.diagnostics.push(Diagnostic::error(
            DiagnosticCode::ConfigUnknownKey,
            &key.pos,
            message,
        ));
    }
}
