//! The fleet view as a test reads it: its live stream until it lists what the test waits
//! for, and its Stop.

use serde_json::Value;

use super::Robot;
use crate::common::{DEADLINE, OPERATOR_TOKEN};

/// Reads the fleet view's live stream on `robot` until `done` accepts the robots it lists.
pub async fn fleet_until(robot: &Robot, done: impl Fn(&[Value]) -> bool) -> Vec<Value> {
    let mut response = reqwest::Client::new()
        .get(robot.url("/api/fleet/updates"))
        .bearer_auth(OPERATOR_TOKEN)
        .send()
        .await
        .expect("the fleet stream answers");
    assert_eq!(response.status(), 200);
    let mut robots: std::collections::BTreeMap<String, Value> = Default::default();
    let mut buffer = String::new();
    let read = async {
        loop {
            let chunk = response
                .chunk()
                .await
                .expect("stream readable")
                .expect("stream open");
            buffer.push_str(std::str::from_utf8(&chunk).expect("UTF-8"));
            while let Some(end) = buffer.find("\n\n") {
                let message: String = buffer.drain(..end + 2).collect();
                let Some(data) = message.lines().find_map(|l| l.strip_prefix("data: ")) else {
                    continue;
                };
                let data: Value = serde_json::from_str(data).expect("JSON update");
                let id = |r: &Value| r["robot"].as_str().unwrap_or_default().to_owned();
                if let Some(all) = data["robots"].as_array() {
                    robots = all.iter().map(|r| (id(r), r.clone())).collect();
                } else if data["robot"].is_object() {
                    robots.insert(id(&data["robot"]), data["robot"].clone());
                }
                let listed: Vec<Value> = robots.values().cloned().collect();
                if done(&listed) {
                    return listed;
                }
            }
        }
    };
    tokio::time::timeout(DEADLINE, read)
        .await
        .expect("the fleet view shows it within the deadline")
}

/// Whether `robots` lists `id` online with its state.
pub fn online(robots: &[Value], id: &str) -> bool {
    robots
        .iter()
        .any(|r| r["robot"] == id && r["online"] == true && r["state"]["page"].is_string())
}

/// `POST /api/fleet/robots/{target}/stop` on `view` with the operator credential: the status
/// and the body.
pub async fn fleet_stop(view: &Robot, target: &str) -> (u16, Value) {
    let url = view.url(&format!("/api/fleet/robots/{target}/stop"));
    let response = reqwest::Client::new()
        .post(url)
        .bearer_auth(OPERATOR_TOKEN)
        .send()
        .await
        .expect("answers");
    let status = response.status().as_u16();
    (status, response.json().await.expect("JSON"))
}
