//! A `PROJECT` of a video is done when a projector reports the film's end, so `WAIT` sequences
//! speech after it; a failed answer fails the `WAIT`; with no projector connected it is done at
//! once; a later `HIGHLIGHT` or the projector leaving ends a film still playing.

mod common;

use common::{TempBundle, TestServer, WsClient};
use serde_json::{Value, json};

const ACTS: &str = "\
- Label: FILM
  Cmds: [PROJECT clip.webm, WAIT, SAY After the film]
- Label: DARK
  Cmds: [HIGHLIGHT]
";

fn bundle() -> TempBundle {
    TempBundle::new(ACTS)
        .with_file("docent.yaml", "speech: {adapter: log}\n")
        .with_file("media/clip.webm", "not really a video")
}

async fn projector(server: &TestServer) -> WsClient {
    server
        .client(json!({"type": "hello", "role": "projector"}))
        .await
}

fn is(kind: &'static str, command: u64) -> impl Fn(&Value) -> bool {
    move |e| e["type"] == kind && e["command"] == command
}

fn position(events: &[Value], pred: impl Fn(&Value) -> bool) -> Option<usize> {
    events.iter().position(pred)
}

/// The ids of the PROJECT, WAIT and SAY of a FILM trigger.
async fn film(server: &TestServer) -> (u64, u64, u64) {
    let t = server.trigger("FILM", json!({})).await;
    let ids: Vec<u64> = (t["commands"].as_array().expect("commands").iter())
        .map(|c| c["id"].as_u64().expect("id"))
        .collect();
    let [project, wait, say] = ids[..] else {
        panic!("{t}")
    };
    (project, wait, say)
}

#[tokio::test]
async fn the_say_after_a_wait_follows_the_projectors_done() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut proj = projector(&server).await;
    let (project, wait, say) = film(&server).await;

    let command = proj.recv_type("command").await;
    assert_eq!(command["verb"], "PROJECT", "{command}");
    assert_eq!(command["arg"], "clip.webm", "{command}");
    assert_eq!(
        command["args"],
        serde_json::json!({"file": "clip.webm", "kind": "video"}),
        "{command}"
    );
    assert_eq!(command["id"], project, "{command}");
    proj.send(json!({"type": "done", "id": project})).await;

    let events = op.events_until(is("command.sent", say)).await;
    let done = position(&events, is("command.done", project)).expect("PROJECT done");
    let wait_done = position(&events, is("command.done", wait)).expect("WAIT done");
    assert!(position(&events, is("command.started", project)).expect("started") < done);
    assert!(done < wait_done, "{events:#?}");
    // A late answer for a settled film is ignored, not an error.
    proj.send(json!({"type": "done", "id": project})).await;
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["display"]["projector"], "clip.webm", "{state}");
}

#[tokio::test]
async fn a_failed_answer_fails_the_wait() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut proj = projector(&server).await;
    let (project, wait, say) = film(&server).await;
    proj.recv_type("command").await;
    proj.send(json!({"type": "failed", "id": project, "reason": "media error 4"}))
        .await;

    let failed = op.event_where(is("command.failed", project)).await;
    assert_eq!(failed["reason"], "media error 4", "{failed}");
    let events = op.events_until(is("command.failed", wait)).await;
    assert!(
        position(&events, is("command.sent", say)).is_none(),
        "{events:#?}"
    );
}

#[tokio::test]
async fn with_no_projector_a_film_is_done_at_once() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let (project, wait, say) = film(&server).await;
    let events = op.events_until(is("command.sent", say)).await;
    assert!(
        position(&events, is("command.done", project)).expect("done")
            < position(&events, is("command.done", wait)).expect("WAIT done")
    );
}

#[tokio::test]
async fn a_highlight_or_the_projector_leaving_ends_a_film() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut proj = projector(&server).await;

    let (project, _, say) = film(&server).await;
    proj.recv_type("command").await;
    server.trigger("DARK", json!({})).await;
    let cancelled = op.event_where(is("command.cancelled", project)).await;
    // The projector channel's policy (replace) cuts the film short.
    assert_eq!(
        cancelled["reason"],
        "replaced by act DARK from the HTTP API"
    );
    op.event_where(is("command.sent", say)).await;

    let (project, wait, say) = film(&server).await;
    proj.recv_where(|f| f["type"] == "command" && f["id"] == project)
        .await;
    drop(proj);
    let failed = op.event_where(is("command.failed", project)).await;
    assert_eq!(failed["reason"], "the projector disconnected", "{failed}");
    let events = op.events_until(is("command.failed", wait)).await;
    assert!(
        position(&events, is("command.sent", say)).is_none(),
        "{events:#?}"
    );
}
