//! The websocket protocol: hello and welcome, triggers answered with `triggered` or `error`,
//! display clients fed with commands and the current state, and bad frames answered while the
//! connection stays usable.

use crate::common;

use common::{TestServer, WsClient, bundle};
use serde_json::json;
use tokio_tungstenite::tungstenite::Message;

async fn fig4() -> TestServer {
    TestServer::start(&bundle("tests/fixtures/fig4-verbatim")).await
}

#[tokio::test]
async fn a_trigger_is_answered_with_its_ref_and_resolved_commands() {
    let server = fig4().await;
    let mut op = server.operator().await;
    assert_eq!(op.welcome["protocol"], 4);
    assert_eq!(op.welcome["role"], "operator");
    assert_eq!(op.welcome["state"]["context"], "Text");
    op.send(
        json!({"type": "trigger", "label": "WHERE_FROM", "context": "TextGroup", "ref": "q-7"}),
    )
    .await;
    let t = op.recv_type("triggered").await;
    assert_eq!(t["ref"], "q-7");
    assert_eq!(t["text"], "Where are you from?");
    assert_eq!(t["commands"][0]["verb"], "SAY");
    assert!(t["commands"][0]["id"].as_u64().is_some());
    op.send(json!({"type": "trigger", "label": "WELCOMEE", "ref": "q-8"}))
        .await;
    let e = op.recv_type("error").await;
    assert_eq!(
        (
            e["code"].as_str(),
            e["ref"].as_str(),
            e["suggestion"].as_str()
        ),
        (Some("unknown-act"), Some("q-8"), Some("WELCOME"))
    );
    server.stop().await;
}

#[tokio::test]
async fn every_bad_frame_gets_an_error_and_the_connection_stays_usable() {
    let server = fig4().await;
    let mut c = WsClient::connect(&format!("ws://{}/ws", server.addr)).await;
    let cases: Vec<(String, &str)> = vec![
        (r#"{"type":"trigger","label":"OK"}"#.into(), "hello-first"),
        ("not json at all".into(), "malformed-json"),
        (r#"{"label":"OK"}"#.into(), "missing-type"),
        (r#"{"type":"dance"}"#.into(), "unknown-type"),
        (r#"{"type":"propose"}"#.into(), "bad-frame"),
        (r#"{"type":"mark","mark":"party"}"#.into(), "bad-frame"),
        // Frame types added later are known too: malformed, not unknown.
        (r#"{"type":"language"}"#.into(), "bad-frame"),
        (
            r#"{"type":"attract","state":"dancing"}"#.into(),
            "bad-frame",
        ),
        (r#"{"type":"hello","role":"pilot"}"#.into(), "bad-frame"),
        (r#"{"type":"hello","role":"adapter"}"#.into(), "no-verbs"),
        (
            format!(r#"{{"type":"trigger","label":"{}"}}"#, "X".repeat(20_000)),
            "frame-too-large",
        ),
    ];
    for (frame, code) in &cases {
        c.send_text(frame).await;
        let e = c.recv_type("error").await;
        assert_eq!(e["code"], *code, "for {frame:.60}: {e}");
        assert!(!e["message"].as_str().unwrap().is_empty());
    }
    c.send_message(Message::binary(vec![1, 2, 3])).await;
    assert_eq!(c.recv_type("error").await["code"], "binary-frame");
    c.send(json!({"type": "hello", "role": "dm", "token": common::DM_TOKEN}))
        .await;
    assert_eq!(c.recv_type("welcome").await["role"], "dm");
    c.send(json!({"type": "hello", "role": "dm", "token": common::DM_TOKEN}))
        .await;
    assert_eq!(c.recv_type("error").await["code"], "already-introduced");
    c.send(json!({"type": "trigger", "label": "OK", "ref": "after"}))
        .await;
    assert_eq!(c.recv_type("triggered").await["ref"], "after");
    server.stop().await;
}

#[tokio::test]
async fn roles_limit_what_a_client_may_do() {
    let server = fig4().await;
    let mut projector = server
        .client(json!({"type": "hello", "role": "projector"}))
        .await;
    projector
        .send(json!({"type": "trigger", "label": "OK", "ref": "p"}))
        .await;
    let e = projector.recv_type("error").await;
    assert_eq!(
        (e["code"].as_str(), e["ref"].as_str()),
        (Some("forbidden"), Some("p"))
    );
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    // A kiosk's stop ends only visitors' speech (tests/channel_policies.rs): allowed.
    kiosk.send(json!({"type": "stop", "ref": "k"})).await;
    assert_eq!(kiosk.recv_type("stopped").await["ref"], "k");
    // A kiosk may not change the context.
    kiosk
        .send(json!({"type": "context", "context": "TextChild"}))
        .await;
    assert_eq!(kiosk.recv_type("error").await["code"], "forbidden");
    server.stop().await;
}

#[tokio::test]
async fn display_clients_get_commands_and_late_ones_get_the_current_state() {
    let server = fig4().await;
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    let mut projector = server
        .client(json!({"type": "hello", "role": "projector"}))
        .await;
    assert_eq!(
        projector.welcome["state"]["display"]["projector"],
        serde_json::Value::Null
    );
    let mut op = server.operator().await;
    op.send(json!({"type": "trigger", "label": "WELCOME", "ref": "w"}))
        .await;
    let page = kiosk.recv_type("command").await;
    assert_eq!(
        (
            page["verb"].as_str(),
            page["arg"].as_str(),
            page["ref"].as_str()
        ),
        (
            Some("DISPLAY_PAGE"),
            Some("Welcome/Welcome.html"),
            Some("w")
        )
    );
    op.send(json!({"type": "trigger", "label": "RUN_VIDEO_EXHIBIT"}))
        .await;
    let shown = projector.recv_type("command").await;
    assert_eq!(
        (shown["verb"].as_str(), shown["arg"].as_str()),
        (Some("PROJECT"), Some("Exhibit/video.mp4"))
    );
    let changed = op
        .event_where(|e| e["type"] == "display.changed" && e["projector"] == "Exhibit/video.mp4")
        .await;
    assert_eq!(changed["page"], "Welcome/Welcome.html");
    let late = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    assert_eq!(
        late.welcome["state"]["display"]["page"],
        "Welcome/Welcome.html"
    );
    assert_eq!(
        late.welcome["state"]["display"]["projector"],
        "Exhibit/video.mp4"
    );
    server.stop().await;
}

#[tokio::test]
async fn operators_see_clients_come_and_go_and_can_set_the_context() {
    let server = fig4().await;
    let mut op = server.operator().await;
    let kiosk = server
        .client(json!({"type": "hello", "role": "kiosk", "name": "front"}))
        .await;
    let joined = op
        .event_where(|e| e["type"] == "client.connected" && e["role"] == "kiosk")
        .await;
    assert_eq!(
        (joined["role"].as_str(), joined["name"].as_str()),
        (Some("kiosk"), Some("front"))
    );
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["clients"].as_object().unwrap().len(), 2, "{state}");
    drop(kiosk);
    let left = op.event("client.left").await;
    assert_eq!(left["client"], joined["client"]);
    op.send(json!({"type": "context", "context": "TextGroup", "ref": "c"}))
        .await;
    // The answer and the event travel separately: take them in either order.
    let (mut answer, mut event) = (None, None);
    while answer.is_none() || event.is_none() {
        let f = op.recv().await;
        match f["type"].as_str() {
            Some("context") => answer = Some(f),
            Some("event") if f["event"]["type"] == "context.changed" => {
                event = Some(f["event"].clone())
            }
            _ => {}
        }
    }
    assert_eq!(answer.unwrap()["context"], "TextGroup");
    assert_eq!(event.unwrap()["source"], "operator");
    server.stop().await;
}

#[tokio::test]
async fn a_client_that_only_triggers_can_decline_the_event_stream() {
    let server = fig4().await;
    let mut quiet = server
        .client(json!({"type": "hello", "role": "dm", "events": false}))
        .await;
    let mut op = server.operator().await;
    quiet
        .send(json!({"type": "trigger", "label": "OK", "ref": "one"}))
        .await;
    assert_eq!(quiet.recv_type("triggered").await["ref"], "one");
    op.event("act.triggered").await;
    quiet
        .send(json!({"type": "trigger", "label": "OK", "ref": "two"}))
        .await;
    // The very next frame is the answer: no events came in between.
    assert_eq!(quiet.recv().await["type"], "triggered");
    server.stop().await;
}

#[tokio::test]
async fn a_kiosk_reports_pages_it_shows_on_its_own() {
    let server = fig4().await;
    let mut op = server.operator().await;
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    kiosk
        .send(json!({"type": "page", "page": "Welcome/Welcome.html"}))
        .await;
    let changed = op.event("display.changed").await;
    assert_eq!(changed["page"], "Welcome/Welcome.html");
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["display"]["page"], "Welcome/Welcome.html");
    for page in ["../acts.yaml", "nowhere.html"] {
        kiosk.send(json!({"type": "page", "page": page})).await;
        assert_eq!(
            kiosk.recv_type("error").await["code"],
            "unknown-page",
            "{page}"
        );
    }
    op.send(json!({"type": "page", "page": "Welcome/Welcome.html"}))
        .await;
    assert_eq!(op.recv_type("error").await["code"], "forbidden");
    server.stop().await;
}
