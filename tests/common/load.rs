//! A dialog manager that keeps triggering while a test breaks something else (a broker, a
//! rosbridge), so that the test can check that every trigger answered meanwhile is in the
//! corpus once.

use std::collections::HashMap;

use serde_json::json;
use tokio_util::sync::CancellationToken;

use super::{DM_TOKEN, WsClient};

/// Triggers `label` from a dialog manager at `addr` (`host:port`) in rounds of ten until
/// `stop`; returns the refs answered.
pub async fn keep_triggering(
    addr: String,
    label: &'static str,
    stop: CancellationToken,
) -> Vec<String> {
    let mut dm = WsClient::connect(&format!("ws://{addr}/ws")).await;
    let hello = json!({"type": "hello", "role": "dm", "token": DM_TOKEN, "events": false});
    dm.send(hello).await;
    dm.recv_type("welcome").await;
    let mut answered = Vec::new();
    for round in 0.. {
        if stop.is_cancelled() {
            break;
        }
        for i in 0..10 {
            let reference = format!("load-{round}-{i}");
            dm.send(json!({"type": "trigger", "label": label, "ref": reference}))
                .await;
        }
        for _ in 0..10 {
            let answer = dm.recv_type("triggered").await;
            answered.push(answer["ref"].as_str().expect("its ref").to_owned());
        }
    }
    answered
}

/// Asserts that each of `answered` has exactly one `act.triggered` in `corpus_lines`.
pub fn each_once(answered: &[String], corpus_lines: &[serde_json::Value]) {
    assert!(
        answered.len() >= 10,
        "the load ran: {} answered",
        answered.len()
    );
    let mut times: HashMap<&str, usize> = HashMap::new();
    for event in corpus_lines.iter().filter(|e| e["type"] == "act.triggered") {
        if let Some(reference) = event["ref"].as_str() {
            *times.entry(reference).or_default() += 1;
        }
    }
    for reference in answered {
        let times = times.get(reference.as_str()).copied().unwrap_or_default();
        assert_eq!(times, 1, "{reference} in the corpus {times} times");
    }
}
