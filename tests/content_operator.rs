//! What the operator console takes from a bundle: acts' `Group` and `Key`, and `docent.yaml`'s
//! `access:` and `operator:` sections, with every problem at its file, line and column.

mod common;

use std::collections::BTreeMap;
use std::fs;
use std::path::Path;

use common::check::{assert_plain, bundle, check, loaded, only, places, yaml};
use docent::content::config::{Camera, Credential};

fn groups(pairs: &[(&str, &str)]) -> BTreeMap<String, String> {
    pairs
        .iter()
        .map(|(g, c)| ((*g).to_owned(), (*c).to_owned()))
        .collect()
}

const BOUNDS: &str = "drive: { bounds: { min_x: 0, min_y: 0, max_x: 20, max_y: 12 } }";

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

#[test]
fn the_map_must_be_a_picture_of_the_bundle_and_needs_bounds() {
    let acts = ("acts.yaml", "- Label: A\n  Text: a\n");
    let missing = bundle(&[
        acts,
        ("docent.yaml", "operator:\n  map: pages/images/plan.png\n"),
    ]);
    let report = check(missing.path());
    assert_eq!(
        places(&report),
        [
            ("missing-file", "docent.yaml:2:8".to_owned()),
            ("map-needs-bounds", "docent.yaml:2:8".to_owned()),
        ]
    );
    assert!(
        report.diagnostics[0]
            .message
            .starts_with("There is no file `pages/images/plan.png`."),
        "{}",
        report.diagnostics[0].message
    );
    assert!(report.diagnostics[1].message.contains("`drive: bounds`"));
    assert_plain(&report);

    let config = yaml(&[BOUNDS, "operator:", "  map: pages/images/plan.png"]);
    let miscased = bundle(&[
        acts,
        ("docent.yaml", &config),
        ("pages/images/Plan.png", "png"),
    ]);
    let report = check(miscased.path());
    assert_eq!(
        places(&report),
        [("miscased-file", "docent.yaml:3:8".to_owned())]
    );
    assert!(report.diagnostics[0].message.contains("`images/Plan.png`"));

    let config = yaml(&[BOUNDS, "operator:", "  map: pages/../media/plan.png"]);
    let outside = bundle(&[acts, ("docent.yaml", &config), ("media/plan.png", "png")]);
    let report = check(outside.path());
    assert_eq!(
        places(&report),
        [("path-outside-bundle", "docent.yaml:3:8".to_owned())]
    );

    let config = yaml(&[BOUNDS, "operator:", "  map: pages/index.html"]);
    let not_a_picture = bundle(&[acts, ("docent.yaml", &config)]);
    let report = check(not_a_picture.path());
    assert_eq!(
        places(&report),
        [("config-bad-value", "docent.yaml:3:8".to_owned())]
    );
    assert!(
        report.diagnostics[0]
            .message
            .contains("png, jpg, jpeg, gif, webp, svg"),
        "{}",
        report.diagnostics[0].message
    );

    let config = yaml(&[BOUNDS, "operator:", "  map: media/hall.svg"]);
    let good = bundle(&[acts, ("docent.yaml", &config), ("media/hall.svg", "<svg/>")]);
    let bundle = loaded(check(good.path()));
    assert_eq!(
        bundle.config.operator.map.as_deref(),
        Some("media/hall.svg")
    );
}

#[test]
fn visitor_groups_follow_the_contexts_of_the_bundle() {
    let acts = "- Label: A\n  Text: a\n  TextChild: kid\n";
    let found = bundle(&[("acts.yaml", acts)]);
    let bundle_found = loaded(check(found.path()));
    assert_eq!(
        bundle_found.config.operator.visitor_groups,
        groups(&[("children", "TextChild"), ("single", "Text")])
    );

    let declared = bundle(&[
        ("acts.yaml", acts),
        (
            "docent.yaml",
            "contexts: [TextGroup, TextChild, TextFormal]\n",
        ),
    ]);
    assert_eq!(
        loaded(check(declared.path()))
            .config
            .operator
            .visitor_groups,
        groups(&[
            ("children", "TextChild"),
            ("group", "TextGroup"),
            ("single", "Text")
        ])
    );

    let config = yaml(&[
        "contexts: [TextGroup, TextChild, TextFormal]",
        "operator:",
        "  visitor_groups:",
        "    single: TextFormal",
        "    group: TextGrop",
    ]);
    let written = bundle(&[("acts.yaml", acts), ("docent.yaml", &config)]);
    let report = check(written.path());
    assert_eq!(
        places(&report),
        [("unknown-context", "docent.yaml:5:12".to_owned())]
    );
    assert!(
        report.diagnostics[0].message.contains(
            "The visitor group `group` switches to the context `TextGrop`, but this bundle \
             has no such context (it has Text, TextGroup, TextChild, TextFormal). Did you mean \
             `TextGroup`?"
        ),
        "{}",
        report.diagnostics[0].message
    );
    assert_plain(&report);

    let config = "operator: { visitor_groups: { single: TextFormal, children: Text } }\n";
    let config = format!("contexts: [TextFormal]\n{config}");
    let remapped = bundle(&[
        ("acts.yaml", "- Label: A\n  Text: a\n"),
        ("docent.yaml", &config),
    ]);
    assert_eq!(
        loaded(check(remapped.path()))
            .config
            .operator
            .visitor_groups,
        groups(&[("children", "Text"), ("single", "TextFormal")])
    );
}

#[test]
fn tokens_are_checked_and_never_shown() {
    let acts = ("acts.yaml", "- Label: A\n  Text: a\n");
    let weak = yaml(&[
        "access:",
        "  operator_token: hunter2",
        "  dm_token: dm-token-0123456789",
    ]);
    let dir = bundle(&[acts, ("docent.yaml", &weak)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [("weak-credential", "docent.yaml:2:19".to_owned())]
    );
    let message = &report.diagnostics[0].message;
    assert!(!message.contains("hunter2"), "{message}");
    assert!(message.contains("at least 16"), "{message}");
    assert_plain(&report);

    let strong = yaml(&[
        "access:",
        "  operator_token: \"op-token-0123456789\"",
        "  dm_token: dm-token-0123456789",
    ]);
    let dir = bundle(&[acts, ("docent.yaml", &strong)]);
    let bundle = loaded(check(dir.path()));
    let access = &bundle.config.access;
    assert_eq!(
        access.operator_token,
        Some(Credential::new("op-token-0123456789").expect("strong"))
    );
    assert_eq!(
        access.dm_token.as_ref().map(Credential::expose),
        Some("dm-token-0123456789")
    );
    let shown = format!("{bundle:?}");
    assert!(!shown.contains("token-0123456789"), "Debug leaks a token");
    assert!(shown.contains("Credential(***)"));
}

#[test]
fn unknown_console_settings_get_suggestions() {
    let config = yaml(&[
        "acces:",
        "  operator_token: op-token-0123456789",
        "operator:",
        "  situation: [question]",
        "  camra: none",
    ]);
    let dir = bundle(&[
        ("acts.yaml", "- Label: A\n  Text: a\n"),
        ("docent.yaml", &config),
    ]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("config-unknown-key", "docent.yaml:1:1".to_owned()),
            ("config-unknown-key", "docent.yaml:4:3".to_owned()),
            ("config-unknown-key", "docent.yaml:5:3".to_owned()),
        ]
    );
    let hints: Vec<&str> = report
        .diagnostics
        .iter()
        .map(|d| d.message.as_str())
        .collect();
    assert!(hints[0].contains("Did you mean `access`?"), "{}", hints[0]);
    assert!(
        hints[1].contains("Did you mean `situations`?"),
        "{}",
        hints[1]
    );
    assert!(hints[2].contains("Did you mean `camera`?"), "{}", hints[2]);
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
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("dialogs/museum-tour");
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
