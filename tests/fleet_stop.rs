//! Issue 24 over a real mosquitto: Stop always gets through. Wrong commands published on
//! `docent/ID/cmd` by anyone who can reach the broker never lock the local console, the HTTP
//! API or the fleet view out of Stop; a forged `stopped` answer (another topic, another robot,
//! unsigned, badly signed, a guessed ref) is never taken for a stop; and nothing published on
//! the broker contains a credential.

use crate::common;
use crate::fleet_support;

use common::{DM_TOKEN, OPERATOR_TOKEN, WsClient, bundle};
use fleet_support::{
    Mosquitto, Robot, TestClient, fleet_stop, fleet_until, fresh_ref, logged, online, signed,
    signed_reply,
};
use rumqttc::QoS;
use serde_json::{Value, json};

/// Badly signed commands published in one burst (below mosquitto's default queue of 1000 per
/// client, which would drop the rest whatever Docent does).
const FLOOD: usize = 500;

#[tokio::test]
async fn wrong_commands_over_mqtt_never_lock_this_machine_or_the_fleet_out_of_stop() {
    let broker = Mosquitto::start();
    let robot = Robot::start(&bundle("dialogs/info-terminal"), &broker, "hall-1");
    fleet_until(&robot, |r| online(r, "hall-1")).await;
    let mut attacker = TestClient::connect(&broker, "attacker", &["docent/+/reply"]);
    let stop = json!({"type": "stop"});
    // Raw wrong credentials as the first fleet commands carried them, then wrong signatures:
    // the broker is on this machine, so today they counted against 127.0.0.1.
    let mut codes = Vec::new();
    for attempt in 0..12 {
        let reference = fresh_ref();
        let command = if attempt < 6 {
            json!({"type": "stop", "ref": reference, "token": format!("guess-{attempt}")})
        } else {
            signed(
                "hall-1",
                ("operator", "a-wrong-credential"),
                &reference,
                &stop,
            )
        };
        let reply = attacker.ask_envelope("hall-1", &reference, command).await;
        codes.push(reply.to_string());
    }

    // A burst of badly signed commands, not waited for, then a rightly signed Stop: checked as
    // they arrive, they never crowd it out.
    let flooded = std::time::Instant::now();
    for _ in 0..FLOOD {
        let command = signed(
            "hall-1",
            ("operator", "a-wrong-credential"),
            &fresh_ref(),
            &stop,
        );
        attacker.command("hall-1", command).await;
    }
    let answer = attacker.ask("hall-1", json!({"type": "stop"})).await;
    assert_eq!(answer["type"], "stopped", "{answer}");
    println!(
        "{FLOOD} bad commands and a signed Stop answered in {:?}",
        flooded.elapsed()
    );

    // The local console: HTTP Stop and a websocket stop from 127.0.0.1.
    let response = reqwest::Client::new()
        .post(robot.url("/api/stop"))
        .bearer_auth(OPERATOR_TOKEN)
        .send()
        .await
        .expect("answers");
    assert_eq!(response.status(), 202, "HTTP Stop from 127.0.0.1");
    let mut console = WsClient::connect(&format!("ws://{}/ws", robot.addr)).await;
    let hello = json!({"type": "hello", "role": "operator", "token": OPERATOR_TOKEN});
    console.send(hello).await;
    console.recv_type("welcome").await;
    console.send(json!({"type": "stop", "ref": "local"})).await;
    assert_eq!(console.recv_type("stopped").await["ref"], "local");
    // The fleet view's Stop, and a rightly signed command, after the flood.
    let (status, body) = fleet_stop(&robot, "hall-1").await;
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["answer"]["type"], "stopped", "{body}");
    let answer = attacker.ask("hall-1", json!({"type": "stop"})).await;
    assert_eq!(answer["type"], "stopped", "{answer}");
    assert_eq!(logged(&robot.corpus, "stop").len(), 5);

    // What the wrong ones were told: the raw credential refused unread, the bad signatures
    // counted (under MQTT's own key) until they wait.
    let code = |reply: &String| {
        let reply: Value = serde_json::from_str(reply).expect("JSON");
        fleet_support::reply_frame(&reply)["code"].clone()
    };
    assert!(
        codes[..6].iter().all(|c| code(c) == "unsigned-command"),
        "{codes:?}"
    );
    assert!(
        codes[6..10].iter().all(|c| code(c) == "bad-signature"),
        "{codes:?}"
    );
    assert!(
        codes[11..].iter().all(|c| code(c) == "too-many-attempts"),
        "{codes:?}"
    );
}

#[tokio::test]
async fn a_forged_stopped_answer_is_never_taken_for_a_stop() {
    let broker = Mosquitto::start();
    let view = Robot::start(&bundle("dialogs/info-terminal"), &broker, "hall-1");
    // A robot the view hears of, played by the test, and a forger reading its commands.
    let mut ghost = TestClient::connect(&broker, "ghost", &["docent/ghost-1/cmd"]);
    let state = json!({"online": true, "robot": "ghost-1", "page": "index.html"});
    for (leaf, payload) in [("status", json!({"online": true})), ("state", state)] {
        let topic = format!("docent/ghost-1/{leaf}");
        let retained = (ghost.client).publish(topic, QoS::AtLeastOnce, true, payload.to_string());
        retained.await.expect("published");
    }
    fleet_until(&view, |r| online(r, "ghost-1") && online(r, "hall-1")).await;

    let stopping = tokio::spawn(async move {
        let answer = fleet_stop(&view, "ghost-1").await;
        (view, answer)
    });
    let command = ghost
        .next("docent/ghost-1/cmd", |c| c["ref"].is_string())
        .await;
    let reference = command["ref"].as_str().expect("a ref").to_owned();
    let stopped = json!({"type": "stopped"});
    let forgeries = [
        // The first fleet view's answer format, on the robot's reply topic: unsigned.
        (
            "docent/ghost-1/reply",
            json!({"type": "stopped", "ref": reference}),
        ),
        // Rightly signed, but on another robot's topic.
        (
            "docent/hall-1/reply",
            signed_reply("ghost-1", &reference, &stopped, OPERATOR_TOKEN),
        ),
        // Rightly signed by another robot, on the asked robot's topic.
        (
            "docent/ghost-1/reply",
            signed_reply("hall-1", &reference, &stopped, OPERATOR_TOKEN),
        ),
        // Signed with another credential, or with none.
        (
            "docent/ghost-1/reply",
            signed_reply("ghost-1", &reference, &stopped, DM_TOKEN),
        ),
        (
            "docent/ghost-1/reply",
            json!({"robot": "ghost-1", "ref": reference, "frame": stopped.to_string()}),
        ),
        // An unsigned refusal, as a robot whose clock is off answers: told as a hint only.
        (
            "docent/ghost-1/reply",
            json!({"robot": "ghost-1", "ref": reference,
                "frame": json!({"type": "error", "code": "stale-command"}).to_string()}),
        ),
        // A guessed ref.
        (
            "docent/ghost-1/reply",
            signed_reply("ghost-1", "fleet-stop-1", &stopped, OPERATOR_TOKEN),
        ),
    ];
    for (topic, forgery) in &forgeries {
        ghost.publish(topic, forgery).await;
    }
    let (view, (status, body)) = stopping.await.expect("the stop ran");
    assert_eq!(status, 504, "a forged answer was taken: {body}");
    assert_eq!(body["code"], "robot-silent", "{body}");
    let said = body["error"].as_str().unwrap_or_default();
    assert!(
        said.contains("not signed with this view's operator credential"),
        "{said}"
    );

    // The same view takes an answer bound to its request: the forgeries were the difference.
    let stopping = tokio::spawn(async move { fleet_stop(&view, "ghost-1").await });
    let command = ghost
        .next("docent/ghost-1/cmd", |c| c["ref"].is_string())
        .await;
    assert!(command.get("token").is_none(), "{command}");
    let reference = command["ref"].as_str().expect("a ref").to_owned();
    let genuine = signed_reply("ghost-1", &reference, &stopped, OPERATOR_TOKEN);
    ghost.publish("docent/ghost-1/reply", &genuine).await;
    let (status, body) = stopping.await.expect("the stop ran");
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["answer"]["type"], "stopped", "{body}");
}

#[tokio::test]
async fn nothing_published_on_the_broker_contains_a_credential() {
    let broker = Mosquitto::start();
    let mut reader = TestClient::connect(&broker, "reader", &["#"]);
    let bundle = bundle("dialogs/info-terminal");
    let first = Robot::start(&bundle, &broker, "hall-1");
    let second = Robot::start(&bundle, &broker, "hall-2");
    fleet_until(&first, |r| online(r, "hall-1") && online(r, "hall-2")).await;

    // A fleet Stop, a refused websocket hello (an event on the broker), a command as the dm.
    let (status, body) = fleet_stop(&first, "hall-2").await;
    assert_eq!(status, 200, "{body}");
    let mut refused = WsClient::connect(&format!("ws://{}/ws", first.addr)).await;
    let hello = json!({"type": "hello", "role": "operator", "token": DM_TOKEN});
    refused.send(hello).await;
    refused.frames_until_closed().await;
    let reference = fresh_ref();
    let context = json!({"type": "context", "context": "Text"});
    let as_dm = signed("hall-1", ("dm", DM_TOKEN), &reference, &context);
    reader.command("hall-1", as_dm).await;

    // Every message up to the answers and the refusal's event is read and scanned.
    let (mut stop_answered, mut refusal_seen, mut dm_answered, mut stop_sent) =
        (false, false, false, false);
    let mut scanned = 0;
    while !(stop_answered && refusal_seen && dm_answered && stop_sent) {
        let message = reader.recv().await;
        scanned += 1;
        for credential in [OPERATOR_TOKEN, DM_TOKEN] {
            assert!(
                !message.text.contains(credential),
                "{} carries a credential: {}",
                message.topic,
                message.text
            );
        }
        let json = &message.json;
        match message.topic.as_str() {
            "docent/hall-2/cmd" => stop_sent = true,
            "docent/hall-2/reply" => {
                stop_answered |= json["frame"]
                    .as_str()
                    .is_some_and(|f| f.contains("stopped"))
            }
            "docent/hall-1/reply" => dm_answered |= json["ref"] == reference.as_str(),
            "docent/hall-1/events" => refusal_seen |= json["type"] == "client.refused",
            _ => {}
        }
    }
    println!("{scanned} messages scanned");
    drop(second);
}
