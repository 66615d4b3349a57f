//! External adapters over the websocket: they declare verbs, receive commands in order, answer
//! done or failed; no adapter, a silent one or one that leaves gives `command.failed`.

mod common;

use common::{TempBundle, TestServer, WsClient};
use serde_json::{Value, json};

const ACTS: &str = r#"
- Label: GREET
  Text: [Good morning]
  Cmds: [LIGHTS on, SAY Second sentence, LIGHTS dim]
- Label: SHOW
  Cmds: [LIGHTS off]
"#;

fn bundle(timeout: &str) -> TempBundle {
    let config = format!(
        "speech: {{adapter: ws}}\nadapters: {{timeout: {timeout}}}\nverbs:\n  LIGHTS: {{adapter: ws, argument: required}}\n"
    );
    TempBundle::new(ACTS).with_file("docent.yaml", &config)
}

async fn adapter(server: &TestServer, verbs: &[&str]) -> WsClient {
    server
        .client(json!({"type": "hello", "role": "adapter", "name": "robot", "verbs": verbs}))
        .await
}

fn terminal(e: &Value) -> bool {
    matches!(
        e["type"].as_str(),
        Some("command.done" | "command.failed" | "command.cancelled")
    )
}

#[tokio::test]
async fn an_adapter_receives_its_verbs_in_order_and_completes_them() {
    let b = bundle("5s");
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut speech = adapter(&server, &["SAY"]).await;
    let mut lights = adapter(&server, &["LIGHTS"]).await;
    let t = server.trigger("GREET", json!({"ref": "g"})).await;
    let mut said = Vec::new();
    for _ in 0..2 {
        let c = speech.recv_type("command").await;
        assert_eq!(c["ref"], "g");
        said.push(c["arg"].as_str().unwrap().to_owned());
        speech.send(json!({"type": "started", "id": c["id"]})).await;
        speech.send(json!({"type": "done", "id": c["id"]})).await;
    }
    assert_eq!(said, ["Good morning", "Second sentence"]);
    let mut switched = Vec::new();
    for _ in 0..2 {
        let c = lights.recv_type("command").await;
        switched.push(c["arg"].as_str().unwrap().to_owned());
        lights.send(json!({"type": "done", "id": c["id"]})).await;
    }
    assert_eq!(switched, ["on", "dim"]);
    let ids: Vec<u64> = t["commands"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["id"].as_u64().unwrap())
        .collect();
    let mut done = Vec::new();
    while done.len() < 4 {
        let e = op.event_where(terminal).await;
        assert_eq!(e["type"], "command.done", "{e}");
        done.push(e["command"].as_u64().unwrap());
    }
    done.sort_unstable();
    assert_eq!(done, ids);
    server.stop().await;
}

#[tokio::test]
async fn a_failure_answer_becomes_command_failed_with_its_reason() {
    let b = bundle("5s");
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut lights = adapter(&server, &["LIGHTS"]).await;
    server.trigger("SHOW", json!({})).await;
    let c = lights.recv_type("command").await;
    lights
        .send(json!({"type": "failed", "id": c["id"], "reason": "relay stuck"}))
        .await;
    let e = op.event_where(terminal).await;
    assert_eq!(
        (e["type"].as_str(), e["reason"].as_str()),
        (Some("command.failed"), Some("relay stuck"))
    );
    lights.send(json!({"type": "done", "id": c["id"]})).await;
    assert_eq!(lights.recv_type("error").await["code"], "unknown-command");
    server.stop().await;
}

#[tokio::test]
async fn no_adapter_a_silent_adapter_or_a_leaving_one_fails_the_command() {
    let b = bundle("300ms");
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    server.trigger("SHOW", json!({})).await;
    let e = op.event_where(terminal).await;
    assert_eq!(e["type"], "command.failed");
    assert!(
        e["reason"]
            .as_str()
            .unwrap()
            .contains("no adapter for LIGHTS"),
        "{e}"
    );

    let mut silent = adapter(&server, &["LIGHTS"]).await;
    server.trigger("SHOW", json!({})).await;
    silent.recv_type("command").await;
    let e = op.event_where(terminal).await;
    assert_eq!(e["type"], "command.failed");
    assert!(
        e["reason"]
            .as_str()
            .unwrap()
            .contains("no adapter answered"),
        "{e}"
    );

    server.trigger("SHOW", json!({})).await;
    silent.recv_type("command").await;
    drop(silent);
    let e = op.event_where(terminal).await;
    assert_eq!(
        (e["type"].as_str(), e["reason"].as_str()),
        (Some("command.failed"), Some("the adapter disconnected"))
    );
    // The server keeps running: the next act still reaches a fresh adapter.
    let mut fresh = adapter(&server, &["LIGHTS"]).await;
    server.trigger("SHOW", json!({})).await;
    let c = fresh.recv_type("command").await;
    fresh.send(json!({"type": "done", "id": c["id"]})).await;
    assert_eq!(op.event_where(terminal).await["type"], "command.done");
    server.stop().await;
}

#[tokio::test]
async fn stop_sends_cancel_to_adapters_and_cancels_what_they_owe() {
    let b = bundle("5s");
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut speech = adapter(&server, &["SAY"]).await;
    server.trigger("GREET", json!({})).await;
    let c = speech.recv_type("command").await;
    let (status, _) = server.post("/api/stop", None).await;
    assert_eq!(status, 202);
    let cancel = speech.recv_type("cancel").await;
    assert_eq!(cancel["reason"], "stop request");
    let e = op
        .event_where(|e| terminal(e) && e["command"] == c["id"])
        .await;
    assert_eq!(e["type"], "command.cancelled");
    server.stop().await;
}

#[tokio::test]
async fn an_adapter_is_told_which_of_its_verbs_go_elsewhere() {
    let b = TempBundle::new(ACTS).with_file("docent.yaml", "speech: {adapter: log}\nverbs:\n  LIGHTS: {adapter: ws}\n");
    let server = TestServer::start(b.path()).await;
    let mut a = adapter(&server, &["LIGHTS", "SAY", "DANCE"]).await;
    let first = a.recv_type("error").await;
    assert_eq!(first["code"], "verb-not-routed");
    assert!(first["message"].as_str().unwrap().starts_with("SAY goes to the log adapter"), "{first}");
    let second = a.recv_type("error").await;
    assert!(second["message"].as_str().unwrap().starts_with("DANCE is not a verb"), "{second}");
    // Still connected and served for what is routed to it.
    server.trigger("SHOW", json!({})).await;
    assert_eq!(a.recv_type("command").await["verb"], "LIGHTS");
    server.stop().await;
}
