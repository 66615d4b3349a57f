//! The websocket frames and the HTTP trigger body against docs/PROTOCOL.md's own examples: each
//! frame built here is written exactly as the document shows it, and each client frame the
//! document shows is read as it says. A frame that changes shape fails here before a client
//! does; so does an example the document lets go stale.

use std::time::{Duration, UNIX_EPOCH};

use docent_content::Language;
use docent_content::config::ServerLimits;

use crate::client_frames::{ClientFrame, HelloFrame, MarkKind, TriggerFrame, TriggerOptions};
use crate::events::{ClientRole, Event, EventKind, KioskCause, Source};
use crate::server_frames::{
    NotCarriedOut, OutcomeFrame, ResolvedCommand, Speaking, Triggered, caption_frame, error_frame,
    event_frame, marked_frame, outcome_frame, speaking_frame, state_frame, triggered_frame,
    welcome_frame,
};
use crate::state::{Display, LimitsView, Pose, ReloadView, StateView};
use crate::{ErrorCode, ProjectorState};

const PROTOCOL_MD: &str = include_str!("../../docs/PROTOCOL.md");

/// `frame` as docs/PROTOCOL.md writes it: the document holds it verbatim.
fn documented(frame: &str) -> &str {
    assert!(
        PROTOCOL_MD.contains(frame),
        "docs/PROTOCOL.md does not show this frame:\n{frame}"
    );
    frame
}

fn english() -> Language {
    Language::parse("en").expect("a language tag")
}

fn home_state(pose: Option<Pose>) -> StateView {
    StateView {
        display: Display {
            page: Some("index.html".into()),
            projector_state: ProjectorState::Black,
            ..Display::default()
        },
        pose,
        context: "Text".into(),
        language: english(),
        reload: ReloadView::default(),
        corpus: None,
    }
}

#[test]
fn welcome_and_state_are_written_as_documented() {
    let welcome = welcome_frame(1, ClientRole::Kiosk, &home_state(Some(Pose::default())));
    assert_eq!(
        welcome,
        documented(
            r#"{"type":"welcome","protocol":4,"client":1,"role":"kiosk","state":{"display":{"page":"index.html","projector":null,"projector_kind":null,"highlight":null,"highlight_areas":null,"projector_state":"black"},"pose":{"x":0.0,"y":0.0,"heading":0.0,"moving":false},"context":"Text","language":"en","reload":{"refused":null,"trouble":null,"not_applied":[]}}}"#
        )
    );
    assert_eq!(
        state_frame(&home_state(None)),
        documented(
            r#"{"type":"state","state":{"display":{"page":"index.html","projector":null,"projector_kind":null,"highlight":null,"highlight_areas":null,"projector_state":"black"},"pose":null,"context":"Text","language":"en","reload":{"refused":null,"trouble":null,"not_applied":[]}}}"#
        )
    );
}

#[test]
fn triggered_is_written_as_documented_without_the_texts_language() {
    let text = "Hello everyone! Welcome to our exhibition of vintage computers.";
    let triggered = Triggered {
        trigger: 3,
        reference: Some("t1".into()),
        label: "GREETING".into(),
        context: "TextGroup".into(),
        variant: Some("TextGroup".into()),
        alternative: Some(0),
        text: Some(text.into()),
        // The HTTP answer carries it; the frame never did.
        language: Some(english()),
        commands: vec![
            ResolvedCommand {
                id: 4,
                verb: "SAY".into(),
                arg: Some(text.into()),
            },
            ResolvedCommand {
                id: 5,
                verb: "DISPLAY_PAGE".into(),
                arg: Some("index.html".into()),
            },
        ],
    };
    assert_eq!(
        triggered_frame(&triggered),
        documented(
            r#"{"type":"triggered","ref":"t1","trigger":3,"label":"GREETING","context":"TextGroup","variant":"TextGroup","alternative":0,"text":"Hello everyone! Welcome to our exhibition of vintage computers.","commands":[{"id":4,"verb":"SAY","arg":"Hello everyone! Welcome to our exhibition of vintage computers."},{"id":5,"verb":"DISPLAY_PAGE","arg":"index.html"}]}"#
        )
    );
    let answer = serde_json::to_value(&triggered).expect("serializes");
    assert_eq!(answer["language"], "en");
}

#[test]
fn error_outcome_and_notices_are_written_as_documented() {
    let message = "there is no act labelled \"GRETING\"; did you mean \"GREETING\"?";
    assert_eq!(
        error_frame(ErrorCode::UnknownAct, message, Some("t2"), Some("GREETING")),
        documented(
            r#"{"type":"error","code":"unknown-act","message":"there is no act labelled \"GRETING\"; did you mean \"GREETING\"?","ref":"t2","suggestion":"GREETING"}"#
        )
    );
    let outcome = OutcomeFrame {
        command: 14,
        trigger: 9,
        reference: Some("kiosk-1"),
        label: "READ_SCHEDULE",
        verb: "SAY",
        outcome: NotCarriedOut::Cancelled,
        reason: "the speech queue was full (2 waiting), so this was not carried out",
        ended_by_visitor: false,
    };
    assert_eq!(
        outcome_frame(&outcome),
        documented(
            r#"{"type":"outcome","command":14,"trigger":9,"ref":"kiosk-1","label":"READ_SCHEDULE","verb":"SAY","outcome":"cancelled","reason":"the speech queue was full (2 waiting), so this was not carried out","ended_by_visitor":false}"#
        )
    );
    let visitor = Speaking {
        source: Source::Kiosk,
        client: Some(7),
    };
    assert_eq!(
        speaking_frame(Some(visitor)),
        documented(
            r#"{"type":"speaking","speaking":true,"source":"kiosk","client":7,"stoppable":true}"#
        )
    );
    assert_eq!(
        speaking_frame(None),
        documented(
            r#"{"type":"speaking","speaking":false,"source":null,"client":null,"stoppable":false}"#
        )
    );
    let said = "Please follow me to our first stop, the minicomputer.";
    assert_eq!(
        caption_frame(Some((42, said))),
        documented(
            r#"{"type":"caption","text":"Please follow me to our first stop, the minicomputer.","command":42}"#
        )
    );
    assert_eq!(
        caption_frame(None),
        documented(r#"{"type":"caption","text":null,"command":null}"#)
    );
    assert_eq!(
        marked_frame(Some("m2"), MarkKind::Group, Some("children"), Some(1)),
        documented(r#"{"type":"marked","ref":"m2","mark":"group","value":"children","session":1}"#)
    );
}

#[test]
fn an_event_frame_wraps_the_events_line() {
    // The document's transcripts were taken at event format version 1.
    let time = UNIX_EPOCH + Duration::from_millis(1_795_383_947_506);
    let kind = EventKind::ContextChanged {
        source: Source::Operator,
        context: "TextGroup".into(),
    };
    let mut event = Event::new(4, time, 1_347_444, kind);
    event.v = 1;
    let transcript = documented(
        r#"dm <- {"type":"event","event":{"v":1,"seq":4,"time":"2026-11-22T21:45:47.506Z","mono_us":1347444,"type":"context.changed","source":"operator","context":"TextGroup"}}"#,
    );
    assert_eq!(
        Some(event_frame(&event).as_str()),
        transcript.strip_prefix("dm <- ")
    );
}

fn hello(text: &str) -> HelloFrame {
    match serde_json::from_str(documented(text)) {
        Ok(ClientFrame::Hello(hello)) => hello,
        other => panic!("{text} read as {other:?}"),
    }
}

#[test]
fn documented_hellos_are_read_with_their_defaults() {
    let operator = hello(
        r#"{"type": "hello", "role": "operator", "name": "wizard", "token": "<the operator credential>"}"#,
    );
    assert_eq!(operator.role, ClientRole::Operator);
    assert_eq!(operator.name.as_deref(), Some("wizard"));
    assert_eq!(operator.token.as_deref(), Some("<the operator credential>"));
    assert!(operator.events, "events default to true");
    assert!(operator.verbs.is_empty() && operator.page.is_none() && operator.language.is_none());

    let planner = hello(
        r#"{"type": "hello", "role": "dm", "name": "planner", "token": "<the dialog-manager credential>", "events": false}"#,
    );
    assert_eq!(planner.role, ClientRole::Dm);
    assert!(!planner.events);

    let kiosk =
        hello(r#"{"type": "hello", "role": "kiosk", "name": "front-screen", "page": "map.html"}"#);
    assert_eq!(kiosk.role, ClientRole::Kiosk);
    assert_eq!(kiosk.page.as_deref(), Some("map.html"));

    let robot = hello(
        r#"{"type": "hello", "role": "adapter", "name": "robot", "verbs": ["SAY", "LIGHTS"]}"#,
    );
    assert_eq!(robot.role, ClientRole::Adapter);
    assert_eq!(robot.verbs, ["SAY", "LIGHTS"]);
    assert!(robot.robot_events.is_empty());
}

fn trigger(text: &str) -> TriggerFrame {
    match serde_json::from_str(documented(text)) {
        Ok(ClientFrame::Trigger(trigger)) => trigger,
        other => panic!("{text} read as {other:?}"),
    }
}

#[test]
fn documented_triggers_are_read_with_their_defaults() {
    let full = trigger(
        r#"{"type": "trigger", "label": "WHERE_FROM", "context": "TextGroup", "interrupt": false, "ref": "q-7"}"#,
    );
    assert_eq!(full.label, "WHERE_FROM");
    assert_eq!(full.context.as_deref(), Some("TextGroup"));
    assert_eq!(full.reference.as_deref(), Some("q-7"));
    assert!(!full.interrupt && full.via.is_none() && full.element.is_none());

    let kiosk = trigger(r#"{"type": "trigger", "label": "SHOW_TOUR_MAP", "ref": "btn-2"}"#);
    assert_eq!(kiosk.label, "SHOW_TOUR_MAP");
    assert!(kiosk.context.is_none() && !kiosk.interrupt);
    assert!(
        KioskCause::is_touch(kiosk.via),
        "no via is a visitor's touch"
    );

    let timer = r#"{"type":"trigger","label":"IDLE","via":"timer","element":"the clock"}"#;
    let Ok(ClientFrame::Trigger(timer)) = serde_json::from_str(timer) else {
        panic!("{timer} is a trigger");
    };
    assert_eq!(timer.via, Some(KioskCause::Timer));
    assert_eq!(timer.element.as_deref(), Some("the clock"));
}

#[test]
fn a_trigger_frame_with_an_unknown_field_names_every_known_one() {
    let text = r#"{"type": "trigger", "label": "OK", "colour": "red"}"#;
    let error = serde_json::from_str::<ClientFrame>(documented(text)).unwrap_err();
    assert_eq!(
        error.to_string(),
        "unknown field `colour`, expected one of `label`, `context`, `interrupt`, `ref`, `via`, \
         `element`"
    );
    documented(&format!(r#"a \"trigger\" frame is not right: {error}""#));
    let missing = serde_json::from_str::<ClientFrame>(r#"{"type": "trigger", "colour": "red"}"#);
    assert!(
        missing
            .unwrap_err()
            .to_string()
            .starts_with("unknown field `colour`"),
        "an unknown field is named before a missing label"
    );
}

#[test]
fn the_http_trigger_body_reads_as_documented() {
    let body: TriggerOptions =
        serde_json::from_str(r#"{"context":"TextChild","interrupt":true,"ref":"visitor-42"}"#)
            .expect("the documented body");
    assert_eq!(
        body,
        TriggerOptions {
            context: Some("TextChild".into()),
            interrupt: true,
            reference: Some("visitor-42".into()),
        }
    );
    let empty: TriggerOptions = serde_json::from_str("{}").expect("all defaults");
    assert_eq!(empty, TriggerOptions::default());
    let error = serde_json::from_str::<TriggerOptions>(r#"{"colour":"red"}"#).unwrap_err();
    documented(&format!("the request body is not right: {error}"));
    for kiosk_only in [
        r#"{"label":"X"}"#,
        r#"{"via":"timer"}"#,
        r#"{"element":"b"}"#,
    ] {
        assert!(
            serde_json::from_str::<TriggerOptions>(kiosk_only).is_err(),
            "{kiosk_only} is not an HTTP trigger's"
        );
    }
}

#[test]
fn trigger_frame_and_http_body_read_options_alike() {
    for options in [
        r#""context":"TextChild","interrupt":true,"ref":"r""#,
        r#""interrupt":false"#,
        r#""ref":null"#,
        r#""context":null"#,
    ] {
        let body: TriggerOptions =
            serde_json::from_str(&format!("{{{options}}}")).expect("an HTTP body");
        let frame = format!(r#"{{"type":"trigger","label":"A",{options}}}"#);
        let Ok(ClientFrame::Trigger(frame)) = serde_json::from_str(&frame) else {
            panic!("{frame} is a trigger");
        };
        let read = TriggerOptions {
            context: frame.context,
            interrupt: frame.interrupt,
            reference: frame.reference,
        };
        assert_eq!(read, body, "{options}");
    }
}

/// `GET /api/state`'s `limits`, as the document's snapshot shows it: the defaults, under an
/// open-files limit of 4096 (the systemd unit's `LimitNOFILE=`).
#[test]
fn the_state_limits_are_written_as_documented() {
    let prefix = "  \"limits\": ";
    let line = (PROTOCOL_MD.lines().find(|l| l.starts_with(prefix)))
        .expect("docs/PROTOCOL.md shows `limits` in GET /api/state");
    let shown: serde_json::Value =
        serde_json::from_str(line.trim_start_matches(prefix)).expect("the example is JSON");
    let limits = LimitsView::new(&ServerLimits::default(), Some(4096));
    assert_eq!(serde_json::to_value(limits).expect("serialises"), shown);
}
