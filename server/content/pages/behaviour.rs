//! What a page does that fights the robot or the kiosk, though the page itself is fine in a
//! browser: a `<html lang>` other than its language folder's (the browser hyphenates, reads
//! aloud and picks fonts in the wrong language), a film or sound that starts with its sound
//! on (it plays over the robot's speech), and a form on a page the attract loop shows (the
//! first touch ends the loop and leaves the page, so the form cannot be filled).

use std::collections::BTreeSet;

use crate::DiagnosticCode;
use crate::config::SiteConfig;
use crate::diagnostic::Diagnostic;
use crate::language::Language;

use super::languages::StrayFolders;
use super::scan::{PageScan, Value};
use super::text::SourceText;

/// The pages (inside `pages/`) that any attract loop shows: `kiosk: attract:` and each
/// range of opening hours with its own.
pub(super) fn attract_pages(config: &SiteConfig) -> BTreeSet<String> {
    let mut loops: Vec<_> = config.kiosk.attract.iter().collect();
    if let Some(schedule) = &config.schedule {
        let hours =
            (schedule.week.iter().flatten()).chain(schedule.special_days.values().flatten());
        loops.extend(hours.filter_map(|h| h.attract.as_ref()));
    }
    loops
        .into_iter()
        .flat_map(|l| l.pages.iter().cloned())
        .collect()
}

/// The language a page is shown in: that of its language folder (`pages/de/`), else the
/// default. `None` for a page of a folder named like a language the bundle lacks (reported
/// as `unknown-language`), or when `languages:` is not written (the default is then a
/// guess, not the author's word).
fn folder_language<'c>(
    config: &'c SiteConfig,
    stray: &StrayFolders,
    rel: &str,
) -> Option<&'c Language> {
    if config.language_places.is_empty() || stray.page_fallback(rel).is_some() {
        return None;
    }
    let languages = &config.languages;
    (languages.translated().iter())
        .find(|l| rel.starts_with(languages.page_folder(l).as_str()))
        .or(Some(languages.default_language()))
}

/// `<html lang="en">` on a page of `pages/de/` (`rel`, inside `pages/`): warned at the
/// value. Tags of one language (`en-gb` in the `en` pages) agree.
pub(super) fn check_lang(
    source: &SourceText,
    found: &PageScan,
    config: &SiteConfig,
    stray: &StrayFolders,
    rel: &str,
    out: &mut Vec<Diagnostic>,
) {
    let (Some(lang), Some(folder)) = (&found.lang, folder_language(config, stray, rel)) else {
        return;
    };
    let Some(written) = Language::parse(&lang.text) else {
        return; // not a short tag (`lang=""`, `x-klingon`): nothing to compare
    };
    let primary = |l: &Language| l.as_str().split('-').next().unwrap_or_default().to_owned();
    if primary(&written) == primary(folder) {
        return;
    }
    let place = if folder == config.languages.default_language() {
        format!(
            "the pages of the default language `{folder}` (`pages/` outside the language folders)"
        )
    } else {
        format!("the `{folder}` pages (`pages/{folder}/`)")
    };
    let message = format!(
        "This page says it is in `{written}` (`<html lang=\"{text}\">`), but it is one of \
         {place}: the browser hyphenates and reads it aloud as `{written}`. Write \
         `<html lang=\"{folder}\">`, or move the page into the folder of the language it is \
         in (`pages/{written}/`).",
        text = lang.text,
    );
    out.push(Diagnostic::warning(
        DiagnosticCode::PageLanguageMismatch,
        &source.pos(lang.at),
        message,
    ));
}

/// `<video autoplay>` or `<audio autoplay>` without `muted`: warned at `autoplay`.
pub(super) fn check_autoplay(source: &SourceText, found: &PageScan, out: &mut Vec<Diagnostic>) {
    for Value { text: element, at } in &found.autoplay_sound {
        let what = if element == "audio" {
            "This sound starts by itself"
        } else {
            "This film starts by itself, with its sound on,"
        };
        let message = format!(
            "{what} when the page opens, so it plays over whatever the robot is \
             saying. Add `muted` to the `<{element}>` (`<{element} autoplay muted>`), or remove \
             `autoplay` and start it from an act (`PROJECT` for the projector, or a \
             `data-act` button the visitor taps)."
        );
        out.push(Diagnostic::warning(
            DiagnosticCode::AutoplaySound,
            &source.pos(*at),
            message,
        ));
    }
}

/// A form on a page the attract loop shows: warned once per page, at its first field.
pub(super) fn check_attract_form(source: &SourceText, found: &PageScan, out: &mut Vec<Diagnostic>) {
    let Some(Value { text: element, at }) = found.form_fields.first() else {
        return;
    };
    let message = format!(
        "This page is shown by the attract loop (`attract: pages:` in docent.yaml), \
         and the first touch ends the loop and goes back to the home page, so this \
         `<{element}>` can never be filled in. Move the form to a page visitors reach from \
         the home page, or take this page out of the attract loop."
    );
    out.push(Diagnostic::warning(
        DiagnosticCode::AttractPageForm,
        &source.pos(*at),
        message,
    ));
}

/// `data-action="WELCOME"`: an attribute like `data-act` that the page script does not read,
/// so touching the element does nothing. A warning: a page's own script may use the name.
pub(super) fn check_act_typo(
    source: &SourceText,
    name: &Value,
    value: &str,
    out: &mut Vec<Diagnostic>,
) {
    let label = value.trim();
    let looks_like_label = !label.is_empty()
        && label
            .chars()
            .all(|c| c.is_alphanumeric() || matches!(c, '_' | '-' | ' '));
    if !looks_like_label {
        return;
    }
    let message = format!(
        "`{}` is not an attribute Docent reads, so touching this does nothing. Write \
         `data-act=\"{label}\"` instead to trigger the act.",
        name.text
    );
    out.push(Diagnostic::warning(
        DiagnosticCode::ActAttributeTypo,
        &source.pos(name.at),
        message,
    ));
}
