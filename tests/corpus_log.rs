//! The corpus log: every event with its fields, in sequence, flushed as it happens, so that a
//! crash of Docent loses nothing already logged; a graceful shutdown (SIGTERM) ends it cleanly.

use crate::common;

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};

use common::{TempBundle, TestServer, WsClient, read_corpus};
use serde_json::{Value, json};

const ACTS: &str = r#"
- Label: GREET
  Text: [Hello there, Good day]
  TextGroup: [Hello everyone]
  Cmds:
    - DISPLAY_PAGE index.html
    - SET_WAYPOINT 1 1
    - DRIVE_START
"#;
const CONFIG: &str = "speech: {adapter: log, rate: 600}\ndrive: {speed: 10, pose_rate: 20}\n";

fn fields(e: &Value, names: &[&str]) {
    for name in names {
        assert!(
            e.get(*name).is_some_and(|v| !v.is_null()),
            "{name} missing in {e}"
        );
    }
}

#[tokio::test]
async fn the_log_holds_every_event_with_its_fields_in_sequence() {
    let b = TempBundle::new(ACTS).with_file("docent.yaml", CONFIG);
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    // The touchscreen: DISPLAY_PAGE is done when it reports the page shown.
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    let t = server
        .trigger("GREET", json!({"context": "TextGroup", "ref": "visitor-1"}))
        .await;
    let page = kiosk.recv_type("command").await;
    kiosk.send(json!({"type": "done", "id": page["id"]})).await;
    let mut pending: Vec<Value> = t["commands"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["id"].clone())
        .collect();
    while !pending.is_empty() {
        let done = op.event("command.done").await;
        pending.retain(|id| *id != done["command"]);
    }
    drop(op);
    let log = server.stop().await;

    let seqs: Vec<u64> = log.iter().map(|e| e["seq"].as_u64().unwrap()).collect();
    assert_eq!(
        seqs,
        (1..=log.len() as u64).collect::<Vec<_>>(),
        "no gaps, in order"
    );
    let monos: Vec<u64> = log.iter().map(|e| e["mono_us"].as_u64().unwrap()).collect();
    assert!(monos.windows(2).all(|w| w[0] <= w[1]));
    for e in &log {
        fields(e, &["v", "seq", "time", "mono_us", "type"]);
        assert_eq!(e["v"], 4);
        assert!(e["time"].as_str().unwrap().ends_with('Z'));
    }
    assert_eq!(log[0]["type"], "server.started");
    assert!(log.iter().any(|e| e["type"] == "server.stopping"));
    let act = log.iter().find(|e| e["type"] == "act.triggered").unwrap();
    fields(
        act,
        &[
            "trigger",
            "source",
            "label",
            "context",
            "variant",
            "alternative",
            "text",
            "at",
        ],
    );
    assert_eq!(
        (
            act["label"].as_str(),
            act["source"].as_str(),
            act["ref"].as_str(),
            act["variant"].as_str(),
            act["text"].as_str()
        ),
        (
            Some("GREET"),
            Some("http"),
            Some("visitor-1"),
            Some("TextGroup"),
            Some("Hello everyone")
        )
    );
    assert_eq!(
        (act["alternative"].as_u64(), act["at"].as_str()),
        (Some(0), Some("acts.yaml:2"))
    );
    for kind in ["command.sent", "command.started", "command.done"] {
        let commands: Vec<&Value> = log.iter().filter(|e| e["type"] == kind).collect();
        assert_eq!(commands.len(), 4, "{kind}");
        for c in commands {
            fields(c, &["command", "trigger", "label", "source", "verb", "at"]);
            assert_eq!(c["trigger"], act["trigger"]);
        }
    }
    let sent_say = log
        .iter()
        .find(|e| e["type"] == "command.sent" && e["verb"] == "SAY")
        .unwrap();
    assert_eq!(
        (sent_say["arg"].as_str(), sent_say["adapter"].as_str()),
        (Some("Hello everyone"), Some("log"))
    );
    assert_eq!(
        sent_say["args"],
        serde_json::json!({"text": "Hello everyone", "language": "en"})
    );
    for kind in [
        "display.changed",
        "pose",
        "drive.arrived",
        "client.connected",
        "client.left",
    ] {
        assert!(log.iter().any(|e| e["type"] == kind), "no {kind} event");
    }
}

/// Runs the real `docent` binary on a bundle; returns the child and its address.
fn spawn_docent(bundle: &std::path::Path, corpus: &std::path::Path) -> (Child, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_docent"))
        .args([
            "serve",
            bundle.to_str().unwrap(),
            "--listen",
            "127.0.0.1:0",
            "--corpus",
            corpus.to_str().unwrap(),
        ])
        .env("DOCENT_OPERATOR_TOKEN", common::OPERATOR_TOKEN)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("docent starts");
    let mut lines = BufReader::new(child.stdout.take().unwrap()).lines();
    let addr = (&mut lines)
        .map_while(Result::ok)
        .find_map(|l| {
            l.trim().strip_prefix("websocket:").map(|u| {
                u.trim()
                    .trim_start_matches("ws://")
                    .trim_end_matches("/ws")
                    .to_owned()
            })
        })
        .expect("docent prints its websocket address");
    // Keep reading what it prints so its stdout never breaks.
    std::thread::spawn(move || lines.for_each(drop));
    (child, addr)
}

#[tokio::test]
async fn the_log_survives_a_crash() {
    let b = TempBundle::new(ACTS).with_file("docent.yaml", CONFIG);
    let corpus = tempfile::tempdir().unwrap();
    let (mut child, addr) = spawn_docent(b.path(), corpus.path());
    let mut op = WsClient::operator_at(&addr).await;
    op.send(json!({"type": "trigger", "label": "GREET", "ref": "before-crash"}))
        .await;
    let t = op.recv_type("triggered").await;
    let say = t["commands"][0]["id"].clone();
    op.event_where(|e| e["type"] == "command.done" && e["command"] == say)
        .await;
    child.kill().expect("SIGKILL");
    child.wait().unwrap();
    let log = read_corpus(corpus.path());
    let act = log
        .iter()
        .find(|e| e["type"] == "act.triggered")
        .expect("the trigger was logged");
    assert_eq!(act["ref"], "before-crash");
    // Everything up to the SAY's start (a third of a second before its end, which the test
    // saw) was on disk; only the last couple of milliseconds may be missing.
    assert!(
        log.iter()
            .any(|e| e["type"] == "command.started" && e["command"] == say)
    );
    let seqs: Vec<u64> = log.iter().map(|e| e["seq"].as_u64().unwrap()).collect();
    assert_eq!(
        seqs,
        (1..=log.len() as u64).collect::<Vec<_>>(),
        "whole lines, no gaps"
    );
    assert!(
        !log.iter().any(|e| e["type"] == "server.stopping"),
        "it crashed; it did not stop"
    );
}

#[tokio::test]
async fn sigterm_shuts_down_gracefully_and_flushes_the_log() {
    let b = TempBundle::new(ACTS).with_file("docent.yaml", CONFIG);
    let corpus = tempfile::tempdir().unwrap();
    let (mut child, addr) = spawn_docent(b.path(), corpus.path());
    let mut kiosk = WsClient::connect(&format!("ws://{addr}/ws")).await;
    kiosk.send(json!({"type": "hello", "role": "kiosk"})).await;
    kiosk.recv_type("welcome").await;
    let status = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let exit = child.wait().unwrap();
    assert!(exit.success(), "docent exits 0 on SIGTERM: {exit}");
    let log = read_corpus(corpus.path());
    let kinds: Vec<&str> = log.iter().map(|e| e["type"].as_str().unwrap()).collect();
    assert_eq!(kinds.first(), Some(&"server.started"));
    assert!(kinds.contains(&"server.stopping"));
    assert!(
        log.iter()
            .any(|e| e["type"] == "client.left" && e["reason"] == "server shutting down"),
        "{kinds:?}"
    );
}
