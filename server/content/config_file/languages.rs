//! `languages:` (the bundle's languages, the first the default) and `speech: voices:` (the
//! espeak-ng voice of each). Read apart from the other sections because both need the other:
//! a voice's language must be one of `languages:`, and a bundle without `languages:` speaks
//! the language of its `speech: voice`.

use std::collections::BTreeMap;

use crate::DiagnosticCode;
use crate::acts_file::yaml::{Kind, Node};
use crate::config::{Language, Languages, SiteConfig};
use crate::diagnostic::Diagnostic;
use crate::language::LANGUAGE_USAGE;
use crate::model::Located;

use serde_json::{Value, json};

use super::Reader;

/// A short BCP 47 language tag, as `content::Language::parse` reads it (any case).
pub(crate) const LANGUAGE_PATTERN: &str = "^[A-Za-z]{2,3}(-([A-Za-z]{2}|[0-9]{3}|[A-Za-z]{4}))?$";

const LANGUAGES_USAGE: &str = "`languages` lists the bundle's languages, the default first, \
                               e.g. `languages: [en, de]`.";
const VOICES_USAGE: &str = "`voices` gives each language its espeak-ng voice, e.g. \
                            `voices: {en: en-gb, de: de}`.";

/// The schema of `languages:`: one tag or a list of different tags.
pub(crate) fn schema(description: &'static str) -> Value {
    let language = json!({
        "type": "string",
        "pattern": LANGUAGE_PATTERN,
        "description": "A short language tag, e.g. `en`, `de` or `pt-br`.",
    });
    json!({
        "description": description,
        "anyOf": [
            language,
            { "type": "array", "items": language, "minItems": 1, "uniqueItems": true },
        ],
    })
}

impl Reader {
    /// `languages:`: a list (or a single tag), no repeats; every tag checked. A list written
    /// without its brackets (`en, fr`) or with language names (`English`) is reported and
    /// read as meant, so that the texts in those languages bring no errors of their own.
    pub(super) fn languages(&mut self, node: &Node) -> Vec<Located<Language>> {
        let items: Vec<&Node> = match &node.kind {
            Kind::Seq(items) => items.iter().collect(),
            Kind::Str { .. } | Kind::Guessed(_) => {
                if let Some(meant) = self.languages_without_brackets(node) {
                    return meant;
                }
                vec![node]
            }
            _ => {
                self.bad(node, LANGUAGES_USAGE);
                return Vec::new();
            }
        };
        let mut out: Vec<Located<Language>> = Vec::new();
        for item in items {
            let Some(language) = self.language(item) else {
                continue;
            };
            if out.iter().any(|l| l.value == language) {
                let told = |d: &Diagnostic| (d.line, d.column) == (item.pos.line, item.pos.column);
                if self.diagnostics.iter().any(told) {
                    continue; // a name (`English`) already reported with its tag
                }
                let message = format!(
                    "`{language}` is listed twice in `languages:`. Remove the second `{language}`."
                );
                self.diagnostics.push(Diagnostic::error(
                    DiagnosticCode::ConfigBadValue,
                    &item.pos,
                    message,
                ));
                continue;
            }
            out.push(Located {
                value: language,
                pos: item.pos.clone(),
            });
        }
        if matches!(&node.kind, Kind::Seq(items) if items.is_empty()) {
            self.bad(node, LANGUAGES_USAGE);
        }
        out
    }

    /// `languages: en, fr`: the list meant, after saying how to write it; `None` when the text
    /// has no comma or a part is no language.
    fn languages_without_brackets(&mut self, node: &Node) -> Option<Vec<Located<Language>>> {
        let text = node.as_text()?;
        if !text.contains(',') {
            return None;
        }
        let mut meant: Vec<Language> = Vec::new();
        for part in text.split(',') {
            let language = Language::parse(part).or_else(|| Language::from_name(part))?;
            if !meant.contains(&language) {
                meant.push(language);
            }
        }
        let tags: Vec<&str> = meant.iter().map(Language::as_str).collect();
        let message = format!(
            "`{}` is not a language tag but several: write the languages as a list in \
             brackets: `languages: [{}]`. Docent reads them as that list meanwhile.",
            text.trim(),
            tags.join(", ")
        );
        self.diagnostics.push(Diagnostic::error(
            DiagnosticCode::BadLanguage,
            &node.pos,
            message,
        ));
        let located = meant.into_iter().map(|value| Located {
            value,
            pos: node.pos.clone(),
        });
        Some(located.collect())
    }

    /// One language tag; a language written by its name (`English`) is reported with its tag
    /// and taken as meant; `None` after any other `bad-language` at `node`.
    pub(super) fn language(&mut self, node: &Node) -> Option<Language> {
        let text = node.as_text().unwrap_or_default();
        if let Some(language) = Language::parse(text) {
            return Some(language);
        }
        if let Some(meant) = Language::from_name(text) {
            let message = format!(
                "`{}` is the name of a language, not its tag: write `{meant}`. {LANGUAGE_USAGE}",
                text.trim()
            );
            self.diagnostics.push(Diagnostic::error(
                DiagnosticCode::BadLanguage,
                &node.pos,
                message,
            ));
            return Some(meant);
        }
        let found = node
            .as_text()
            .map_or_else(|| node.describe().to_owned(), |t| format!("`{t}`"));
        let message = format!("{found} is not a language tag. {LANGUAGE_USAGE}");
        self.diagnostics.push(Diagnostic::error(
            DiagnosticCode::BadLanguage,
            &node.pos,
            message,
        ));
        None
    }

    /// `speech: voices:`: language → voice name, each language checked later against
    /// `languages:` (which may be written after `speech:`).
    pub(super) fn voices(
        &mut self,
        node: &Node,
        is_voice_name: fn(&str) -> bool,
    ) -> Vec<(Located<Language>, String)> {
        let Kind::Map(entries) = &node.kind else {
            if !matches!(node.kind, Kind::Null) {
                self.bad(node, VOICES_USAGE);
            }
            return Vec::new();
        };
        let mut out: Vec<(Located<Language>, String)> = Vec::new();
        for (key, value) in entries {
            let Some(language) = self.language(key) else {
                continue;
            };
            if out.iter().any(|(l, _)| l.value == language) {
                self.bad(key, "This language has a voice already.");
                continue;
            }
            let usage = "A voice is an espeak-ng voice name such as `en`, `en-gb` or `de`.";
            let parse = |t: &str| is_voice_name(t).then(|| t.to_owned());
            if let Some(voice) = self.setting(value, usage, parse) {
                let pos = key.pos.clone();
                out.push((
                    Located {
                        value: language,
                        pos,
                    },
                    voice,
                ));
            }
        }
        out
    }

    /// Puts the languages and voices together once the whole file is read: without
    /// `languages:`, the bundle speaks the language of `speech: voice` (English when that is
    /// not a language tag or not written); every language gets its voice.
    pub(super) fn settle_languages(
        &mut self,
        written: Vec<Located<Language>>,
        voices: Vec<(Located<Language>, String)>,
        voice_written: bool,
        config: &mut SiteConfig,
    ) {
        let from_voice = || {
            voice_written
                .then(|| Language::parse(&config.speech.voice))
                .flatten()
        };
        config.languages = Languages::new(written.iter().map(|l| l.value.clone()).collect())
            .unwrap_or_else(|| Languages::single(from_voice().unwrap_or_else(Language::english)));
        config.language_places = written;
        let mut chosen: BTreeMap<Language, String> = BTreeMap::new();
        for (language, voice) in voices {
            if !config.languages.all().contains(&language.value) {
                let message = format!(
                    "`{}` has a voice but is not one of the bundle's languages ({}). Add it to \
                     `languages:` or remove its voice.",
                    language.value,
                    config.languages.listed()
                );
                self.diagnostics.push(Diagnostic::error(
                    DiagnosticCode::UnknownLanguage,
                    &language.pos,
                    message,
                ));
                continue;
            }
            config.voice_places.push(language.clone());
            chosen.insert(language.value, voice);
        }
        let default = config.languages.default_language().clone();
        config.speech.voices.clear(); // the defaults' English voice is not this bundle's
        for language in config.languages.all() {
            let voice = chosen.remove(language).unwrap_or_else(|| {
                if *language == default && voice_written {
                    config.speech.voice.clone()
                } else {
                    language.as_str().to_owned()
                }
            });
            config.speech.voices.insert(language.clone(), voice);
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::config_file::test_support::{parse, problems};

    fn voices(text: &str) -> Vec<(String, String)> {
        let config = parse(text).config;
        (config.speech.voices.iter())
            .map(|(l, v)| (l.to_string(), v.clone()))
            .collect()
    }

    #[test]
    fn the_first_language_is_the_default_and_each_gets_a_voice() {
        let file = parse("languages: [en, de]\nspeech:\n  voices: {en: en-gb}\n");
        assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
        assert_eq!(file.config.languages.default_language().as_str(), "en");
        assert_eq!(file.config.languages.listed(), "en, de");
        let expected = [("de", "de"), ("en", "en-gb")].map(|(l, v)| (l.into(), v.into()));
        assert_eq!(
            voices("languages: [en, de]\nspeech:\n  voices: {en: en-gb}\n"),
            expected
        );
    }

    #[test]
    fn without_languages_the_bundle_speaks_its_voices_language_or_english() {
        let german = parse("speech:\n  voice: de\n").config;
        assert_eq!(german.languages.listed(), "de");
        assert_eq!(
            voices("speech:\n  voice: de\n"),
            [("de".into(), "de".into())]
        );
        assert_eq!(
            parse("speech:\n  voice: gmw/en\n")
                .config
                .languages
                .listed(),
            "en"
        );
        assert_eq!(parse("home: a.html\n").config.languages.listed(), "en");
        // `speech: voice` speaks the default language when `languages:` is written too.
        let both = "languages: [de, en]\nspeech:\n  voice: de-1\n";
        let expected = [("de", "de-1"), ("en", "en")].map(|(l, v)| (l.into(), v.into()));
        assert_eq!(voices(both), expected);
    }

    #[test]
    fn a_bad_tag_a_repeated_language_and_a_foreign_voice_are_reported_where_written() {
        let found = problems("languages: [en, english, en]\nspeech:\n  voices:\n    fr: fr\n");
        let codes: Vec<(&str, u32, u32)> = found.iter().map(|p| (p.0, p.1, p.2)).collect();
        assert_eq!(
            codes,
            [
                ("bad-language", 1, 17),
                ("config-bad-value", 1, 26),
                ("unknown-language", 4, 5)
            ],
            "{found:?}"
        );
    }
}
