//! A language a bundle speaks: a short BCP 47 language tag (`en`, `de`, `pt-br`), written in
//! `docent.yaml`'s `languages:`, after the `@` of a translated text key (`Text@de:`), in a
//! page's `data-language` and in the `language` frames and events. One type, parsed in one
//! place, so that every one of those agrees on what a tag is and how it is spelt.

use std::fmt;
use std::sync::Arc;

use serde::{Serialize, Serializer};

/// A short BCP 47 language tag, stored in lower case: a language of two or three letters,
/// optionally followed by one subtag: a region (two letters or three digits) or a script
/// (four letters). `en`, `de`, `pt-br`, `es-419`, `sr-latn`.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Language(Arc<str>);

/// How a tag is written, for messages that explain a refused one.
pub const LANGUAGE_USAGE: &str = "A language is a short language tag: two or three letters \
                                  (`en`, `de`, `fr`), optionally a hyphen and a region \
                                  (`pt-br`, `en-gb`).";

impl Language {
    /// The tag `text` (any case), or `None` when it is not a short language tag.
    pub fn parse(text: &str) -> Option<Language> {
        let lower = text.trim().to_ascii_lowercase();
        let mut parts = lower.split('-');
        let primary = parts.next()?;
        let primary_ok =
            (2..=3).contains(&primary.len()) && primary.bytes().all(|b| b.is_ascii_lowercase());
        let subtag_ok = match parts.next() {
            None => true,
            Some(sub) => {
                let letters = sub.bytes().all(|b| b.is_ascii_lowercase());
                let digits = sub.bytes().all(|b| b.is_ascii_digit());
                (sub.len() == 2 && letters)
                    || (sub.len() == 3 && digits)
                    || (sub.len() == 4 && letters)
            }
        };
        (primary_ok && subtag_ok && parts.next().is_none()).then(|| Language(lower.into()))
    }

    /// The tag of a language written by its name, in English or in itself (`English`,
    /// `Deutsch`, `Français`): what an author means by `languages: [English, German]`.
    pub fn from_name(name: &str) -> Option<Language> {
        let name = name.trim().to_lowercase();
        let tag = LANGUAGE_NAMES
            .iter()
            .find(|(_, names)| names.contains(&name.as_str()))?
            .0;
        Language::parse(tag)
    }

    /// The tag `text` when it is one of the common languages Docent knows by name (`de`,
    /// `FR`), so that a word such as `new` or `old` is not taken for a language.
    pub fn common(text: &str) -> Option<Language> {
        let lower = text.trim().to_ascii_lowercase();
        let known = LANGUAGE_NAMES.iter().any(|(tag, _)| *tag == lower);
        known.then(|| Language(lower.into()))
    }

    /// The language's English name (`German` for `de`, and for `de-at`), when Docent knows it.
    pub fn english_name(&self) -> Option<String> {
        let primary = self.0.split('-').next().unwrap_or(&self.0);
        let (_, names) = LANGUAGE_NAMES.iter().find(|(tag, _)| *tag == primary)?;
        let name = names.first()?;
        let mut letters = name.chars();
        let first = letters.next()?.to_uppercase();
        Some(first.chain(letters).collect())
    }

    /// The tag as Docent writes it (lower case).
    pub fn as_str(&self) -> &str {
        &self.0
    }

    /// English, the language of a bundle that names none and no voice.
    pub fn english() -> Language {
        Language(Arc::from("en"))
    }
}

/// Common language names (in English, in the language itself, and some in German) and their
/// tags, for the hint after a name written where a tag belongs.
const LANGUAGE_NAMES: &[(&str, &[&str])] = &[
    ("en", &["english", "englisch", "anglais"]),
    ("de", &["german", "deutsch", "allemand"]),
    (
        "fr",
        &[
            "french",
            "français",
            "francais",
            "französisch",
            "franzosisch",
        ],
    ),
    ("it", &["italian", "italiano", "italienisch"]),
    ("es", &["spanish", "español", "espanol", "spanisch"]),
    ("nl", &["dutch", "nederlands", "niederländisch"]),
    (
        "pt",
        &["portuguese", "português", "portugues", "portugiesisch"],
    ),
    ("ja", &["japanese", "日本語", "japanisch"]),
    ("zh", &["chinese", "中文", "chinesisch", "mandarin"]),
    ("ko", &["korean", "한국어"]),
    ("ru", &["russian", "русский", "russisch"]),
    ("uk", &["ukrainian", "українська"]),
    ("pl", &["polish", "polski", "polnisch"]),
    ("cs", &["czech", "čeština", "tschechisch"]),
    ("sv", &["swedish", "svenska", "schwedisch"]),
    ("da", &["danish", "dansk", "dänisch"]),
    ("nb", &["norwegian", "norsk", "norwegisch"]),
    ("fi", &["finnish", "suomi", "finnisch"]),
    ("el", &["greek", "ελληνικά", "griechisch"]),
    ("tr", &["turkish", "türkçe", "türkisch"]),
    ("ar", &["arabic", "العربية", "arabisch"]),
    ("he", &["hebrew", "עברית", "hebräisch"]),
    ("hu", &["hungarian", "magyar", "ungarisch"]),
    ("ca", &["catalan", "català", "katalanisch"]),
];

impl fmt::Display for Language {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl Serialize for Language {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(&self.0)
    }
}

impl<'de> serde::Deserialize<'de> for Language {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let text = String::deserialize(deserializer)?;
        Language::parse(&text).ok_or_else(|| serde::de::Error::custom(LANGUAGE_USAGE))
    }
}

/// The languages of a bundle (`languages:`), the first the default. Never empty.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Languages {
    list: Vec<Language>,
}

impl Languages {
    /// `list` as written; `None` when it is empty.
    pub fn new(list: Vec<Language>) -> Option<Languages> {
        (!list.is_empty()).then_some(Languages { list })
    }

    /// A bundle of one language.
    pub fn single(language: Language) -> Languages {
        Languages {
            list: vec![language],
        }
    }

    /// The default language: the first listed.
    pub fn default_language(&self) -> &Language {
        &self.list[0]
    }

    /// Every language, the default first.
    pub fn all(&self) -> &[Language] {
        &self.list
    }

    /// The languages other than the default: those texts and pages are translated into.
    pub fn translated(&self) -> &[Language] {
        &self.list[1..]
    }

    /// The listed language spelt `text` (any case), if any.
    pub fn find(&self, text: &str) -> Option<&Language> {
        let wanted = Language::parse(text)?;
        self.list.iter().find(|l| **l == wanted)
    }

    /// The page a kiosk in another language falls back to: `de/tour.html` (a page of the
    /// German folder `pages/de/`) → `tour.html`; `None` for a path in no language folder.
    pub fn page_fallback<'p>(&self, rel: &'p str) -> Option<&'p str> {
        (self.translated().iter())
            .find_map(|l| rel.strip_prefix(self.page_folder(l).as_str()))
            .filter(|rest| !rest.is_empty())
    }

    /// The folder under `pages/` that `language`'s pages are shown from: none (`""`) for the
    /// default language, `de/` for German. With [`Languages::page_fallback`] the one place
    /// that knows this layout; the kiosk shell gets the result per language
    /// ([`Languages::page_folders`]) and only puts it before a page or takes it off a path.
    pub fn page_folder(&self, language: &Language) -> String {
        if language == self.default_language() {
            String::new()
        } else {
            format!("{language}/")
        }
    }

    /// Each language's [`Languages::page_folder`], the default first.
    pub fn page_folders(&self) -> Vec<(&Language, String)> {
        (self.list.iter())
            .map(|l| (l, self.page_folder(l)))
            .collect()
    }

    /// The tags as a list for messages: `en, de`.
    pub fn listed(&self) -> String {
        let tags: Vec<&str> = self.list.iter().map(Language::as_str).collect();
        tags.join(", ")
    }
}

impl Default for Languages {
    fn default() -> Self {
        Languages::single(Language::english())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_tags_are_read_in_any_case_and_kept_in_lower_case() {
        for (written, kept) in [
            ("en", "en"),
            ("DE", "de"),
            ("pt-BR", "pt-br"),
            ("es-419", "es-419"),
            ("sr-Latn", "sr-latn"),
            ("gsw", "gsw"),
        ] {
            assert_eq!(
                Language::parse(written).map(|l| l.to_string()).as_deref(),
                Some(kept)
            );
        }
    }

    #[test]
    fn anything_else_is_not_a_language() {
        for bad in [
            "", "e", "english", "en_gb", "en-", "-en", "en-gb-x", "d3", "en-g", "de-12",
        ] {
            assert_eq!(Language::parse(bad), None, "{bad:?}");
        }
    }

    #[test]
    fn common_language_names_give_their_tag() {
        for (name, tag) in [("English", "en"), ("Deutsch", "de"), ("Français", "fr")] {
            assert_eq!(
                Language::from_name(name).map(|l| l.to_string()).as_deref(),
                Some(tag)
            );
        }
        assert_eq!(Language::from_name("Klingon"), None);
    }

    #[test]
    fn the_first_language_is_the_default_and_the_rest_are_translated() {
        let list = ["en", "de", "fr"]
            .map(|t| Language::parse(t).expect("tag"))
            .to_vec();
        let languages = Languages::new(list).expect("not empty");
        assert_eq!(languages.default_language().as_str(), "en");
        assert_eq!(languages.translated().len(), 2);
        assert_eq!(languages.find("DE").map(Language::as_str), Some("de"));
        assert_eq!(languages.find("it"), None);
        assert_eq!(languages.listed(), "en, de, fr");
        assert_eq!(languages.page_fallback("de/tour.html"), Some("tour.html"));
        assert_eq!(languages.page_fallback("fr/img/a.png"), Some("img/a.png"));
        assert_eq!(
            languages.page_fallback("en/tour.html"),
            None,
            "the default has no folder"
        );
        assert_eq!(languages.page_fallback("tour.html"), None);
        assert_eq!(Languages::new(Vec::new()), None);
    }

    #[test]
    fn each_language_shows_pages_from_its_folder_and_the_default_from_none() {
        let list = ["en", "de", "pt-br"]
            .map(|t| Language::parse(t).expect("tag"))
            .to_vec();
        let languages = Languages::new(list).expect("not empty");
        let folders: Vec<(&str, String)> = (languages.page_folders().into_iter())
            .map(|(l, f)| (l.as_str(), f))
            .collect();
        let expected = [("en", ""), ("de", "de/"), ("pt-br", "pt-br/")];
        assert_eq!(folders, expected.map(|(l, f)| (l, f.to_owned())));
        // A page shown from a folder falls back to the page the bundle names.
        for (language, folder) in languages.page_folders().into_iter().skip(1) {
            let path = format!("{folder}tour.html");
            assert_eq!(
                languages.page_fallback(&path),
                Some("tour.html"),
                "{language}"
            );
        }
        assert_eq!(
            languages.page_fallback("de/"),
            None,
            "a folder alone is no page"
        );
        assert_eq!(languages.page_fallback("pt/tour.html"), None);
    }
}
