//! What the operator console takes from the acts: `Group` and `Key`, with every problem at its
//! file, line and column; and everything the shipped museum tour gives the console. The
//! `access:` and `operator:` sections of `docent.yaml`: `content_operator_settings.rs`.

use crate::common;

use std::fs;
use std::path::Path;

use common::check::{assert_plain, bundle, check, groups, loaded, only, places, yaml};
use docent_content::config::Camera;

#[test]
fn groups_and_keys_reach_the_acts() {
    let acts = yaml(&[
        "- Label: HELLO",
        "  Group: Greetings",
        "  Key: h",
        "  Text: Hello",
        "- Label: BYE",
        "  Key: 0",
        "  Text: Bye",
        "- Label: PLAIN",
        "  Text: Plain",
    ]);
    let bundle = loaded(check(bundle(&[("small-talk.yaml", &acts)]).path()));
    let hello = bundle.act("HELLO").expect("act");
    assert_eq!(
        (hello.group.as_deref(), hello.group_name(), hello.key),
        (Some("Greetings"), "Greetings", Some('H'))
    );
    let bye = bundle.act("BYE").expect("act");
    assert_eq!(
        (bye.group.as_deref(), bye.group_name(), bye.key),
        (None, "small-talk", Some('0'))
    );
    assert_eq!(bundle.act("PLAIN").expect("act").key, None);
}

#[test]
fn bad_keys_and_groups_are_located_with_plain_hints() {
    let acts = yaml(&[
        "- Label: A",
        "  Key: Alt+W",
        "  Text: a",
        "- Label: B",
        "  Key: WW",
        "  Text: b",
        "- Label: C",
        "  Key:",
        "  Text: c",
        "- Label: D",
        "  Key: é",
        "  Grup: Small talk",
        "  Text: d",
        "- Label: E",
        "  Key: [A, B]",
        "  Group: \"\"",
        "  Text: e",
    ]);
    let dir = bundle(&[("acts.yaml", &acts)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("bad-key", "acts.yaml:2:8".to_owned()),
            ("bad-key", "acts.yaml:5:8".to_owned()),
            ("bad-key", "acts.yaml:8:6".to_owned()),
            ("bad-key", "acts.yaml:11:8".to_owned()),
            ("unknown-key", "acts.yaml:12:3".to_owned()),
            ("bad-key", "acts.yaml:15:8".to_owned()),
            ("bad-value", "acts.yaml:16:10".to_owned()),
        ]
    );
    let messages: Vec<&str> = report
        .diagnostics
        .iter()
        .map(|d| d.message.as_str())
        .collect();
    assert!(
        messages[0].contains("without Alt or other keys: `Key: W`"),
        "{}",
        messages[0]
    );
    assert!(
        messages[1].contains("`WW` is not one letter or digit"),
        "{}",
        messages[1]
    );
    assert!(
        messages[1].contains("fires this act with Alt+W"),
        "{}",
        messages[1]
    );
    assert!(
        messages[2].starts_with("`Key` is empty."),
        "{}",
        messages[2]
    );
    assert!(
        messages[3].contains("`é` is not one letter or digit"),
        "{}",
        messages[3]
    );
    assert!(
        messages[4].contains("Did you mean `Group`?"),
        "{}",
        messages[4]
    );
    assert!(
        messages[5].contains("but this one is a list"),
        "{}",
        messages[5]
    );
    assert!(messages[6].contains("`Group` is empty"), "{}", messages[6]);
    assert!(report.bundle.is_none());
    assert_plain(&report);
}

#[test]
fn a_key_used_twice_is_reported_at_the_later_act_naming_the_first() {
    let dir = bundle(&[
        ("a.yaml", "- Label: ONE\n  Key: w\n  Text: one\n"),
        (
            "b.yaml",
            "- Label: TWO\n  Text: two\n  Key: W\n- Label: THREE\n  Key: \"w\"\n",
        ),
    ]);
    let report = check(dir.path());
    let found: Vec<_> = places(&report)
        .into_iter()
        .filter(|(code, _)| *code != "empty-act")
        .collect();
    assert_eq!(
        found,
        [
            ("duplicate-key-binding", "b.yaml:3:8".to_owned()),
            ("duplicate-key-binding", "b.yaml:5:8".to_owned()),
        ]
    );
    let twice = only(&report, "duplicate-key-binding");
    assert!(
        twice[0]
            .message
            .starts_with("The key `W` is already given to the act `ONE` at a.yaml:2, so Alt+W cannot also fire `TWO`."),
        "{}",
        twice[0].message
    );
    assert!(twice[1].message.contains("`ONE` at a.yaml:2"));
    assert!(twice[1].message.contains("fire `THREE`"));
    assert!(report.bundle.is_none());
    assert_plain(&report);
}

/// Width and height of a PNG file, from its header.
fn png_size(path: &Path) -> (u32, u32) {
    let bytes = fs::read(path).expect("read the picture");
    assert_eq!(&bytes[1..4], b"PNG", "{} is a PNG", path.display());
    let number = |at: usize| u32::from_be_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
    (number(16), number(20))
}

#[test]
fn the_museum_tour_gives_the_console_a_map_keys_and_situations() {
    let root = common::repo().join("dialogs/museum-tour");
    let bundle = loaded(check(&root));
    let operator = &bundle.config.operator;
    assert_eq!(operator.map.as_deref(), Some("pages/images/map.png"));
    assert_eq!(operator.camera, Camera::WebRtc);
    assert_eq!(
        operator.situations,
        [
            "question",
            "misunderstanding",
            "laughter",
            "interruption",
            "leaving"
        ]
    );
    assert_eq!(
        operator.visitor_groups,
        groups(&[
            ("children", "TextChild"),
            ("group", "TextGroup"),
            ("single", "Text")
        ])
    );
    let key = |label: &str| bundle.act(label).expect("act").key;
    for (label, expected) in [
        ("GREETING", 'W'),
        ("FAREWELL", 'B'),
        ("YES", 'Y'),
        ("NO", 'N'),
        ("GO_TO_MINICOMPUTER", '1'),
        ("GO_TO_CARD_PUNCH", '2'),
        ("GO_TO_HOME_COMPUTER", '3'),
        ("END_TOUR", '0'),
    ] {
        assert_eq!(key(label), Some(expected), "{label}");
    }
    assert!(bundle.acts.iter().all(|a| a.group.is_some()));
    // The console draws the robot by scaling drive.bounds onto the whole picture.
    let bounds = bundle.config.drive.bounds.expect("bounds");
    let (width, height) = png_size(&root.join("pages/images/map.png"));
    let metres = (bounds.max_x - bounds.min_x, bounds.max_y - bounds.min_y);
    assert_eq!(
        f64::from(width) / metres.0,
        f64::from(height) / metres.1,
        "a {width}x{height} map of a {metres:?} m area has the same scale across and down"
    );
}

#[test]
fn keywords_reach_the_act_and_bad_ones_are_located() {
    let acts = yaml(&[
        "- Label: VIDEO",
        "  Keywords: [film, \" Projektion \"]",
        "  Text: Watch",
        "- Label: ONE",
        "  Keywords: movie night",
        "  Text: One",
    ]);
    let loaded_bundle = loaded(check(bundle(&[("acts.yaml", &acts)]).path()));
    assert_eq!(
        loaded_bundle.act("VIDEO").expect("act").keywords,
        ["film", "Projektion"]
    );
    assert_eq!(
        loaded_bundle.act("ONE").expect("act").keywords,
        ["movie night"]
    );

    let acts = yaml(&[
        "- Label: A",
        "  Keywords: [film, \"\", [x]]",
        "  Text: a",
        "- Label: B",
        "  Keywords:",
        "  Text: b",
    ]);
    let dir = bundle(&[("acts.yaml", &acts)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("bad-value", "acts.yaml:2:20".to_owned()),
            ("bad-value", "acts.yaml:2:24".to_owned()),
            ("bad-value", "acts.yaml:5:11".to_owned()),
        ]
    );
    for diagnostic in &report.diagnostics {
        assert!(
            diagnostic.message.contains("Keywords: [film, video"),
            "{}",
            diagnostic.message
        );
    }
    assert_plain(&report);
}
