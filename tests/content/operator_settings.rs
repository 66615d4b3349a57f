//! What the operator console takes from `docent.yaml`: the `operator:` section (the map, the
//! visitor groups) and `access:` (credentials, checked and never shown), with every problem at
//! its file, line and column.

use crate::common;

use common::check::{assert_plain, bundle, check, groups, loaded, places, yaml};
use docent_content::config::Credential;

const BOUNDS: &str = "drive: { bounds: { min_x: 0, min_y: 0, max_x: 20, max_y: 12 } }";

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
