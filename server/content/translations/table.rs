//! The texts a translator works on: one row per text alternative of every act variant, in
//! the bundle's order (acts files by name, acts and variants as written), each keyed by the
//! stable key `LABEL/Variant/N` (N from 1 in written order, the variant without its `@`).

use std::fmt;

use crate::{Bundle, Language};

/// The stable key of one text: `GREETING/TextChild/2`.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct TextKey {
    /// The act's label.
    pub label: String,
    /// The variant's name without a language (`TextChild`).
    pub variant: String,
    /// The alternative's number, from 1.
    pub number: usize,
}

impl TextKey {
    /// The key written `text` (a label may itself contain `/`; the last two parts are the
    /// variant and the number), or `None` when it is not shaped `LABEL/Variant/N`.
    pub fn parse(text: &str) -> Option<TextKey> {
        let mut parts = text.trim().rsplitn(3, '/');
        let number = parts.next()?;
        let variant = parts.next()?;
        let label = parts.next()?;
        let number_ok = !number.is_empty() && number.bytes().all(|b| b.is_ascii_digit());
        let number: usize = number_ok.then(|| number.parse().ok()).flatten()?;
        (number >= 1 && !variant.is_empty() && !label.is_empty()).then(|| TextKey {
            label: label.to_owned(),
            variant: variant.to_owned(),
            number,
        })
    }
}

impl fmt::Display for TextKey {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}/{}", self.label, self.variant, self.number)
    }
}

/// One text to translate.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Row {
    /// Its stable key.
    pub key: TextKey,
    /// The text in the bundle's default language.
    pub source: String,
    /// Its translation into the language exported, if the bundle has one.
    pub translation: Option<String>,
    /// Where the source is written (`acts.yaml:3`), for the translator.
    pub place: String,
}

/// Every text of `bundle` with its translation into `language`. An alternative has a
/// translation when the variant's `@language` list has an alternative of the same number.
pub fn rows(bundle: &Bundle, language: &Language) -> Vec<Row> {
    let mut rows = Vec::new();
    for act in &bundle.acts {
        for variant in &act.variants {
            let translated = variant.translations.get(language);
            for (i, alternative) in variant.alternatives.iter().enumerate() {
                let translation = translated
                    .and_then(|t| t.alternatives.get(i))
                    .map(|t| t.value.clone());
                rows.push(Row {
                    key: TextKey {
                        label: act.label.clone(),
                        variant: variant.name.clone(),
                        number: i + 1,
                    },
                    source: alternative.value.clone(),
                    translation,
                    place: format!("{}:{}", alternative.pos.file, alternative.pos.line),
                });
            }
        }
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_key_is_label_variant_and_number_from_one() {
        let key = TextKey::parse("GREETING/TextChild/2").expect("a key");
        assert_eq!(
            (key.label.as_str(), key.variant.as_str(), key.number),
            ("GREETING", "TextChild", 2)
        );
        assert_eq!(key.to_string(), "GREETING/TextChild/2");
        let slashed = TextKey::parse("ROOM/2/Text/1").expect("a label with a slash");
        assert_eq!(slashed.label, "ROOM/2");
    }

    #[test]
    fn anything_else_is_no_key() {
        for bad in [
            "",
            "GREETING",
            "GREETING/Text",
            "GREETING/Text/0",
            "GREETING/Text/x",
            "GREETING/Text/-1",
            "/Text/1",
            "GREETING//1",
            "GREETING/Text/1.5",
        ] {
            assert_eq!(TextKey::parse(bad), None, "{bad:?}");
        }
    }
}
