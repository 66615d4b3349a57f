//! Messages that point the right way: mistakes whose first symptom used to be told as another
//! mistake, with advice that made things worse. German acts in a file of their own (told as a
//! duplicate label per act: "rename one of them"); `languages:` the wrong way round (a
//! `duplicate-key` at every translation, a `missing-translation` for every text, page problems,
//! and nothing at `docent.yaml`). Each test asserts the code, file, line and column, the words
//! of the hint, and that the misleading knock-on messages are gone.

use crate::common;

use common::check::{bundle, check, places, yaml};
use common::languages::{GERMAN_HOME, HOME, TWO};
use docent_content::Severity;

/// The English original: three acts.
fn english() -> String {
    yaml(&[
        "- Label: WELCOME",
        "  Text: Welcome to the museum! I am the robot of this house.",
        "- Label: PAINTING",
        "  Text:",
        "    - This is the painting of the old harbour, made in 1872.",
        "    - The old harbour, painted in 1872.",
        "- Label: GOODBYE",
        "  Text: Thank you for your visit, and goodbye!",
    ])
}

/// The same acts, the texts translated into German, the labels kept.
fn german() -> String {
    yaml(&[
        "# Deutsche Fassung",
        "- Label: WELCOME",
        "  Text: Willkommen im Museum! Ich bin der Roboter dieses Hauses.",
        "- Label: PAINTING",
        "  Text:",
        "    - Das ist das Gemälde des alten Hafens, gemalt 1872.",
        "    - Der alte Hafen, gemalt 1872.",
        "- Label: GOODBYE",
        "  Text: Danke für Ihren Besuch und auf Wiedersehen!",
    ])
}

#[test]
fn german_acts_in_their_own_file_are_told_once_to_go_beside_the_original_as_text_at_de() {
    let (english, german) = (english(), german());
    let dir = bundle(&[("acts.yaml", &english), ("acts_de.yaml", &german)]);
    let report = check(dir.path());
    // Once, at the copy's first act; no `duplicate-label` at either file.
    assert_eq!(
        places(&report),
        [("translated-acts-file", "acts_de.yaml:2:10".to_owned())]
    );
    let told = &report.diagnostics[0];
    assert_eq!(told.severity, Severity::Error);
    for words in [
        "`acts_de.yaml` repeats 3 of its 3 act label(s) from `acts.yaml` (such as `WELCOME`)",
        "texts in German (`de`)",
        "Translations go beside the original, in `acts.yaml`",
        "write `Text@de:` with the translated texts",
        "`languages: [en, de]`",
        "docent translations export BUNDLE --language de",
    ] {
        assert!(told.message.contains(words), "{words}: {}", told.message);
    }
    assert!(!told.message.contains("rename"), "{}", told.message);
}

#[test]
fn a_translated_copy_is_found_whatever_its_name_and_order_and_by_its_texts_alone() {
    let (english, german) = (english(), german());
    // `acts-de.yml` sorts before `acts.yaml`; the bundle already speaks German.
    for copy in ["acts-de.yml", "acts.DE.yaml", "tour_deutsch.yaml"] {
        let dir = bundle(&[
            TWO,
            HOME,
            GERMAN_HOME,
            ("acts.yaml", &english),
            (copy, &german),
        ]);
        let report = check(dir.path());
        let found: Vec<_> = places(&report)
            .into_iter()
            .filter(|(code, _)| *code != "missing-translation")
            .collect();
        assert_eq!(
            found,
            [("translated-acts-file", format!("{copy}:2:10"))],
            "{copy}"
        );
        let message = &report.diagnostics[0].message;
        assert!(
            message.contains("`Text@de:`") && !message.contains("languages: ["),
            "{copy}: {message}"
        );
    }
    // In a folder named for its language: Docent reads no acts file there, so before, its
    // acts vanished without a word.
    let dir = bundle(&[("acts.yaml", &english), ("de/acts.yaml", &german)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("translated-acts-file", "de/acts.yaml:2:10".to_owned())]
    );
    let message = &report.diagnostics[0].message;
    assert!(
        message.contains("reads acts files only at the top of the bundle folder")
            && message.contains("`Text@de:`"),
        "{message}"
    );
    // The original named for the default language, the copy for none: the texts tell.
    let dir = bundle(&[("acts_en.yaml", &english), ("acts.yaml", &german)]);
    assert_eq!(
        places(&check(dir.path())),
        [("translated-acts-file", "acts.yaml:2:10".to_owned())]
    );
    // No language in the name: the texts are German by their words.
    let dir = bundle(&[("acts.yaml", &english), ("more.yaml", &german)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("translated-acts-file", "more.yaml:2:10".to_owned())]
    );
    assert!(report.diagnostics[0].message.contains("German (`de`)"));
}

#[test]
fn a_copy_with_the_same_texts_or_few_shared_labels_is_still_a_duplicate_label() {
    let english = english();
    // An old copy saved under another name: real duplicates, told as such.
    let dir = bundle(&[("acts.yaml", &english), ("acts_copy.yaml", &english)]);
    let report = check(dir.path());
    let codes: Vec<&str> = report.diagnostics.iter().map(|d| d.code.as_str()).collect();
    assert_eq!(codes, ["duplicate-label"; 6], "{:#?}", report.diagnostics);
    // One German act among three new ones: not a translation of the file.
    let other = yaml(&[
        "- Label: WELCOME",
        "  Text: Willkommen im Museum! Ich bin der Roboter dieses Hauses.",
        "- Label: TOUR",
        "  Text: Folgen Sie mir bitte.",
        "- Label: MAP",
        "  Text: Hier ist der Plan.",
        "- Label: CAFE",
        "  Text: Das Café ist im Erdgeschoss.",
    ]);
    let dir = bundle(&[("acts.yaml", &english), ("tour.yaml", &other)]);
    assert_eq!(
        places(&check(dir.path())),
        [
            ("duplicate-label", "acts.yaml:1:10".to_owned()),
            ("duplicate-label", "tour.yaml:1:10".to_owned()),
        ]
    );
}

/// English `Text:` keys with German `Text@de:` translations, one act with a `TextChild` too.
fn english_with_german() -> String {
    yaml(&[
        "- Label: WELCOME",
        "  Text: Welcome to the museum! I am the robot of this house.",
        "  Text@de: Willkommen im Museum! Ich bin der Roboter dieses Hauses.",
        "- Label: PAINTING",
        "  Text:",
        "    - This is the painting of the old harbour, made in 1872.",
        "    - The old harbour, painted in 1872.",
        "  Text@de:",
        "    - Das ist das Gemälde des alten Hafens, gemalt 1872.",
        "    - Der alte Hafen, gemalt 1872.",
        "  TextChild: A ship! Can you see the ship?",
        "  TextChild@de: Ein Schiff! Siehst du das Schiff?",
        "- Label: GOODBYE",
        "  Text: Thank you for your visit, and goodbye!",
        "  Text@de: Danke für Ihren Besuch und auf Wiedersehen!",
    ])
}

#[test]
fn languages_written_the_wrong_way_round_are_told_once_at_docent_yaml_and_nowhere_else() {
    let acts = english_with_german();
    let config =
        "# The museum speaks English and German.\nlanguages: [de, en]\ncontexts: [TextChild]\n";
    let dir = bundle(&[
        ("docent.yaml", config),
        HOME,
        GERMAN_HOME,
        ("acts.yaml", &acts),
    ]);
    let report = check(dir.path());
    // Read as written: 4 errors and 7 warnings, a `duplicate-key` at each of the 4 `@de` keys,
    // a `missing-translation` for each of the 4 texts, a `missing-page-translation` for both
    // pages, and at docent.yaml only `language-unreachable` for `en`. Now: once, at `de`.
    assert_eq!(
        places(&report),
        [("languages-reversed", "docent.yaml:2:13".to_owned())]
    );
    let told = &report.diagnostics[0];
    assert_eq!(told.severity, Severity::Error);
    for words in [
        "`languages:` lists `de` first",
        "3 act(s) have `Text@de:` translations and none has `Text@en:`",
        "the plain texts are in English (`en`)",
        "Write `languages: [en, de]`",
    ] {
        assert!(told.message.contains(words), "{words}: {}", told.message);
    }
    // Written the right way round, the same bundle has nothing to tell.
    let fixed = config.replace("[de, en]", "[en, de]");
    std::fs::write(dir.path().join("docent.yaml"), fixed).expect("write");
    assert_eq!(places(&check(dir.path())), []);
}

#[test]
fn a_german_bundle_with_english_translations_is_not_taken_for_a_reversed_one() {
    // German plain texts and `Text@en:` translations, `languages: [de, en]`: as meant.
    let acts = yaml(&[
        "- Label: WELCOME",
        "  Text: Willkommen im Museum! Ich bin der Roboter dieses Hauses.",
        "  Text@en: Welcome to the museum! I am the robot of this house.",
        "- Label: GOODBYE",
        "  Text: Danke für Ihren Besuch und auf Wiedersehen!",
        "  Text@en: Thank you for your visit, and goodbye!",
    ]);
    let english_home = (
        "pages/index.html",
        "<!doctype html><title>Start</title><button data-language=\"en\">English</button>",
    );
    let dir = bundle(&[
        ("docent.yaml", "languages: [de, en]\n"),
        english_home,
        ("pages/en/index.html", "<!doctype html><title>Start</title>"),
        ("acts.yaml", &acts),
    ]);
    assert_eq!(places(&check(dir.path())), []);
    // One `Text@de` slipped into it (the default language's key twice) stays that mistake,
    // at its line: the plain texts are German by their words.
    let slipped = acts.replace(
        "  Text@en: Thank you",
        "  Text@de: Tschüss und bis bald!\n  Text@en: Thank you",
    );
    std::fs::write(dir.path().join("acts.yaml"), slipped).expect("write");
    assert_eq!(
        places(&check(dir.path())),
        [("duplicate-key", "acts.yaml:6:3".to_owned())]
    );
}
