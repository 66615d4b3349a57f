//! The corpus disk failing under a running server, injected for real: a small tmpfs filled
//! up mid-session and then given space again, a tmpfs remounted read-only and back, the
//! corpus folder removed with `rm -rf`. Each time triggers the log cannot hold are refused
//! with `corpus-unwritable`, the operator is told at once in words (an event, and the state
//! a console joining later is welcomed with), the server keeps serving, and once the disk
//! works again it recovers by itself: the next trigger is accepted and logged, and the log
//! has every acknowledged event once, its `seq`s without a gap.

use crate::common;

use std::path::Path;

use common::mount::Tmpfs;
use common::{TempBundle, TestServer, read_corpus};
use serde_json::{Value, json};

const ACTS: &str = "- Label: OK\n  Cmds: [DISPLAY_PAGE index.html]\n";

/// Recordings may use all but 1 KB of the small test disks (the default keeps 1 GB free).
const SMALL_RESERVE: &str = "corpus: {record_limits: {keep_free: 1 KB}}\n";

/// Far more triggers than the room left holds (each writes about 1.5 KB of events).
const MAX_TRIGGERS: usize = 2_000;

/// Triggers `OK` until the server refuses; returns the trigger ids acknowledged and the
/// refusal's status and body.
async fn trigger_until_refused(server: &TestServer) -> (Vec<u64>, u16, Value) {
    let mut acknowledged = Vec::new();
    for n in 0..MAX_TRIGGERS {
        let (status, body) = server
            .post(
                "/api/acts/OK/trigger",
                Some(json!({"ref": format!("t{n}")})),
            )
            .await;
        match status {
            202 => acknowledged.push(body["trigger"].as_u64().expect("trigger id")),
            _ => return (acknowledged, status, body),
        }
    }
    panic!("{MAX_TRIGGERS} triggers accepted: the disk never filled up");
}

/// Asserts that triggers are refused before anything is carried out, and the server serves.
async fn refused_while_failing(server: &TestServer, words: &str) {
    let (status, body) = server
        .post("/api/acts/OK/trigger", Some(json!({"ref": "refused"})))
        .await;
    assert_eq!(
        (status, body["code"].as_str()),
        (503, Some("corpus-unwritable")),
        "{body}"
    );
    let error = body["error"].as_str().unwrap_or_default();
    assert!(error.starts_with("not triggered"), "{body}");
    let (status, state) = server.get("/api/state").await;
    assert_eq!(status, 200, "the server keeps serving: {state}");
    assert_eq!(state["corpus"], words, "{state}");
    // A console that joins now is welcomed with the same words.
    let late = server.operator().await;
    assert_eq!(late.welcome["state"]["corpus"], words);
}

/// Every line of the corpus, checked: `seq`s 1, 2, 3, ... each once, and every trigger in
/// `acknowledged` there.
fn complete_log(corpus: &Path, acknowledged: &[u64]) -> Vec<Value> {
    let lines = read_corpus(corpus);
    let seqs: Vec<u64> = lines
        .iter()
        .map(|e| e["seq"].as_u64().expect("seq"))
        .collect();
    let expected: Vec<u64> = (1..=seqs.len() as u64).collect();
    assert_eq!(seqs, expected, "every seq once, none missing");
    for trigger in acknowledged {
        assert!(
            lines
                .iter()
                .any(|e| e["type"] == "act.triggered" && e["trigger"] == *trigger),
            "acknowledged trigger {trigger} is not in the log"
        );
    }
    lines
}

/// `rm -rf dir`, again if the writer made a file in it meanwhile (a late line of the last
/// trigger found its file removed), until it is gone.
fn remove_all(dir: &Path) {
    for _ in 0..10 {
        match std::fs::remove_dir_all(dir) {
            Ok(()) => return,
            Err(e) if e.kind() == std::io::ErrorKind::DirectoryNotEmpty => continue,
            Err(e) => panic!("rm -rf {}: {e}", dir.display()),
        }
    }
    panic!("{} could not be removed", dir.display());
}

fn of_type<'a>(lines: &'a [Value], kind: &str) -> Vec<&'a Value> {
    lines.iter().filter(|e| e["type"] == kind).collect()
}

#[tokio::test]
async fn a_full_disk_mid_session_refuses_triggers_tells_the_operator_and_recovers_once_space_is_back()
 {
    let bundle = TempBundle::new(ACTS);
    let scratch = tempfile::tempdir().expect("scratch");
    let disk = Tmpfs::mount(&scratch.path().join("corpus"), 512);
    let server = TestServer::start_with(bundle.path(), |o| {
        o.corpus_dir = scratch.path().join("corpus");
        o.media_cache = scratch.path().join("media-cache");
    })
    .await;
    let mut op = server.operator().await;
    op.send(json!({"type": "mark", "mark": "session_start", "ref": "s"}))
        .await;
    op.recv_type("marked").await;
    server.trigger("OK", json!({"ref": "before"})).await;
    let filler = server.corpus.join("filler");
    disk.fill_leaving(&filler, 16 * 1024);

    let (mut acknowledged, status, body) = trigger_until_refused(&server).await;
    assert_eq!(
        (status, body["code"].as_str()),
        (503, Some("corpus-unwritable")),
        "{body}"
    );
    assert!(
        acknowledged.len() >= 2,
        "the room left held some: {acknowledged:?}"
    );
    let told = op.event("corpus.unwritable").await;
    let words = format!(
        "The corpus disk is full ({}): free space on it; triggers are refused until then. \
         Events wait in memory.",
        server.corpus.display()
    );
    assert_eq!(told["message"], words.as_str(), "{told}");
    assert_eq!(told["fault"], "disk-full");
    refused_while_failing(&server, &words).await;

    std::fs::remove_file(&filler).expect("space freed");
    let back = op.event("corpus.writable").await;
    assert!(back["unwritable_ms"].as_u64().is_some(), "{back}");
    let (_, state) = server.get("/api/state").await;
    assert_eq!(state["corpus"], Value::Null, "the alert is gone: {state}");
    let after = server.trigger("OK", json!({"ref": "after"})).await;
    acknowledged.push(after["trigger"].as_u64().expect("trigger id"));
    op.send(json!({"type": "mark", "mark": "session_end", "ref": "e"}))
        .await;
    op.recv_type("marked").await;

    let corpus = server.corpus.clone();
    let lines = server.stop().await;
    let checked = complete_log(&corpus, &acknowledged);
    assert_eq!(lines.len(), checked.len());
    assert_eq!(of_type(&lines, "corpus.unwritable").len(), 1, "said once");
    assert_eq!(of_type(&lines, "corpus.writable").len(), 1);
    assert!(of_type(&lines, "corpus.gap").is_empty(), "nothing was lost");
    assert_eq!(of_type(&lines, "session.ended").len(), 1);
    drop(disk);
}

#[tokio::test]
async fn a_disk_remounted_read_only_refuses_triggers_until_it_is_writable_again() {
    let bundle = TempBundle::new(ACTS).with_file("docent.yaml", SMALL_RESERVE);
    let scratch = tempfile::tempdir().expect("scratch");
    let corpus = scratch.path().join("corpus");
    // The sessions' folders on a disk of their own: a remount needs no file open for
    // writing on it, and a session's log is closed when the session ends.
    let disk = Tmpfs::mount(&corpus.join("sessions"), 1024);
    let server = TestServer::start_with(bundle.path(), |o| o.corpus_dir = corpus.clone()).await;
    let mut op = server.operator().await;
    let mut acknowledged = Vec::new();
    for mark in ["session_start", "session_end"] {
        op.send(json!({"type": "mark", "mark": mark})).await;
        op.recv_type("marked").await;
        let ok = server.trigger("OK", json!({})).await;
        acknowledged.push(ok["trigger"].as_u64().expect("trigger id"));
    }
    disk.remount(false);
    // A kiosk that comes now is asked to record the next session once it can be stored.
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk", "name": "kiosk"}))
        .await;

    // The next session's folder cannot be made: its start is carried out, not confirmed.
    op.send(json!({"type": "mark", "mark": "session_start", "ref": "ro"}))
        .await;
    let answer = op.recv_where(|f| f["ref"] == "ro").await;
    assert_eq!(answer["code"], "corpus-unwritable", "{answer}");
    let told = op.event("corpus.unwritable").await;
    assert_eq!(told["fault"], "read-only", "{told}");
    let words = told["message"].as_str().expect("words").to_owned();
    assert!(
        words.starts_with(&format!(
            "The corpus disk is read-only ({})",
            server.corpus.display()
        )),
        "{words}"
    );
    refused_while_failing(&server, &words).await;

    disk.remount(true);
    op.event("corpus.writable").await;
    // The session begun meanwhile is recorded from now on.
    let record = kiosk.recv_type("record").await;
    assert_eq!(record["file"], "media/audio-1.webm", "{record}");
    let ok = server.trigger("OK", json!({"ref": "after"})).await;
    acknowledged.push(ok["trigger"].as_u64().expect("trigger id"));
    op.send(json!({"type": "mark", "mark": "session_end"}))
        .await;
    op.recv_type("marked").await;

    let corpus = server.corpus.clone();
    let lines = server.stop().await;
    complete_log(&corpus, &acknowledged);
    assert_eq!(
        of_type(&lines, "session.started").len(),
        2,
        "the refused start is logged"
    );
    assert_eq!(of_type(&lines, "corpus.writable").len(), 1);
    drop(disk);
}

#[tokio::test]
async fn a_corpus_folder_removed_mid_session_is_made_again_and_the_operator_told() {
    let bundle = TempBundle::new(ACTS);
    let server = TestServer::start(bundle.path()).await;
    let mut op = server.operator().await;
    op.send(json!({"type": "mark", "mark": "session_start"}))
        .await;
    op.recv_type("marked").await;
    server.trigger("OK", json!({"ref": "before"})).await;
    remove_all(&server.corpus);

    let mut acknowledged = Vec::new();
    for n in 0..3 {
        let ok = server
            .trigger("OK", json!({"ref": format!("after{n}")}))
            .await;
        acknowledged.push(ok["trigger"].as_u64().expect("trigger id"));
    }
    // The session's log was open: found removed after the next write, and written again.
    let told = op.event("corpus.recreated").await;
    let session_log = told["path"].as_str().unwrap_or_default().to_owned();
    assert!(session_log.ends_with("/events.jsonl"), "{told}");
    let message = told["message"].as_str().unwrap_or_default();
    assert!(
        message.contains("was removed while Docent was running: Docent made it again"),
        "{told}"
    );
    op.send(json!({"type": "mark", "mark": "session_end"}))
        .await;
    op.recv_type("marked").await;
    let folder = Path::new(&session_log).parent().expect("session folder");
    let manifest: Value =
        serde_json::from_slice(&std::fs::read(folder.join("session.json")).expect("manifest"))
            .expect("JSON");
    assert!(manifest["ended"].is_object(), "{manifest}");
    // The day log was closed during the session: found missing when opened again.
    let ok = server.trigger("OK", json!({"ref": "between"})).await;
    acknowledged.push(ok["trigger"].as_u64().expect("trigger id"));
    let day = op.event("corpus.recreated").await;
    let day_log = day["path"].as_str().unwrap_or_default().to_owned();
    assert!(day_log.contains("/days/"), "{day}");
    assert!(Path::new(&day_log).is_file(), "{day_log} made again");

    let lines = server.stop().await;
    // What was removed is gone; from the first line written again on, nothing is missing.
    let first = lines[0]["seq"].as_u64().expect("seq");
    let seqs: Vec<u64> = lines
        .iter()
        .map(|e| e["seq"].as_u64().expect("seq"))
        .collect();
    assert_eq!(seqs, (first..first + seqs.len() as u64).collect::<Vec<_>>());
    for trigger in &acknowledged {
        assert!(
            lines
                .iter()
                .any(|e| e["type"] == "act.triggered" && e["trigger"] == *trigger),
            "trigger {trigger}, acknowledged after the removal, is not in the log"
        );
    }
    assert_eq!(of_type(&lines, "corpus.recreated").len(), 2);
}

/// PUTs chunk `seq` of the recording a `record` frame asked for.
async fn put_chunk(server: &TestServer, record: &Value, seq: u64, body: &[u8]) -> (u16, Value) {
    let url = server.url(&format!(
        "{}{seq}",
        record["upload"].as_str().expect("upload")
    ));
    let response = reqwest::Client::new()
        .put(url)
        .bearer_auth(record["token"].as_str().expect("token"))
        .body(body.to_vec())
        .send()
        .await
        .expect("PUT");
    let status = response.status().as_u16();
    (status, response.json().await.unwrap_or(Value::Null))
}

#[tokio::test]
async fn a_recording_pauses_while_the_corpus_disk_is_full_and_goes_on_once_space_is_back() {
    let bundle = TempBundle::new(ACTS).with_file("docent.yaml", SMALL_RESERVE);
    let scratch = tempfile::tempdir().expect("scratch");
    let disk = Tmpfs::mount(&scratch.path().join("corpus"), 1024);
    let server = TestServer::start_with(bundle.path(), |o| {
        o.corpus_dir = scratch.path().join("corpus");
        o.media_cache = scratch.path().join("media-cache");
    })
    .await;
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk", "name": "kiosk"}))
        .await;
    let mut op = server.operator().await;
    op.send(json!({"type": "mark", "mark": "session_start"}))
        .await;
    op.recv_type("marked").await;
    let record = kiosk.recv_type("record").await;
    assert_eq!(put_chunk(&server, &record, 0, b"HEAD").await.0, 200);

    let filler = server.corpus.join("filler");
    disk.fill_leaving(&filler, 0);
    trigger_until_refused(&server).await;
    op.event("corpus.unwritable").await;
    let (status, paused) = put_chunk(&server, &record, 1, b"BODY").await;
    assert_eq!(
        (status, paused["code"].as_str()),
        (503, Some("corpus-unwritable")),
        "{paused}"
    );
    let error = paused["error"].as_str().unwrap_or_default();
    assert!(error.contains("The recording pauses"), "{paused}");

    std::fs::remove_file(&filler).expect("space freed");
    op.event("corpus.writable").await;
    let (status, stored) = put_chunk(&server, &record, 1, b"BODY").await;
    assert_eq!((status, &stored["next"]), (200, &json!(2)), "{stored}");
    server.stop().await;
    drop(disk);
}
