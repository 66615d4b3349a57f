//! A flood of triggers leaves bounded queues with every excess command answered, to its sender
//! and in the corpus, with a reason. A binary of its own: it measures the resident memory of
//! the process the server runs in, which other tests running beside it would disturb.

#[path = "common/mod.rs"]
mod common;

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

use common::TestServer;
use common::channels::{LONG_TEXT, bundle};
use serde_json::json;
use tokio_util::sync::CancellationToken;

/// Resident memory of this process, in kB (the server runs in it).
fn rss_kb() -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").expect("proc status");
    let line = status
        .lines()
        .find(|l| l.starts_with("VmRSS:"))
        .expect("VmRSS");
    line.split_whitespace()
        .nth(1)
        .and_then(|n| n.parse().ok())
        .expect("a number")
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_flood_of_operators_leaves_bounded_queues_and_every_excess_say_answered() {
    const CLIENTS: usize = 40;
    const EACH: usize = 250;
    let b = bundle();
    let server = TestServer::start(b.path()).await;
    let before = rss_kb();
    let total = CLIENTS * EACH;
    // One SAY speaks, two wait (the default queue_limit); every other one is refused at once.
    let refused = total - 3;
    // Outcomes are notices, not answers: they may come after the last answer (within 2 ms),
    // so every client reads until all of them have arrived, counted across clients.
    let told_so_far = Arc::new(AtomicUsize::new(0));
    let all_told = CancellationToken::new();
    let mut tasks = Vec::new();
    for n in 0..CLIENTS {
        let hello =
            json!({"type": "hello", "role": "operator", "name": format!("op{n}"), "events": false});
        let mut client = server.client(hello).await;
        let (told_so_far, all_told) = (Arc::clone(&told_so_far), all_told.clone());
        tasks.push(tokio::spawn(async move {
            for i in 0..EACH {
                client
                    .send(json!({"type": "trigger", "label": "LONG", "ref": i.to_string()}))
                    .await;
            }
            let (mut answered, mut cancelled) = (0, Vec::new());
            while answered < EACH || !all_told.is_cancelled() {
                let frame = tokio::select! {
                    frame = client.recv() => frame,
                    () = all_told.cancelled(), if answered == EACH => break,
                };
                match frame["type"].as_str() {
                    Some("triggered") => answered += 1,
                    Some("outcome") => {
                        cancelled.push(frame);
                        if told_so_far.fetch_add(1, Ordering::SeqCst) + 1 == refused {
                            all_told.cancel();
                        }
                    }
                    _ => {}
                }
            }
            (client, cancelled)
        }));
    }
    let mut told = Vec::new();
    let mut clients = Vec::new();
    for task in tasks {
        let (client, cancelled) = task.await.expect("client task");
        told.extend(cancelled);
        clients.push(client);
    }
    let grown_kb = rss_kb().saturating_sub(before);
    let (_, state) = server.get("/api/state").await;
    let queued = state["queues"]["log"]["queued"].as_u64().unwrap_or(0);
    assert!(
        queued <= 1,
        "the speech adapter holds one command at a time: {state}"
    );
    let speech = &state["channels"]["speech"];
    assert_eq!(
        speech["running"]["what"],
        format!("SAY {LONG_TEXT}"),
        "{speech}"
    );
    assert_eq!(speech["running"]["source"], "operator", "{speech}");
    assert_eq!(
        speech["waiting"].as_array().map(Vec::len),
        Some(2),
        "{speech}"
    );
    assert_eq!(
        told.len(),
        refused,
        "every excess SAY is answered to its sender"
    );
    for frame in &told {
        assert_eq!(frame["outcome"], "cancelled", "{frame}");
        assert_eq!(frame["ended_by_visitor"], false, "{frame}");
        let reason = frame["reason"].as_str().unwrap_or_default();
        assert!(
            reason.contains("speech queue was full (2 waiting)"),
            "{reason}"
        );
    }
    eprintln!(
        "flood: {total} SAYs from {CLIENTS} clients, {} refused, RSS grew {grown_kb} kB",
        told.len()
    );
    assert!(
        grown_kb < 64 * 1024,
        "memory stays bounded: grew {grown_kb} kB"
    );
    drop(clients);
    let corpus = server.stop().await;
    let refused = corpus
        .iter()
        .filter(|e| e["type"] == "command.cancelled")
        .filter(|e| {
            e["reason"]
                .as_str()
                .unwrap_or_default()
                .contains("queue was full")
        })
        .count();
    assert_eq!(refused, total - 3, "every refusal is in the corpus");
}
