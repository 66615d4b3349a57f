//! A broker restart is survived, under load: mosquitto is killed and started again on the same
//! port while a dialog manager keeps triggering over the websocket; the robot tells its
//! operators the link went down (`fleet.link`, `/api/state`'s `fleet`), comes back by itself,
//! re-publishes its retained state (the broker kept nothing) and takes commands again, and
//! every trigger answered meanwhile is in the corpus once.

use crate::common;
use crate::fleet_support;

use std::time::Instant;

use common::load::{each_once, keep_triggering};
use common::{WsClient, bundle, read_corpus};
use fleet_support::{Mosquitto, Robot, TestClient};
use serde_json::{Value, json};
use tokio_util::sync::CancellationToken;

#[tokio::test]
async fn a_broker_restart_is_survived() {
    let mut broker = Mosquitto::start();
    let robot = Robot::start(&bundle("dialogs/info-terminal"), &broker, "gate-1");
    let mut operator = WsClient::operator_at(&robot.addr).await;
    let mut mqtt = TestClient::connect(&broker, "restart-test", &["docent/gate-1/#"]);
    mqtt.next("docent/gate-1/state", |s| s["online"] == true)
        .await;
    let stop_load = CancellationToken::new();
    let load = tokio::spawn(keep_triggering(
        robot.addr.clone(),
        "WELCOME",
        stop_load.clone(),
    ));

    broker.kill();
    let down = operator
        .recv_where(|f| {
            f["type"] == "event"
                && f["event"]["type"] == "fleet.link"
                && f["event"]["state"] == "down"
        })
        .await;
    assert!(down["event"]["reason"].is_string(), "{down}");
    let state: Value = fleet_support::operator_get(&robot.url("/api/state")).await;
    assert_eq!(state["fleet"]["robot"], "gate-1");
    assert_eq!(state["fleet"]["link"]["state"], "down", "{state}");

    let restarted = Instant::now();
    broker.restart();
    operator
        .recv_where(|f| {
            f["type"] == "event"
                && f["event"]["type"] == "fleet.link"
                && f["event"]["state"] == "up"
        })
        .await;
    let back = restarted.elapsed();
    // The broker forgot everything (no persistence): the robot published both again, its
    // status first.
    mqtt.next("docent/gate-1/status", |s| s["online"] == true)
        .await;
    let again = mqtt
        .next("docent/gate-1/state", |s| s["online"] == true)
        .await;
    assert_eq!(again["link"]["state"], "up");
    let command = json!({"type": "trigger", "label": "WELCOME"});
    let answer = mqtt.ask("gate-1", command).await;
    assert_eq!(answer["type"], "triggered", "{answer}");
    println!(
        "link up again {back:?} after the broker restarted; commands answered after {:?}",
        restarted.elapsed()
    );
    stop_load.cancel();
    let answered = load.await.expect("the load ran");
    // Every trigger answered while the link went and came back is in the corpus, once.
    each_once(&answered, &read_corpus(&robot.corpus));
    println!("{} triggers answered during the restart", answered.len());
    drop(broker);
}
