//! What `docent check` reports about a bundle in several languages (`languages:`, `Text@de:`,
//! `pages/de/`, `data-language`, `speech: voices:`): one fixture per problem, each at its
//! exact code, file, line and column; and the translations as the loaded model holds them.

use crate::common;

use common::check::{bundle, check, loaded, places, yaml};
use common::languages::{GERMAN_HOME, HOME, TWO};
use docent_content::{Language, Severity};

fn de() -> Language {
    Language::parse("de").expect("a tag")
}

#[test]
fn a_translation_sits_beside_its_original_in_the_model() {
    let acts = yaml(&[
        "- Label: HELLO",
        "  Text: [Hello, Hi]",
        "  Text@de: [Hallo, Hi du]",
        "  TextChild@en: [Hey kids]",
        "  TextChild@DE: [Hallo Kinder]",
    ]);
    let dir = bundle(&[TWO, HOME, GERMAN_HOME, ("acts.yaml", &acts)]);
    let report = check(dir.path());
    assert_eq!(places(&report), []);
    let bundle = loaded(report);
    let act = bundle.act("HELLO").expect("act");
    let names: Vec<&str> = act.variants.iter().map(|v| v.name.as_str()).collect();
    assert_eq!(
        names,
        ["Text", "TextChild"],
        "Text@en is the original TextChild"
    );
    let text = act.variant("Text").expect("Text");
    let german = &text.translations[&de()];
    assert_eq!(german.alternatives[0].value, "Hallo");
    assert_eq!((german.pos.line, german.pos.column), (3, 3));
    let child = act.variant("TextChild").expect("TextChild");
    assert_eq!(
        child.translations[&de()].alternatives[0].value,
        "Hallo Kinder"
    );
    assert_eq!(bundle.config.languages.listed(), "en, de");
}

#[test]
fn a_missing_translation_is_a_warning_naming_act_variant_and_language() {
    let acts = yaml(&[
        "- Label: HELLO",
        "  Text: [Hello]",
        "  Text@de: [Hallo]",
        "  TextChild: [Hey kids]",
    ]);
    let dir = bundle(&[TWO, HOME, GERMAN_HOME, ("acts.yaml", &acts)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("missing-translation", "acts.yaml:4:3".to_owned())]
    );
    let warning = &report.diagnostics[0];
    assert_eq!(warning.severity, Severity::Warning);
    assert!(warning.message.contains("`HELLO`"), "{}", warning.message);
    assert!(
        warning.message.contains("`TextChild@de`"),
        "{}",
        warning.message
    );
    assert!(
        report.bundle.is_some(),
        "a warning: the bundle still serves"
    );
}

#[test]
fn a_text_in_a_language_the_bundle_lacks_is_an_error_at_its_key() {
    let acts = yaml(&[
        "- Label: HELLO",
        "  Text: [Hello]",
        "  Text@fr: [Salut]",
        "  Text@de: [Hallo]",
    ]);
    let dir = bundle(&[TWO, HOME, GERMAN_HOME, ("acts.yaml", &acts)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("unknown-language", "acts.yaml:3:3".to_owned())]
    );
    assert!(report.diagnostics[0].message.contains("(en, de)"));
}

#[test]
fn a_suffix_that_is_no_language_tag_is_an_error_at_its_key() {
    let acts = yaml(&[
        "- Label: HELLO",
        "  Text: [Hello]",
        "  Text@german: [Hallo]",
    ]);
    let dir = bundle(&[TWO, HOME, GERMAN_HOME, ("acts.yaml", &acts)]);
    let report = check(dir.path());
    // The German text is still missing, and said so.
    assert_eq!(
        places(&report),
        [
            ("missing-translation", "acts.yaml:2:3".to_owned()),
            ("bad-language", "acts.yaml:3:3".to_owned()),
        ]
    );
}

#[test]
fn the_default_language_written_twice_is_a_duplicate_key() {
    let acts = yaml(&[
        "- Label: HELLO",
        "  Text: [Hello]",
        "  Text@en: [Hello again]",
        "  Text@de: [Hallo]",
    ]);
    let dir = bundle(&[TWO, HOME, GERMAN_HOME, ("acts.yaml", &acts)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("duplicate-key", "acts.yaml:3:3".to_owned())]
    );
}

#[test]
fn a_translation_without_its_original_is_an_error_at_its_key() {
    let acts = yaml(&[
        "- Label: HELLO",
        "  Text: [Hello]",
        "  Text@de: [Hallo]",
        "  TextChild@de: [Hallo Kinder]",
    ]);
    let dir = bundle(&[TWO, HOME, GERMAN_HOME, ("acts.yaml", &acts)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("translation-without-original", "acts.yaml:4:3".to_owned())]
    );
}

#[test]
fn a_bad_or_repeated_language_in_docent_yaml_is_reported_where_written() {
    let acts = "- Label: HELLO\n  Text: [Hello]\n";
    let settings = "languages: [en, klingon, en]\n";
    let dir = bundle(&[("docent.yaml", settings), ("acts.yaml", acts)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("bad-language", "docent.yaml:1:17".to_owned()),
            ("config-bad-value", "docent.yaml:1:26".to_owned()),
        ]
    );
    let twice = &report.diagnostics[1].message;
    assert!(twice.contains("Remove the second `en`."), "{twice}");
    assert!(!twice.contains("Found:"), "{twice}");
}

#[test]
fn a_voice_for_a_language_the_bundle_lacks_is_an_error() {
    let settings = "languages: [en]\nspeech:\n  voices:\n    fr: fr\n";
    let acts = "- Label: HELLO\n  Text: [Hello]\n";
    let dir = bundle(&[("docent.yaml", settings), ("acts.yaml", acts)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("unknown-language", "docent.yaml:4:5".to_owned())]
    );
}

#[test]
fn a_page_missing_in_a_language_is_one_warning_and_links_fall_back_to_it() {
    let acts = "- Label: HELLO\n  Text: [Hello]\n  Text@de: [Hallo]\n";
    let german_home = "<!doctype html><title>Start</title>\n\
                       <a href=\"tour.html\">Rundgang</a> <a href=\"tour.html#top\">Oben</a>\n\
                       <link rel=\"stylesheet\" href=\"style.css\">\n";
    let dir = bundle(&[
        TWO,
        HOME,
        ("acts.yaml", acts),
        ("pages/tour.html", "<!doctype html><title>Tour</title>"),
        ("pages/style.css", "body { color: black }"),
        ("pages/de/index.html", german_home),
    ]);
    let report = check(dir.path());
    // Two links to the untranslated tour and one to the stylesheet: none broken, one warning.
    assert_eq!(
        places(&report),
        [("missing-page-translation", "pages/tour.html:1:1".to_owned())]
    );
    assert!(report.diagnostics[0].message.contains("pages/de/tour.html"));
}

#[test]
fn a_language_button_must_name_one_of_the_bundles_languages() {
    let acts = "- Label: HELLO\n  Text: [Hello]\n  Text@de: [Hallo]\n";
    let page = "<!doctype html><meta charset=\"utf-8\"><title>Start</title>\n\
                <button data-language=\"fr\">Français</button>\n\
                <button data-language=\"deutsch\">Deutsch</button>\n\
                <button data-language=\"de\">Deutsch</button>\n";
    let dir = bundle(&[
        TWO,
        ("acts.yaml", acts),
        ("pages/index.html", page),
        ("pages/de/index.html", "<!doctype html><title>Start</title>"),
    ]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("unknown-language", "pages/index.html:2:24".to_owned()),
            ("bad-language", "pages/index.html:3:24".to_owned()),
        ]
    );
}

#[test]
fn the_fixture_bundle_in_two_languages_loads_with_its_one_untranslated_page() {
    let report = check(&common::repo().join("tests/fixtures/two-languages"));
    assert_eq!(
        places(&report),
        [("missing-page-translation", "pages/tour.html:1:1".to_owned())]
    );
    let bundle = loaded(report);
    assert!(bundle.page_offers_language("index.html", &de()));
    assert!(!bundle.page_offers_language("tour.html", &de()));
    assert_eq!(bundle.config.speech.voice_for(&de()), "de");
}
