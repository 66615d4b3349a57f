//! Consent is a state the recording path reads, not an event it might see (issue 24): against a
//! real server on 127.0.0.1:0 with a protocol client in the kiosk's place.
//!
//! - The recording controller acts on session ends and consents however far the hub's
//!   broadcast runs ahead of it: the tests publish twice the broadcast's capacity in one go
//!   (nothing else runs meanwhile on the test's single thread), which used to make it skip
//!   them.
//! - A withdrawal is carried out before its `marked` answer: the media are gone by then, and no
//!   chunk sent after it is acknowledged, while operators flood triggers and the kiosk uploads.
//! - What is left is exported without the visitors' recordings.

use crate::common;

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

use common::{DEADLINE, TempBundle, TestServer, WsClient, session_dirs};
use docent::corpus::export::{ExportFormat, ExportWarning, export_session};
use docent::events::{
    Consent, EVENT_CHANNEL_CAPACITY, EventKind, Hub, NoteWritten, SessionEnd, Source,
};
use docent::operator::Confirmation;
use docent::state::AppState;
use serde_json::{Value, json};
use tokio::sync::watch;

const ACTS: &str = "- Label: WELCOME\n  Text: [Hello!]\n";

fn site() -> TempBundle {
    TempBundle::new(ACTS)
        .with_file(
            "docent.yaml",
            "speech: {adapter: log}\ncorpus: {session_start: marked}\n",
        )
        .with_file(
            "pages/index.html",
            r#"<html><body><button data-act="WELCOME">Hello</button></body></html>"#,
        )
}

/// A server recording a session an operator started, its state, and the kiosk with its
/// `record` frame.
struct Recorded {
    server: TestServer,
    state: AppState,
    kiosk: WsClient,
    op: WsClient,
    record: Value,
    _bundle: TempBundle,
}

async fn recorded() -> Recorded {
    let bundle = site();
    let taken = Mutex::new(None);
    let server = TestServer::start_prepared(
        bundle.path(),
        |_| {},
        |s| *taken.lock().unwrap() = Some(s.state().clone()),
    )
    .await;
    let state = taken.lock().unwrap().take().expect("the server's state");
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk", "name": "kiosk"}))
        .await;
    let mut op = server.operator().await;
    op.send(json!({"type": "mark", "mark": "session_start"}))
        .await;
    op.recv_type("marked").await;
    let record = kiosk.recv_type("record").await;
    Recorded {
        server,
        state,
        kiosk,
        op,
        record,
        _bundle: bundle,
    }
}

/// PUTs chunk `seq` of the recording `record` asked for; its status.
async fn chunk(http: &reqwest::Client, server: &TestServer, record: &Value, seq: u64) -> u16 {
    let url = server.url(&format!("{}{seq}", record["upload"].as_str().unwrap()));
    let response = http
        .put(url)
        .bearer_auth(record["token"].as_str().unwrap())
        .body(vec![b'x'; 1024])
        .send()
        .await
        .expect("PUT");
    response.status().as_u16()
}

/// Publishes twice as many events as the hub's broadcast holds, without yielding: every
/// broadcast subscriber that did not run meanwhile lags past them.
fn flood(hub: &Hub) {
    for i in 0..2 * EVENT_CHANNEL_CAPACITY {
        hub.publish(EventKind::NoteWritten(NoteWritten {
            session: None,
            text: format!("flood {i}"),
            source: Source::Server,
            client: 0,
        }));
    }
}

#[tokio::test]
async fn a_session_end_in_a_flood_of_events_still_stops_the_recording() {
    let Recorded {
        server,
        state,
        mut kiosk,
        op: _op,
        record,
        _bundle,
    } = recorded().await;
    let http = reqwest::Client::new();
    assert_eq!(chunk(&http, &server, &record, 0).await, 200);
    state.visits.end(Source::Operator, None, SessionEnd::Marked);
    flood(&state.hub);
    let stop = kiosk.recv_type("record-stop").await;
    assert_eq!(
        (&stop["recording"], &stop["reason"]),
        (&record["recording"], &json!("session-ended"))
    );
    drop(kiosk);
    server.stop().await;
}

#[tokio::test]
async fn a_withdrawal_in_a_flood_of_events_still_removes_the_media() {
    let Recorded {
        server,
        state,
        mut kiosk,
        op: _op,
        record,
        _bundle,
    } = recorded().await;
    let http = reqwest::Client::new();
    assert_eq!(chunk(&http, &server, &record, 0).await, 200);
    let media = session_dirs(&server.corpus)[0].join("media");
    assert!(media.join("audio-1.webm").is_file());
    // Noted behind the recording path's back, as only the hub would tell it.
    let session = state.visits.set_consent(
        Consent::Withdrawn,
        Confirmation::Confirmed,
        Source::Operator,
        0,
    );
    assert_eq!(session, Ok(1));
    flood(&state.hub);
    let stop = kiosk.recv_type("record-stop").await;
    assert_eq!(stop["reason"], "consent");
    assert_eq!(chunk(&http, &server, &record, 1).await, 410);
    assert!(!media.exists(), "the media are removed");
    drop(kiosk);
    server.stop().await;
}

/// Sends `count` triggers over a fresh operator connection, without waiting for answers.
async fn trigger_flood(mut op: WsClient, count: usize) {
    for i in 0..count {
        op.send(json!({"type": "trigger", "label": "WELCOME", "ref": format!("f{i}")}))
            .await;
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn no_chunk_is_acknowledged_after_a_withdrawal_is_answered_and_the_export_has_no_media() {
    let Recorded {
        server,
        state: _state,
        mut kiosk,
        mut op,
        record,
        _bundle,
    } = recorded().await;
    let server = Arc::new(server);
    let mut rounds_record = Some(record);
    // Ten rounds: a session, a kiosk uploading as fast as it can, two operators flooding
    // triggers, and a withdrawal.
    for round in 0..10 {
        let record = match rounds_record.take() {
            Some(record) => record,
            None => {
                op.send(json!({"type": "mark", "mark": "session_start"}))
                    .await;
                op.recv_type("marked").await;
                kiosk.recv_type("record").await
            }
        };
        let answered = Arc::new(AtomicBool::new(false));
        // How many chunks the server stored (a 200 comes once a chunk is appended).
        let (stored_tx, mut stored) = watch::channel(0);
        let uploader = tokio::spawn({
            let (server, record, answered) =
                (Arc::clone(&server), record.clone(), Arc::clone(&answered));
            async move {
                let http = reqwest::Client::new();
                let mut after = Vec::new();
                for seq in 0.. {
                    let sent_after_answer = answered.load(Ordering::SeqCst);
                    let status = chunk(&http, &server, &record, seq).await;
                    if sent_after_answer && status != 410 {
                        after.push((seq, status));
                    }
                    if status == 410 {
                        return after;
                    }
                    assert_eq!(status, 200, "chunk {seq}");
                    stored_tx.send_replace(seq + 1);
                }
                after
            }
        });
        let flooders = [server.operator().await, server.operator().await]
            .map(|op| tokio::spawn(trigger_flood(op, 300)));
        // Some chunks first, so that there is something to remove: four stored (4 KiB).
        tokio::time::timeout(DEADLINE, stored.wait_for(|chunks| *chunks >= 4))
            .await
            .expect("four chunks stored within the deadline")
            .expect("the uploader ended before four chunks were stored");
        let media = session_dirs(&server.corpus)
            .into_iter()
            .max()
            .unwrap()
            .join("media");
        let audio = std::fs::metadata(media.join("audio-1.webm")).expect("the audio is written");
        assert!(audio.len() >= 4096, "{} bytes", audio.len());
        op.send(json!({"type": "mark", "mark": "consent", "value": "withdrawn", "confirm": true, "ref": "w"}))
            .await;
        op.recv_where(|f| f["type"] == "marked" && f["ref"] == "w")
            .await;
        answered.store(true, Ordering::SeqCst);
        assert!(
            !media.exists(),
            "round {round}: the media are gone when the mark is answered"
        );
        let after = uploader.await.unwrap();
        assert_eq!(
            after,
            [],
            "round {round}: chunks sent after the answer were taken"
        );
        for flooder in flooders {
            flooder.await.unwrap();
        }
        op.send(json!({"type": "mark", "mark": "session_end"}))
            .await;
        op.recv_type("marked").await;
    }
    drop((kiosk, op));
    let corpus = server.corpus.clone();
    Arc::into_inner(server)
        .expect("the only handle")
        .stop()
        .await;
    for dir in session_dirs(&corpus) {
        let out = tempfile::tempdir().unwrap();
        let exported = export_session(&dir, ExportFormat::Eaf, out.path()).unwrap();
        assert_eq!(
            exported.files.len(),
            1,
            "only the EAF: {:?}",
            exported.files
        );
        assert!(
            (exported.warnings.iter()).any(|w| matches!(w, ExportWarning::MediaWithheld { .. })),
            "{:?}",
            exported.warnings
        );
    }
}
