//! A fleet over a real mosquitto: two `docent serve --mqtt` processes on one broker appear in
//! one fleet view; a signed command over MQTT reaches the right robot only and is answered on
//! its reply topic, signed, with the websocket's own error codes; a kiosk role, a wrong
//! signature, a raw credential, a command for another robot, a stale and a replayed one are
//! refused; the fleet view's Stop stops the right robot; the last will says offline after
//! `kill -9`, and a robot that stops says so itself; a Docent without a broker says so; a
//! retained message over the message limit is dropped and the links stay up.

use crate::common;
use crate::fleet_support;

use std::time::Duration;

use common::{DEADLINE, DM_TOKEN, OPERATOR_TOKEN, bundle};
use fleet_support::{
    Mosquitto, Robot, TestClient, fleet_until, fresh_ref, logged, online, reply_frame, signed,
    signed_at,
};
use rumqttc::{AsyncClient, Event, Incoming, MqttOptions, QoS};
use serde_json::{Value, json};

#[tokio::test]
async fn two_robots_on_one_broker_are_one_fleet_and_commands_reach_the_right_one_only() {
    let broker = Mosquitto::start();
    let bundle = bundle("dialogs/info-terminal");
    let first = Robot::start(&bundle, &broker, "hall-1");
    let second = Robot::start(&bundle, &broker, "hall-2");

    // Either robot's /fleet shows both, with their state.
    let robots = fleet_until(&first, |r| online(r, "hall-1") && online(r, "hall-2")).await;
    let hall2 = robots
        .iter()
        .find(|r| r["robot"] == "hall-2")
        .expect("listed");
    assert_eq!(hall2["state"]["bundle"], "info-terminal");
    assert_eq!(hall2["state"]["page"], "index.html");
    assert_eq!(hall2["state"]["console"], second.url("/operator"));
    assert_eq!(hall2["state"]["link"]["state"], "up");
    assert!(hall2["state"]["pose"].is_object(), "{hall2}");
    let snapshot: Value = fleet_support::operator_get(&second.url("/api/fleet")).await;
    assert_eq!(snapshot["link"]["state"], "up");
    let unsigned = reqwest::get(first.url("/api/fleet"))
        .await
        .expect("answers");
    assert_eq!(unsigned.status(), 401);

    // A trigger over MQTT reaches hall-1 only; a context reaches hall-2 (as the dm).
    let mut mqtt = TestClient::connect(&broker, "fleet-test", &["docent/+/reply"]);
    let answer = mqtt
        .ask("hall-1", json!({"type": "trigger", "label": "WELCOME"}))
        .await;
    assert_eq!(answer["type"], "triggered", "{answer}");
    let context = json!({"type": "context", "context": "Text", "ref": "c2"});
    let reference = fresh_ref();
    let as_dm = signed("hall-2", ("dm", DM_TOKEN), &reference, &context);
    let reply = mqtt.ask_envelope("hall-2", &reference, as_dm).await;
    assert!(fleet_support::reply_signed(&reply, DM_TOKEN), "{reply}");
    assert_eq!(reply_frame(&reply)["type"], "context", "{reply}");
    let triggered = |robot: &Robot| logged(&robot.corpus, "act.triggered");
    assert_eq!(triggered(&first).len(), 1);
    assert_eq!(triggered(&first)[0]["label"], "WELCOME");
    assert!(triggered(&second).is_empty(), "{:?}", triggered(&second));
    let joined = logged(&first.corpus, "client.connected");
    assert!(
        joined
            .iter()
            .any(|e| e["name"] == "mqtt" && e["role"] == "operator")
    );

    // Refusals are answered unsigned, with the command's ref, and run nothing.
    let trigger = json!({"type": "trigger", "label": "WELCOME"});
    let refused = async |mqtt: &mut TestClient, robot: &str, command: Value| {
        let reference = command["ref"].as_str().expect("a ref").to_owned();
        let reply = mqtt.ask_envelope(robot, &reference, command).await;
        assert!(reply["mac"].is_null(), "{reply}");
        reply_frame(&reply)
    };
    // Signed with a wrong credential: logged once as `client.refused`.
    let wrong = signed(
        "hall-1",
        ("operator", "not-the-credential"),
        &fresh_ref(),
        &trigger,
    );
    let answer = refused(&mut mqtt, "hall-1", wrong).await;
    assert_eq!(answer["code"], "bad-signature", "{answer}");
    assert_eq!(
        answer["message"],
        "the command's mac is not signed with the operator credential (DOCENT_OPERATOR_TOKEN)"
    );
    // The raw credential of the first fleet commands: refused unread, never echoed.
    let raw =
        json!({"type": "trigger", "label": "WELCOME", "ref": fresh_ref(), "token": OPERATOR_TOKEN});
    let answer = refused(&mut mqtt, "hall-1", raw).await;
    assert_eq!(answer["code"], "unsigned-command", "{answer}");
    assert!(!answer.to_string().contains(OPERATOR_TOKEN));
    // Signed for hall-2 but published on hall-1's topic; too old; replayed.
    let elsewhere = signed(
        "hall-2",
        ("operator", OPERATOR_TOKEN),
        &fresh_ref(),
        &trigger,
    );
    let answer = refused(&mut mqtt, "hall-1", elsewhere).await;
    assert_eq!(answer["code"], "bad-signature", "{answer}");
    let old_ts = fleet_support::now_ms() - 60_000;
    let old = signed_at(
        "hall-1",
        ("operator", OPERATOR_TOKEN),
        &fresh_ref(),
        &trigger,
        old_ts,
    );
    assert_eq!(
        refused(&mut mqtt, "hall-1", old).await["code"],
        "stale-command"
    );
    let once = signed(
        "hall-1",
        ("operator", OPERATOR_TOKEN),
        &fresh_ref(),
        &json!({"type": "context", "context": "Text"}),
    );
    let reference = once["ref"].as_str().expect("ref").to_owned();
    let reply = mqtt.ask_envelope("hall-1", &reference, once.clone()).await;
    assert_eq!(reply_frame(&reply)["type"], "context", "{reply}");
    assert_eq!(
        refused(&mut mqtt, "hall-1", once).await["code"],
        "replayed-command"
    );
    assert_eq!(logged(&first.corpus, "client.refused").len(), 1);
    // A kiosk needs no credential on the websocket; over a broker it is refused.
    let kiosk = signed("hall-1", ("kiosk", OPERATOR_TOKEN), &fresh_ref(), &trigger);
    let answer = refused(&mut mqtt, "hall-1", kiosk).await;
    assert_eq!(
        (answer["type"].as_str(), answer["code"].as_str()),
        (Some("error"), Some("forbidden"))
    );
    // Not JSON, an unknown frame: the websocket's reading of it.
    mqtt.command("hall-1", json!("{oops")).await;
    let answer = mqtt.ask("hall-1", json!({"type": "dance"})).await;
    assert_eq!(answer["code"], "unknown-type", "{answer}");
    assert_eq!(triggered(&first).len(), 1, "nothing refused was triggered");

    // Stop from hall-1's fleet view stops hall-2, and only it.
    let (status, stopped) = fleet_support::fleet_stop(&first, "hall-2").await;
    assert_eq!(status, 200, "{stopped}");
    assert_eq!(stopped["answer"]["type"], "stopped", "{stopped}");
    assert_eq!(logged(&second.corpus, "stop").len(), 1);
    assert_eq!(logged(&second.corpus, "stop")[0]["source"], "operator");
    assert!(logged(&first.corpus, "stop").is_empty());
    let unknown = reqwest::Client::new()
        .post(first.url("/api/fleet/robots/hall-9/stop"))
        .bearer_auth(OPERATOR_TOKEN)
        .send()
        .await
        .expect("answers");
    assert_eq!(unknown.status(), 404);
}

#[tokio::test]
async fn a_docent_without_a_broker_says_so_at_api_fleet() {
    let server = common::TestServer::start(&bundle("dialogs/info-terminal")).await;
    let (status, body) = server.get("/api/fleet").await;
    assert_eq!(status, 404, "{body}");
    assert_eq!(body["code"], "not-found");
    let error = body["error"].as_str().expect("a message");
    assert!(error.contains("--mqtt URL --robot-id ID"), "{error}");
    let (_, state) = server.get("/api/state").await;
    assert!(state["fleet"].is_null(), "{state}");
    let page = reqwest::get(server.url("/fleet")).await.expect("answers");
    assert_eq!(page.status(), 200);
    server.stop().await;
}

#[tokio::test]
async fn the_last_will_says_offline_after_kill_9() {
    let broker = Mosquitto::start();
    let mut mqtt = TestClient::connect(&broker, "will-test", &["docent/+/status"]);
    let mut robot = Robot::start(&bundle("dialogs/info-terminal"), &broker, "dock-1");
    let status = mqtt
        .next("docent/dock-1/status", |s| s["online"] == true)
        .await;
    assert_eq!(status["robot"], "dock-1");
    robot.kill_9();
    let started = std::time::Instant::now();
    let will = mqtt
        .next("docent/dock-1/status", |s| s["online"] == false)
        .await;
    assert_eq!(will["robot"], "dock-1");
    println!("last will seen {:?} after kill -9", started.elapsed());
    assert!(
        started.elapsed() < Duration::from_secs(16),
        "within 1.5 keep-alives"
    );
}

#[tokio::test]
async fn a_robot_that_stops_says_offline_itself() {
    let broker = Mosquitto::start();
    let mut mqtt = TestClient::connect(&broker, "goodbye-test", &["docent/+/state"]);
    let mut robot = Robot::start(&bundle("dialogs/info-terminal"), &broker, "dock-2");
    mqtt.next("docent/dock-2/state", |s| s["online"] == true)
        .await;
    robot.terminate();
    let goodbye = mqtt
        .next("docent/dock-2/state", |s| s["online"] == false)
        .await;
    assert_eq!(goodbye["reason"], "the robot's Docent stopped", "{goodbye}");
}

#[tokio::test]
async fn a_battery_robot_event_shows_in_the_state() {
    let broker = Mosquitto::start();
    let mut mqtt = TestClient::connect(&broker, "battery-test", &["docent/+/state"]);
    let robot = Robot::start(&bundle("dialogs/info-terminal"), &broker, "dock-3");
    mqtt.next("docent/dock-3/state", |s| {
        s["battery"].is_null() && s["online"] == true
    })
    .await;
    let mut sensor = common::WsClient::connect(&format!("ws://{}/ws", robot.addr)).await;
    let hello = json!({"type": "hello", "role": "adapter", "name": "power", "robot_events": ["battery.state"]});
    sensor.send(hello).await;
    sensor.recv_type("welcome").await;
    let reading = json!({"type": "robot", "event": "battery.state", "data": {"percentage": 0.42}});
    sensor.send(reading).await;
    let state = mqtt
        .next("docent/dock-3/state", |s| s["battery"].is_object())
        .await;
    assert_eq!(state["battery"]["percent"], 42.0, "{state}");
    assert_eq!(state["battery"]["event"], "battery.state");
}

/// Publishes `size` bytes, retained, on `topic`, with a client allowed to send that much;
/// returns once the broker has it.
async fn publish_retained(broker: &Mosquitto, topic: &str, size: usize) {
    let mut options = MqttOptions::new(format!("big-{topic}"), "127.0.0.1", broker.port);
    options.set_max_packet_size(size + 1024, size + 1024);
    let (client, mut events) = AsyncClient::new(options, 8);
    (client.publish(topic, QoS::AtLeastOnce, true, vec![b'x'; size]))
        .await
        .expect("queued");
    let acked = async {
        loop {
            match events.poll().await.expect("the broker takes it") {
                Event::Incoming(Incoming::PubAck(_)) => return,
                _ => continue,
            }
        }
    };
    tokio::time::timeout(DEADLINE, acked)
        .await
        .expect("acknowledged within the deadline");
}

#[tokio::test]
async fn a_retained_message_over_the_limit_is_dropped_and_the_links_stay_up() {
    let broker = Mosquitto::start();
    let bundle = bundle("dialogs/info-terminal");
    let mut first = Robot::start(&bundle, &broker, "hall-1");
    let mut second = Robot::start(&bundle, &broker, "hall-2");
    fleet_until(&first, |r| online(r, "hall-1") && online(r, "hall-2")).await;

    // 300 KiB, retained: where every fleet view reads states, and on hall-1's command topic.
    publish_retained(&broker, "docent/ghost/state", 300 * 1024).await;
    publish_retained(&broker, "docent/hall-1/cmd", 300 * 1024).await;

    // hall-1 still takes commands after it, and its fleet view still stops hall-2.
    let mut mqtt = TestClient::connect(&broker, "fleet-test", &["docent/+/reply"]);
    let context = json!({"type": "context", "context": "Text"});
    assert_eq!(mqtt.ask("hall-1", context.clone()).await["type"], "context");
    let (status, stopped) = fleet_support::fleet_stop(&first, "hall-2").await;
    assert_eq!(status, 200, "{stopped}");
    assert_eq!(stopped["answer"]["type"], "stopped", "{stopped}");
    // A robot that connects now gets the retained messages at once, and stays up too.
    let third = Robot::start(&bundle, &broker, "hall-3");
    let robots = fleet_until(&third, |r| online(r, "hall-1") && online(r, "hall-3")).await;
    assert!(!robots.iter().any(|r| r["robot"] == "ghost"), "{robots:?}");
    assert_eq!(mqtt.ask("hall-1", context).await["type"], "context");

    first.terminate();
    second.terminate();
    for robot in [&first, &second, &third] {
        let links = logged(&robot.corpus, "fleet.link");
        let down: Vec<&Value> = links.iter().filter(|e| e["state"] == "down").collect();
        assert!(down.is_empty(), "{down:?}");
    }
}
