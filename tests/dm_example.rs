//! The example dialog manager (`examples/dialog-manager`), run as a site runs it (its
//! `run.sh`, a real Python process with the `websockets` package) against a real server on
//! 127.0.0.1:0: it greets a person the robot notices close by, moves the tour on when a film
//! ends, offers help to a visitor idle on a page (autonomous mode), proposes instead of
//! triggering in mixed-initiative mode, and stops at once, saying why, on a wrong credential
//! or an act the bundle lacks.

use crate::common;

use std::process::{Child, Command, Stdio};

use common::{DM_TOKEN, TempBundle, TestServer, WsClient, repo};
use serde_json::{Value, json};

const ACTS: &str = "\
- Label: HELLO
  Text: [Hello there!]
- Label: FILM
  Cmds: [PROJECT clip.webm]
- Label: NEXT
  Text: [Let us move on.]
- Label: OTHER_PAGE
  Cmds: [DISPLAY_PAGE other.html]
- Label: HELP
  Text: [Can I help you?]
";

fn bundle() -> TempBundle {
    TempBundle::new(ACTS)
        .with_file(
            "docent.yaml",
            "speech: {adapter: log}\ncorpus: {session_start_events: [person.near]}\n",
        )
        .with_file("media/clip.webm", "not really a video")
        .with_file(
            "pages/index.html",
            "<!doctype html><title>Home</title><button data-act=OTHER_PAGE>More</button>",
        )
        .with_file("pages/other.html", "<!doctype html><title>Other</title>")
}

/// The dialog manager's process, killed when the test ends.
struct Dm(Child);

impl Drop for Dm {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn dm_command(server: &TestServer, extra: &[&str]) -> Command {
    let mut command = Command::new(repo().join("examples/dialog-manager/run.sh"));
    let url = server.url("/ws").replace("http://", "ws://");
    command.args(["--url", &url, "--greet-act", "HELLO", "--help-act", "HELP"]);
    command.args(["--after-video", "FILM=NEXT", "--idle", "1"]);
    command.args(extra);
    command
}

async fn start_dm(server: &TestServer, op: &mut WsClient, mode: &str) -> Dm {
    let mut command = dm_command(server, &["--token", DM_TOKEN, "--mode", mode]);
    let child = command.stdout(Stdio::null()).spawn().expect("run.sh");
    let dm = Dm(child);
    op.event_where(|e| e["type"] == "client.connected" && e["role"] == "dm")
        .await;
    dm
}

async fn sensor(server: &TestServer) -> WsClient {
    let hello = json!({"type": "hello", "role": "adapter", "name": "tracker",
        "robot_events": ["person.near"]});
    server.client(hello).await
}

fn by_dm(label: &'static str) -> impl Fn(&Value) -> bool {
    move |e| e["type"] == "act.triggered" && e["label"] == label && e["source"] == "dm"
}

#[tokio::test]
async fn autonomous_it_greets_moves_the_tour_on_and_offers_help() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let _dm = start_dm(&server, &mut op, "autonomous").await;
    let mut tracker = sensor(&server).await;
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    let mut projector = server
        .client(json!({"type": "hello", "role": "projector"}))
        .await;
    // Too far: nothing. Close: the session starts and the dialog manager greets, once.
    let far = json!({"type": "robot", "event": "person.near", "data": {"distance": 4.0}});
    tracker.send(far).await;
    let near = json!({"type": "robot", "event": "person.near", "data": {"distance": 0.8}});
    tracker.send(near.clone()).await;
    let seen = op.events_until(by_dm("HELLO")).await;
    let robots = seen.iter().filter(|e| e["type"] == "robot").count();
    assert_eq!(robots, 2, "greeted after the close one: {seen:?}");
    // The film ends: the tour moves on.
    op.send(json!({"type": "trigger", "label": "FILM"})).await;
    let command = projector.recv_type("command").await;
    assert_eq!(command["verb"], "PROJECT");
    projector
        .send(json!({"type": "started", "id": command["id"]}))
        .await;
    projector
        .send(json!({"type": "done", "id": command["id"]}))
        .await;
    let seen = op.events_until(by_dm("NEXT")).await;
    assert!(
        seen.iter()
            .any(|e| e["type"] == "command.done" && e["verb"] == "PROJECT"),
        "{seen:?}"
    );
    // A page other than home, then a second without anything: help is offered.
    op.send(json!({"type": "trigger", "label": "OTHER_PAGE"}))
        .await;
    let command = kiosk.recv_type("command").await;
    assert_eq!(command["args"]["page"], "other.html", "{command}");
    kiosk
        .send(json!({"type": "done", "id": command["id"]}))
        .await;
    let seen = op.events_until(by_dm("HELP")).await;
    assert!(seen.iter().all(|e| e["type"] != "touch"), "{seen:?}");
    // A second close person in the same session is not greeted again.
    tracker.send(near).await;
    let seen = op
        .events_until(|e| e["type"] == "robot" && e["data"]["distance"] == 0.8)
        .await;
    assert!(!seen.iter().any(by_dm("HELLO")), "{seen:?}");
    let all = server.stop().await;
    let by: Vec<&str> = (all.iter())
        .filter(|e| e["type"] == "act.triggered" && e["source"] == "dm")
        .map(|e| e["label"].as_str().unwrap())
        .collect();
    assert_eq!(by, ["HELLO", "NEXT", "HELP"], "in the corpus too");
}

#[tokio::test]
async fn in_mixed_initiative_it_proposes_to_the_operator() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let _dm = start_dm(&server, &mut op, "mixed").await;
    let mut tracker = sensor(&server).await;
    let near = json!({"type": "robot", "event": "person.near", "data": {"distance": 1.2}});
    tracker.send(near).await;
    let proposal = op.event("proposal.made").await;
    assert_eq!(proposal["label"], "HELLO");
    assert_eq!(proposal["reason"], "a person came within 1.2 m");
    op.send(json!({"type": "accept", "proposal": proposal["proposal"]}))
        .await;
    let triggered = op.event("act.triggered").await;
    assert_eq!(
        (triggered["label"].as_str(), triggered["source"].as_str()),
        (Some("HELLO"), Some("operator"))
    );
    server.stop().await;
}

#[tokio::test]
async fn a_wrong_credential_or_a_missing_act_stops_it_saying_why() {
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    // Run beside the server (a blocking wait would stall the server it asks).
    let run = async |extra: &[&str]| {
        let command = tokio::process::Command::from(dm_command(&server, extra));
        let out = { command }.output().await.expect("run.sh");
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    let (code, said) = run(&["--token", "not-the-dialog-manager-credential"]).await;
    assert_eq!(code, Some(1), "{said}");
    assert!(said.contains("dm: Docent refused"), "{said}");
    let (code, said) = run(&["--token", DM_TOKEN, "--help-act", "HLEP"]).await;
    assert_eq!(code, Some(1), "{said}");
    assert!(
        said.contains("the bundle has no act HLEP; give existing labels"),
        "{said}"
    );
    server.stop().await;
}
