//! A client that stops reading is dropped; everyone else keeps getting their frames.

use crate::common;

use common::{TempBundle, TestServer, WsClient};
use serde_json::json;

#[tokio::test]
async fn a_client_that_stops_reading_is_dropped_without_slowing_the_others() {
    let acts = format!(
        "- Label: SHOW\n  Text: [\"{}\"]\n  Cmds: [DISPLAY_PAGE index.html]\n",
        "word ".repeat(150)
    );
    let b = TempBundle::new(&acts).with_file("docent.yaml", "speech: {adapter: log, rate: 600}\n");
    let server = TestServer::start(b.path()).await;
    // Says hello as an operator (so every event is sent to it), then never reads again.
    let mut stalled = WsClient::connect(&format!("ws://{}/ws", server.addr)).await;
    stalled
        .send(json!({"type": "hello", "role": "operator", "name": "stalled", "token": common::OPERATOR_TOKEN}))
        .await;
    // A dialog manager triggers as fast as the server answers it, and keeps being answered.
    let mut sender = server.client(json!({"type": "hello", "role": "dm"})).await;
    let mut answered = 0u64;
    loop {
        for _ in 0..50 {
            sender
                .send(json!({"type": "trigger", "label": "SHOW", "interrupt": true}))
                .await;
        }
        for _ in 0..50 {
            sender.recv_type("triggered").await;
            answered += 1;
        }
        let (_, state) = server.get("/api/state").await;
        let clients = state["clients"].as_object().unwrap();
        if !clients.values().any(|c| c["name"] == "stalled") {
            break;
        }
        assert!(answered < 200_000, "the stalled client was never dropped");
    }
    sender
        .send(json!({"type": "trigger", "label": "SHOW", "ref": "after"}))
        .await;
    assert_eq!(sender.recv_type("triggered").await["ref"], "after");
    drop(stalled);
    let log = server.stop().await;
    let joined = log
        .iter()
        .find(|e| e["type"] == "client.connected" && e["name"] == "stalled")
        .unwrap();
    let left = log
        .iter()
        .find(|e| e["type"] == "client.left" && e["client"] == joined["client"])
        .unwrap();
    // Closed with a code, whichever limit it met first: its queue, its reading, or the events.
    let reason = left["reason"].as_str().unwrap();
    assert!(reason.starts_with("too slow"), "{left}");
    assert!(
        [1008, 1013].contains(&left["code"].as_u64().unwrap_or_default()),
        "{left}"
    );
}
