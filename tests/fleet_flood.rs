//! A burst of signed commands over a real mosquitto: every one is answered on the reply topic,
//! run, or refused with `rate-limited` when more wait to run than the robot queues, signed
//! either way; none is dropped without a word.

use crate::common;
use crate::fleet_support;

use std::collections::HashMap;

use common::{OPERATOR_TOKEN, bundle};
use fleet_support::{
    Mosquitto, Robot, TestClient, fleet_until, fresh_ref, online, reply_frame, signed,
};
use serde_json::json;

#[tokio::test]
async fn a_burst_of_signed_commands_is_answered_every_one() {
    const COMMANDS: usize = 300;
    const BURST: usize = 60;
    let broker = Mosquitto::start();
    let robot = Robot::start(&bundle("dialogs/info-terminal"), &broker, "hall-1");
    fleet_until(&robot, |r| online(r, "hall-1")).await;
    let mut mqtt = TestClient::connect(&broker, "flood-test", &["docent/+/reply"]);
    // Answered once: the client is subscribed to the replies.
    let first = mqtt
        .ask("hall-1", json!({"type": "trigger", "label": "WELCOME"}))
        .await;
    assert_eq!(first["type"], "triggered", "{first}");
    // Bursts within what the test's own MQTT client keeps in flight, each more than the robot
    // queues to run (32).
    let mut asked = Vec::with_capacity(COMMANDS);
    let mut answers: HashMap<String, String> = HashMap::new();
    for _ in 0..COMMANDS / BURST {
        for _ in 0..BURST {
            let reference = fresh_ref();
            let trigger = json!({"type": "trigger", "label": "WELCOME"});
            let command = signed("hall-1", ("operator", OPERATOR_TOKEN), &reference, &trigger);
            mqtt.command("hall-1", command).await;
            asked.push(reference);
        }
        while answers.len() < asked.len() {
            let reply = mqtt.next("docent/hall-1/reply", |_| true).await;
            assert!(
                fleet_support::reply_signed(&reply, OPERATOR_TOKEN),
                "{reply}"
            );
            let frame = reply_frame(&reply);
            if frame["type"] == "outcome" {
                // A SAY the speech queue had no room for: told, not an answer.
                continue;
            }
            let kind = match frame["type"].as_str() {
                Some("error") => frame["code"].as_str().unwrap_or_default().to_owned(),
                other => other.unwrap_or_default().to_owned(),
            };
            assert!(kind == "triggered" || kind == "rate-limited", "{frame}");
            let reference = reply["ref"].as_str().expect("a ref").to_owned();
            let again = answers.insert(reference, kind);
            assert_eq!(again, None, "answered twice: {reply}");
        }
    }
    assert!(asked.iter().all(|r| answers.contains_key(r)));
    let refused = answers.values().filter(|k| *k == "rate-limited").count();
    println!("{COMMANDS} commands: {refused} refused as rate-limited, the rest run");
    assert!(
        refused > 0,
        "bursts of {BURST} never filled the queue of 32"
    );
}
