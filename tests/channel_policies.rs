//! Who speaks when, on a real server with real websocket clients: a kiosk cannot interrupt an
//! operator's speech, a visitor's second tap does not queue the same act again, leaving a page
//! ends the speech it started, a visitor's stop ends only visitors' speech, and a flood of
//! triggers leaves bounded queues (`tests/flood.rs`, a binary of its own).

use crate::common;

use common::channels::bundle;
use common::{TempBundle, TestServer, WsClient};
use serde_json::{Value, json};

async fn kiosk(server: &TestServer) -> WsClient {
    server
        .client(json!({"type": "hello", "role": "kiosk", "name": "kiosk"}))
        .await
}

/// A server on the test bundle, with an operator and a kiosk connected (keep the bundle).
async fn start() -> (TempBundle, TestServer, WsClient, WsClient) {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let op = server.operator().await;
    let visitor = kiosk(&server).await;
    (b, server, op, visitor)
}

type Pred<'a> = &'a dyn Fn(&Value) -> bool;

/// Frames until every predicate has matched one of them (in any order), all kept.
async fn until_all(client: &mut WsClient, preds: &[Pred<'_>]) -> Vec<Value> {
    let mut seen: Vec<Value> = Vec::new();
    while !preds.iter().all(|p| seen.iter().any(p)) {
        seen.push(client.recv().await);
    }
    seen
}

/// The frame in `frames` that `pred` matches.
fn find<'f>(frames: &'f [Value], pred: Pred<'_>) -> &'f Value {
    frames
        .iter()
        .find(|f| pred(f))
        .unwrap_or_else(|| panic!("not in {frames:#?}"))
}

/// An event frame whose event has `kind` and the trigger reference `reference` (its SAY).
fn event(kind: &'static str, reference: &'static str) -> impl Fn(&Value) -> bool {
    move |f| f["type"] == "event" && f["event"]["type"] == kind && f["event"]["ref"] == reference
}

/// The outcome event of the SAY triggered with `reference`.
fn say_ended(reference: &'static str) -> impl Fn(&Value) -> bool {
    move |f| {
        let e = &f["event"];
        f["type"] == "event"
            && e["ref"] == reference
            && e["verb"] == "SAY"
            && ["command.done", "command.failed", "command.cancelled"]
                .contains(&e["type"].as_str().unwrap_or(""))
    }
}

fn frame(kind: &'static str, reference: &'static str) -> impl Fn(&Value) -> bool {
    move |f| f["type"] == kind && f["ref"] == reference
}

async fn trigger(client: &mut WsClient, label: &str, reference: &str, interrupt: bool) {
    let frame =
        json!({"type": "trigger", "label": label, "ref": reference, "interrupt": interrupt});
    client.send(frame).await;
}

#[tokio::test]
async fn a_kiosk_interrupt_cannot_cancel_an_operators_say() {
    let (_b, server, mut op, mut visitor) = start().await;
    trigger(&mut op, "LONG", "op", false).await;
    until_all(&mut op, &[&event("command.started", "op")]).await;
    trigger(&mut visitor, "HELLO", "v", true).await;
    until_all(&mut visitor, &[&frame("triggered", "v")]).await;
    // The visitor's SAY waits behind the operator's; a stop then ends both. Had the interrupt
    // cancelled the operator's SAY, its outcome would carry the interrupt's reason.
    until_all(&mut op, &[&event("command.sent", "v")]).await;
    op.send(json!({"type": "stop"})).await;
    let seen = until_all(&mut op, &[&say_ended("op"), &say_ended("v")]).await;
    for reference in ["op", "v"] {
        let outcome = &find(&seen, &say_ended(reference))["event"];
        assert_eq!(outcome["type"], "command.cancelled", "{outcome}");
        assert_eq!(outcome["reason"], "stop request", "{outcome}");
    }
    let told = until_all(&mut visitor, &[&frame("outcome", "v")]).await;
    let told = find(&told, &frame("outcome", "v"));
    assert_eq!(
        (&told["verb"], &told["outcome"]),
        (&json!("SAY"), &json!("cancelled"))
    );
    assert_eq!(told["reason"], "stop request");
    server.stop().await;
}

#[tokio::test]
async fn a_second_tap_on_an_act_already_speaking_is_answered_not_queued() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut visitor = kiosk(&server).await;
    trigger(&mut visitor, "READ", "1", false).await;
    until_all(&mut visitor, &[&frame("triggered", "1")]).await;
    trigger(&mut visitor, "READ", "2", false).await;
    let answer = visitor.recv_where(|f| f["ref"] == "2").await;
    assert_eq!(answer["type"], "error", "{answer}");
    assert_eq!(answer["code"], "already-speaking", "{answer}");
    let corpus = server.stop().await;
    let says = corpus
        .iter()
        .filter(|e| e["type"] == "command.sent" && e["verb"] == "SAY")
        .count();
    assert_eq!(says, 1, "READ was queued once");
    assert!(
        corpus
            .iter()
            .any(|e| e["type"] == "trigger.refused" && e["code"] == "already-speaking")
    );
}

#[tokio::test]
async fn leaving_the_page_ends_the_speech_it_started_but_not_the_operators() {
    let (_b, server, mut op, mut visitor) = start().await;
    trigger(&mut visitor, "READ", "r", false).await;
    until_all(&mut op, &[&event("command.started", "r")]).await;
    visitor
        .send(json!({"type": "page", "page": "map.html"}))
        .await;
    let seen = until_all(&mut op, &[&say_ended("r")]).await;
    let outcome = &find(&seen, &say_ended("r"))["event"];
    assert_eq!(outcome["type"], "command.cancelled", "{outcome}");
    assert_eq!(outcome["reason"], "the visitor left the page for map.html");
    let told = until_all(&mut visitor, &[&frame("outcome", "r")]).await;
    let told = find(&told, &frame("outcome", "r"));
    assert_eq!(told["reason"], outcome["reason"]);
    assert_eq!(told["ended_by_visitor"], true, "{told}");
    // Speech the visitor left waiting behind the operator's ends too; the operator's goes on.
    trigger(&mut op, "LONG", "op", false).await;
    until_all(&mut op, &[&event("command.started", "op")]).await;
    trigger(&mut visitor, "HELLO", "h", false).await;
    until_all(&mut op, &[&event("command.sent", "h")]).await;
    visitor
        .send(json!({"type": "page", "page": "index.html"}))
        .await;
    let seen = until_all(&mut op, &[&say_ended("h")]).await;
    let outcome = &find(&seen, &say_ended("h"))["event"];
    assert_eq!(
        outcome["reason"],
        "the visitor left the page for index.html"
    );
    assert!(
        !seen.iter().any(say_ended("op")),
        "the operator's SAY went on"
    );
    op.send(json!({"type": "stop"})).await;
    let seen = until_all(&mut op, &[&say_ended("op")]).await;
    assert_eq!(
        find(&seen, &say_ended("op"))["event"]["reason"],
        "stop request"
    );
    server.stop().await;
}

#[tokio::test]
async fn a_visitors_act_that_shows_another_page_ends_their_earlier_speech() {
    let (_b, server, mut op, mut visitor) = start().await;
    trigger(&mut visitor, "READ", "r", false).await;
    until_all(&mut op, &[&event("command.started", "r")]).await;
    trigger(&mut visitor, "MAP", "m", false).await;
    let seen = until_all(&mut op, &[&say_ended("r")]).await;
    let outcome = &find(&seen, &say_ended("r"))["event"];
    assert_eq!(outcome["type"], "command.cancelled", "{outcome}");
    assert_eq!(outcome["reason"], "the visitor moved on (act MAP)");
    let told = until_all(&mut visitor, &[&frame("outcome", "r")]).await;
    assert_eq!(
        find(&told, &frame("outcome", "r"))["ended_by_visitor"],
        true
    );
    server.stop().await;
}

#[tokio::test]
async fn a_visitors_stop_ends_visitors_speech_only_and_kiosks_see_who_speaks() {
    let (_b, server, mut op, mut visitor) = start().await;
    trigger(&mut visitor, "READ", "r", false).await;
    let speaking = |f: &Value| f["type"] == "speaking" && f["speaking"] == true;
    let seen = until_all(&mut visitor, &[&frame("triggered", "r"), &speaking]).await;
    let now = find(&seen, &speaking);
    assert_eq!(
        (&now["source"], &now["stoppable"]),
        (&json!("kiosk"), &json!(true)),
        "{now}"
    );
    visitor.send(json!({"type": "stop", "ref": "s"})).await;
    let quiet = |f: &Value| f["type"] == "speaking" && f["speaking"] == false;
    until_all(&mut visitor, &[&frame("stopped", "s"), &quiet]).await;
    let seen = until_all(&mut op, &[&say_ended("r")]).await;
    let outcome = &find(&seen, &say_ended("r"))["event"];
    assert_eq!(outcome["type"], "command.cancelled", "{outcome}");
    trigger(&mut op, "LONG", "op", false).await;
    let seen = until_all(&mut visitor, &[&speaking]).await;
    let now = find(&seen, &speaking);
    assert_eq!(
        (&now["source"], &now["stoppable"]),
        (&json!("operator"), &json!(false)),
        "{now}"
    );
    // A touchscreen that connects while the operator speaks is told so at once.
    let mut late = kiosk(&server).await;
    let first = late.recv().await;
    assert_eq!(
        (&first["type"], &first["source"]),
        (&json!("speaking"), &json!("operator")),
        "{first}"
    );
    visitor.send(json!({"type": "stop", "ref": "t"})).await;
    until_all(&mut visitor, &[&frame("stopped", "t")]).await;
    op.send(json!({"type": "stop"})).await;
    let seen = until_all(&mut op, &[&say_ended("op")]).await;
    let outcome = &find(&seen, &say_ended("op"))["event"];
    assert_eq!(
        outcome["reason"], "stop request",
        "the visitor's stop left it: {outcome}"
    );
    server.stop().await;
}
