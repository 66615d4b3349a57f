//! Pages in several languages: `pages/de/welcome.html` is the German `welcome.html`, shown
//! when the visitor's language is German and the file exists, else the default language's
//! `pages/welcome.html`. Checked here: each page missing in a language (one warning per page
//! and language, not per link to it), each `data-language` button naming a language the
//! bundle does not have, and a folder of pages in a language `languages:` lacks (`pages/de/`
//! beside `languages: [en, fr]`), once, its links read as a language folder's.

use std::collections::BTreeSet;

use crate::DiagnosticCode;
use crate::commands::CommandChecker;
use crate::config::SiteConfig;
use crate::diagnostic::Diagnostic;
use crate::language::{LANGUAGE_USAGE, Language};
use crate::model::{Located, Pos};
use crate::paths::BundleArea;

/// Warns about each page of the default language (`pages/*.html` outside the language
/// folders) that has no version in one of the bundle's other languages.
pub(super) fn check_translated_pages(
    checker: &CommandChecker<'_>,
    pages: &[String],
    stray: &StrayFolders,
    out: &mut Vec<Diagnostic>,
) {
    let languages = checker.languages();
    let present: BTreeSet<&str> = pages.iter().map(String::as_str).collect();
    for page in pages {
        if languages.page_fallback(page).is_some() || stray.page_fallback(page).is_some() {
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
                DiagnosticCode::MissingPageTranslation,
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
        out.push(Diagnostic::error(DiagnosticCode::BadLanguage, pos, message));
        return None;
    };
    if !languages.all().contains(&language) {
        let message = format!(
            "This button switches to `{language}`, which is not one of the bundle's languages \
             ({}): the visitor would see \"This language is not available here.\" on tapping it. Add `{language}` to `languages:` in \
             docent.yaml, or correct the button.",
            languages.listed()
        );
        out.push(Diagnostic::error(
            DiagnosticCode::UnknownLanguage,
            pos,
            message,
        ));
        return None;
    }
    Some(Located {
        value: language,
        pos: pos.clone(),
    })
}

/// Folders directly under `pages/` named like a language tag the bundle does not list and
/// holding a page of the same name as one of the default language (`pages/de/index.html`
/// beside `pages/index.html`): translated pages of a language missing from `languages:`.
/// The copy of a page tells them from `css/` or `img/`, whose names are tags too.
#[derive(Default)]
pub(super) struct StrayFolders {
    folders: BTreeSet<String>,
}

impl StrayFolders {
    /// The stray language folders among `files` (paths inside `pages/`).
    pub(super) fn find(checker: &CommandChecker<'_>, files: &[String]) -> StrayFolders {
        let languages = checker.languages();
        let is_page = |rel: &str| {
            let lower = rel.to_ascii_lowercase();
            lower.ends_with(".html") || lower.ends_with(".htm")
        };
        let top: BTreeSet<&str> = (files.iter())
            .filter(|f| is_page(f) && !f.contains('/'))
            .map(String::as_str)
            .collect();
        let folders = (files.iter())
            .filter_map(|f| f.split_once('/'))
            .filter(|(_, rest)| is_page(rest) && top.contains(rest))
            .filter(|(folder, _)| {
                Language::parse(folder).is_some_and(|l| !languages.all().contains(&l))
            })
            .map(|(folder, _)| (*folder).to_owned())
            .collect();
        StrayFolders { folders }
    }

    /// `de/tour.html` → `tour.html` for a page of a stray folder, as for a language folder.
    pub(super) fn page_fallback<'p>(&self, rel: &'p str) -> Option<&'p str> {
        let (folder, rest) = rel.split_once('/')?;
        (self.folders.contains(folder) && !rest.is_empty()).then_some(rest)
    }

    /// One `unknown-language` for each stray folder, at its first page.
    pub(super) fn report(
        &self,
        checker: &CommandChecker<'_>,
        pages: &[String],
        out: &mut Vec<Diagnostic>,
    ) {
        let languages = checker.languages();
        for folder in &self.folders {
            let prefix = format!("{folder}/");
            let Some(first) = pages.iter().find(|p| p.starts_with(&prefix)) else {
                continue;
            };
            let message = format!(
                "`pages/{folder}/` looks like the pages of the language `{folder}`, which is not \
                 in `languages:` ({}), so no visitor ever sees them. Add `{folder}` to \
                 `languages:` in docent.yaml, or rename the folder.",
                languages.listed()
            );
            let pos = Pos::start_of(format!("pages/{first}"));
            out.push(Diagnostic::error(
                DiagnosticCode::UnknownLanguage,
                &pos,
                message,
            ));
        }
    }
}

/// Warns about each language of `languages:` but the default that no page offers with a
/// `data-language` button (`offered`: page, language): a visitor can never choose it, only
/// an operator or a dialog manager can.
pub(crate) fn check_reachable_languages(
    config: &SiteConfig,
    offered: &[(String, Language)],
    out: &mut Vec<Diagnostic>,
) {
    let default = config.languages.default_language();
    for Located { value, pos } in &config.language_places {
        if value == default || offered.iter().any(|(_, l)| l == value) {
            continue;
        }
        let message = format!(
            "No page has a button for `{value}` (`data-language=\"{value}\"`), so visitors \
             cannot choose it; only an operator or a dialog manager can. Add a button such as \
             `<button data-language=\"{value}\">…</button>` to the home page (and a button \
             back to `{default}` on its `{value}` version)."
        );
        out.push(Diagnostic::warning(
            DiagnosticCode::LanguageUnreachable,
            pos,
            message,
        ));
    }
}
