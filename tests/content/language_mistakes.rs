//! What `docent check` says about the mistakes authors make with languages: a translation
//! with more or fewer texts than its original, `languages:` without brackets or with language
//! names, a name after the `@`, the default language written twice, a page folder or a button
//! for a language not declared, a declared language no page offers. One fixture per mistake,
//! each at its exact code, file, line and column, with the words of its hint.

use crate::common;

use common::check::{bundle, check, places, yaml};
use common::languages::{GERMAN_HOME, HOME, TWO};
use docent_content::Severity;

#[test]
fn a_translation_with_fewer_texts_than_its_original_is_a_warning_at_its_key() {
    let acts = yaml(&[
        "- Label: HELLO",
        "  Text: [Hello, Hi, Good morning]",
        "  Text@de: [Hallo, Hi du]",
    ]);
    let dir = bundle(&[TWO, HOME, GERMAN_HOME, ("acts.yaml", &acts)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("translation-count", "acts.yaml:3:3".to_owned())]
    );
    let warning = &report.diagnostics[0];
    assert_eq!(warning.severity, Severity::Warning);
    for words in [
        "`Text@de` has 2 texts but `Text` has 3",
        "translation N goes with text N",
    ] {
        assert!(warning.message.contains(words), "{}", warning.message);
    }
}

#[test]
fn a_translation_with_more_texts_than_its_original_is_a_warning_at_its_key() {
    let acts = yaml(&[
        "- Label: HELLO",
        "  Text:",
        "    - Hello",
        "    - Hi",
        "    - Good morning",
        "  Text@de:",
        "    - Hallo",
        "    - Hi du",
        "    - Guten Morgen",
        "    - Moin",
    ]);
    let dir = bundle(&[TWO, HOME, GERMAN_HOME, ("acts.yaml", &acts)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("translation-count", "acts.yaml:6:3".to_owned())]
    );
    let message = &report.diagnostics[0].message;
    for words in ["`Text@de` has 4 texts but `Text` has 3", "never appear"] {
        assert!(message.contains(words), "{message}");
    }
}

#[test]
fn languages_without_brackets_are_read_as_the_list_meant() {
    let acts = "- Label: HELLO\n  Text: [Hello]\n  Text@de: [Hallo]\n";
    let dir = bundle(&[
        ("docent.yaml", "languages: en, de\n"),
        HOME,
        GERMAN_HOME,
        ("acts.yaml", acts),
    ]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("bad-language", "docent.yaml:1:12".to_owned())],
        "no knock-on error for Text@de"
    );
    let message = &report.diagnostics[0].message;
    assert!(
        message.contains("as a list in brackets: `languages: [en, de]`"),
        "{message}"
    );
}

#[test]
fn language_names_are_answered_with_their_tags_and_read_as_meant() {
    let acts = "- Label: HELLO\n  Text: [Hello]\n  Text@de: [Hallo]\n";
    let dir = bundle(&[
        ("docent.yaml", "languages: [English, Deutsch]\n"),
        HOME,
        GERMAN_HOME,
        ("acts.yaml", acts),
    ]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("bad-language", "docent.yaml:1:13".to_owned()),
            ("bad-language", "docent.yaml:1:22".to_owned()),
        ]
    );
    assert!(report.diagnostics[0].message.contains("write `en`"));
    assert!(report.diagnostics[1].message.contains("write `de`"));
    assert!(
        report
            .diagnostics
            .iter()
            .all(|d| !d.message.contains("a list"))
    );
}

#[test]
fn a_language_name_after_the_at_suggests_the_tag() {
    let acts = yaml(&[
        "- Label: HELLO",
        "  Text: [Hello]",
        "  Text@de: [Hallo]",
        "  Text@french: [Salut]",
    ]);
    let dir = bundle(&[TWO, HOME, GERMAN_HOME, ("acts.yaml", &acts)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("bad-language", "acts.yaml:4:3".to_owned())]
    );
    let message = &report.diagnostics[0].message;
    assert!(message.contains("Write `Text@fr` for french."), "{message}");
}

#[test]
fn the_default_written_twice_says_why_the_keys_are_the_same() {
    let acts = yaml(&["- Label: HELLO", "  Text: [Salut]", "  Text@fr: [Bonjour]"]);
    let dir = bundle(&[
        ("docent.yaml", "languages: [fr, en]\n"),
        (
            "pages/index.html",
            "<!doctype html><title>Start</title><button data-language=\"en\">English</button>",
        ),
        ("pages/en/index.html", "<!doctype html><title>Start</title>"),
        ("acts.yaml", &acts),
    ]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("missing-translation", "acts.yaml:2:3".to_owned()),
            ("duplicate-key", "acts.yaml:3:3".to_owned()),
        ]
    );
    let message = &report.diagnostics[1].message;
    assert!(
        message.contains("because `fr` is the default language, the first in `languages:`"),
        "{message}"
    );
}

#[test]
fn a_page_folder_of_an_undeclared_language_is_reported_once_without_broken_links() {
    let acts = "- Label: HELLO\n  Text: [Hello]\n  Text@fr: [Salut]\n";
    let german = "<!doctype html><title>Start</title>\n\
                  <link rel=\"stylesheet\" href=\"style.css\"> <a href=\"tour.html\">Rundgang</a>\n";
    let dir = bundle(&[
        ("docent.yaml", "languages: [en, fr]\n"),
        (
            "pages/index.html",
            "<!doctype html><title>Start</title><button data-language=\"fr\">Francais</button>",
        ),
        ("pages/style.css", "body { color: black }"),
        ("pages/tour.html", "<!doctype html><title>Tour</title>"),
        ("pages/fr/index.html", "<!doctype html><title>Debut</title>"),
        ("pages/fr/tour.html", "<!doctype html><title>Visite</title>"),
        ("pages/de/index.html", german),
        ("pages/css/extra.css", "p { margin: 0 }"),
        ("acts.yaml", acts),
    ]);
    let report = check(dir.path());
    // `css` is a tag too, but `pages/css/` holds no copy of a page: not a language folder.
    assert_eq!(
        places(&report),
        [("unknown-language", "pages/de/index.html:1:1".to_owned())]
    );
    let message = &report.diagnostics[0].message;
    for words in [
        "`pages/de/` looks like the pages of the language `de`",
        "not in `languages:`",
        "add `de` to `languages:`",
        "rename the folder",
    ] {
        assert!(
            message.to_lowercase().contains(&words.to_lowercase()),
            "{message}"
        );
    }
}

#[test]
fn a_button_for_an_undeclared_language_says_what_the_visitor_would_see() {
    let acts = "- Label: HELLO\n  Text: [Hello]\n  Text@de: [Hallo]\n";
    let page = "<!doctype html><title>Start</title>\n\
                <button data-language=\"de\">Deutsch</button> <button data-language=\"fr\">Francais</button>\n";
    let dir = bundle(&[
        TWO,
        GERMAN_HOME,
        ("acts.yaml", acts),
        ("pages/index.html", page),
    ]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("unknown-language", "pages/index.html:2:68".to_owned())]
    );
    let message = &report.diagnostics[0].message;
    assert!(
        message.contains("the visitor would see \"This language is not available here.\""),
        "{message}"
    );
}

#[test]
fn a_language_no_page_offers_is_a_warning_at_its_place_in_languages() {
    let acts = "- Label: HELLO\n  Text: [Hello]\n  Text@de: [Hallo]\n  Text@fr: [Salut]\n";
    let dir = bundle(&[
        ("docent.yaml", "languages: [en, de, fr]\n"),
        HOME,
        GERMAN_HOME,
        ("pages/fr/index.html", "<!doctype html><title>Debut</title>"),
        ("acts.yaml", acts),
    ]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("language-unreachable", "docent.yaml:1:21".to_owned())],
        "not `en`, the default; not `de`, which the home page offers"
    );
    let warning = &report.diagnostics[0];
    assert_eq!(warning.severity, Severity::Warning);
    assert!(
        warning.message.contains("data-language=\"fr\""),
        "{}",
        warning.message
    );
    assert!(
        warning.message.contains("visitors cannot choose it"),
        "{}",
        warning.message
    );
}
