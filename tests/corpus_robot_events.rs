//! Robot events: an adapter process on the robot tells of what its sensors noticed, by names
//! it declared in its `hello`; each is logged as a `robot` event that operators see, and one
//! the site lists in `corpus: session_start_events` starts a visitor session (source
//! `adapter`) before its own line, so the session begins when the robot notices its visitors.
//! Against a real server on 127.0.0.1:0, with protocol clients in the adapter's place.

use crate::common;

use common::{TempBundle, TestServer, WsClient, json_lines, session_dirs};
use docent::corpus::layout::SESSION_EVENTS;
use serde_json::{Value, json};

fn bundle(corpus: &str) -> TempBundle {
    TempBundle::new("- Label: WELCOME\n  Text: [Hello!]\n").with_file(
        "docent.yaml",
        &format!("speech: {{adapter: log}}\ncorpus: {corpus}\n"),
    )
}

async fn tracker(server: &TestServer) -> WsClient {
    let hello = json!({"type": "hello", "role": "adapter", "name": "people-tracker",
        "robot_events": ["person.near", "battery.low"]});
    server.client(hello).await
}

#[tokio::test]
async fn a_listed_robot_event_starts_a_session_and_every_one_is_logged_and_shown() {
    let b = bundle("{session_start_events: [person.near], session_idle: 0s}");
    let folder = tempfile::tempdir().unwrap();
    let server = TestServer::start_with(b.path(), |o| o.corpus_dir = folder.path().into()).await;
    let mut op = server.operator().await;
    let mut sensor = tracker(&server).await;
    // Not listed: logged, starts nothing.
    sensor
        .send(json!({"type": "robot", "event": "battery.low", "data": {"percent": 14}}))
        .await;
    let low = op.event("robot").await;
    assert_eq!(
        (&low["event"], &low["data"]["percent"]),
        (&json!("battery.low"), &json!(14))
    );
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["session"], Value::Null, "battery.low starts nothing");
    // Listed: the session starts first, then the event is its first line after the start.
    sensor
        .send(json!({"type": "robot", "event": "person.near", "data": {"distance_m": 1.2}}))
        .await;
    let started = op.event("session.started").await;
    assert_eq!(started["source"], "adapter");
    let near = op.event("robot").await;
    assert!(started["seq"].as_u64() < near["seq"].as_u64());
    // Another while it runs starts no second one.
    sensor
        .send(json!({"type": "robot", "event": "person.near"}))
        .await;
    op.event_where(|e| e["type"] == "robot" && e["data"].is_null())
        .await;
    let corpus = server.corpus.clone();
    let all = server.stop().await;
    assert_eq!(
        all.iter()
            .filter(|e| e["type"] == "session.started")
            .count(),
        1
    );
    let sessions = session_dirs(&corpus);
    let log = json_lines(&sessions[0].join(SESSION_EVENTS));
    let robot: Vec<&str> = (log.iter())
        .filter(|e| e["type"] == "robot")
        .map(|e| e["event"].as_str().unwrap())
        .collect();
    assert_eq!(robot, ["person.near", "person.near"]);
}

#[tokio::test]
async fn robot_events_come_only_from_adapters_by_declared_names() {
    let b = bundle("{session_start: marked, session_start_events: [person.near]}");
    let server = TestServer::start(b.path()).await;
    let mut sensor = tracker(&server).await;
    sensor
        .send(json!({"type": "robot", "event": "door.open"}))
        .await;
    let error = sensor.recv_type("error").await;
    assert_eq!(error["code"], "bad-frame");
    assert!(
        error["message"]
            .as_str()
            .unwrap()
            .contains("person.near, battery.low"),
        "{error}"
    );
    let big = "x".repeat(5000);
    sensor
        .send(json!({"type": "robot", "event": "person.near", "data": big}))
        .await;
    let error = sensor.recv_type("error").await;
    assert!(
        error["message"].as_str().unwrap().contains("at most 4096"),
        "{error}"
    );
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    kiosk
        .send(json!({"type": "robot", "event": "person.near"}))
        .await;
    assert_eq!(kiosk.recv_type("error").await["code"], "forbidden");
    // With `session_start: marked`, even a listed event starts nothing.
    let mut op = server.operator().await;
    sensor
        .send(json!({"type": "robot", "event": "person.near"}))
        .await;
    op.event("robot").await;
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["session"], Value::Null);
    // A sensor without verbs is an adapter all the same; one with neither is refused, and so
    // is a badly named event.
    for (hello, says) in [
        (json!({"type": "hello", "role": "adapter"}), "robot_events"),
        (
            json!({"type": "hello", "role": "adapter", "robot_events": ["Person Near"]}),
            "lower-case",
        ),
    ] {
        let mut refused = server.connect().await;
        refused.send(hello).await;
        let error = refused.recv_type("error").await;
        assert!(error["message"].as_str().unwrap().contains(says), "{error}");
    }
    let all = server.stop().await;
    assert!(
        all.iter()
            .any(|e| e["type"] == "robot" && e["event"] == "person.near")
    );
    assert!(
        !all.iter()
            .any(|e| e["type"] == "robot" && e["event"] == "door.open")
    );
}
