//! Every event written and read back through the same types, lines of the older formats, and
//! lines this Docent does not know.

use std::time::{Duration, UNIX_EPOCH};

use super::samples::{every_kind, variant};
use super::*;
use crate::events::{
    BundleRefused, CommandSent, Consent, Event, RecordingEvent, SessionEnd, SessionEnded,
    SessionStarted, Source,
};
use crate::{Open, ProjectorState};
use docent_content::Args;

/// Reads a line, which must be an event this Docent knows.
fn known(line: &str) -> (Head, EventKind) {
    let read = Line::parse(line.as_bytes()).unwrap_or_else(|e| panic!("{e}: {line}"));
    match read.event {
        LineEvent::Event(kind) => (read.head, kind),
        LineEvent::Newer(name) => panic!("{name} taken for a newer type: {line}"),
    }
}

#[test]
fn every_variant_is_written_and_read_back_the_same_through_the_same_type() {
    let kinds = every_kind();
    let places: Vec<usize> = kinds.iter().map(variant).collect();
    assert_eq!(
        places,
        (0..=50).collect::<Vec<_>>(),
        "one of each, in order"
    );
    let time = UNIX_EPOCH + Duration::from_millis(1_795_000_000_123);
    for (n, kind) in kinds.into_iter().enumerate() {
        let event = Event::new(n as u64 + 1, time, 42 + n as u64, kind);
        let mut written = Vec::new();
        event.write_line(&mut written, Some(40));
        let line = std::str::from_utf8(&written).unwrap().trim_end();
        let (head, read) = known(line);
        assert_eq!(
            serde_json::to_string(&read).unwrap(),
            serde_json::to_string(&event.kind).unwrap(),
            "read back as written: {line}"
        );
        assert_eq!(variant(&read), n);
        // The same through `Deserialize` itself, as any other program reads an event.
        let written = serde_json::to_string(&event.kind).unwrap();
        let direct: EventKind = serde_json::from_str(&written).unwrap();
        assert_eq!(serde_json::to_string(&direct).unwrap(), written);
        let type_name = serde_json::to_value(&event.kind).unwrap()["type"].clone();
        let expected = Head {
            v: Some(crate::EVENT_FORMAT_VERSION),
            seq: Some(n as u64 + 1),
            time: Some("2026-11-18T11:06:40.123Z".into()),
            mono_us: Some(42 + n as u64),
            session_us: Some(2 + n as u64),
            kind: type_name.as_str().map(str::to_owned),
        };
        assert_eq!(head, expected, "{line}");
        assert_eq!(Head::parse(line.as_bytes()).unwrap(), expected);
        assert!(is_event_type(expected.kind.as_deref().unwrap()));
    }
}

#[test]
fn the_two_fields_not_read_back_read_as_none_and_empty() {
    let (_, sent) = known(
        r#"{"v":4,"type":"command.sent","command":2,"trigger":1,"source":"http","label":"GO","at":"a.yaml:1","verb":"SET_WAYPOINT","arg":"1 2","args":{"x":1.0,"y":2.0,"heading":null},"adapter":"sim"}"#,
    );
    let EventKind::CommandSent(CommandSent { args, adapter, .. }) = sent else {
        panic!("{sent:?}")
    };
    assert_eq!((*args).clone(), Args::None {});
    assert_eq!(adapter, "sim");
    let (_, refused) = known(
        r#"{"v":4,"type":"bundle.refused","diagnostics":[{"severity":"error","code":"x","message":"m","file":"a.yaml","line":1,"column":2}],"changed":["a.yaml"],"elapsed_ms":3}"#,
    );
    let EventKind::BundleRefused(BundleRefused { diagnostics, .. }) = refused else {
        panic!("{refused:?}")
    };
    assert!(diagnostics.is_empty());
}

/// Lines as formats 1 to 3 wrote them (`docs/CORPUS.md`, "Common fields"): what each lacks
/// reads as its default.
#[test]
fn lines_of_the_older_formats_still_read() {
    // Format 1: `command.sent` without `args`.
    let (head, sent) = known(
        r#"{"v":1,"seq":3,"time":"2026-11-22T19:01:36.288Z","mono_us":5463977,"type":"command.sent","command":2,"trigger":1,"source":"http","label":"GREETING","at":"smalltalk.yaml:7","verb":"SAY","arg":"Hi!","adapter":"espeak"}"#,
    );
    assert_eq!((head.v, head.session_us), (Some(1), None));
    assert!(matches!(
        sent,
        EventKind::CommandSent(CommandSent { command: 2, .. })
    ));
    // Format 2: a `display.changed` from before `projector_state`, a `session.ended` without
    // its `reason`.
    let (_, shown) = known(
        r#"{"v":2,"seq":9,"time":"2026-11-22T19:01:37.000Z","mono_us":5500000,"type":"display.changed","page":"index.html","projector":null,"highlight":null}"#,
    );
    let EventKind::DisplayChanged {
        page,
        projector_state,
        ..
    } = shown
    else {
        panic!("{shown:?}")
    };
    assert_eq!(page.as_deref(), Some("index.html"));
    assert_eq!(projector_state, ProjectorState::Black);
    let (_, ended) = known(
        r#"{"v":2,"seq":40,"time":"2026-11-22T19:09:00.000Z","mono_us":9000000,"type":"session.ended","session":1,"source":"operator","client":2}"#,
    );
    assert!(matches!(
        ended,
        EventKind::SessionEnded(SessionEnded {
            reason: SessionEnd::Marked,
            ..
        })
    ));
    // Format 3: a session's line, its `session.started` without `consent` and `page`, an
    // `act.triggered` without `language`.
    let (head, started) = known(
        r#"{"v":3,"seq":5,"time":"2026-11-24T10:15:02.000Z","mono_us":100,"session_us":0,"type":"session.started","session":1,"source":"operator","client":1}"#,
    );
    assert_eq!(head.session_us, Some(0));
    let EventKind::SessionStarted(SessionStarted { consent, page, .. }) = started else {
        panic!("{started:?}")
    };
    assert_eq!((consent, page), (Consent::Recorded, None));
    let (_, act) = known(
        r#"{"v":3,"seq":6,"time":"2026-11-24T10:15:02.001Z","mono_us":1100,"session_us":1000,"type":"act.triggered","trigger":2,"source":"operator","client":1,"label":"TOUR","at":"acts.yaml:4","context":"Text","variant":"Text","alternative":0,"text":"Follow me","interrupt":false}"#,
    );
    let EventKind::ActTriggered {
        act,
        text,
        language,
        ..
    } = act
    else {
        panic!("{act:?}")
    };
    assert_eq!((&*act.label, act.source), ("TOUR", Source::Operator));
    assert_eq!((text.as_deref(), language), (Some("Follow me"), None));
}

#[test]
fn a_client_left_from_before_name_and_ended_still_reads() {
    let (_, left) = known(
        r#"{"v":4,"seq":15,"time":"2026-11-22T19:02:15.020Z","mono_us":16360471,"type":"client.left","client":2,"role":"kiosk","reason":"connection lost"}"#,
    );
    let EventKind::ClientLeft(crate::events::ClientLeft {
        name, ended, code, ..
    }) = left
    else {
        panic!("{left:?}")
    };
    assert_eq!((name, ended, code), (None, None, None));
}

#[test]
fn a_type_newer_than_this_docent_is_passed_over_by_name() {
    let line = r#"{"v":4,"seq":1,"session_us":5,"type":"robot.dance","style":"waltz"}"#;
    let read = Line::parse(line.as_bytes()).unwrap();
    assert!(matches!(&read.event, LineEvent::Newer(name) if name == "robot.dance"));
    assert_eq!(read.head.session_us, Some(5));
    assert!(!is_event_type("robot.dance") && !is_event_type(""));
    assert!(is_event_type("recording.started") && is_event_type("server.stopping"));
    // Every variant's tag, as serde's derived deserializers know them.
    assert_eq!(
        (EventKind::names().len(), RecordingEvent::names().len()),
        (47, 4)
    );
}

#[test]
fn a_code_added_later_reads_as_written() {
    let (_, refused) = known(
        r#"{"v":4,"type":"trigger.refused","source":"kiosk","client":1,"label":"TOUR","code":"too-sleepy","message":"later"}"#,
    );
    let EventKind::TriggerRefused { code, .. } = refused else {
        panic!("{refused:?}")
    };
    assert_eq!(code, Open::Newer("too-sleepy".into()));
}

#[test]
fn a_known_type_whose_fields_do_not_read_names_the_field() {
    let problem = |line: &str| Line::parse(line.as_bytes()).unwrap_err().to_string();
    assert_eq!(
        problem(r#"{"v":3,"session_us":1,"type":"command.done","command":2}"#),
        "missing field `verb` at line 1 column 56"
    );
    assert_eq!(
        problem(r#"{"v":3,"session_us":1,"type":"drive.arrived","x":1,"y":"north"}"#),
        "invalid type: string \"north\", expected f64 at line 1 column 63"
    );
    assert_eq!(
        problem(r#"{"v":3,"session_us":1,"type":"recording.stopped","session":1}"#),
        "missing field `recording` at line 1 column 61"
    );
    assert_eq!(
        problem(r#"{"v":3,"session_us":1}"#),
        "missing field `type` at line 1 column 22"
    );
    assert_eq!(
        problem(r#"{"v":3,"type":null}"#),
        "invalid type: null, expected a string at line 1 column 18"
    );
}

#[test]
fn a_pose_without_its_numbers_reads_them_as_nan() {
    let (_, pose) = known(r#"{"v":4,"type":"pose","x":1,"y":2,"heading":"north","moving":true}"#);
    let EventKind::Pose { x, heading, .. } = pose else {
        panic!("{pose:?}")
    };
    assert_eq!(x, 1.0);
    assert!(heading.is_nan());
    let (_, pose) = known(r#"{"v":4,"type":"pose","y":2,"moving":true,"frame":"hall"}"#);
    let EventKind::Pose { x, frame, .. } = pose else {
        panic!("{pose:?}")
    };
    assert!(x.is_nan());
    assert_eq!(frame.as_deref(), Some("hall"));
}

#[test]
fn a_pose_line_is_told_by_the_type_its_writer_writes() {
    let pose = EventKind::Pose {
        x: 1.0,
        y: 2.0,
        heading: 90.0,
        moving: false,
        frame: None,
    };
    let event = crate::events::Event::new(1, UNIX_EPOCH + Duration::from_secs(1), 0, pose);
    let head = Head::parse(event.json().as_bytes()).expect("a head");
    assert!(head.kind.as_deref().is_some_and(is_pose), "{head:?}");
    for other in ["act.triggered", "robot", "", "Pose"] {
        assert!(!is_pose(other), "{other}");
    }
}
