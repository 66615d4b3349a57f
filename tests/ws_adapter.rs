//! External adapters over the websocket: they declare verbs, receive commands in order, answer
//! done or failed; no adapter, a silent one or one that leaves gives `command.failed`.

use crate::common;

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
    lights.send(json!({"type": "done", "id": 424_242})).await;
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
    let b = TempBundle::new(ACTS).with_file(
        "docent.yaml",
        "speech: {adapter: log}\nverbs:\n  LIGHTS: {adapter: ws}\n",
    );
    let server = TestServer::start(b.path()).await;
    let mut a = adapter(&server, &["LIGHTS", "SAY", "DANCE"]).await;
    let warning = a.recv_type("error").await;
    assert_eq!(warning["code"], "verb-not-routed");
    let message = warning["message"].as_str().unwrap();
    assert!(
        message.starts_with("SAY goes to the log adapter; DANCE is not a verb of this bundle;"),
        "{message}"
    );
    assert!(!message.contains("LIGHTS"), "{message}");
    // Still connected and served for what is routed to it.
    server.trigger("SHOW", json!({})).await;
    assert_eq!(a.recv_type("command").await["verb"], "LIGHTS");
    server.stop().await;
}

#[tokio::test]
async fn a_started_command_is_off_the_answer_clock_and_the_next_waits_its_turn() {
    let b = bundle("300ms");
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut speech = adapter(&server, &["SAY"]).await;
    let mut lights = adapter(&server, &["LIGHTS"]).await;
    let t = server.trigger("GREET", json!({})).await;
    let id = |i: usize| t["commands"][i]["id"].clone();
    let first_say = speech.recv_type("command").await;
    assert_eq!(first_say["id"], id(0));
    speech
        .send(json!({"type": "started", "id": first_say["id"]}))
        .await;
    lights.recv_type("command").await;
    // The lights adapter never answers: its oldest command fails after 300 ms, then the next.
    for expected in [id(1), id(3)] {
        let e = op.event_where(terminal).await;
        assert_eq!(
            (e["type"].as_str(), &e["command"]),
            (Some("command.failed"), &expected),
            "{e}"
        );
    }
    // Well past 300 ms, the started SAY is still running, and the second SAY, not yet its
    // turn, is not on the clock either.
    speech
        .send(json!({"type": "done", "id": first_say["id"]}))
        .await;
    let e = op.event_where(terminal).await;
    assert_eq!(
        (e["type"].as_str(), &e["command"]),
        (Some("command.done"), &id(0))
    );
    let e = op.event_where(terminal).await;
    assert_eq!(
        (e["type"].as_str(), &e["command"]),
        (Some("command.failed"), &id(2)),
        "then its clock runs"
    );
    server.stop().await;
}

#[tokio::test]
async fn a_second_adapters_answer_to_a_settled_command_is_no_error() {
    let b = bundle("5s");
    let server = TestServer::start(b.path()).await;
    let mut first = adapter(&server, &["LIGHTS"]).await;
    let mut second = adapter(&server, &["LIGHTS"]).await;
    server.trigger("SHOW", json!({})).await;
    let c1 = first.recv_type("command").await;
    let c2 = second.recv_type("command").await;
    assert_eq!(c1["id"], c2["id"], "both serve LIGHTS");
    first.send(json!({"type": "done", "id": c1["id"]})).await;
    second.send(json!({"type": "done", "id": c2["id"]})).await;
    second.send(json!({"type": "done", "id": 999_999})).await;
    let e = second.recv_type("error").await;
    assert!(
        e["message"].as_str().unwrap().contains("999999"),
        "only the unknown id is an error: {e}"
    );
    server.stop().await;
}

#[tokio::test]
async fn a_wait_after_a_failed_command_abandons_the_rest_of_the_act() {
    let acts = "- Label: GO\n  Text: [Follow me]\n  Cmds: [SET_WAYPOINT 1 1, DRIVE_START, WAIT, DISPLAY_PAGE index.html]\n";
    let b = TempBundle::new(acts).with_file(
        "docent.yaml",
        "speech: {adapter: log, rate: 600}\ndrive: {adapter: ws}\n",
    );
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let t = server.trigger("GO", json!({})).await;
    let page = t["commands"][4]["id"].clone();
    let wait = t["commands"][3]["id"].clone();
    let events = op
        .events_until(|e| e["command"] == page && terminal(e))
        .await;
    let wait_end = events
        .iter()
        .find(|e| e["command"] == wait && terminal(e))
        .unwrap();
    assert_eq!(wait_end["type"], "command.failed");
    assert!(
        wait_end["reason"]
            .as_str()
            .unwrap()
            .contains("did not succeed (no adapter for SET_WAYPOINT"),
        "{wait_end}"
    );
    let page_end = events.last().unwrap();
    assert_eq!(page_end["type"], "command.cancelled");
    assert!(
        !events
            .iter()
            .any(|e| e["type"] == "command.sent" && e["command"] == page),
        "never sent"
    );
    let (_, state) = server.get("/api/state").await;
    assert_eq!(
        state["display"]["page"], "index.html",
        "the page did not change"
    );
    server.stop().await;
}

#[tokio::test]
async fn shutdown_settles_what_adapters_owe_and_logs_them_leaving() {
    let b = bundle("30s");
    let server = TestServer::start(b.path()).await;
    let mut lights = adapter(&server, &["LIGHTS"]).await;
    let t = server.trigger("SHOW", json!({})).await;
    lights.recv_type("command").await;
    let log = server.stop().await;
    let id = &t["commands"][0]["id"];
    let end = log
        .iter()
        .find(|e| &e["command"] == id && terminal(e))
        .expect("an outcome for the owed command");
    assert_eq!(
        (end["type"].as_str(), end["reason"].as_str()),
        (
            Some("command.cancelled"),
            Some("the server is shutting down")
        )
    );
    assert!(
        log.iter()
            .any(|e| e["type"] == "client.left" && e["role"] == "adapter")
    );
    drop(lights);
}

#[tokio::test]
async fn a_say_is_sent_with_how_long_saying_it_takes_at_the_sites_rate() {
    let config =
        "speech: {adapter: ws, rate: 120}\nverbs:\n  LIGHTS: {adapter: ws, argument: required}\n";
    let b = TempBundle::new(ACTS).with_file("docent.yaml", config);
    let server = TestServer::start(b.path()).await;
    let mut speech = adapter(&server, &["SAY"]).await;
    let mut lights = adapter(&server, &["LIGHTS"]).await;
    server.trigger("GREET", json!({})).await;
    let say = speech.recv_type("command").await;
    // The server's one rule (words at the site's rate, and a breath): 2 words at 120 a minute.
    let expected = docent::content::speaking_time("Good morning", 120);
    assert_eq!(expected.as_millis(), 1_100);
    assert_eq!(say["speaking_ms"], json!(1_100), "{say}");
    let light = lights.recv_type("command").await;
    assert!(
        light.get("speaking_ms").is_none(),
        "only a SAY has it: {light}"
    );
    server.stop().await;
}
