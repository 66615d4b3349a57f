//! A log that cannot be written refuses triggers and loses nothing acknowledged, on the real
//! binary and a real file system: `docent` runs under a 64 KiB file size limit (`ulimit -f`,
//! with `SIGXFSZ` ignored, so a write beyond it fails with `EFBIG` as a full disk would). It is
//! triggered over HTTP until it answers `503 corpus-unwritable` (the request that met the limit
//! is carried out but not confirmed; the next is refused). The server keeps serving, and says
//! why in the operator's words (`/api/state`'s `corpus`, the `corpus.unwritable` event); every
//! trigger it answered `202` is in the log, every line written is whole. The limit never goes
//! away, so the events kept in memory are lost at the stop: the run ends with exit status 1.

use crate::common;

use std::process::Command;

use common::TempBundle;
use common::WsClient;
use common::process::{serve_args, start};
use serde_json::{Value, json};

const LIMIT_KIB: u64 = 64;
/// Far more triggers than the limit holds (each writes about 1.5 KB of events).
const MAX_TRIGGERS: usize = 5_000;

#[tokio::test]
async fn a_log_that_cannot_grow_refuses_triggers_and_keeps_every_acknowledged_one() {
    let bundle = TempBundle::new("- Label: OK\n  Cmds: [DISPLAY_PAGE index.html]\n")
        .with_file("pages/index.html", "<!doctype html><title>home</title>");
    let corpus = bundle.path().join("corpus");
    // The shell ignores SIGXFSZ (an ignored signal stays ignored across exec) and limits the
    // size of files the server writes; then it becomes the server.
    let mut command = Command::new("bash");
    command
        .arg("-c")
        .arg(format!(
            "trap '' XFSZ; ulimit -f {LIMIT_KIB}; exec \"$0\" \"$@\""
        ))
        .arg(env!("CARGO_BIN_EXE_docent"))
        .args(serve_args(bundle.path(), &corpus));
    let (mut child, addr) = start(command);
    let mut op = WsClient::operator_at(&addr).await;

    let client = reqwest::Client::new();
    let url = format!("http://{addr}/api/acts/OK/trigger");
    let mut acknowledged = Vec::new();
    let mut refusal = None;
    for n in 0..MAX_TRIGGERS {
        let answer = (client.post(&url))
            .json(&json!({"ref": format!("t{n}")}))
            .send()
            .await
            .expect("the server answers");
        let status = answer.status().as_u16();
        let body: Value = answer.json().await.expect("a JSON body");
        match status {
            202 => acknowledged.push(body["trigger"].as_u64().expect("trigger id")),
            _ => {
                refusal = Some((status, body));
                break;
            }
        }
    }
    let (status, body) = refusal.expect("the full log refuses a trigger");
    assert_eq!(status, 503, "{body}");
    assert_eq!(body["code"], "corpus-unwritable", "{body}");
    // The request whose events met the limit was carried out, and says it is not confirmed.
    let error = body["error"].as_str().unwrap_or_default();
    assert!(error.contains("File too large"), "names the cause: {body}");
    // From then on triggers are refused before anything is carried out.
    let next = (client.post(&url))
        .json(&json!({"ref": "after"}))
        .send()
        .await
        .expect("the server answers");
    assert_eq!(next.status().as_u16(), 503);
    let next: Value = next.json().await.expect("a JSON body");
    assert_eq!(next["code"], "corpus-unwritable", "{next}");
    let not_triggered = next["error"].as_str().unwrap_or_default();
    assert!(not_triggered.starts_with("not triggered"), "{next}");
    eprintln!("first refusal: {body}\nnext: {next}");
    assert!(
        acknowledged.len() > 10,
        "the log held some triggers first: {}",
        acknowledged.len()
    );

    // The server keeps serving, and the operator is told what to do.
    let told = op.event("corpus.unwritable").await;
    assert_eq!(told["fault"], "too-large", "{told}");
    let state: Value = (client.get(format!("http://{addr}/api/state")))
        .bearer_auth(common::OPERATOR_TOKEN)
        .send()
        .await
        .expect("the server answers")
        .json()
        .await
        .expect("a JSON body");
    let words = state["corpus"].as_str().expect("the operator's words");
    assert_eq!(words, told["message"], "{state}");
    assert!(words.contains("raise the file size limit"), "{words}");

    // A graceful stop: the events still waiting are lost, so the run ends with exit status 1.
    let stopped = Command::new("kill")
        .arg(child.id().to_string())
        .status()
        .expect("kill runs");
    assert!(stopped.success());
    let exit = child.wait().expect("docent exits");
    assert_eq!(exit.code(), Some(1), "{exit}");

    let logs = docent::corpus::layout::event_logs(&corpus).expect("corpus folder");
    let [log] = logs.as_slice() else {
        panic!("one day log: {logs:?}")
    };
    let bytes = std::fs::read(log).expect("the log");
    assert!(bytes.len() as u64 <= LIMIT_KIB * 1024);
    // Whole lines, parsed; a last piece without its newline was never acknowledged.
    let whole = &bytes[..bytes.iter().rposition(|b| *b == b'\n').map_or(0, |i| i + 1)];
    let events: Vec<Value> = (whole.split(|b| *b == b'\n'))
        .filter(|line| !line.is_empty())
        .map(|line| serde_json::from_slice(line).expect("a whole JSON line"))
        .collect();
    for trigger in &acknowledged {
        assert!(
            events
                .iter()
                .any(|e| e["type"] == "act.triggered" && e["trigger"] == *trigger),
            "acknowledged trigger {trigger} is not in the log"
        );
    }
    eprintln!(
        "{} triggers acknowledged before the log was full ({} bytes, {} events)",
        acknowledged.len(),
        bytes.len(),
        events.len()
    );
}
