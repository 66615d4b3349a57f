//! Speech and drive run side by side; `WAIT` sequences them; stop, `DRIVE_STOP` and interrupting
//! triggers preempt. Observed through an operator's event stream on a real server.

use crate::common;

use common::{TempBundle, TestServer};
use serde_json::{Value, json};

const ACTS: &str = r#"
- Label: TOUR
  Text: [Follow me please]
  Cmds:
    - SET_WAYPOINT 1 0
    - DRIVE_START
    - WAIT
    - SAY Here we are
- Label: LONG
  Text:
    - "This sentence goes on and on, far longer than any test would ever wait for it to finish, because it has very many words in it: one two three four five six seven eight nine ten eleven twelve thirteen fourteen fifteen sixteen seventeen eighteen nineteen twenty twenty-one twenty-two twenty-three twenty-four twenty-five twenty-six twenty-seven twenty-eight twenty-nine thirty thirty-one thirty-two thirty-three thirty-four thirty-five thirty-six thirty-seven thirty-eight thirty-nine forty forty-one forty-two forty-three forty-four forty-five forty-six forty-seven forty-eight forty-nine fifty and then some more words until the end."
- Label: FAR
  Cmds: [SET_WAYPOINT 19 11, DRIVE_START]
- Label: HELLO
  Text: [Hello]
- Label: PAUSE
  Text: [One]
  Cmds: [WAIT 50ms, SAY Two, WAIT, SAY Three]
- Label: HALT
  Text: [Stopping now]
  Cmds: [DRIVE_STOP]
"#;

const CONFIG: &str = "speech: {adapter: log, rate: 120}\ndrive: {speed: 2, pose_rate: 50, bounds: {min_x: 0, min_y: 0, max_x: 20, max_y: 12}}\n";

fn bundle() -> TempBundle {
    TempBundle::new(ACTS).with_file("docent.yaml", CONFIG)
}

fn is(kind: &'static str, command: u64) -> impl Fn(&Value) -> bool {
    move |e| e["type"] == kind && e["command"] == command
}

fn position(events: &[Value], pred: impl Fn(&Value) -> bool) -> usize {
    events
        .iter()
        .position(pred)
        .unwrap_or_else(|| panic!("event not found in {events:#?}"))
}

fn ids(triggered: &Value) -> Vec<u64> {
    triggered["commands"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["id"].as_u64().unwrap())
        .collect()
}

#[tokio::test]
async fn speech_and_drive_run_side_by_side_and_wait_sequences_them() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let t = server.trigger("TOUR", json!({})).await;
    let [say, _waypoint, drive, wait, here] = ids(&t)[..] else {
        panic!("{t}")
    };
    let events = op.events_until(is("command.done", here)).await;
    // The drive started while the first SAY was still being spoken.
    assert!(
        position(&events, is("command.started", drive))
            < position(&events, is("command.done", say))
    );
    // The WAIT ended only after both were done, and only then was the last SAY sent.
    let wait_done = position(&events, is("command.done", wait));
    assert!(position(&events, is("command.done", say)) < wait_done);
    assert!(position(&events, is("command.done", drive)) < wait_done);
    assert!(position(&events, |e| e["type"] == "drive.arrived") < wait_done);
    assert!(wait_done < position(&events, is("command.sent", here)));
    let poses: Vec<&Value> = events.iter().filter(|e| e["type"] == "pose").collect();
    assert!(poses.len() >= 2, "the base reports its pose while driving");
    assert_eq!(
        (
            poses.last().unwrap()["x"].as_f64(),
            poses.last().unwrap()["y"].as_f64()
        ),
        (Some(1.0), Some(0.0))
    );
    server.stop().await;
}

#[tokio::test]
async fn a_timed_wait_pauses_and_a_plain_wait_covers_every_earlier_command() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let t = server.trigger("PAUSE", json!({})).await;
    let [one, pause, two, wait, three] = ids(&t)[..] else {
        panic!("{t}")
    };
    let events = op.events_until(is("command.done", three)).await;
    let at = |p| position(&events, p);
    assert!(at(is("command.done", pause)) < at(is("command.sent", two)));
    assert!(at(is("command.done", one)) < at(is("command.done", wait)));
    assert!(at(is("command.done", two)) < at(is("command.done", wait)));
    assert!(at(is("command.done", wait)) < at(is("command.sent", three)));
    let done_pause = &events[at(is("command.done", pause))];
    let sent_pause = &events[at(is("command.sent", pause))];
    assert!(
        done_pause["mono_us"].as_u64().unwrap() - sent_pause["mono_us"].as_u64().unwrap() >= 50_000
    );
    server.stop().await;
}

#[tokio::test]
async fn stop_preempts_a_long_say_and_a_running_drive_and_the_next_act_works() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let long = ids(&server.trigger("LONG", json!({})).await)[0];
    let far = ids(&server.trigger("FAR", json!({})).await)[1];
    op.event_where(|e| e["type"] == "pose" && e["moving"] == true)
        .await;
    op.send(json!({"type": "stop", "ref": "s1"})).await;
    let mut seen = op.events_until(is("command.cancelled", long)).await;
    if !seen.iter().any(is("command.cancelled", far)) {
        seen.extend(op.events_until(is("command.cancelled", far)).await);
    }
    assert!(
        seen.iter()
            .any(|e| e["type"] == "stop" && e["source"] == "operator")
    );
    assert!(!seen.iter().any(is("command.done", long)));
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["pose"]["moving"], false, "{state}");
    assert!(state["pose"]["x"].as_f64().unwrap() < 19.0);
    assert_eq!(state["speaking"], Value::Null);
    // The server keeps working.
    let hello = ids(&server.trigger("HELLO", json!({})).await)[0];
    op.event_where(is("command.done", hello)).await;
    server.stop().await;
}

#[tokio::test]
async fn state_names_the_running_say_its_text_and_its_verb_apart() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let long = ids(&server.trigger("LONG", json!({})).await)[0];
    op.event_where(is("command.started", long)).await;
    let (_, state) = server.get("/api/state").await;
    let text = state["speaking"].as_str().expect("a text being spoken");
    assert!(text.starts_with("This sentence goes on"), "{state}");
    let queue = &state["queues"]["log"];
    assert_eq!(queue["current"], format!("SAY {text}"), "{state}");
    assert_eq!(queue["current_verb"], "SAY", "{state}");
    let idle = &state["queues"]["display"];
    assert_eq!(idle, &json!({"current": null, "queued": 0}), "{state}");
    server.stop().await;
}

#[tokio::test]
async fn an_act_with_drive_stop_preempts_everything_but_keeps_its_own_speech() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let long = ids(&server.trigger("LONG", json!({})).await)[0];
    let far = ids(&server.trigger("FAR", json!({})).await)[1];
    op.event_where(is("command.started", far)).await;
    let halt = ids(&server.trigger("HALT", json!({})).await);
    let events = op.events_until(is("command.done", halt[0])).await;
    assert!(events.iter().any(is("command.cancelled", long)));
    assert!(events.iter().any(is("command.cancelled", far)));
    assert!(
        events
            .iter()
            .any(|e| e["type"] == "stop" && e["reason"] == "DRIVE_STOP in act HALT")
    );
    assert!(
        events.iter().any(is("command.done", halt[1])),
        "DRIVE_STOP itself is done"
    );
    server.stop().await;
}

#[tokio::test]
async fn an_interrupting_trigger_cuts_current_speech_short() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let long = ids(&server.trigger("LONG", json!({})).await)[0];
    op.event_where(is("command.started", long)).await;
    let hello = ids(&server.trigger("HELLO", json!({"interrupt": true})).await)[0];
    let events = op.events_until(is("command.done", hello)).await;
    let cancelled = &events[position(&events, is("command.cancelled", long))];
    assert_eq!(cancelled["reason"], "interrupted by act HELLO");
    assert!(
        position(&events, is("command.cancelled", long))
            < position(&events, is("command.started", hello))
    );
    server.stop().await;
}

#[tokio::test]
async fn speech_says_one_utterance_at_a_time_in_trigger_order() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let first = ids(&server.trigger("HELLO", json!({})).await)[0];
    let second = ids(&server.trigger("TOUR", json!({})).await)[0];
    let events = op.events_until(is("command.done", second)).await;
    assert!(
        position(&events, is("command.done", first))
            < position(&events, is("command.started", second))
    );
    server.stop().await;
}

const LATER_STOP: &str = r#"
- Label: GO_THEN_STOP
  Cmds: [SET_WAYPOINT 19 0, DRIVE_START, WAIT 100ms, DRIVE_STOP, SAY Stopped here]
- Label: TALK_THEN_MORE
  Text: [First part]
  Cmds: [WAIT, SAY Second part]
- Label: HUSH
  Text: [Quiet please]
"#;

#[tokio::test]
async fn a_drive_stop_after_a_wait_stops_the_drive_when_it_is_reached() {
    let b = TempBundle::new(LATER_STOP).with_file("docent.yaml", CONFIG);
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let t = server.trigger("GO_THEN_STOP", json!({})).await;
    let [_, drive, pause, stop, said] = ids(&t)[..] else {
        panic!("{t}")
    };
    let events = op.events_until(is("command.done", said)).await;
    let at = |kind, id| position(&events, is(kind, id));
    let stopped = position(&events, |e| e["type"] == "stop");
    assert!(
        at("command.started", drive) < stopped,
        "no stop at trigger time"
    );
    assert!(at("command.done", pause) < stopped);
    assert!(stopped < at("command.cancelled", drive));
    assert!(at("command.cancelled", drive) < at("command.done", stop));
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["pose"]["moving"], false);
    assert!(state["pose"]["x"].as_f64().unwrap() < 5.0, "{state}");
    server.stop().await;
}

#[tokio::test]
async fn an_interrupt_also_drops_speech_an_act_has_not_sent_yet() {
    let b = TempBundle::new(LATER_STOP).with_file("docent.yaml", CONFIG);
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let talk = ids(&server.trigger("TALK_THEN_MORE", json!({})).await);
    op.event_where(is("command.started", talk[0])).await;
    let hush = ids(&server.trigger("HUSH", json!({"interrupt": true})).await)[0];
    let mut events = op.events_until(is("command.done", hush)).await;
    if !events.iter().any(is("command.cancelled", talk[2])) {
        events.extend(op.events_until(is("command.cancelled", talk[2])).await);
    }
    assert!(events.iter().any(is("command.cancelled", talk[0])));
    assert!(
        !events.iter().any(is("command.sent", talk[2])),
        "the second part is never said"
    );
    server.stop().await;
}

#[tokio::test]
async fn an_act_with_a_wait_keeps_its_place_in_the_speech_queue() {
    let b = TempBundle::new(LATER_STOP).with_file("docent.yaml", CONFIG);
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    for _ in 0..20 {
        op.send(json!({"type": "trigger", "label": "TALK_THEN_MORE"}))
            .await;
        op.send(json!({"type": "trigger", "label": "HUSH"})).await;
    }
    let mut sent_say = Vec::new();
    while sent_say.len() < 40 {
        let e = op
            .event_where(|e| e["type"] == "command.sent" && e["verb"] == "SAY")
            .await;
        if e["arg"] != "Second part" {
            sent_say.push(e["arg"].as_str().unwrap().to_owned());
        }
    }
    for pair in sent_say.chunks(2) {
        assert_eq!(pair, ["First part", "Quiet please"]);
    }
    server.stop().await;
}
