//! Pages in several languages: `pages/de/welcome.html` is the German `welcome.html`, shown
//! when the visitor's language is German and the file exists, else the default language's
//! `pages/welcome.html`. Checked here: each page missing in a language (one warning per page
//! and language, not per link to it) and each `data-language` button naming a language the
//! bundle does not have.

use std::collections::BTreeSet;

use crate::content::commands::CommandChecker;
use crate::content::diagnostic::Diagnostic;
use crate::content::language::{LANGUAGE_USAGE, Language};
use crate::content::model::{Located, Pos};
use crate::content::paths::BundleArea;

/// Warns about each page of the default language (`pages/*.html` outside the language
/// folders) that has no version in one of the bundle's other languages.
pub(super) fn check_translated_pages(
    checker: &CommandChecker<'_>,
    pages: &[String],
    out: &mut Vec<Diagnostic>,
) {
    let languages = checker.languages();
    let present: BTreeSet<&str> = pages.iter().map(String::as_str).collect();
    for page in pages {
        if languages.page_fallback(page).is_some() {
            continue; // a translation itself
        }
        for language in languages.translated() {
            let translated = format!("{language}/{page}");
            if present.contains(translated.as_str())
                || checker.resolve(BundleArea::Pages, &translated).is_ok()
            {
                continue;
            }
            let message = format!(
                "The page `{page}` has no `{language}` version, so a visitor in `{language}` \
                 sees it in `{default}`. Add `pages/{translated}` (a translated copy of this \
                 page), or ignore this if the page needs no translation.",
                default = languages.default_language(),
            );
            let pos = Pos::start_of(format!("pages/{page}"));
            out.push(Diagnostic::warning(
                "missing-page-translation",
                &pos,
                message,
            ));
        }
    }
}

/// The language a `data-language` value names, or `None` after reporting why it names none
/// of the bundle's languages.
pub(super) fn offered_language(
    checker: &CommandChecker<'_>,
    value: &str,
    pos: &Pos,
    out: &mut Vec<Diagnostic>,
) -> Option<Located<Language>> {
    let languages = checker.languages();
    let Some(language) = Language::parse(value) else {
        let message = format!(
            "`data-language=\"{value}\"` does not name a language. {LANGUAGE_USAGE} This \
             bundle's languages are {}.",
            languages.listed()
        );
        out.push(Diagnostic::error("bad-language", pos, message));
        return None;
    };
    if !languages.all().contains(&language) {
        let message = format!(
            "This button switches to `{language}`, which is not one of the bundle's languages \
             ({}), so tapping it would do nothing. Add `{language}` to `languages:` in \
             docent.yaml, or correct the button.",
            languages.listed()
        );
        out.push(Diagnostic::error("unknown-language", pos, message));
        return None;
    }
    Some(Located {
        value: language,
        pos: pos.clone(),
    })
}
