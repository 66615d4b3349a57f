//! The corpus folder by visitor session: a session's events go to its own folder, with a
//! manifest, and carry the session clock; every other event goes to the run's day log. Read
//! back as a researcher would: from the files alone.

use crate::common;

use common::process::spawn_docent;
use common::{TempBundle, TestServer, WsClient, json_lines, read_corpus, session_dirs};
use docent::corpus::layout::SESSION_EVENTS;
use docent::corpus::manifest::SessionManifest;
use serde_json::{Value, json};

const ACTS: &str = r#"
- Label: WELCOME
  Text: [Hello!]
  TextChild: [Hi there!]
"#;

fn tour() -> TempBundle {
    TempBundle::new(ACTS).with_file("docent.yaml", "speech: {adapter: log}\n")
}

/// A kiosk bundle whose page offers WELCOME, with `corpus` settings.
fn kiosk_tour(corpus: &str) -> TempBundle {
    TempBundle::new(ACTS)
        .with_file(
            "docent.yaml",
            &format!("speech: {{adapter: log}}\ncorpus: {corpus}\n"),
        )
        .with_file(
            "pages/index.html",
            r#"<html><body><button data-act="WELCOME">Hello</button></body></html>"#,
        )
}

fn is(kind: &'static str) -> impl Fn(&Value) -> bool {
    move |e| e["type"] == kind
}

#[tokio::test]
async fn a_sessions_events_are_in_its_folder_on_its_clock_and_the_rest_in_the_day_log() {
    let b = tour();
    // Our own folder: the server's own is removed when it stops.
    let folder = tempfile::tempdir().unwrap();
    let server = TestServer::start_with(b.path(), |o| o.corpus_dir = folder.path().into()).await;
    let corpus = server.corpus.clone();
    let mut op = server.operator().await;
    op.send(json!({"type": "trigger", "label": "WELCOME", "ref": "before"}))
        .await;
    op.recv_type("triggered").await;
    op.send(json!({"type": "mark", "mark": "session_start"}))
        .await;
    op.recv_type("marked").await;
    op.send(json!({"type": "mark", "mark": "group", "value": "children"}))
        .await;
    op.recv_type("marked").await;
    op.send(json!({"type": "trigger", "label": "WELCOME", "ref": "during"}))
        .await;
    assert_eq!(op.recv_type("triggered").await["text"], "Hi there!");
    op.send(json!({"type": "mark", "mark": "session_end"}))
        .await;
    op.recv_type("marked").await;
    // Answered once the end is written, by then the session's log is closed and unlocked.
    let log = std::fs::File::open(session_dirs(&corpus)[0].join(SESSION_EVENTS)).unwrap();
    log.try_lock()
        .expect("an ended session's log is no longer held");
    drop(log);
    op.send(json!({"type": "trigger", "label": "WELCOME", "ref": "after"}))
        .await;
    op.recv_type("triggered").await;
    let all = server.stop().await;

    // Nothing lost, nothing twice: the files together hold the run, seq 1, 2, 3, ...
    let seqs: Vec<u64> = all.iter().map(|e| e["seq"].as_u64().unwrap()).collect();
    assert_eq!(seqs, (1..=all.len() as u64).collect::<Vec<_>>());

    let dirs = session_dirs(&corpus);
    assert_eq!(dirs.len(), 1, "{dirs:?}");
    let session = json_lines(&dirs[0].join(SESSION_EVENTS));
    let first = &session[0];
    let last = session.last().unwrap();
    assert_eq!(first["type"], "session.started");
    assert_eq!(
        (last["type"].as_str(), last["reason"].as_str()),
        (Some("session.ended"), Some("marked"))
    );
    let start = first["mono_us"].as_u64().unwrap();
    for e in &session {
        assert_eq!(e["v"], 4);
        let on_session_clock = e["session_us"].as_u64().expect("session_us");
        assert_eq!(
            on_session_clock,
            e["mono_us"].as_u64().unwrap() - start,
            "{e}"
        );
    }
    let refs = |events: &[Value]| -> Vec<String> {
        (events.iter())
            .filter(|e| e["type"] == "act.triggered")
            .map(|e| e["ref"].as_str().unwrap().to_owned())
            .collect()
    };
    assert_eq!(refs(&session), ["during"]);
    let outside: Vec<Value> = (all.iter())
        .filter(|e| !session.iter().any(|s| s["seq"] == e["seq"]))
        .cloned()
        .collect();
    assert_eq!(refs(&outside), ["before", "after"]);
    assert!(outside.iter().all(|e| e.get("session_us").is_none()));
    assert_eq!(outside[0]["type"], "server.started");

    let manifest = SessionManifest::read_from(&dirs[0]).unwrap();
    let name = dirs[0].file_name().unwrap().to_str().unwrap();
    assert_eq!(manifest.session, name);
    assert_eq!(manifest.number, 1);
    assert_eq!(manifest.docent, env!("CARGO_PKG_VERSION"));
    let bundle = std::fs::canonicalize(b.path()).unwrap();
    assert_eq!(manifest.bundle.as_deref(), bundle.to_str());
    assert_eq!(manifest.started.seq, first["seq"].as_u64().unwrap());
    assert_eq!(manifest.started.time, first["time"].as_str().unwrap());
    assert_eq!(manifest.started.source, "operator");
    let ended = manifest.ended.expect("ended");
    assert_eq!(
        (ended.seq, ended.reason.as_deref()),
        (last["seq"].as_u64().unwrap(), Some("marked"))
    );
    assert_eq!(manifest.group.as_deref(), Some("children"));
    assert_eq!(manifest.context.as_deref(), Some("TextChild"));
}

#[tokio::test]
async fn a_shutdown_ends_the_running_session_after_its_clients_left() {
    let b = tour();
    // Our own folder: the server's own is removed when it stops.
    let folder = tempfile::tempdir().unwrap();
    let server = TestServer::start_with(b.path(), |o| o.corpus_dir = folder.path().into()).await;
    let corpus = server.corpus.clone();
    let mut op = server.operator().await;
    op.send(json!({"type": "mark", "mark": "session_start"}))
        .await;
    op.recv_type("marked").await;
    read_corpus(&corpus); // readable while the server runs
    server.stop().await;
    let dirs = session_dirs(&corpus);
    let session = json_lines(&dirs[0].join(SESSION_EVENTS));
    let kinds: Vec<&str> = session
        .iter()
        .map(|e| e["type"].as_str().unwrap())
        .collect();
    assert!(kinds.contains(&"server.stopping"), "{kinds:?}");
    assert!(kinds.contains(&"client.left"), "{kinds:?}");
    let last = session.last().unwrap();
    assert_eq!(last["type"], "session.ended");
    assert_eq!(
        (last["source"].as_str(), last["reason"].as_str()),
        (Some("server"), Some("server-stopping"))
    );
    assert!(last.get("client").is_none(), "no client ended it: {last}");
    let ended = SessionManifest::read_from(&dirs[0]).unwrap().ended.unwrap();
    assert_eq!(ended.source, "server");
}

#[tokio::test]
async fn a_killed_server_leaves_an_open_session_with_a_readable_log_and_manifest() {
    let b = tour();
    let corpus = tempfile::tempdir().unwrap();
    let (mut child, addr) = spawn_docent(b.path(), corpus.path());
    let mut op = WsClient::operator_at(&addr).await;
    op.send(json!({"type": "mark", "mark": "session_start"}))
        .await;
    op.recv_type("marked").await;
    op.send(json!({"type": "trigger", "label": "WELCOME", "ref": "acknowledged"}))
        .await;
    op.recv_type("triggered").await;
    child.kill().expect("SIGKILL");
    child.wait().unwrap();
    let dirs = session_dirs(corpus.path());
    assert_eq!(dirs.len(), 1);
    let manifest = SessionManifest::read_from(&dirs[0]).expect("a whole manifest");
    assert_eq!(manifest.ended, None, "nobody ended it");
    let session = json_lines(&dirs[0].join(SESSION_EVENTS));
    assert!(
        (session.iter()).any(|e| e["type"] == "act.triggered" && e["ref"] == "acknowledged"),
        "the acknowledged trigger is in the session's log"
    );
}

// On the real clock: a paused one jumps ahead while the corpus writer's thread works, and the
// idle end itself is timed on a paused clock in `operator::visits`' unit tests.
#[tokio::test]
async fn a_visitors_tap_starts_a_session_that_ends_after_the_idle_time_without_a_touch() {
    let b = kiosk_tour("{session_idle: 1s}");
    let server = TestServer::start(b.path()).await;
    let mut op = server.operator().await;
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    // Measured from before the tap: the server's idle clock starts when it takes the tap.
    let tapped = tokio::time::Instant::now();
    kiosk
        .send(json!({"type": "trigger", "label": "WELCOME", "ref": "tap"}))
        .await;
    kiosk.recv_type("triggered").await;
    let started = op.event_where(is("session.started")).await;
    assert_eq!(
        (started["source"].as_str(), started["session"].as_u64()),
        (Some("kiosk"), Some(1))
    );
    let act = op
        .event_where(|e| e["type"] == "act.triggered" && e["ref"] == "tap")
        .await;
    assert!(
        started["seq"].as_u64() < act["seq"].as_u64(),
        "the tap's act is in the session it started"
    );
    let ended = op.event_where(is("session.ended")).await;
    let waited = tapped.elapsed();
    assert!(
        waited >= std::time::Duration::from_secs(1),
        "ended {waited:?} after the tap"
    );
    assert_eq!(
        (ended["reason"].as_str(), ended["source"].as_str()),
        (Some("idle"), Some("server"))
    );
    server.stop().await;
}

#[tokio::test]
async fn with_session_start_marked_a_tap_starts_nothing_and_a_dialog_manager_may_mark_one() {
    let b = kiosk_tour("{session_start: marked}");
    let server = TestServer::start(b.path()).await;
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    kiosk
        .send(json!({"type": "trigger", "label": "WELCOME"}))
        .await;
    kiosk.recv_type("triggered").await;
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["session"], Value::Null, "no session from a tap");
    let mut dm = server
        .client(json!({"type": "hello", "role": "dm", "name": "planner"}))
        .await;
    dm.send(json!({"type": "mark", "mark": "session_start"}))
        .await;
    assert_eq!(dm.recv_type("marked").await["session"], 1);
    dm.send(json!({"type": "mark", "mark": "group", "value": "children"}))
        .await;
    assert_eq!(
        dm.recv_type("error").await["code"],
        "forbidden",
        "groups are the operator's"
    );
    dm.send(json!({"type": "mark", "mark": "session_end"}))
        .await;
    assert_eq!(dm.recv_type("marked").await["session"], 1);
    let all = server.stop().await;
    let started = all.iter().find(|e| e["type"] == "session.started").unwrap();
    assert_eq!(started["source"], "dm");
    assert_eq!(
        all.iter()
            .filter(|e| e["type"] == "session.started")
            .count(),
        1
    );
}

#[tokio::test]
async fn consent_is_noted_in_the_log_and_the_manifest_and_a_withdrawal_stays() {
    let b = kiosk_tour("{consent: declined}");
    let folder = tempfile::tempdir().unwrap();
    let server = TestServer::start_with(b.path(), |o| o.corpus_dir = folder.path().into()).await;
    let corpus = server.corpus.clone();
    let mut op = server.operator().await;
    op.send(json!({"type": "mark", "mark": "consent", "value": "recorded"}))
        .await;
    assert_eq!(op.recv_type("error").await["code"], "no-session");
    op.send(json!({"type": "mark", "mark": "session_start"}))
        .await;
    op.recv_type("marked").await;
    let started = op.event_where(is("session.started")).await;
    assert_eq!(started["consent"], "declined", "the site's default");
    op.send(json!({"type": "mark", "mark": "consent", "value": "recorded"}))
        .await;
    assert_eq!(op.recv_type("marked").await["value"], "recorded");
    op.send(json!({"type": "mark", "mark": "consent", "value": "maybe"}))
        .await;
    let bad = op.recv_type("error").await;
    assert_eq!(bad["code"], "bad-mark");
    assert!(
        bad["message"]
            .as_str()
            .unwrap()
            .contains("recorded, declined, withdrawn"),
        "{bad}"
    );
    op.send(json!({"type": "mark", "mark": "consent", "value": "withdrawn"}))
        .await;
    let unconfirmed = op.recv_type("error").await;
    assert_eq!(unconfirmed["code"], "confirmation-required", "it deletes");
    op.send(json!({"type": "mark", "mark": "consent", "value": "withdrawn", "confirm": true}))
        .await;
    op.recv_type("marked").await;
    op.send(json!({"type": "mark", "mark": "consent", "value": "recorded"}))
        .await;
    let refused = op.recv_type("error").await;
    assert_eq!(refused["code"], "bad-mark");
    assert!(
        refused["message"].as_str().unwrap().contains("withdrawn"),
        "{refused}"
    );
    let all = server.stop().await;
    let changes: Vec<&str> = (all.iter())
        .filter(|e| e["type"] == "consent.changed")
        .map(|e| e["consent"].as_str().unwrap())
        .collect();
    assert_eq!(changes, ["recorded", "withdrawn"]);
    let manifest = SessionManifest::read_from(&session_dirs(&corpus)[0]).unwrap();
    assert_eq!(manifest.consent, "withdrawn");
}
