//! Recordings uploaded into a session's folder, against a real server on 127.0.0.1:0 with a
//! protocol client in the kiosk's place: the `record` frame after a session starts, chunks
//! stored in order and once, a gap answered with the chunk expected, the upload token the only
//! key, the clock answer, `recording.*` events and the manifest's `media`; a declined consent
//! records nothing, a withdrawn one removes the media and refuses later chunks; bytes beyond
//! what was acknowledged are cut before the next chunk.

use crate::common;

use std::io::Write;
use std::path::PathBuf;

use common::{TempBundle, TestServer, WsClient, session_dirs};
use docent::corpus::manifest::SessionManifest;
use docent::corpus::purge::purge;
use serde_json::{Value, json};

const ACTS: &str = "- Label: WELCOME\n  Text: [Hello!]\n";

/// A kiosk bundle whose sessions are started by marks, with more `corpus` settings.
fn site(corpus: &str) -> TempBundle {
    TempBundle::new(ACTS)
        .with_file(
            "docent.yaml",
            &format!("speech: {{adapter: log}}\ncorpus: {{session_start: marked{corpus}}}\n"),
        )
        .with_file(
            "pages/index.html",
            r#"<html><body><button data-act="WELCOME">Hello</button></body></html>"#,
        )
}

async fn kiosk(server: &TestServer) -> WsClient {
    server
        .client(json!({"type": "hello", "role": "kiosk", "name": "kiosk"}))
        .await
}

async fn mark(op: &mut WsClient, mark: &str, value: Option<&str>) {
    let mut frame = json!({"type": "mark", "mark": mark});
    if let Some(value) = value {
        frame["value"] = value.into();
    }
    op.send(frame).await;
    op.recv_type("marked").await;
}

/// PUTs chunk `seq` of the recording a `record` frame asked for, with `token`.
async fn put(
    server: &TestServer,
    record: &Value,
    seq: u64,
    body: &[u8],
    token: &str,
) -> (u16, Value) {
    let url = server.url(&format!("{}{seq}", record["upload"].as_str().unwrap()));
    let response = reqwest::Client::new()
        .put(url)
        .bearer_auth(token)
        .body(body.to_vec())
        .send()
        .await
        .expect("PUT");
    let status = response.status().as_u16();
    (status, response.json().await.unwrap_or(Value::Null))
}

async fn chunk(server: &TestServer, record: &Value, seq: u64, body: &[u8]) -> (u16, Value) {
    put(server, record, seq, body, record["token"].as_str().unwrap()).await
}

/// A server recording a session an operator started: the kiosk has its `record` frame. The
/// corpus is in `folder`, which outlives the server.
struct Recording {
    server: TestServer,
    kiosk: WsClient,
    op: WsClient,
    record: Value,
    folder: tempfile::TempDir,
    bundle: TempBundle,
}

async fn recording() -> Recording {
    let b = site("");
    let folder = tempfile::tempdir().unwrap();
    let server = TestServer::start_with(b.path(), |o| o.corpus_dir = folder.path().into()).await;
    let mut kiosk = kiosk(&server).await;
    let mut op = server.operator().await;
    mark(&mut op, "session_start", None).await;
    let record = kiosk.recv_type("record").await;
    Recording {
        server,
        kiosk,
        op,
        record,
        folder,
        bundle: b,
    }
}

fn media(server: &TestServer, file: &str) -> PathBuf {
    session_dirs(&server.corpus)[0].join(file)
}

#[tokio::test]
async fn chunks_are_stored_in_order_once_and_the_recording_is_placed_on_the_session_clock() {
    let Recording {
        server,
        mut kiosk,
        mut op,
        record,
        folder,
        bundle: _bundle,
    } = recording().await;
    assert_eq!(record["tracks"], json!(["audio"]));
    assert_eq!(record["mime"], "audio/webm;codecs=opus");
    assert_eq!(record["file"], "media/audio-1.webm");
    let file = media(&server, "media/audio-1.webm");
    assert!(file.is_file(), "made before the frame went out");

    let stored = |acked: u64, next: u64| (200, json!({"acked": acked, "next": next}));
    assert_eq!(chunk(&server, &record, 0, b"HEAD").await, stored(4, 1));
    assert_eq!(
        chunk(&server, &record, 0, b"HEAD").await,
        stored(4, 1),
        "a resend is not appended"
    );
    let (status, gap) = chunk(&server, &record, 2, b"LATE").await;
    assert_eq!(
        (status, &gap["code"], &gap["next"]),
        (409, &json!("chunk-out-of-order"), &json!(1))
    );
    let (status, refused) = put(&server, &record, 1, b"EVIL", "not-the-token").await;
    assert_eq!((status, &refused["code"]), (401, &json!("unauthorized")));
    let (status, _) = put(&server, &record, 1, b"EVIL", common::OPERATOR_TOKEN).await;
    assert_eq!(status, 401, "the operator's credential opens no recording");
    assert_eq!(chunk(&server, &record, 1, b"BODY").await, stored(8, 2));
    assert_eq!(std::fs::read(&file).unwrap(), b"HEADBODY");

    // The clock answer, then the kiosk's start placed on the session clock.
    kiosk.send(json!({"type": "clock", "t0": 12.5})).await;
    let clock = kiosk.recv_type("clock").await;
    assert_eq!(clock["t0"], 12.5);
    let server_us = clock["server_us"].as_u64().unwrap();
    let id = record["recording"].as_u64().unwrap();
    kiosk
        .send(
            json!({"type": "recording-started", "recording": id, "mime": "audio/webm;codecs=opus",
            "mono_us": server_us, "clock_error_us": 150}),
        )
        .await;
    let started = op.event("recording.started").await;
    assert_eq!(started["file"], "media/audio-1.webm");
    assert_eq!(started["track"], "audio");
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["recording"]["kiosks"][0]["state"], "recording");

    mark(&mut op, "session_end", None).await;
    let stop = kiosk.recv_type("record-stop").await;
    assert_eq!(
        (&stop["recording"], &stop["reason"]),
        (&json!(id), &json!("session-ended"))
    );
    assert_eq!(
        chunk(&server, &record, 2, b"TAIL").await,
        stored(12, 3),
        "the last chunk after the stop"
    );
    kiosk
        .send(json!({"type": "recording-stopped", "recording": id}))
        .await;
    let stopped = op.event("recording.stopped").await;
    assert_eq!(
        (&stopped["bytes"], &stopped["chunks"]),
        (&json!(12), &json!(3))
    );
    let (status, gone) = chunk(&server, &record, 3, b"MORE").await;
    assert_eq!((status, &gone["code"]), (410, &json!("recording-gone")));
    drop(kiosk);
    let all = server.stop().await;

    let started_line = all
        .iter()
        .find(|e| e["type"] == "recording.started")
        .unwrap();
    let session_line = all.iter().find(|e| e["type"] == "session.started").unwrap();
    let expected = server_us - session_line["mono_us"].as_u64().unwrap();
    assert_eq!(started_line["start_us"], expected);
    let dir = session_dirs(folder.path())[0].clone();
    let manifest = SessionManifest::read_from(&dir).unwrap();
    assert_eq!(manifest.media.len(), 1);
    let entry = &manifest.media[0];
    assert_eq!(
        (entry.file.as_str(), entry.track.as_str()),
        ("media/audio-1.webm", "audio")
    );
    assert_eq!(
        (entry.start_us, entry.clock_error_us, entry.recording),
        (expected, 150, id)
    );
    assert_eq!(
        std::fs::read(dir.join("media/audio-1.webm")).unwrap(),
        b"HEADBODYTAIL"
    );
    // Purge removes the media with the rest, and says so file by file.
    let mut removed = Vec::new();
    purge(folder.path(), &manifest.session, |f| {
        removed.push(f.path.to_string_lossy().into_owned())
    })
    .unwrap();
    let media: Vec<&String> = removed.iter().filter(|p| p.contains("/media/")).collect();
    let name = &manifest.session;
    assert_eq!(
        media,
        [
            &format!("sessions/{name}/media/audio-1.webm"),
            &format!("sessions/{name}/media/audio-1.webm.chunks")
        ]
    );
    assert!(!dir.exists());
}

#[tokio::test]
async fn a_declined_session_records_nothing_until_consent_is_given() {
    let b = site(", consent: declined");
    let server = TestServer::start(b.path()).await;
    let mut kiosk = kiosk(&server).await;
    let mut op = server.operator().await;
    mark(&mut op, "session_start", None).await;
    let (status, body) = reqwest::Client::new()
        .put(server.url("/api/recordings/1/chunks/0"))
        .bearer_auth("anything")
        .body("x")
        .send()
        .await
        .map(|r| (r.status().as_u16(), r))
        .unwrap();
    assert_eq!(status, 410, "no recording to upload to");
    let bad = reqwest::Client::new()
        .put(server.url("/api/recordings/x/chunks/0"))
        .body("x")
        .send()
        .await
        .unwrap();
    assert_eq!(bad.status().as_u16(), 400);
    assert_eq!(bad.json::<Value>().await.unwrap()["code"], "bad-request");
    assert_eq!(
        body.json::<Value>().await.unwrap()["code"],
        "recording-gone"
    );
    // Events are handled in order: the first `record` frame answers the consent, not the start.
    mark(&mut op, "consent", Some("recorded")).await;
    let record = kiosk.recv_type("record").await;
    assert_eq!(
        (&record["recording"], &record["file"]),
        (&json!(1), &json!("media/audio-1.webm"))
    );
    let all = server.stop().await;
    let consent = all
        .iter()
        .position(|e| e["type"] == "consent.changed")
        .unwrap();
    assert!(
        all[..consent]
            .iter()
            .all(|e| !e["type"].as_str().unwrap().starts_with("recording."))
    );
}

#[tokio::test]
async fn withdrawn_consent_stops_the_recording_removes_its_media_and_refuses_later_chunks() {
    let Recording {
        server,
        mut kiosk,
        mut op,
        record,
        folder,
        bundle: _bundle,
    } = recording().await;
    let id = record["recording"].as_u64().unwrap();
    assert_eq!(chunk(&server, &record, 0, b"HEAD").await.0, 200);
    kiosk
        .send(
            json!({"type": "recording-started", "recording": id, "mime": "audio/webm",
            "mono_us": 1, "clock_error_us": 1}),
        )
        .await;
    op.event("recording.started").await;
    op.send(json!({"type": "mark", "mark": "consent", "value": "withdrawn", "confirm": true}))
        .await;
    op.recv_type("marked").await;
    let stop = kiosk.recv_type("record-stop").await;
    assert_eq!(stop["reason"], "consent");
    let deleted = op.event("recording.deleted").await;
    assert_eq!(
        deleted["files"],
        json!(["media/audio-1.webm", "media/audio-1.webm.chunks"])
    );
    assert_eq!(deleted["consent"], "withdrawn");
    let dir = session_dirs(&server.corpus)[0].clone();
    assert!(!dir.join("media").exists(), "the media folder is gone");
    let (status, gone) = chunk(&server, &record, 1, b"BODY").await;
    assert_eq!((status, &gone["code"]), (410, &json!("recording-gone")));
    drop(kiosk);
    server.stop().await;
    let manifest = SessionManifest::read_from(&session_dirs(folder.path())[0]).unwrap();
    assert_eq!(
        (manifest.consent.as_str(), manifest.media.len()),
        ("withdrawn", 0)
    );
}

#[tokio::test]
async fn bytes_beyond_the_acknowledged_length_are_cut_before_the_next_chunk() {
    let Recording {
        server,
        kiosk: _kiosk,
        op: _op,
        record,
        folder: _folder,
        bundle: _bundle,
    } = recording().await;
    assert_eq!(chunk(&server, &record, 0, b"HEAD").await.0, 200);
    let file = media(&server, "media/audio-1.webm");
    // A torn append: bytes in the file that were never acknowledged.
    let mut torn = std::fs::OpenOptions::new()
        .append(true)
        .open(&file)
        .unwrap();
    torn.write_all(b"TORN-HALF-CHUNK").unwrap();
    assert_eq!(chunk(&server, &record, 1, b"BODY").await.0, 200);
    assert_eq!(std::fs::read(&file).unwrap(), b"HEADBODY");
    server.stop().await;
}

#[tokio::test]
async fn a_kiosk_that_cannot_record_is_told_to_operators_at_once() {
    let Recording {
        server,
        mut kiosk,
        mut op,
        record,
        folder: _folder,
        bundle: _bundle,
    } = recording().await;
    let id = record["recording"].as_u64().unwrap();
    kiosk
        .send(
            json!({"type": "recording-failed", "recording": id, "code": "permission-denied",
            "message": "NotAllowedError: Permission denied"}),
        )
        .await;
    let failed = op.event("recording.failed").await;
    assert_eq!(
        (&failed["code"], &failed["recording"]),
        (&json!("permission-denied"), &json!(id))
    );
    let stopped = op.event("recording.stopped").await;
    assert_eq!(stopped["reason"], "failed");
    let (_, state) = server.get("/api/state").await;
    let kiosk_state = &state["recording"]["kiosks"][0];
    assert_eq!(
        (&kiosk_state["state"], &kiosk_state["code"]),
        (&json!("failed"), &json!("permission-denied"))
    );
    let (status, _) = chunk(&server, &record, 0, b"HEAD").await;
    assert_eq!(status, 410, "a failed recording takes no chunks");
    server.stop().await;
}

/// A server whose `corpus: record_limits` are `limits`, a session started by its operator, and
/// its kiosk.
async fn limited(limits: &str) -> (TestServer, WsClient, WsClient, TempBundle) {
    let b = site(&format!(", record_limits: {{{limits}}}"));
    let server = TestServer::start(b.path()).await;
    let kiosk = kiosk(&server).await;
    let mut op = server.operator().await;
    mark(&mut op, "session_start", None).await;
    (server, kiosk, op, b)
}

#[tokio::test]
async fn a_kiosk_uploading_past_its_limits_is_stopped_and_the_robot_goes_on() {
    for (limits, per) in [
        ("per_session: 10 kB", "per_session"),
        ("per_kiosk: 10 kB", "per_kiosk"),
    ] {
        let (server, mut kiosk, mut op, _b) = limited(limits).await;
        let record = kiosk.recv_type("record").await;
        let id = record["recording"].clone();
        for seq in 0..2 {
            assert_eq!(chunk(&server, &record, seq, &[7; 4000]).await.0, 200);
        }
        let (status, refused) = chunk(&server, &record, 2, &[7; 4000]).await;
        assert_eq!((status, &refused["code"]), (507, &json!("recording-limit")));
        let said = refused["error"].as_str().unwrap();
        assert!(said.contains(per) && said.contains("10.0 kB"), "{said}");
        let failed = op.event("recording.failed").await;
        assert_eq!(
            (&failed["code"], &failed["recording"]),
            (&json!("limit-reached"), &id)
        );
        assert_eq!(kiosk.recv_type("record-stop").await["recording"], id);
        // Refused for good, and nothing more was written.
        assert_eq!(chunk(&server, &record, 2, &[7; 10]).await.0, 410);
        let file = media(&server, record["file"].as_str().unwrap());
        assert_eq!(std::fs::metadata(&file).unwrap().len(), 8000);
        // The robot goes on: an act is still acknowledged and logged.
        op.send(json!({"type": "trigger", "label": "WELCOME", "ref": "t"}))
            .await;
        op.recv_where(|f| f["type"] == "triggered" && f["ref"] == "t")
            .await;
        drop(kiosk);
        server.stop().await;
    }
}

#[tokio::test]
async fn no_recording_starts_when_the_disk_has_no_more_than_its_reserve() {
    // More than any test machine's disk holds: the reserve is never there.
    let (server, mut kiosk, mut op, _b) = limited("keep_free: 1000 TB").await;
    let failed = op.event("recording.failed").await;
    assert_eq!(failed["code"], "disk-full");
    let said = failed["message"].as_str().unwrap();
    assert!(
        said.contains("keep_free") && said.contains("1000.0 TB"),
        "{said}"
    );
    // The kiosk was asked for nothing, and triggers are still taken.
    kiosk
        .send(json!({"type": "trigger", "label": "WELCOME", "ref": "k"}))
        .await;
    let answer = kiosk
        .recv_where(|f| f["type"] == "record" || f["ref"] == "k")
        .await;
    assert_eq!(answer["type"], "triggered", "{answer}");
    drop(kiosk);
    let events = server.stop().await;
    assert!(!events.iter().any(|e| e["type"] == "recording.started"));
}
