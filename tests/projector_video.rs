//! `PROJECT` and `HIGHLIGHT` are done only when a projector reports them: a picture once
//! painted, a film at its end (so `WAIT` sequences speech after it). A failed report fails
//! the `WAIT`; with no projector connected they fail at once; a projector leaving fails what it
//! owed; a report missing after `adapters: timeout` fails it (paused clock). The display state
//! follows the reports: a film that ended is black (or held), never replayed.

use crate::common;

use common::{TempBundle, TestServer, WsClient};
use serde_json::{Value, json};

const ACTS: &str = "\
- Label: FILM
  Cmds: [PROJECT clip.webm, WAIT, SAY After the film]
- Label: PICTURE
  Cmds: [PROJECT still.png, WAIT, SAY After the picture]
- Label: DARK
  Cmds: [HIGHLIGHT]
";

fn bundle_with(config: &str) -> TempBundle {
    TempBundle::new(ACTS)
        .with_file("docent.yaml", config)
        .with_file("media/clip.webm", "not really a video")
        .with_file("media/still.png", "not really a picture")
}

fn bundle() -> TempBundle {
    bundle_with("speech: {adapter: log}\n")
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

/// Triggers `label` from the operator's websocket; the ids of its three commands.
async fn act(op: &mut WsClient, label: &str) -> (u64, u64, u64) {
    op.send(json!({"type": "trigger", "label": label, "ref": label}))
        .await;
    let t = op.recv_type("triggered").await;
    let ids: Vec<u64> = (t["commands"].as_array().expect("commands").iter())
        .map(|c| c["id"].as_u64().expect("id"))
        .collect();
    let [project, wait, say] = ids[..] else {
        panic!("{t}")
    };
    (project, wait, say)
}

async fn projector_state(server: &TestServer) -> Value {
    let (_, state) = server.get("/api/state").await;
    state["display"].clone()
}

#[tokio::test]
async fn the_say_after_a_wait_follows_the_projectors_done_and_the_screen_goes_black() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut proj = projector(&server).await;
    let (project, wait, say) = act(&mut op, "FILM").await;

    let command = proj.recv_type("command").await;
    assert_eq!(command["verb"], "PROJECT", "{command}");
    assert_eq!(
        command["args"],
        json!({"file": "clip.webm", "kind": "video"}),
        "{command}"
    );
    assert_eq!(command["id"], project, "{command}");
    assert_eq!(projector_state(&server).await["projector_state"], "loading");
    proj.send(json!({"type": "started", "id": project})).await;
    let playing = op
        .event_where(|e| e["type"] == "display.changed" && e["projector_state"] == "playing")
        .await;
    assert_eq!(playing["projector"], "clip.webm", "{playing}");
    proj.send(json!({"type": "done", "id": project})).await;

    let events = op.events_until(is("command.sent", say)).await;
    let done = position(&events, is("command.done", project)).expect("PROJECT done");
    let wait_done = position(&events, is("command.done", wait)).expect("WAIT done");
    assert!(done < wait_done, "{events:#?}");
    let black = position(&events, |e| {
        e["type"] == "display.changed" && e["projector_state"] == "black"
    })
    .expect("black after the film");
    assert_eq!(events[black]["projector"], Value::Null, "{events:#?}");
    // A late answer for a settled film is ignored, not an error.
    proj.send(json!({"type": "done", "id": project})).await;
    let display = projector_state(&server).await;
    assert_eq!(display["projector"], Value::Null, "{display}");
    assert_eq!(display["projector_state"], "black", "{display}");

    // A projector connecting now is not sent the finished film.
    let late = projector(&server).await;
    let shown = &late.welcome["state"]["display"];
    assert_eq!(shown["projector"], Value::Null, "{shown}");
}

#[tokio::test]
async fn a_film_the_projector_holds_stays_named_as_held() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut proj = projector(&server).await;
    let (project, _, say) = act(&mut op, "FILM").await;
    proj.recv_type("command").await;
    proj.send(json!({"type": "started", "id": project})).await;
    proj.send(json!({"type": "done", "id": project, "held": true}))
        .await;
    op.event_where(is("command.sent", say)).await;
    let display = projector_state(&server).await;
    assert_eq!(display["projector"], "clip.webm", "{display}");
    assert_eq!(display["projector_state"], "held", "{display}");
}

#[tokio::test]
async fn a_picture_is_done_only_after_the_projector_reports_it_painted() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut proj = projector(&server).await;
    let (project, wait, say) = act(&mut op, "PICTURE").await;
    let command = proj.recv_type("command").await;
    assert_eq!(command["args"]["kind"], "image", "{command}");
    // Before the report the picture is only on its way, and the WAIT waits.
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["display"]["projector_state"], "loading", "{state}");
    assert_eq!(state["queues"]["display"]["queued"], 1, "{state}");

    proj.send(json!({"type": "done", "id": project})).await;
    let events = op.events_until(is("command.sent", say)).await;
    let shown = position(&events, |e| {
        e["type"] == "display.changed" && e["projector_state"] == "shown"
    })
    .expect("shown");
    let done = position(&events, is("command.done", project)).expect("done");
    assert!(shown < done, "{events:#?}");
    assert!(done < position(&events, is("command.done", wait)).expect("WAIT done"));
}

#[tokio::test]
async fn a_failed_answer_fails_the_wait_and_leaves_the_projector_black() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut proj = projector(&server).await;
    let (project, wait, say) = act(&mut op, "FILM").await;
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
    assert_eq!(projector_state(&server).await["projector"], Value::Null);
}

#[tokio::test]
async fn with_no_projector_a_projection_fails_at_once_and_the_wait_reports_it() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    for label in ["FILM", "PICTURE"] {
        let (project, wait, say) = act(&mut op, label).await;
        let events = op.events_until(is("command.failed", wait)).await;
        let failed = &events[position(&events, is("command.failed", project)).expect("failed")];
        assert_eq!(failed["reason"], "no projector connected", "{failed}");
        assert!(position(&events, is("command.started", project)).is_none());
        assert!(position(&events, is("command.sent", say)).is_none());
        let display = projector_state(&server).await;
        assert_eq!(display["projector"], Value::Null, "{display}");
    }
    op.send(json!({"type": "trigger", "label": "DARK"})).await;
    let failed = op
        .event_where(|e| e["type"] == "command.failed" && e["verb"] == "HIGHLIGHT")
        .await;
    assert_eq!(failed["reason"], "no projector connected", "{failed}");
}

#[tokio::test]
async fn a_highlight_or_the_projector_leaving_ends_a_film_or_picture() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut proj = projector(&server).await;

    let (project, _, _) = act(&mut op, "FILM").await;
    proj.recv_type("command").await;
    op.send(json!({"type": "trigger", "label": "DARK"})).await;
    let cancelled = op.event_where(is("command.cancelled", project)).await;
    // The projector channel's policy (replace) cuts the film short.
    assert_eq!(
        cancelled["reason"],
        "replaced by act DARK from the operator"
    );

    for label in ["FILM", "PICTURE"] {
        let (project, wait, say) = act(&mut op, label).await;
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
        assert_eq!(projector_state(&server).await["projector"], Value::Null);
        proj = projector(&server).await;
    }
}

#[tokio::test(start_paused = true)]
async fn a_projector_that_never_reports_fails_the_command_after_the_timeout() {
    let b = bundle_with("speech: {adapter: log}\nadapters: {timeout: 5s}\n");
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut proj = projector(&server).await;
    for label in ["PICTURE", "FILM"] {
        // Measured from before the trigger: the server's clock starts when it sends, and with
        // the clock paused, time may move on while the command is on its way.
        let asked = tokio::time::Instant::now();
        let (project, wait, _) = act(&mut op, label).await;
        proj.recv_type("command").await;
        let failed = op.event_where(is("command.failed", project)).await;
        let waited = asked.elapsed();
        assert!(
            waited >= std::time::Duration::from_secs(5),
            "failed after {waited:?}"
        );
        let what = if label == "FILM" {
            "the film playing"
        } else {
            "it shown"
        };
        assert_eq!(
            failed["reason"],
            format!("the projector did not report {what} within 5s"),
            "{failed}"
        );
        op.event_where(is("command.failed", wait)).await;
        // What the projector would show late must not contradict the log: it is told to go
        // black.
        let cancel = proj.recv_type("cancel").await;
        assert_eq!(cancel["reason"], failed["reason"], "{cancel}");
        assert_eq!(projector_state(&server).await["projector_state"], "black");
    }
    // A film that reported its start is not timed out: its end may be far off.
    let (project, _, _) = act(&mut op, "FILM").await;
    proj.recv_type("command").await;
    proj.send(json!({"type": "started", "id": project})).await;
    op.event_where(is("command.started", project)).await;
    // Three times the timeout, within the websocket's idle limit (a silent test client is not
    // answering pings).
    tokio::time::sleep(std::time::Duration::from_secs(15)).await;
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["display"]["projector_state"], "playing", "{state}");
    proj.send(json!({"type": "done", "id": project})).await;
    op.event_where(is("command.done", project)).await;
}

#[tokio::test]
async fn a_stop_cancels_a_film_and_tells_the_projector_to_go_black() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut proj = projector(&server).await;
    let (project, _, _) = act(&mut op, "FILM").await;
    proj.recv_type("command").await;
    proj.send(json!({"type": "started", "id": project})).await;
    op.event_where(is("command.started", project)).await;
    op.send(json!({"type": "stop"})).await;
    let cancelled = op.event_where(is("command.cancelled", project)).await;
    assert_eq!(cancelled["reason"], "stop request", "{cancelled}");
    let cancel = proj.recv_type("cancel").await;
    assert_eq!(cancel["reason"], "stop request", "{cancel}");
    let display = projector_state(&server).await;
    assert_eq!(display["projector"], Value::Null, "{display}");
    assert_eq!(display["projector_state"], "black", "{display}");
}
