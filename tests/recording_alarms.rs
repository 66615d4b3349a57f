//! Issue 28, findings 1 and 2, at the protocol: a kiosk that leaves is not a device failure
//! (its recording stops as `kiosk-left`, nothing is `recording.failed`); a kiosk's failure is
//! current in `/api/state` only until its cause ends (the next session, or the kiosk recording
//! again); and a consent mark that would delete a session's recordings is refused without
//! `confirm: true` (`confirmation-required`, nothing deleted), and once confirmed says in the
//! log what it deleted, with its bytes.

use crate::common;

use common::{TempBundle, TestServer, WsClient, session_dirs};
use serde_json::{Value, json};

/// A kiosk bundle whose sessions are started by marks.
fn site() -> TempBundle {
    TempBundle::new("- Label: WELCOME\n  Text: [Hello!]\n")
        .with_file(
            "docent.yaml",
            "speech: {adapter: log}\ncorpus: {session_start: marked}\n",
        )
        .with_file(
            "pages/index.html",
            r#"<html><body><button data-act="WELCOME">Hello</button></body></html>"#,
        )
}

/// A server with a kiosk and an operator, a session started and the kiosk's `record` frame.
async fn recording(b: &TempBundle) -> (TestServer, WsClient, WsClient, Value) {
    let server = TestServer::start(b.path()).await;
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk", "name": "kiosk"}))
        .await;
    let mut op = server.operator().await;
    op.send(json!({"type": "mark", "mark": "session_start"}))
        .await;
    op.recv_type("marked").await;
    let record = kiosk.recv_type("record").await;
    (server, kiosk, op, record)
}

/// The kiosk says recording `record` began.
async fn started(kiosk: &mut WsClient, record: &Value) {
    kiosk
        .send(
            json!({"type": "recording-started", "recording": record["recording"],
            "mime": "audio/webm", "mono_us": 1, "clock_error_us": 1}),
        )
        .await;
}

/// Uploads chunk `seq` of `record` as its kiosk does.
async fn chunk(server: &TestServer, record: &Value, seq: u64, body: &'static [u8]) -> u16 {
    let url = format!("{}{seq}", record["upload"].as_str().unwrap());
    let answer = reqwest::Client::new()
        .put(server.url(&url))
        .bearer_auth(record["token"].as_str().unwrap())
        .body(body)
        .send()
        .await
        .unwrap();
    answer.status().as_u16()
}

#[tokio::test]
async fn a_kiosk_that_leaves_stops_its_recording_as_kiosk_left_and_fails_nothing() {
    let b = site();
    let (server, mut kiosk, mut op, record) = recording(&b).await;
    started(&mut kiosk, &record).await;
    op.event("recording.started").await;
    drop(kiosk); // the page closed: its connection ends
    let stopped = op.event("recording.stopped").await;
    assert_eq!(stopped["reason"], "kiosk-left");
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["recording"]["kiosks"], json!([]), "nothing current");
    let all = server.stop().await;
    assert!(
        all.iter().all(|e| e["type"] != "recording.failed"),
        "a kiosk that leaves is not a failure"
    );
}

#[tokio::test]
async fn a_kiosk_failure_is_current_until_the_next_session_and_clears_when_it_records_again() {
    let b = site();
    let (server, mut kiosk, mut op, record) = recording(&b).await;
    kiosk
        .send(
            json!({"type": "recording-failed", "recording": record["recording"],
            "code": "no-device", "message": "the audio device stopped"}),
        )
        .await;
    op.event("recording.failed").await;
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["recording"]["kiosks"][0]["state"], "failed");
    op.send(json!({"type": "mark", "mark": "session_start"}))
        .await;
    let again = kiosk.recv_type("record").await;
    let (_, state) = server.get("/api/state").await;
    let current = &state["recording"]["kiosks"][0];
    assert_eq!(
        (&current["state"], &current["code"]),
        (&json!("starting"), &Value::Null),
        "the failure was the last session's: {state}"
    );
    started(&mut kiosk, &again).await;
    op.event("recording.started").await;
    let (_, state) = server.get("/api/state").await;
    let current = &state["recording"]["kiosks"][0];
    assert_eq!(
        (&current["state"], &current["code"]),
        (&json!("recording"), &Value::Null)
    );
    server.stop().await;
}

#[tokio::test]
async fn a_consent_that_deletes_recordings_needs_confirm_and_the_log_says_what_it_deleted() {
    let b = site();
    let (server, mut kiosk, mut op, record) = recording(&b).await;
    assert_eq!(chunk(&server, &record, 0, b"HEAD").await, 200);
    started(&mut kiosk, &record).await;
    op.event("recording.started").await;
    let (_, state) = server.get("/api/state").await;
    let kept = &state["recording"]["kept"];
    assert_eq!((&kept["files"], &kept["bytes"]), (&json!(1), &json!(4)));

    for refusal in ["declined", "withdrawn"] {
        op.send(json!({"type": "mark", "mark": "consent", "value": refusal, "ref": "slip"}))
            .await;
        let error = op.recv_type("error").await;
        assert_eq!(
            (&error["code"], &error["ref"]),
            (&json!("confirmation-required"), &json!("slip"))
        );
    }
    assert_eq!(
        chunk(&server, &record, 1, b"BODY").await,
        200,
        "still recording"
    );
    let media = session_dirs(&server.corpus)[0].join("media");
    let sizes: u64 = (std::fs::read_dir(&media).unwrap())
        .map(|f| f.unwrap().metadata().unwrap().len())
        .sum();

    op.send(json!({"type": "mark", "mark": "consent", "value": "declined", "confirm": true}))
        .await;
    op.recv_type("marked").await;
    assert!(!media.exists(), "deleted once confirmed");
    let deleted = op.event("recording.deleted").await;
    assert_eq!(deleted["consent"], "declined");
    assert_eq!(deleted["bytes"], json!(sizes), "{deleted}");
    let all = server.stop().await;
    let consents: Vec<&Value> = (all.iter())
        .filter(|e| e["type"] == "consent.changed")
        .map(|e| &e["consent"])
        .collect();
    assert_eq!(consents, [&json!("declined")], "the slips changed nothing");
}
