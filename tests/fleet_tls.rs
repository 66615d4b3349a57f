//! `mqtts://`: a robot reaches a mosquitto TLS listener whose certificate its CA file vouches
//! for, and publishes its retained state through it; with the system's CAs instead (which do
//! not know the test CA) the link stays down and operators are told why.

use crate::common;
use crate::fleet_support;

use common::{WsClient, bundle};
use fleet_support::{Mosquitto, Robot, TestClient};
use serde_json::Value;

#[tokio::test]
async fn a_robot_reaches_a_tls_broker_its_ca_file_vouches_for() {
    let (broker, tls_port, ca) = Mosquitto::start_with_tls();
    let mut mqtt = TestClient::connect(&broker, "tls-test", &["docent/+/state"]);
    let url = format!("mqtts://127.0.0.1:{tls_port}");
    let ca = ca.to_string_lossy().into_owned();
    let _robot = Robot::start_at(
        &bundle("dialogs/info-terminal"),
        &url,
        "tls-1",
        &["--mqtt-ca", &ca],
    );
    let state = mqtt
        .next("docent/tls-1/state", |s| s["online"] == true)
        .await;
    assert_eq!(
        state["link"]["broker"],
        format!("mqtts://127.0.0.1:{tls_port}")
    );
    assert_eq!(state["link"]["state"], "up");
}

#[tokio::test]
async fn a_tls_broker_no_trusted_ca_vouches_for_is_refused_and_said() {
    let (_broker, tls_port, _ca) = Mosquitto::start_with_tls();
    let url = format!("mqtts://127.0.0.1:{tls_port}");
    let robot = Robot::start_at(&bundle("dialogs/info-terminal"), &url, "tls-2", &[]);
    let mut operator = WsClient::operator_at(&robot.addr).await;
    let state: Value = fleet_support::operator_get(&robot.url("/api/state")).await;
    let link = &state["fleet"]["link"];
    let reason = if link["state"] == "down" {
        link["reason"].clone()
    } else {
        assert_eq!(link["state"], "connecting", "{state}");
        let down = operator
            .recv_where(|f| f["type"] == "event" && f["event"]["type"] == "fleet.link")
            .await;
        assert_eq!(down["event"]["state"], "down", "{down}");
        down["event"]["reason"].clone()
    };
    let reason = reason.as_str().expect("a reason");
    assert!(
        reason.contains("TLS") || reason.contains("certificate"),
        "{reason}"
    );
}
