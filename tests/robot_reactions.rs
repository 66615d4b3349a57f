//! Reactions: `reactions:` in docent.yaml maps a robot event to an act, with a condition on
//! the event's data and a cool-down. A robot event reaches a dialog manager, triggers its
//! mapped act (source `robot`) once per cool-down, and a condition the data cannot decide is
//! told as `reaction.failed`. Against a real server on 127.0.0.1:0, with a protocol client
//! as the robot's sensor adapter and another as the dialog manager.

use crate::common;

use common::{TempBundle, TestServer, WsClient};
use serde_json::{Value, json};

const ACTS: &str = "- Label: GREETING\n  Text: [Hello! Come closer.]\n\
                    - Label: LOW_BATTERY\n  Text: [I need to charge soon.]\n";

fn bundle() -> TempBundle {
    TempBundle::new(ACTS).with_file(
        "docent.yaml",
        "speech: {adapter: log}\n\
         reactions:\n\
         \x20 - event: person.near\n\
         \x20   if: distance < 1.5\n\
         \x20   act: GREETING\n\
         \x20   cooldown: 1h\n\
         \x20 - event: battery\n\
         \x20   if: percentage <= 20 and charging == false\n\
         \x20   act: LOW_BATTERY\n",
    )
}

async fn sensor(server: &TestServer) -> WsClient {
    let hello = json!({"type": "hello", "role": "adapter", "name": "people-tracker",
        "robot_events": ["person.near", "battery", "bumper"]});
    server.client(hello).await
}

async fn dm(server: &TestServer) -> WsClient {
    server
        .client(json!({"type": "hello", "role": "dm", "name": "planner"}))
        .await
}

/// Everything the dialog manager sees up to the robot event `marker`, sent last: the intake
/// handles robot events one after another, so whatever an earlier one caused comes before.
async fn until_marker(dm: &mut WsClient, sensor: &mut WsClient, marker: &str) -> Vec<Value> {
    let frame = json!({"type": "robot", "event": "bumper", "data": {"marker": marker}});
    sensor.send(frame).await;
    dm.events_until(|e| e["type"] == "robot" && e["data"]["marker"] == marker)
        .await
}

fn triggered(events: &[Value]) -> Vec<(&str, &str, &str)> {
    (events.iter())
        .filter(|e| e["type"] == "act.triggered")
        .map(|e| {
            (
                e["label"].as_str().unwrap(),
                e["source"].as_str().unwrap(),
                e["ref"].as_str().unwrap_or_default(),
            )
        })
        .collect()
}

#[tokio::test]
async fn a_robot_event_reaches_the_dm_and_triggers_its_act_once_per_cooldown() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut planner = dm(&server).await;
    let mut tracker = sensor(&server).await;
    // Too far: the dialog manager sees the event, nothing is triggered.
    let far = json!({"type": "robot", "event": "person.near", "data": {"distance": 3.2}});
    tracker.send(far).await;
    let seen = until_marker(&mut planner, &mut tracker, "far").await;
    let robot = seen.iter().find(|e| e["type"] == "robot").unwrap();
    assert_eq!(robot["data"]["distance"], 3.2);
    assert_eq!(robot["client"], tracker.welcome["client"]);
    assert_eq!(triggered(&seen), []);
    // Close: GREETING, as source robot, after the event that caused it.
    let near = json!({"type": "robot", "event": "person.near", "data": {"distance": 1.1}});
    tracker.send(near.clone()).await;
    let seen = until_marker(&mut planner, &mut tracker, "near").await;
    assert_eq!(
        triggered(&seen),
        [("GREETING", "robot", "reaction 1: person.near")]
    );
    let cause = seen.iter().position(|e| e["type"] == "robot").unwrap();
    let effect = seen.iter().position(|e| e["type"] == "act.triggered");
    assert!(effect > Some(cause), "{seen:?}");
    // Close again within the hour's cool-down: seen, not triggered again.
    tracker.send(near).await;
    let seen = until_marker(&mut planner, &mut tracker, "again").await;
    assert_eq!(seen.iter().filter(|e| e["type"] == "robot").count(), 2);
    assert_eq!(triggered(&seen), []);
    // The other reaction, with two comparisons, has its own cool-down.
    let low = json!({"type": "robot", "event": "battery",
        "data": {"percentage": 18, "charging": false}});
    tracker.send(low).await;
    let seen = until_marker(&mut planner, &mut tracker, "battery").await;
    assert_eq!(
        triggered(&seen),
        [("LOW_BATTERY", "robot", "reaction 2: battery")]
    );
    let all = server.stop().await;
    let acts: Vec<&str> = (all.iter())
        .filter(|e| e["type"] == "act.triggered")
        .map(|e| e["label"].as_str().unwrap())
        .collect();
    assert_eq!(acts, ["GREETING", "LOW_BATTERY"], "the corpus agrees");
}

#[tokio::test]
async fn data_the_condition_cannot_decide_is_told_once_per_cooldown() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut tracker = sensor(&server).await;
    let odd = json!({"type": "robot", "event": "person.near", "data": {"range": 1.0}});
    tracker.send(odd.clone()).await;
    let failed = op.event("reaction.failed").await;
    assert_eq!(
        (&failed["reaction"], &failed["event"], &failed["act"]),
        (&json!(1), &json!("person.near"), &json!("GREETING"))
    );
    let reason = failed["reason"].as_str().unwrap();
    assert!(
        reason.contains("the event's data has no field `distance`")
            && reason.contains("distance < 1.5")
            && reason.contains("fix `if:`"),
        "{reason}"
    );
    // Told once per cool-down, not at the sensor's rate; and never taken as a trigger.
    tracker.send(odd).await;
    let seen = until_marker(&mut op, &mut tracker, "odd").await;
    assert!(
        seen.iter()
            .all(|e| e["type"] != "reaction.failed" && e["type"] != "act.triggered"),
        "{seen:?}"
    );
    let text = json!({"type": "robot", "event": "battery", "data": {"percentage": "low"}});
    tracker.send(text).await;
    let failed = op.event("reaction.failed").await;
    assert!(
        failed["reason"].as_str().unwrap().contains(
            "`percentage` is text (\"low\"), but the condition compares it with a number"
        ),
        "{failed}"
    );
    server.stop().await;
}

#[tokio::test]
async fn a_reaction_never_overrides_the_operator() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut tracker = sensor(&server).await;
    // The reaction's act runs at the dialog manager's priority, below the operator's: its
    // speech waits behind the operator's (speech queues by default), never cuts it short.
    op.send(json!({"type": "trigger", "label": "LOW_BATTERY", "ref": "op"}))
        .await;
    op.event_where(|e| e["type"] == "command.started" && e["verb"] == "SAY")
        .await;
    let near = json!({"type": "robot", "event": "person.near", "data": {"distance": 0.5}});
    tracker.send(near).await;
    let seen = op
        .events_until(|e| {
            e["type"] == "command.started" && e["verb"] == "SAY" && e["source"] == "robot"
        })
        .await;
    let says: Vec<(&str, &str)> = (seen.iter())
        .filter(|e| e["verb"] == "SAY" && e["type"] != "command.sent")
        .map(|e| (e["type"].as_str().unwrap(), e["label"].as_str().unwrap()))
        .collect();
    assert_eq!(
        says,
        [
            ("command.done", "LOW_BATTERY"),
            ("command.started", "GREETING")
        ],
        "the operator's speech ran to its end before the reaction's began: {seen:?}"
    );
    server.stop().await;
}
