//! `languages:` written the wrong way round. The first language in `languages:` is the one of
//! the plain `Text:` keys; an author who writes `languages: [de, en]` over English `Text:` keys
//! and German `Text@de:` translations gets, read as written, a `duplicate-key` at every
//! `Text@de` (the default language's key twice), a `missing-translation` for every text (no
//! `Text@en`) and page problems, and nothing at `docent.yaml`, where the mistake is.
//!
//! Told once instead, at the first language of `languages:`, with the order meant; the acts and
//! pages are then read in that order, so the knock-on problems it explains are not reported.
//! The order is taken as reversed when acts have translations into the first language
//! (`Text@de:`) and a later language has none at all (the one the plain texts' common words
//! name, when several have none; never when their words name another): that language is the
//! plain texts'. And either the plain texts' words are that language's, or (their words do
//! not say) at least two acts, most of those with text, have a translation into the first.

use std::collections::BTreeMap;
use std::path::Path;

use crate::config::{Language, Languages, SiteConfig};
use crate::diagnostic::{Diagnostic, DiagnosticCode};
use crate::gather::{CheckedFile, Gathered, gather};
use crate::load::ActsReplacements;
use crate::model::Located;
use crate::translated_copy::{guess_language, plain_texts};

/// The acts files (`names`) and pages read and checked, in the order of `languages:` as meant:
/// when it is written the wrong way round (told in `out`), `config` takes the order meant and
/// everything is read again, so the knock-on problems of the written order are not reported.
pub(crate) fn gather_as_meant(
    root: &Path,
    names: &[String],
    config: &mut SiteConfig,
    replaced: &ActsReplacements,
    out: &mut Vec<Diagnostic>,
) -> Gathered {
    let mut found = Vec::new();
    let mut gathered = gather(root, names, config, replaced, &mut found);
    if let Some((meant, places)) = meant_languages(config, &gathered.files, out) {
        (config.languages, config.language_places) = (meant, places);
        found.clear();
        gathered = gather(root, names, config, replaced, &mut found);
    }
    out.append(&mut found);
    gathered
}

/// The languages as meant, and their places, when `languages:` is written the wrong way round
/// (reported in `out`); `None` when its order agrees with the acts.
fn meant_languages(
    config: &SiteConfig,
    files: &[CheckedFile],
    out: &mut Vec<Diagnostic>,
) -> Option<(Languages, Vec<Located<Language>>)> {
    let written = config.languages.all();
    let first = written.first()?;
    let mut tagged: BTreeMap<&Language, usize> = BTreeMap::new();
    for (language, acts) in files.iter().flat_map(|f| &f.tagged) {
        *tagged.entry(language).or_default() += acts;
    }
    let in_first = tagged.get(first).copied().unwrap_or(0);
    if in_first == 0 {
        return None;
    }
    let texts = (files.iter())
        .flat_map(|f| &f.acts)
        .flat_map(|a| plain_texts(&a.variants));
    let guessed = guess_language(texts);
    let plain = plain_language(config, &tagged, guessed)?;
    // The plain texts are that language by their words; or, when their words do not say
    // (short texts), at least two acts and most of those with text have such a translation.
    let with_text = (files.iter())
        .flat_map(|f| &f.acts)
        .filter(|a| !a.variants.is_empty())
        .count();
    let most = in_first >= 2 && in_first * 2 > with_text;
    if guessed != Some(plain.as_str()) && !most {
        return None;
    }
    let mut meant: Vec<Language> = vec![plain.clone()];
    meant.extend(written.iter().filter(|l| **l != plain).cloned());
    let mut places = config.language_places.clone();
    places.sort_by_key(|l| meant.iter().position(|m| *m == l.value));
    let place = config.language_places.first()?;
    out.push(told(first, &plain, &meant, in_first, place));
    Some((Languages::new(meant)?, places))
}

/// The later language no act translates into: the plain `Text:` keys' (the one their common
/// words say, when several are never translated into).
fn plain_language(
    config: &SiteConfig,
    tagged: &BTreeMap<&Language, usize>,
    guessed: Option<&str>,
) -> Option<Language> {
    let never: Vec<&Language> = (config.languages.translated().iter())
        .filter(|l| !tagged.contains_key(l))
        .collect();
    match (never.as_slice(), guessed) {
        // Their words say another language: the plain texts are not the untranslated one.
        ([only], Some(words)) if words != only.as_str() => None,
        ([only], _) => Some((*only).clone()),
        (several, Some(words)) => several
            .iter()
            .find(|l| l.as_str() == words)
            .map(|l| (*l).clone()),
        _ => None,
    }
}

fn told(
    first: &Language,
    plain: &Language,
    meant: &[Language],
    in_first: usize,
    place: &Located<Language>,
) -> Diagnostic {
    let name = |l: &Language| {
        l.english_name()
            .map_or(format!("`{l}`"), |n| format!("{n} (`{l}`)"))
    };
    let list: Vec<&str> = meant.iter().map(Language::as_str).collect();
    let message = format!(
        "`languages:` lists `{first}` first, which makes {} the language of the plain `Text:` \
         keys, but the acts are written the other way round: {in_first} act(s) have \
         `Text@{first}:` translations and none has `Text@{plain}:`, so the plain texts are in \
         {}. Write `languages: [{}]`: the first language is the one of the plain `Text:` keys, \
         the others are those after the `@`. Docent checks the acts in that order meanwhile.",
        name(first),
        name(plain),
        list.join(", ")
    );
    Diagnostic::error(DiagnosticCode::LanguagesReversed, &place.pos, message)
}
