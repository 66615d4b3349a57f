//! Tests of reading `docent.yaml` as a whole: the documented example, defaults, unknown keys,
//! bad values, site verbs and syntax errors. The sections' own tests sit beside them.

use std::time::Duration;

use crate::config::{AdapterKind, ArgRule, Bounds, SiteConfig};

use super::test_support::{parse, problems};

#[test]
fn the_documented_example_maps_onto_site_config() {
    let text = "home: start.html\ncontexts: [TextGroup, TextFormally, TextChild]\n\
        speech:\n  adapter: espeak\n  voice: en-us\n  rate: 160\ndisplay:\n  adapter: ws\n\
        drive:\n  adapter: sim\n  speed: 0.5\n  pose_rate: 5\n  \
        bounds: { min_x: 0, min_y: 0, max_x: 20, max_y: 12 }\nadapters:\n  timeout: 45s\n\
        verbs:\n  LIGHTS:\n    adapter: ws\n    argument: required\n    \
        description: Switch the showcase lights\n  BELL:\n";
    let file = parse(text);
    assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
    let config = file.config;
    assert_eq!(config.home, "start.html");
    assert_eq!(file.home.map(|h| (h.pos.line, h.pos.column)), Some((1, 7)));
    assert_eq!(config.contexts, ["TextGroup", "TextFormally", "TextChild"]);
    assert_eq!(config.speech.adapter, Some(AdapterKind::Espeak));
    assert_eq!(
        (config.speech.voice.as_str(), config.speech.rate_wpm),
        ("en-us", 160)
    );
    assert_eq!(config.display.adapter, AdapterKind::Ws);
    assert_eq!(
        (
            config.drive.adapter,
            config.drive.speed,
            config.drive.pose_hz
        ),
        (AdapterKind::DriveSim, 0.5, 5.0)
    );
    assert_eq!(
        config.drive.bounds,
        Some(Bounds {
            min_x: 0.0,
            min_y: 0.0,
            max_x: 20.0,
            max_y: 12.0
        })
    );
    assert_eq!(config.adapter_timeout, Duration::from_secs(45));
    let lights = &config.verbs["LIGHTS"];
    assert_eq!(
        (lights.adapter, lights.argument),
        (AdapterKind::Ws, ArgRule::Required)
    );
    assert_eq!(
        lights.description.as_deref(),
        Some("Switch the showcase lights")
    );
    assert_eq!(
        (config.verbs["BELL"].adapter, config.verbs["BELL"].argument),
        (AdapterKind::Ws, ArgRule::Optional)
    );
}

#[test]
fn an_empty_file_gives_the_defaults() {
    let file = parse("# nothing set yet\n");
    assert!(file.diagnostics.is_empty());
    assert_eq!(file.config, SiteConfig::default());
    assert!(file.home.is_none());
}

#[test]
fn unknown_keys_are_located_with_a_suggestion() {
    let found = problems("hoem: x.html\nspeech:\n  volume: 3\n  rat: 100\n");
    let located: Vec<_> = found.iter().map(|(c, l, col, _)| (*c, *l, *col)).collect();
    assert_eq!(
        located,
        [
            ("config-unknown-key", 1, 1),
            ("config-unknown-key", 3, 3),
            ("config-unknown-key", 4, 3)
        ]
    );
    assert!(found[0].3.contains("Did you mean `home`?"));
    assert!(!found[1].3.contains("Did you mean"));
    assert!(found[2].3.contains("Did you mean `rate`?"));
}

#[test]
fn bad_values_are_located_and_defaults_kept() {
    let text = [
        "speech:",
        "  adapter: espeek",
        "  voice: \"-x\"",
        "  rate: 1000",
        "drive:",
        "  speed: -1",
        "  pose_rate: 100",
        "  bounds: { min_x: 5, min_y: 0, max_x: 1, max_y: 2 }",
        "adapters:",
        "  timeout: 30",
        "contexts: [TextGroup, Group, TextGroup]",
    ];
    let file = parse(&text.join("\n"));
    let located: Vec<_> = file
        .diagnostics
        .iter()
        .map(|d| (d.code.as_str(), d.line, d.column))
        .collect();
    assert_eq!(
        located,
        [
            ("config-bad-value", 2, 12),
            ("config-bad-value", 3, 10),
            ("config-bad-value", 4, 9),
            ("config-bad-value", 6, 10),
            ("config-bad-value", 7, 14),
            ("config-bad-value", 8, 11),
            ("config-bad-value", 10, 12),
            ("config-bad-value", 11, 23),
            ("config-bad-value", 11, 30),
        ]
    );
    assert!(
        file.diagnostics[0]
            .message
            .contains("Did you mean `espeak`?")
    );
    assert_eq!(file.config.speech, SiteConfig::default().speech);
    assert_eq!(file.config.drive, SiteConfig::default().drive);
    assert_eq!(file.config.contexts, ["TextGroup"]);
}

#[test]
fn site_verbs_must_be_capitalised_and_new() {
    let found = problems("verbs:\n  SAY: {}\n  lights: {}\n  FOG:\n    argument: sometimes\n");
    let located: Vec<_> = found.iter().map(|(c, l, col, _)| (*c, *l, *col)).collect();
    assert_eq!(
        located,
        [
            ("config-bad-value", 2, 3),
            ("config-bad-value", 3, 3),
            ("config-bad-value", 5, 15)
        ]
    );
}

#[test]
fn syntax_errors_and_duplicates_are_reported() {
    assert_eq!(problems("home: [x\n")[0].0, "config-syntax");
    let found = problems("home: a.html\nhome: b.html\n");
    assert_eq!(
        (found[0].0, found[0].1, found[0].2),
        ("duplicate-key", 2, 1)
    );
}

#[test]
fn a_rosbridge_section_is_read_with_its_events() {
    use crate::config::{PoseMessage, TopicEvent};
    let text = "drive: {adapter: rosbridge}\nrosbridge:\n  url: ws://robot.local:9090\n  \
        goal_topic: /goal_pose\n  frame: map\n  action: /navigate_to_pose\n  \
        pose_topic: /odom\n  pose_type: nav_msgs/msg/Odometry\n  stop_topic: /docent/stop\n  \
        cmd_vel: none\n  tolerance: 0.5\n  events:\n    - {topic: /humans/bodies/tracked, \
        type: hri_msgs/msg/IdsList, event: person.near}\n";
    let file = parse(text);
    assert!(file.diagnostics.is_empty(), "{:?}", file.diagnostics);
    let ros = file.config.rosbridge;
    assert_eq!(file.config.drive.adapter, AdapterKind::Rosbridge);
    assert_eq!(ros.url.as_deref(), Some("ws://robot.local:9090"));
    assert_eq!(ros.action.as_deref(), Some("/navigate_to_pose"));
    assert_eq!(
        (ros.pose_topic.as_str(), ros.pose_type),
        ("/odom", PoseMessage::Odometry)
    );
    assert_eq!(
        (ros.stop_topic.as_deref(), ros.cmd_vel),
        (Some("/docent/stop"), None)
    );
    assert_eq!(ros.tolerance, 0.5);
    assert_eq!(
        ros.events,
        [TopicEvent {
            topic: "/humans/bodies/tracked".into(),
            message_type: "hri_msgs/msg/IdsList".into(),
            event: "person.near".into(),
        }]
    );
    let defaults = parse("rosbridge: {url: ws://10.0.0.2:9090}\n")
        .config
        .rosbridge;
    assert_eq!(
        (
            defaults.goal_topic.as_str(),
            defaults.frame.as_str(),
            defaults.pose_topic.as_str()
        ),
        ("/goal_pose", "map", "/amcl_pose")
    );
    assert_eq!(defaults.cmd_vel.as_deref(), Some("/cmd_vel"));
    assert_eq!(defaults.stall, Some(std::time::Duration::from_secs(30)));
    let never = parse("rosbridge: {url: ws://10.0.0.2:9090, stall: 0s}\n");
    assert_eq!(never.config.rosbridge.stall, None);
}

#[test]
fn a_rosbridge_drive_without_a_url_is_told_where_it_is_set() {
    let found = problems("speech: {adapter: log}\ndrive:\n  adapter: rosbridge\n");
    assert_eq!(found.len(), 1, "{found:?}");
    let (code, line, column, message) = &found[0];
    assert_eq!((*code, *line, *column), ("rosbridge-url-missing", 3, 12));
    assert!(message.contains("url: ws://"), "{message}");
    let found = problems("rosbridge:\n  frame: map\n");
    assert_eq!(
        found.iter().map(|p| (p.0, p.1, p.2)).collect::<Vec<_>>(),
        [("rosbridge-url-missing", 2, 3)]
    );
}

#[test]
fn rosbridge_mistakes_are_told_at_their_place() {
    let cases: [(&str, (&str, u32, u32), &str); 7] = [
        (
            "rosbridge:\n  url: ws://r:9090\n  stall: 500ms\n",
            ("config-bad-value", 3, 10),
            "at least 1s",
        ),
        (
            "rosbridge:\n  url: http://robot:9090\n",
            ("config-bad-value", 2, 8),
            "ws://",
        ),
        (
            "rosbridge:\n  url: ws://r:9090\n  goal_topc: /g\n",
            ("config-unknown-key", 3, 3),
            "goal_topic",
        ),
        (
            "rosbridge:\n  url: ws://r:9090\n  tolerance: 0\n",
            ("config-bad-value", 3, 14),
            "metres",
        ),
        (
            "rosbridge:\n  url: ws://r:9090\n  pose_type: Odometry\n",
            ("config-bad-value", 3, 14),
            "nav_msgs/msg/Odometry",
        ),
        (
            "rosbridge:\n  url: ws://r:9090\n  events:\n    - {topic: /b, type: std_msgs/msg/String, event: Bumper}\n",
            ("config-bad-value", 4, 53),
            "lower-case",
        ),
        (
            "rosbridge:\n  url: ws://r:9090\n  events:\n    - {topic: /b, event: bump}\n",
            ("config-bad-value", 4, 7),
            "lacks `type`",
        ),
    ];
    for (text, (code, line, column), says) in cases {
        let found = problems(text);
        assert_eq!(found.len(), 1, "{text}: {found:?}");
        let (c, l, col, message) = &found[0];
        assert_eq!((*c, *l, *col), (code, line, column), "{text}: {message}");
        assert!(message.contains(says), "{text}: {message}");
    }
}
