//! What operators and dialog managers share over the websocket: proposals accepted or
//! dismissed (mixed initiative), corpus marks (visitor sessions, groups, situations), the
//! WebRTC signalling relay between an operator and a kiosk, and the recent history a console
//! gets when it joins.

use crate::common;

use common::{TempBundle, TestServer, WsClient};
use serde_json::{Value, json};

const ACTS: &str = r#"
- Label: WELCOME
  Text: [Hello!]
  TextGroup: ["Hello, everybody!"]
  TextChild: [Hi there!]
- Label: GOODBYE
  Text: [Goodbye!]
"#;

fn tour() -> TempBundle {
    TempBundle::new(ACTS).with_file(
        "docent.yaml",
        "speech: {adapter: log}\noperator: { situations: [question, laughter] }\n",
    )
}

async fn dm(server: &TestServer) -> WsClient {
    server
        .client(json!({"type": "hello", "role": "dm", "name": "planner"}))
        .await
}

#[tokio::test]
async fn an_accepted_proposal_is_triggered_on_the_operators_behalf() {
    let b = tour();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut dm = dm(&server).await;
    dm.send(
        json!({"type": "propose", "label": "WELCOME", "context": "TextGroup",
                   "reason": "three visitors arrived", "ref": "p1"}),
    )
    .await;
    let proposed = dm.recv_type("proposed").await;
    assert_eq!(proposed["ref"], "p1");
    let id = proposed["proposal"].as_u64().unwrap();
    let made = op.event("proposal.made").await;
    assert_eq!(
        (
            made["proposal"].as_u64(),
            made["label"].as_str(),
            made["reason"].as_str()
        ),
        (Some(id), Some("WELCOME"), Some("three visitors arrived"))
    );
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["proposals"][0]["proposal"].as_u64(), Some(id));
    op.send(json!({"type": "accept", "proposal": id, "ref": "a1"}))
        .await;
    let triggered = op.recv_type("triggered").await;
    assert_eq!(
        (triggered["ref"].as_str(), triggered["text"].as_str()),
        (Some("a1"), Some("Hello, everybody!"))
    );
    let accepted = dm.event("proposal.accepted").await;
    assert_eq!(accepted["trigger"], triggered["trigger"]);
    // Settled once: a second accept (another console, a double key press) is refused.
    op.send(json!({"type": "accept", "proposal": id, "ref": "a2"}))
        .await;
    assert_eq!(op.recv_type("error").await["code"], "unknown-proposal");
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["proposals"], json!([]));
    let corpus = server.stop().await;
    let act = corpus
        .iter()
        .find(|e| e["type"] == "act.triggered")
        .expect("the act ran");
    assert_eq!(
        (act["label"].as_str(), act["source"].as_str()),
        (Some("WELCOME"), Some("operator"))
    );
    assert!(
        corpus
            .iter()
            .any(|e| e["type"] == "proposal.accepted" && e["proposal"] == id)
    );
}

#[tokio::test]
async fn a_dismissed_proposal_is_not_triggered() {
    let b = tour();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut dm = dm(&server).await;
    dm.send(json!({"type": "propose", "label": "GOODBYE"}))
        .await;
    let id = dm.recv_type("proposed").await["proposal"].as_u64().unwrap();
    op.send(json!({"type": "dismiss", "proposal": id, "ref": "d1"}))
        .await;
    let dismissed = op.recv_type("dismissed").await;
    assert_eq!(
        (dismissed["ref"].as_str(), dismissed["proposal"].as_u64()),
        (Some("d1"), Some(id))
    );
    assert_eq!(dm.event("proposal.dismissed").await["label"], "GOODBYE");
    op.send(json!({"type": "accept", "proposal": id})).await;
    assert_eq!(op.recv_type("error").await["code"], "unknown-proposal");
    let corpus = server.stop().await;
    assert!(
        !corpus.iter().any(|e| e["type"] == "act.triggered"),
        "nothing ran"
    );
    assert!(
        corpus
            .iter()
            .any(|e| e["type"] == "proposal.dismissed" && e["proposal"] == id)
    );
}

#[tokio::test]
async fn proposals_are_checked_and_each_role_keeps_to_its_part() {
    let b = tour();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut dm = dm(&server).await;
    dm.send(json!({"type": "propose", "label": "WELCOM", "ref": "x"}))
        .await;
    let e = dm.recv_type("error").await;
    assert_eq!(
        (
            e["code"].as_str(),
            e["suggestion"].as_str(),
            e["ref"].as_str()
        ),
        (Some("unknown-act"), Some("WELCOME"), Some("x"))
    );
    dm.send(json!({"type": "propose", "label": "WELCOME", "context": "TextPirate"}))
        .await;
    assert_eq!(dm.recv_type("error").await["code"], "unknown-context");
    op.send(json!({"type": "propose", "label": "WELCOME"}))
        .await;
    assert_eq!(op.recv_type("error").await["code"], "forbidden");
    dm.send(json!({"type": "propose", "label": "WELCOME"}))
        .await;
    let id = dm.recv_type("proposed").await["proposal"].clone();
    dm.send(json!({"type": "accept", "proposal": id})).await;
    assert_eq!(dm.recv_type("error").await["code"], "forbidden");
    dm.send(json!({"type": "mark", "mark": "situation", "value": "question"}))
        .await;
    assert_eq!(dm.recv_type("error").await["code"], "forbidden");
    dm.send(json!({"type": "mark", "mark": "note", "value": "a note"}))
        .await;
    assert_eq!(dm.recv_type("error").await["code"], "forbidden");
    server.stop().await;
}

#[tokio::test]
async fn marks_go_to_the_corpus_and_a_group_sets_its_context() {
    let b = tour();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    op.send(json!({"type": "mark", "mark": "session_end", "ref": "m0"}))
        .await;
    assert_eq!(op.recv_type("error").await["code"], "no-session");
    op.send(json!({"type": "mark", "mark": "session_start", "ref": "m1"}))
        .await;
    let marked = op.recv_type("marked").await;
    assert_eq!(
        (marked["ref"].as_str(), marked["session"].as_u64()),
        (Some("m1"), Some(1))
    );
    op.send(json!({"type": "mark", "mark": "group", "value": "children"}))
        .await;
    op.recv_type("marked").await;
    op.event_where(|e| e["type"] == "context.changed" && e["context"] == "TextChild")
        .await;
    op.send(json!({"type": "trigger", "label": "WELCOME"}))
        .await;
    assert_eq!(op.recv_type("triggered").await["text"], "Hi there!");
    op.send(json!({"type": "mark", "mark": "situation", "value": "laughter"}))
        .await;
    op.recv_type("marked").await;
    op.send(json!({"type": "mark", "mark": "situation", "value": "dancing"}))
        .await;
    let bad = op.recv_type("error").await;
    assert_eq!(bad["code"], "bad-mark");
    assert!(
        bad["message"]
            .as_str()
            .unwrap()
            .contains("question, laughter"),
        "{bad}"
    );
    op.send(json!({"type": "mark", "mark": "note", "value": "  the father reads aloud "}))
        .await;
    assert_eq!(op.recv_type("marked").await["session"], 1);
    for (value, says) in [
        (json!("   "), "needs its text"),
        (json!("x".repeat(501)), "at most 500"),
    ] {
        op.send(json!({"type": "mark", "mark": "note", "value": value}))
            .await;
        let bad = op.recv_type("error").await;
        assert_eq!(bad["code"], "bad-mark");
        assert!(bad["message"].as_str().unwrap().contains(says), "{bad}");
    }
    op.send(json!({"type": "mark", "mark": "session_start"}))
        .await;
    assert_eq!(op.recv_type("marked").await["session"], 2);
    op.send(json!({"type": "mark", "mark": "session_end"}))
        .await;
    assert_eq!(op.recv_type("marked").await["session"], 2);
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["session"], Value::Null);
    let corpus = server.stop().await;
    let marks: Vec<String> = corpus
        .iter()
        .filter(|e| {
            let t = e["type"].as_str().unwrap();
            t.starts_with("session.")
                || t == "visitor.group"
                || t == "situation.marked"
                || t == "note.written"
        })
        .map(|e| {
            let what = e["group"]
                .as_str()
                .or(e["situation"].as_str())
                .or(e["text"].as_str())
                .unwrap_or("");
            format!("{} {} {}", e["type"].as_str().unwrap(), e["session"], what)
        })
        .collect();
    assert_eq!(
        marks,
        [
            "session.started 1 ",
            "visitor.group 1 children",
            "situation.marked 1 laughter",
            "note.written 1 the father reads aloud",
            "session.ended 1 ",
            "session.started 2 ",
            "session.ended 2 ",
        ]
    );
    let group = corpus
        .iter()
        .find(|e| e["type"] == "visitor.group")
        .unwrap();
    assert_eq!(group["context"], "TextChild");
    assert_eq!(group["source"], "operator");
}

#[tokio::test]
async fn signalling_is_relayed_between_an_operator_and_the_kiosk_it_called() {
    let b = tour();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut other_op = server.operator().await;
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    let (op_id, other_id, kiosk_id) = (
        op.welcome["client"].clone(),
        other_op.welcome["client"].clone(),
        kiosk.welcome["client"].clone(),
    );
    // A kiosk cannot reach a console that did not call it.
    kiosk
        .send(json!({"type": "signal", "to": op_id, "data": {"kind": "answer"}}))
        .await;
    assert_eq!(kiosk.recv_type("error").await["code"], "forbidden");
    op.send(json!({"type": "signal", "to": kiosk_id, "data": {"kind": "offer", "sdp": "v=0"}}))
        .await;
    let offer = kiosk.recv_type("signal").await;
    assert_eq!(
        (
            offer["from"].clone(),
            offer["role"].as_str(),
            offer["data"].clone()
        ),
        (
            op_id.clone(),
            Some("operator"),
            json!({"kind": "offer", "sdp": "v=0"})
        )
    );
    kiosk
        .send(json!({"type": "signal", "to": op_id, "data": {"kind": "answer", "sdp": "v=0"}}))
        .await;
    let answer = op.recv_type("signal").await;
    assert_eq!(
        (answer["from"].clone(), answer["role"].as_str()),
        (kiosk_id.clone(), Some("kiosk"))
    );
    kiosk
        .send(json!({"type": "signal", "to": other_id, "data": {"kind": "offer"}}))
        .await;
    assert_eq!(kiosk.recv_type("error").await["code"], "forbidden");
    // Operators signal kiosks only.
    other_op
        .send(json!({"type": "signal", "to": op_id, "data": {"kind": "offer"}}))
        .await;
    assert_eq!(other_op.recv_type("error").await["code"], "forbidden");
    op.send(json!({"type": "signal", "to": 9999, "data": {"kind": "offer"}}))
        .await;
    assert_eq!(op.recv_type("error").await["code"], "unknown-client");
    // A console that goes away without hanging up: the kiosk is told on its behalf.
    drop(op);
    let hangup = kiosk.recv_type("signal").await;
    assert_eq!(
        (hangup["from"].clone(), hangup["data"]["kind"].as_str()),
        (op_id, Some("hangup"))
    );
    server.stop().await;
}

#[tokio::test]
async fn a_console_joining_later_gets_the_recent_history() {
    let b = tour();
    let server = TestServer::start(b.path()).await;
    server.trigger("WELCOME", json!({"ref": "earlier"})).await;
    let mut dm = dm(&server).await;
    dm.send(json!({"type": "propose", "label": "GOODBYE"}))
        .await;
    dm.recv_type("proposed").await;
    let mut late = server.operator().await;
    let act = late.event("act.triggered").await;
    assert_eq!(
        (act["ref"].as_str(), act["text"].as_str()),
        (Some("earlier"), Some("Hello!"))
    );
    assert_eq!(late.event("proposal.made").await["label"], "GOODBYE");
    server.stop().await;
}

#[tokio::test]
async fn signalling_carries_only_call_data() {
    let b = tour();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    let to = kiosk.welcome["client"].clone();
    for data in [json!({}), json!({"kind": "shout"}), json!("offer")] {
        op.send(json!({"type": "signal", "to": to, "data": data}))
            .await;
        assert_eq!(op.recv_type("error").await["code"], "bad-signal", "{data}");
    }
    server.stop().await;
}

#[tokio::test]
async fn a_leaving_dialog_managers_proposals_are_withdrawn() {
    let b = tour();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut dm = dm(&server).await;
    dm.send(json!({"type": "propose", "label": "GOODBYE"}))
        .await;
    let id = dm.recv_type("proposed").await["proposal"].clone();
    drop(dm);
    let withdrawn = op.event("proposal.withdrawn").await;
    assert_eq!(
        (withdrawn["proposal"].clone(), withdrawn["label"].as_str()),
        (id.clone(), Some("GOODBYE"))
    );
    op.send(json!({"type": "accept", "proposal": id})).await;
    assert_eq!(op.recv_type("error").await["code"], "unknown-proposal");
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["proposals"], json!([]));
    let corpus = server.stop().await;
    assert!(!corpus.iter().any(|e| e["type"] == "act.triggered"));
}
