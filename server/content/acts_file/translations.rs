//! Texts in the bundle's other languages, written beside the original: `Text@de:` beside
//! `Text:`, `TextChild@de:` beside `TextChild:`. A reviewer sees original and translation
//! side by side, a missing one shows, and the act's label stays the one id of the act in
//! every language (docs/AUTHORING.md, "Several languages").

use std::collections::BTreeMap;

use crate::DiagnosticCode;
use crate::config::Languages;
use crate::diagnostic::Diagnostic;
use crate::language::{LANGUAGE_USAGE, Language};
use crate::model::{Located, Pos, Translation, Variant};
use crate::translations::same::may_stay_the_same;

/// What the `@` of a text key names.
pub(super) enum Suffix {
    /// The default language: the key is the original text (`Text@en:` is `Text:`).
    Default,
    /// Another of the bundle's languages.
    Other(Language),
    /// Not a language of the bundle (reported).
    Refused,
}

/// Reads the language after the `@` of the text key `name` (`base@tag`) written at `pos`.
pub(super) fn suffix(
    name: &str,
    tag: &str,
    pos: &Pos,
    languages: &Languages,
    out: &mut Vec<Diagnostic>,
) -> Suffix {
    let Some(language) = Language::parse(tag) else {
        let base = name.split_once('@').map_or(name, |(base, _)| base);
        let meant = Language::from_name(tag)
            .map(|l| format!(" Write `{base}@{l}` for {tag}."))
            .unwrap_or_default();
        let message = format!(
            "`{tag}` in `{name}` is not a language tag.{meant} {LANGUAGE_USAGE} The bundle's \
             languages are {}.",
            languages.listed()
        );
        out.push(Diagnostic::error(DiagnosticCode::BadLanguage, pos, message));
        return Suffix::Refused;
    };
    if language == *languages.default_language() {
        return Suffix::Default;
    }
    if languages.translated().contains(&language) {
        return Suffix::Other(language);
    }
    let message = format!(
        "`{name}` is in `{language}`, which is not one of the bundle's languages ({}). Add \
         `{language}` to `languages:` in docent.yaml, or correct the language after the `@`.",
        languages.listed()
    );
    out.push(Diagnostic::error(
        DiagnosticCode::UnknownLanguage,
        pos,
        message,
    ));
    Suffix::Refused
}

/// The translations of one act as they are read, put beside their originals at the end.
#[derive(Default)]
pub(super) struct Pending {
    /// (variant name, language, key as written, its place, texts): texts empty when the
    /// translation was written but unusable (already reported).
    texts: Vec<(String, Language, String, Translation)>,
}

impl Pending {
    /// A translation of `variant` into `language`, written as `key` at `pos`.
    pub(super) fn add(
        &mut self,
        variant: &str,
        language: Language,
        key: &str,
        pos: Pos,
        alternatives: Vec<Located<String>>,
    ) {
        let translation = Translation { pos, alternatives };
        (self.texts).push((variant.to_owned(), language, key.to_owned(), translation));
    }

    /// Puts each translation beside its original, reporting one without an original, and
    /// warns about each text not translated into each of the bundle's other languages.
    pub(super) fn settle(
        self,
        label: &str,
        variants: &mut [Variant],
        languages: &Languages,
        out: &mut Vec<Diagnostic>,
    ) {
        let mut written: BTreeMap<(String, Language), ()> = BTreeMap::new();
        for (name, language, key, translation) in self.texts {
            written.insert((name.clone(), language.clone()), ());
            let Some(variant) = variants.iter_mut().find(|v| v.name == name) else {
                let message = format!(
                    "`{key}` translates `{name}`, but the act `{label}` has no `{name}` in the \
                     default language ({}). Write `{name}:` first; the translation goes beside \
                     it.",
                    languages.default_language()
                );
                out.push(Diagnostic::error(
                    DiagnosticCode::TranslationWithoutOriginal,
                    &translation.pos,
                    message,
                ));
                continue;
            };
            if !translation.alternatives.is_empty() {
                count_mismatch(&key, variant, &translation, out);
                same_as_original(&key, variant, &translation, languages, out);
                variant.translations.insert(language, translation);
            }
        }
        for variant in variants.iter() {
            for language in languages.translated() {
                if written.contains_key(&(variant.name.clone(), language.clone())) {
                    continue;
                }
                let message = format!(
                    "The act `{label}` has no `{name}@{language}`: a visitor in `{language}` \
                     hears the `{default}` text. Add `{name}@{language}:` beside `{name}:`.",
                    name = variant.name,
                    default = languages.default_language(),
                );
                out.push(Diagnostic::warning(
                    DiagnosticCode::MissingTranslation,
                    &variant.pos,
                    message,
                ));
            }
        }
    }
}

/// Warns when the translation `key` has another number of texts than its original: text N
/// goes with text N (the translators' table pairs them by number), so a missing one is a gap
/// and an extra one is never in a table.
fn count_mismatch(
    key: &str,
    variant: &Variant,
    translation: &Translation,
    out: &mut Vec<Diagnostic>,
) {
    let (original, translated) = (variant.alternatives.len(), translation.alternatives.len());
    if original == translated {
        return;
    }
    let name = &variant.name;
    let texts = |n: usize| {
        if n == 1 {
            "1 text".to_owned()
        } else {
            format!("{n} texts")
        }
    };
    let consequence = if translated < original {
        format!(
            "so the texts after number {translated} of `{name}` have no translation here, and a \
             translator's table shows them as untranslated"
        )
    } else {
        format!(
            "so the texts after number {original} of `{key}` translate nothing: they never \
             appear in a translator's table, and an import can replace them"
        )
    };
    let message = format!(
        "`{key}` has {} but `{name}` has {}: translation N goes with text N, {consequence}. \
         Write as many texts in `{key}` as in `{name}`, in the same order.",
        texts(translated),
        texts(original),
    );
    out.push(Diagnostic::warning(
        DiagnosticCode::TranslationCount,
        &translation.pos,
        message,
    ));
}

/// Warns at each text of the translation `key` that is its original itself (not a name, a
/// number or a single word, which may stay the same): copied, not translated.
fn same_as_original(
    key: &str,
    variant: &Variant,
    translation: &Translation,
    languages: &Languages,
    out: &mut Vec<Diagnostic>,
) {
    let pairs = variant.alternatives.iter().zip(&translation.alternatives);
    for (n, (original, translated)) in pairs.enumerate() {
        let text = original.value.trim();
        if translated.value.trim() != text || may_stay_the_same(text) {
            continue;
        }
        let message = format!(
            "Text {} of `{key}` is its `{}` original itself (\"{text}\"): copied, not \
             translated, so a visitor in this language hears the original. Write the \
             translation here (only a name, a number or a single word may stay the same).",
            n + 1,
            languages.default_language(),
        );
        out.push(Diagnostic::warning(
            DiagnosticCode::TranslationSameAsOriginal,
            &translated.pos,
            message,
        ));
    }
}
