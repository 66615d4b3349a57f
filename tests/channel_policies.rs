//! Who speaks when, on a real server with real websocket clients: a kiosk cannot interrupt an
//! operator's speech, a visitor's second tap does not queue the same act again, leaving a page
//! ends the speech it started, a visitor's stop ends only visitors' speech, and a flood of
//! triggers leaves bounded queues with every excess command answered, to its sender and in the
//! corpus, with a reason.

mod common;

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

use common::{TempBundle, TestServer, WsClient};
use serde_json::{Value, json};
use tokio_util::sync::CancellationToken;

const LONG_TEXT: &str = "This sentence goes on and on, far longer than any test would wait for it, one two three four five six seven eight nine ten eleven twelve thirteen fourteen fifteen sixteen seventeen eighteen nineteen twenty twenty-one twenty-two twenty-three twenty-four twenty-five twenty-six twenty-seven twenty-eight twenty-nine thirty and more words until the end.";

fn bundle() -> TempBundle {
    let acts = format!(
        "- Label: LONG\n  Text: [\"{LONG_TEXT}\"]\n- Label: READ\n  Text: [\"{LONG_TEXT} Read.\"]\n\
         - Label: HELLO\n  Text: [Hello]\n- Label: MAP\n  Cmds: [DISPLAY_PAGE map.html]\n"
    );
    TempBundle::new(&acts)
        .with_file("docent.yaml", "speech: {adapter: log, rate: 120}\n")
        .with_file(
            "pages/index.html",
            "<!doctype html><title>home</title><button data-act=\"READ\">Read</button>\
             <button data-act=\"HELLO\">Hi</button><a href=\"map.html\">Map</a>\
             <button data-act=\"MAP\">Map</button>",
        )
        .with_file("pages/map.html", "<!doctype html><title>map</title>")
}

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

/// Resident memory of this process, in kB (the server runs in it).
fn rss_kb() -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").expect("proc status");
    let line = status
        .lines()
        .find(|l| l.starts_with("VmRSS:"))
        .expect("VmRSS");
    line.split_whitespace()
        .nth(1)
        .and_then(|n| n.parse().ok())
        .expect("a number")
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_flood_of_operators_leaves_bounded_queues_and_every_excess_say_answered() {
    const CLIENTS: usize = 40;
    const EACH: usize = 250;
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let before = rss_kb();
    let total = CLIENTS * EACH;
    // One SAY speaks, two wait (the default queue_limit); every other one is refused at once.
    let refused = total - 3;
    // Outcomes are notices, not answers: they may come after the last answer (within 2 ms),
    // so every client reads until all of them have arrived, counted across clients.
    let told_so_far = Arc::new(AtomicUsize::new(0));
    let all_told = CancellationToken::new();
    let mut tasks = Vec::new();
    for n in 0..CLIENTS {
        let hello =
            json!({"type": "hello", "role": "operator", "name": format!("op{n}"), "events": false});
        let mut client = server.client(hello).await;
        let (told_so_far, all_told) = (Arc::clone(&told_so_far), all_told.clone());
        tasks.push(tokio::spawn(async move {
            for i in 0..EACH {
                client
                    .send(json!({"type": "trigger", "label": "LONG", "ref": i.to_string()}))
                    .await;
            }
            let (mut answered, mut cancelled) = (0, Vec::new());
            while answered < EACH || !all_told.is_cancelled() {
                let frame = tokio::select! {
                    frame = client.recv() => frame,
                    () = all_told.cancelled(), if answered == EACH => break,
                };
                match frame["type"].as_str() {
                    Some("triggered") => answered += 1,
                    Some("outcome") => {
                        cancelled.push(frame);
                        if told_so_far.fetch_add(1, Ordering::SeqCst) + 1 == refused {
                            all_told.cancel();
                        }
                    }
                    _ => {}
                }
            }
            (client, cancelled)
        }));
    }
    let mut told = Vec::new();
    let mut clients = Vec::new();
    for task in tasks {
        let (client, cancelled) = task.await.expect("client task");
        told.extend(cancelled);
        clients.push(client);
    }
    let grown_kb = rss_kb().saturating_sub(before);
    let (_, state) = server.get("/api/state").await;
    let queued = state["queues"]["log"]["queued"].as_u64().unwrap_or(0);
    assert!(
        queued <= 1,
        "the speech adapter holds one command at a time: {state}"
    );
    let speech = &state["channels"]["speech"];
    assert_eq!(
        speech["running"]["what"],
        format!("SAY {LONG_TEXT}"),
        "{speech}"
    );
    assert_eq!(speech["running"]["source"], "operator", "{speech}");
    assert_eq!(
        speech["waiting"].as_array().map(Vec::len),
        Some(2),
        "{speech}"
    );
    assert_eq!(
        told.len(),
        refused,
        "every excess SAY is answered to its sender"
    );
    for frame in &told {
        assert_eq!(frame["outcome"], "cancelled", "{frame}");
        assert_eq!(frame["ended_by_visitor"], false, "{frame}");
        let reason = frame["reason"].as_str().unwrap_or_default();
        assert!(
            reason.contains("speech queue was full (2 waiting)"),
            "{reason}"
        );
    }
    eprintln!(
        "flood: {total} SAYs from {CLIENTS} clients, {} refused, RSS grew {grown_kb} kB",
        told.len()
    );
    assert!(
        grown_kb < 64 * 1024,
        "memory stays bounded: grew {grown_kb} kB"
    );
    drop(clients);
    let corpus = server.stop().await;
    let refused = corpus
        .iter()
        .filter(|e| e["type"] == "command.cancelled")
        .filter(|e| {
            e["reason"]
                .as_str()
                .unwrap_or_default()
                .contains("queue was full")
        })
        .count();
    assert_eq!(refused, total - 3, "every refusal is in the corpus");
}
