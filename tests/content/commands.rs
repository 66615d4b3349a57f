//! What `docent check` reports about the commands of acts: verbs and their arguments,
//! highlight areas number by number, site verbs' argument rules and waypoints outside the
//! drive's bounds, each at its exact file, line and column.

use crate::common;

use common::check::{assert_plain, bundle, check, places, yaml};

#[test]
fn verbs_and_arguments_are_checked() {
    let acts = yaml(&[
        "- Label: A",
        "  Cmds:",
        "    - say Hello",
        "    - SAY",
        "    - DRIVE_START fast",
        "    - SET_WAYPOINT 1",
        "    - SET_WAYPOINT 1 2 3 4",
        "    - SET_WAYPOINT x 2",
        "    - WAIT abc",
        "    - WAIT 1.5s",
        "    - WAIT",
        "    - \"SET_WAYPOINT 1 two\"",
        "    - PROJECT",
        "    - HONK",
    ]);
    let dir = bundle(&[("acts.yaml", &acts)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("unknown-verb", "acts.yaml:3:7".to_owned()),
            ("bad-argument", "acts.yaml:4:7".to_owned()),
            ("bad-argument", "acts.yaml:5:19".to_owned()),
            ("bad-argument", "acts.yaml:6:20".to_owned()),
            ("bad-argument", "acts.yaml:7:20".to_owned()),
            ("bad-argument", "acts.yaml:8:20".to_owned()),
            ("bad-argument", "acts.yaml:9:12".to_owned()),
            ("bad-argument", "acts.yaml:12:23".to_owned()),
            ("bad-argument", "acts.yaml:13:7".to_owned()),
            ("unknown-verb", "acts.yaml:14:7".to_owned()),
        ]
    );
    assert!(
        report.diagnostics[0]
            .message
            .contains("Did you mean `SAY`?")
    );
    assert!(
        report.diagnostics[9]
            .message
            .contains("Known commands: SAY, PROJECT")
    );
    assert_plain(&report);
}

#[test]
fn highlight_areas_are_checked_number_by_number() {
    let acts = yaml(&[
        "- Label: A",
        "  Cmds:",
        "    - HIGHLIGHT 0.10 0.20 0.35 0.25",
        "    - HIGHLIGHT 0.1 0.1 0.2 0.2; 0.5 0.5 0.3 0.3 ellipse",
        "    - HIGHLIGHT",
        "    - HIGHLIGHT 0.10 0.20 1.35 0.25",
        "    - HIGHLIGHT 0.8 0.2 0.3 0.25",
        "    - HIGHLIGHT 0.1 0.2 0.3",
        "    - HIGHLIGHT 0 0 1 1; 0.5 half 0.1 0.1",
        "    - \"HIGHLIGHT 0.1 0.2 0.3 0.4 circle\"",
        "    - HIGHLIGHT 0.1 0.2 0.3 0.4;",
    ]);
    let dir = bundle(&[("acts.yaml", &acts)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("bad-argument", "acts.yaml:6:27".to_owned()),
            ("bad-argument", "acts.yaml:7:25".to_owned()),
            ("bad-argument", "acts.yaml:8:17".to_owned()),
            ("bad-argument", "acts.yaml:9:30".to_owned()),
            ("bad-argument", "acts.yaml:10:34".to_owned()),
            ("bad-argument", "acts.yaml:11:32".to_owned()),
        ]
    );
    let messages: Vec<&str> = report
        .diagnostics
        .iter()
        .map(|d| d.message.as_str())
        .collect();
    assert!(
        messages[0].contains("The width `1.35` must be a fraction"),
        "{}",
        messages[0]
    );
    assert!(
        messages[1].contains("past the right edge"),
        "{}",
        messages[1]
    );
    assert!(messages[2].contains("Found 3 value(s)"), "{}", messages[2]);
    assert!(
        messages[3].contains("`half` is not a number"),
        "{}",
        messages[3]
    );
    assert!(
        messages[4].contains("`circle` is not a shape"),
        "{}",
        messages[4]
    );
    assert!(messages[5].contains("no area between"), "{}", messages[5]);
    assert_plain(&report);
}

#[test]
fn site_verbs_follow_their_argument_rule_and_waypoints_their_bounds() {
    let config = yaml(&[
        "drive:",
        "  bounds: { min_x: 0, min_y: 0, max_x: 20, max_y: 12 }",
        "verbs:",
        "  LIGHTS:",
        "    argument: required",
        "  BELL:",
        "    argument: none",
        "  FOG:",
    ]);
    let acts = yaml(&[
        "- Label: A",
        "  Cmds:",
        "    - LIGHTS",
        "    - LIGHTS on",
        "    - BELL now",
        "    - BELL",
        "    - FOG",
        "    - FOG thick",
        "    - SET_WAYPOINT 25 3",
        "    - SET_WAYPOINT 20 12 90",
        "    - lights on",
    ]);
    let dir = bundle(&[("docent.yaml", &config), ("acts.yaml", &acts)]);
    let report = check(dir.path());
    assert_eq!(
        places(&report),
        [
            ("bad-argument", "acts.yaml:3:7".to_owned()),
            ("bad-argument", "acts.yaml:5:12".to_owned()),
            ("waypoint-out-of-bounds", "acts.yaml:9:20".to_owned()),
            ("unknown-verb", "acts.yaml:11:7".to_owned()),
        ]
    );
    assert!(
        report.diagnostics[3]
            .message
            .contains("Did you mean `LIGHTS`?")
    );
}
