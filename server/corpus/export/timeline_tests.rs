//! The timeline read from hand-written log lines: what each event becomes.

use super::*;

/// Reads `lines` (JSON objects without `v`, which is added) into a timeline.
fn read(lines: &[&str]) -> Timeline {
    read_format(3, lines)
}

/// Reads `lines` as written in event format `v`, each made whole first.
fn read_format(v: u32, lines: &[&str]) -> Timeline {
    let mut reader = TimelineReader::default();
    for line in lines {
        let line = whole(v, line);
        reader.read_line(line.as_bytes()).expect(&line);
    }
    reader.finish()
}

/// `line` with `v` and the fields its type must have that it does not set, so that each
/// test writes only what it is about (the server always writes them all).
fn whole(v: u32, line: &str) -> String {
    let mut fields: serde_json::Map<String, serde_json::Value> =
        serde_json::from_str(line).expect(line);
    let kind = fields["type"].as_str().unwrap_or_default().to_owned();
    let mut missing = vec![("v", serde_json::json!(v))];
    let act = [("at", serde_json::json!("acts.yaml:1"))];
    match kind.as_str() {
        "act.triggered" => missing.extend(act.into_iter().chain([
            ("context", serde_json::json!("Text")),
            ("interrupt", serde_json::json!(false)),
        ])),
        "command.sent" => missing.extend(act.into_iter().chain([
            ("args", serde_json::json!({})),
            ("adapter", serde_json::json!("log")),
        ])),
        "command.started" | "command.done" | "command.failed" | "command.cancelled" => {
            missing.extend(act)
        }
        "trigger.refused" => missing.push(("message", serde_json::json!("refused"))),
        "session.started" | "session.ended" => missing.extend([
            ("session", serde_json::json!(1)),
            ("source", serde_json::json!("operator")),
        ]),
        _ => {}
    }
    for (name, value) in missing {
        fields.entry(name).or_insert(value);
    }
    serde_json::Value::Object(fields).to_string()
}

#[test]
fn from_format_4_only_touch_events_are_touches() {
    let lines = [
        r#"{"session_us":0,"type":"session.started","page":"index.html"}"#,
        // A page's timer: not a visitor.
        r#"{"session_us":5,"type":"act.triggered","trigger":1,"source":"kiosk","label":"HINT"}"#,
        r#"{"session_us":10,"type":"touch","client":3,"page":"index.html","element":"button#a","act":"TOUR"}"#,
        r#"{"session_us":11,"type":"act.triggered","trigger":2,"source":"kiosk","label":"TOUR"}"#,
        r#"{"session_us":20,"type":"touch","client":3,"page":"index.html","element":"button#b","act":"SECRET"}"#,
        r#"{"session_us":21,"type":"trigger.refused","source":"kiosk","label":"SECRET","code":"not-offered"}"#,
        r#"{"session_us":30,"type":"touch","client":3,"page":"index.html","element":"a[href=map.html]","link":"map.html"}"#,
        r#"{"session_us":31,"type":"display.changed","page":"map.html"}"#,
        // The idle return home: the kiosk's own doing.
        r#"{"session_us":40,"type":"display.changed","page":"index.html"}"#,
        // A run of rate-limited touches is logged once, as its refusal.
        r#"{"session_us":50,"type":"trigger.refused","source":"kiosk","label":"TOUR","code":"rate-limited"}"#,
        r#"{"session_us":60,"type":"session.ended"}"#,
    ];
    let timeline = read_format(4, &lines);
    let pages: Vec<(u64, u64, &str)> = (timeline.pages.iter())
        .map(|p| (p.start_us, p.end_us, p.page.as_str()))
        .collect();
    assert_eq!(
        pages,
        [
            (0, 31, "index.html"),
            (31, 40, "map.html"),
            (40, 60, "index.html")
        ],
        "the page shown at the start begins the pages"
    );
    let touches: Vec<(u64, Touched)> = (timeline.touches.into_iter())
        .map(|t| (t.at_us, t.what))
        .collect();
    let refused = |label: &str, code: &str| Touched::Refused {
        label: label.into(),
        code: code.into(),
    };
    assert_eq!(
        touches,
        [
            (
                10,
                Touched::Act {
                    label: "TOUR".into()
                }
            ),
            (20, refused("SECRET", "not-offered")),
            (
                30,
                Touched::Page {
                    page: "map.html".into()
                }
            ),
            (50, refused("TOUR", "rate-limited")),
        ]
    );
}

fn command(kind: &str, id: u64, at: u64, verb: &str, extra: &str) -> String {
    format!(
        r#"{{"session_us":{at},"type":"command.{kind}","command":{id},"trigger":1,"source":"operator","label":"TOUR","verb":"{verb}"{extra}}}"#
    )
}

#[test]
fn a_page_no_command_asked_for_is_a_touch_and_every_page_lasts_until_the_next() {
    let lines = [
        r#"{"session_us":0,"type":"session.started"}"#.to_owned(),
        command("sent", 2, 10, "DISPLAY_PAGE", r#","arg":"map.html""#),
        r#"{"session_us":11,"type":"display.changed","page":"map.html"}"#.to_owned(),
        command("done", 2, 500, "DISPLAY_PAGE", ""),
        r#"{"session_us":900,"type":"display.changed","page":"index.html"}"#.to_owned(),
        r#"{"session_us":950,"type":"display.changed","page":"index.html"}"#.to_owned(),
        r#"{"session_us":2000,"type":"session.ended"}"#.to_owned(),
    ];
    let timeline = read(&lines.iter().map(String::as_str).collect::<Vec<_>>());
    let pages: Vec<(u64, u64, &str)> = (timeline.pages.iter())
        .map(|p| (p.start_us, p.end_us, p.page.as_str()))
        .collect();
    assert_eq!(pages, [(11, 900, "map.html"), (900, 2000, "index.html")]);
    let page = Touched::Page {
        page: "index.html".into(),
    };
    assert_eq!(
        timeline.touches,
        [Touch {
            at_us: 900,
            what: page
        }]
    );
    assert!(timeline.ended);
}

#[test]
fn only_a_begun_say_is_an_utterance_and_only_the_acts_own_text_has_its_variant() {
    let act = r#"{"session_us":5,"type":"act.triggered","trigger":1,"source":"kiosk","label":"TOUR","variant":"TextChild","alternative":1,"text":"Come along"}"#;
    let lines = [
        r#"{"session_us":0,"type":"session.started"}"#.to_owned(),
        act.to_owned(),
        command("sent", 2, 6, "SAY", r#","arg":"Come along""#),
        command("started", 2, 7, "SAY", ""),
        command("cancelled", 2, 90, "SAY", r#","reason":"stop request""#),
        command("sent", 3, 91, "SAY", r#","arg":"Here we are""#),
        command("started", 3, 92, "SAY", ""),
        command("sent", 4, 93, "SAY", r#","arg":"Never said""#),
        command("failed", 4, 94, "SAY", r#","reason":"espeak-ng failed""#),
    ];
    let timeline = read(&lines.iter().map(String::as_str).collect::<Vec<_>>());
    let said: Vec<_> = (timeline.utterances)
        .iter()
        .map(|u| {
            (
                u.start_us,
                u.end_us,
                &*u.text,
                u.variant.as_deref(),
                u.alternative,
                &u.outcome,
            )
        })
        .collect();
    let cut = Outcome::Cancelled("stop request".into());
    assert_eq!(
        said,
        [
            (7, 90, "Come along", Some("TextChild"), Some(1), &cut),
            (92, 94, "Here we are", None, None, &Outcome::Open),
        ],
        "the second SAY has no outcome: it ends with the log"
    );
    let never = &timeline.commands[0];
    assert_eq!(
        (never.start_us, never.end_us, &*never.verb),
        (93, 94, "SAY")
    );
    assert_eq!(never.outcome, Outcome::Failed("espeak-ng failed".into()));
    assert!(!timeline.ended, "no session.ended");
    assert_eq!(timeline.end_us, 94);
    assert_eq!(timeline.touches.len(), 1, "a kiosk's trigger is a touch");
}

#[test]
fn a_line_that_is_not_a_session_line_says_why() {
    let problem = |line: &str| {
        TimelineReader::default()
            .read_line(line.as_bytes())
            .unwrap_err()
            .0
    };
    assert_eq!(
        problem(r#"{"v":3,"seq":1,"type":"server.started"}"#),
        "the line has no `session_us`: this is not a session's log (a day log's events belong \
         to no session)"
    );
    assert_eq!(
        problem(r#"{"v":5,"session_us":1,"type":"pose"}"#),
        "event format 5 is newer than this Docent reads (4): export it with the Docent that \
         wrote it"
    );
    assert_eq!(
        problem(r#"{"v":3,"session_us":1,"type":"command.done","command":2}"#),
        "missing field `verb` (column 56)"
    );
    assert_eq!(
        problem(r#"{"v":3,"session_us":1,"type":"pose","x":1"#),
        "EOF while parsing an object (column 41)"
    );
}

#[test]
fn a_newer_type_is_passed_over_and_a_newer_code_shown_as_written() {
    let lines = [
        r#"{"session_us":0,"type":"session.started","page":"index.html"}"#,
        r#"{"session_us":3,"type":"robot.dance","style":"waltz","x":"left"}"#,
        r#"{"session_us":5,"type":"trigger.refused","source":"kiosk","label":"TOUR","code":"too-sleepy"}"#,
        r#"{"session_us":9,"type":"session.ended"}"#,
    ];
    let timeline = read_format(4, &lines);
    let refused = Touched::Refused {
        label: "TOUR".into(),
        code: "too-sleepy".into(),
    };
    assert_eq!(
        timeline.touches,
        [Touch {
            at_us: 5,
            what: refused
        }]
    );
    assert_eq!((timeline.end_us, timeline.ended), (9, true));
}
