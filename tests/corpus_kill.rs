//! `kill -9` at full load loses no acknowledged event: 20 times, the real `docent` binary is
//! loaded by websocket operators (and one HTTP client) that trigger as fast as their
//! acknowledgements come, recording every acknowledged trigger, and is killed with SIGKILL in
//! the middle of it. Then every acknowledged trigger is in its run's log, every line but a
//! last unacknowledged one is whole JSON in sequence without gaps, and the logs of the earlier
//! runs are byte for byte as they were.

use crate::common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use common::process::spawn_docent;
use common::{DEADLINE, TempBundle};
use futures_util::{SinkExt, StreamExt};
use serde_json::{Value, json};
use tokio::sync::Notify;
use tokio_tungstenite::connect_async;
use tokio_tungstenite::tungstenite::Message;

const CYCLES: usize = 20;
const WS_SENDERS: usize = 4;
const ACTS: &str = "- Label: OK\n  Cmds: [DISPLAY_PAGE index.html]\n";

/// Acknowledged triggers of one run.
#[derive(Default)]
struct Tally {
    /// `ref` → trigger id.
    acked: Mutex<BTreeMap<String, u64>>,
    count: AtomicUsize,
    progress: Notify,
}

impl Tally {
    fn ack(&self, reference: String, trigger: u64) {
        self.acked.lock().unwrap().insert(reference, trigger);
        self.count.fetch_add(1, Ordering::Relaxed);
        self.progress.notify_one();
    }

    async fn reached(&self, n: usize) {
        while self.count.load(Ordering::Relaxed) < n {
            self.progress.notified().await;
        }
    }
}

/// One operator triggering `OK` as fast as the acknowledgements come, until the connection
/// dies.
async fn ws_sender(addr: String, name: String, tally: Arc<Tally>) {
    let (mut ws, _) = connect_async(format!("ws://{addr}/ws"))
        .await
        .expect("connects");
    let hello = json!({"type": "hello", "role": "operator", "events": false});
    ws.send(Message::text(hello.to_string()))
        .await
        .expect("hello");
    for n in 0.. {
        let reference = format!("{name}-{n}");
        let trigger = json!({"type": "trigger", "label": "OK", "ref": reference});
        if ws.send(Message::text(trigger.to_string())).await.is_err() {
            return;
        }
        loop {
            let Some(Ok(Message::Text(text))) = ws.next().await else {
                return;
            };
            let frame: Value = serde_json::from_str(&text).expect("JSON frame");
            match frame["type"].as_str() {
                Some("triggered") => {
                    assert_eq!(frame["ref"], reference.as_str());
                    tally.ack(reference, frame["trigger"].as_u64().expect("trigger id"));
                    break;
                }
                Some("error") => panic!("a trigger was refused: {frame}"),
                _ => {}
            }
        }
    }
}

/// The same over HTTP: a 202 is the acknowledgement.
async fn http_sender(addr: String, tally: Arc<Tally>) {
    let client = reqwest::Client::new();
    let url = format!("http://{addr}/api/acts/OK/trigger");
    for n in 0.. {
        let reference = format!("http-{n}");
        let Ok(answer) = client
            .post(&url)
            .json(&json!({"ref": reference}))
            .send()
            .await
        else {
            return;
        };
        assert_eq!(answer.status().as_u16(), 202, "{reference}");
        let Ok(body) = answer.json::<Value>().await else {
            return;
        };
        tally.ack(reference, body["trigger"].as_u64().expect("trigger id"));
    }
}

/// Every event log in the corpus folder, with a checksum of its bytes.
fn checksums(dir: &Path) -> BTreeMap<PathBuf, u64> {
    (docent::corpus::layout::event_logs(dir).expect("corpus dir"))
        .into_iter()
        .map(|path| {
            let bytes = std::fs::read(&path).expect("read");
            // FNV-1a: any change to an earlier file changes it.
            let sum = bytes.iter().fold(0xcbf29ce484222325u64, |h, b| {
                (h ^ u64::from(*b)).wrapping_mul(0x100000001b3)
            });
            (path, sum ^ bytes.len() as u64)
        })
        .collect()
}

/// The run's whole lines as JSON, and the bytes of a last line cut short, if any.
fn read_log(path: &Path) -> (Vec<Value>, Vec<u8>) {
    let bytes = std::fs::read(path).expect("log");
    let mut lines: Vec<&[u8]> = bytes.split(|b| *b == b'\n').collect();
    // The piece after the last newline: empty, or a line the kill cut short.
    let partial = lines.pop().unwrap_or_default().to_vec();
    let events = lines
        .iter()
        .map(|l| {
            serde_json::from_slice(l).unwrap_or_else(|e| {
                panic!(
                    "torn line in {path:?} ({e}): {}",
                    String::from_utf8_lossy(l)
                )
            })
        })
        .collect();
    (events, partial)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn kill_9_at_full_load_loses_no_acknowledged_trigger() {
    let bundle = TempBundle::new(ACTS).with_file("docent.yaml", "speech: {adapter: log}\n");
    let corpus = tempfile::tempdir().expect("corpus dir");
    let mut total_acked = 0;
    for cycle in 0..CYCLES {
        let before = checksums(corpus.path());
        let (mut child, addr) = spawn_docent(bundle.path(), corpus.path());
        let tally = Arc::new(Tally::default());
        let mut senders = tokio::task::JoinSet::new();
        for s in 0..WS_SENDERS {
            let name = format!("ws{s}");
            senders.spawn(ws_sender(addr.clone(), name, tally.clone()));
        }
        senders.spawn(http_sender(addr.clone(), tally.clone()));
        // Killed at a different point of each run, always in full flow.
        let kill_after = 300 + 97 * cycle;
        tokio::time::timeout(DEADLINE, tally.reached(kill_after))
            .await
            .expect("the senders get acknowledgements");
        child.kill().expect("SIGKILL");
        child.wait().expect("reaped");
        tokio::time::timeout(DEADLINE, async {
            while let Some(done) = senders.join_next().await {
                done.expect("a sender failed");
            }
        })
        .await
        .expect("the senders end with the server");

        let after = checksums(corpus.path());
        for (path, sum) in &before {
            assert_eq!(
                after.get(path),
                Some(sum),
                "an earlier log changed: {path:?}"
            );
        }
        let new: Vec<&PathBuf> = after.keys().filter(|p| !before.contains_key(*p)).collect();
        assert_eq!(new.len(), 1, "one new log per run: {new:?}");
        let (events, partial) = read_log(new[0]);
        let seqs: Vec<u64> = events.iter().map(|e| e["seq"].as_u64().unwrap()).collect();
        assert_eq!(
            seqs,
            (1..=events.len() as u64).collect::<Vec<_>>(),
            "run {cycle}"
        );
        let logged: BTreeMap<&str, u64> = (events.iter())
            .filter(|e| e["type"] == "act.triggered")
            .map(|e| (e["ref"].as_str().unwrap(), e["trigger"].as_u64().unwrap()))
            .collect();
        let acked = tally.acked.lock().unwrap();
        let missing: Vec<_> = (acked.iter())
            .filter(|(r, id)| logged.get(r.as_str()) != Some(id))
            .collect();
        assert!(
            missing.is_empty(),
            "run {cycle}: {} of {} acknowledged triggers are not in the log: {missing:?} \
             (partial last line: {:?})",
            missing.len(),
            acked.len(),
            String::from_utf8_lossy(&partial)
        );
        assert!(acked.len() >= kill_after, "run {cycle}");
        total_acked += acked.len();
    }
    assert!(total_acked >= CYCLES * 300);
}
