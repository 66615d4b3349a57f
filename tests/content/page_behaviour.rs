//! What a page does that fights the robot or the kiosk though a browser shows it fine: a
//! `<html lang>` other than its language folder's, a film or sound starting with its sound
//! on, a form on a page the attract loop shows. Each a warning at its file, line and column.

use crate::common;

use common::check::{assert_plain, bundle, check, places, yaml};
use docent_content::Severity;

const ACTS: (&str, &str) = ("acts.yaml", "- Label: INVITE\n  Text: Come closer!\n");

/// The places of `code` in the bundle with `docent.yaml` of `lines` and the extra `files`,
/// each a warning.
fn found(code: &str, lines: &[&str], files: &[(&str, &str)]) -> Vec<String> {
    let config = yaml(lines);
    let mut all = vec![ACTS, ("docent.yaml", config.as_str())];
    all.extend_from_slice(files);
    let dir = bundle(&all);
    let report = check(dir.path());
    assert_plain(&report);
    let errors: Vec<_> = (report.diagnostics.iter())
        .filter(|d| d.code == code && d.severity != Severity::Warning)
        .collect();
    assert!(errors.is_empty(), "warnings, not errors: {errors:?}");
    (places(&report).into_iter())
        .filter(|(c, _)| *c == code)
        .map(|(_, place)| place)
        .collect()
}

#[test]
fn a_page_whose_lang_disagrees_with_its_language_folder_is_told_at_the_value() {
    let lines = ["languages: [en, de]"];
    let pages = [
        (
            "pages/index.html",
            "<!doctype html>\n<html lang=\"en-GB\">\n<p>Hi</p>",
        ),
        // Copied from the English page and translated, but the tag was left.
        (
            "pages/de/index.html",
            "<!doctype html>\n<html lang=\"en\">\n<p>Hallo</p>",
        ),
        (
            "pages/tour.html",
            "<!doctype html>\n\n<html class=x lang=de>\n<p>Rundgang</p>",
        ),
        ("pages/de/tour.html", "<html lang=\"de-AT\"><p>Rundgang</p>"),
        // A folder of the default language's pages named like a tag (`img`, `fr`) is not
        // a language folder; the stray `fr/` is `unknown-language`'s, not this check's.
        ("pages/img/credits.html", "<html lang=\"de\">"),
        ("pages/fr/index.html", "<html lang=\"fr\">"),
    ];
    assert_eq!(
        found("page-language-mismatch", &lines, &pages),
        [
            "pages/de/index.html:2:13",
            "pages/img/credits.html:1:13",
            "pages/tour.html:3:20"
        ]
    );
    let config = yaml(&lines);
    let mut all = vec![ACTS, ("docent.yaml", config.as_str())];
    all.extend_from_slice(&pages);
    let dir = bundle(&all);
    let report = check(dir.path());
    let message = (report.diagnostics.iter())
        .find(|d| d.code == "page-language-mismatch")
        .map(|d| d.message.clone())
        .unwrap_or_default();
    assert!(message.contains("<html lang=\"de\">"), "{message}");
}

#[test]
fn lang_is_not_compared_when_languages_are_not_written() {
    // Without `languages:` the default is Docent's guess, not the author's word.
    let pages = [("pages/index.html", "<html lang=\"de\"><p>Hallo</p>")];
    assert_eq!(
        found("page-language-mismatch", &[], &pages),
        Vec::<String>::new()
    );
}

#[test]
fn a_film_or_sound_starting_with_its_sound_on_is_told_at_autoplay() {
    let page = "<p>Film</p>\n\
                <video autoplay></video>\n\
                <video autoplay muted loop></video>\n\
                <audio controls\n  autoplay=\"\"></audio>\n\
                <video controls></video>\n";
    let files = [("pages/index.html", page)];
    assert_eq!(
        found("autoplay-sound", &[], &files),
        ["pages/index.html:2:8", "pages/index.html:5:3"]
    );
}

#[test]
fn a_form_on_an_attract_page_is_told_at_its_first_field() {
    let lines = [
        "languages: [en, de]",
        "kiosk:",
        "  attract: {after: 2m, pages: [attract/quiz.html, attract/film.html]}",
    ];
    let quiz = "<h1>Quiz</h1>\n  <form>\n<input name=a><select></select></form>";
    let files = [
        ("pages/index.html", "<form><input name=q></form>"),
        ("pages/de/index.html", "<p>Hallo</p>"),
        ("pages/attract/quiz.html", quiz),
        (
            "pages/de/attract/quiz.html",
            "<p>Quiz</p>\n<textarea></textarea>",
        ),
        ("pages/attract/film.html", "<p>Come closer</p>"),
        ("pages/de/attract/film.html", "<p>Komm näher</p>"),
    ];
    // The home page's form is fine: visitors reach it by touching, which ends the loop.
    assert_eq!(
        found("attract-page-form", &lines, &files),
        [
            "pages/attract/quiz.html:2:3",
            "pages/de/attract/quiz.html:2:1"
        ]
    );
}

#[test]
fn a_form_on_a_page_of_a_schedule_ranges_attract_loop_is_told_too() {
    let lines = [
        "schedule:",
        "  closed: closed.html",
        "  open:",
        "    - {days: Sat, hours: 10:00-14:00, attract: {after: 1m, pages: [sat.html]}}",
    ];
    let files = [
        ("pages/index.html", "<p>Hi</p>"),
        ("pages/closed.html", "<p>Closed</p>"),
        (
            "pages/sat.html",
            "<input type=hidden name=from value=attract><p>Sign up:</p> <input type=email>",
        ),
    ];
    assert_eq!(
        found("attract-page-form", &lines, &files),
        ["pages/sat.html:1:60"]
    );
}
