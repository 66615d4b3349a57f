//! The corpus the `docent corpus` tests read, recorded by real servers: an in-process run
//! with two sessions ended, the real binary recording a session in another process (so the
//! log's lock is held by someone else), hand-made damaged folders; and how the tests run
//! the binary and read the files themselves.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use docent::corpus::manifest::SessionManifest;
use serde_json::{Value, json};

use crate::common::process::spawn_docent;
use crate::common::{TempBundle, TestServer, WsClient};

pub const ACTS: &str = r#"
- Label: WELCOME
  Text: [Hello!]
  TextChild: [Hi there!]
"#;

pub fn tour() -> TempBundle {
    TempBundle::new(ACTS).with_file("docent.yaml", "speech: {adapter: log}\n")
}

/// `docent corpus ARGS --corpus CORPUS`: exit status, stdout, stderr.
pub fn corpus_cmd(corpus: &Path, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_docent"))
        .arg("corpus")
        .args(args)
        .arg("--corpus")
        .arg(corpus)
        .output()
        .expect("docent runs");
    let text = |b: Vec<u8>| String::from_utf8(b).expect("UTF-8 output");
    (
        out.status.code().unwrap_or(-1),
        text(out.stdout),
        text(out.stderr),
    )
}

/// Every file under `dir` (links not followed, a link recorded as its target), with its bytes.
pub fn snapshot(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut files = BTreeMap::new();
    let mut pending = vec![dir.to_owned()];
    while let Some(folder) = pending.pop() {
        for entry in std::fs::read_dir(&folder).unwrap() {
            let path = entry.unwrap().path();
            let meta = std::fs::symlink_metadata(&path).unwrap();
            let relative = path.strip_prefix(dir).unwrap().to_owned();
            if meta.is_symlink() {
                let target = std::fs::read_link(&path).unwrap();
                files.insert(relative, target.into_os_string().into_encoded_bytes());
            } else if meta.is_dir() {
                pending.push(path);
            } else {
                files.insert(relative, std::fs::read(&path).unwrap());
            }
        }
    }
    files
}

/// The number of events in a log by type, read here line by line.
pub fn events_by_type(log: &Path) -> BTreeMap<String, u64> {
    let mut counts = BTreeMap::new();
    for line in std::fs::read_to_string(log).unwrap().lines() {
        let event: Value = serde_json::from_str(line).unwrap();
        *counts
            .entry(event["type"].as_str().unwrap().to_owned())
            .or_default() += 1;
    }
    counts
}

pub fn events(log: &Path) -> u64 {
    events_by_type(log).values().sum()
}

pub use crate::common::session_dirs;

/// The session folders of `corpus` (one run's), by their number within the run.
pub fn sessions_by_number(corpus: &Path) -> BTreeMap<u64, (String, PathBuf)> {
    let mut found = BTreeMap::new();
    let Ok(entries) = std::fs::read_dir(corpus.join("sessions")) else {
        return found;
    };
    for entry in entries {
        let dir = entry.unwrap().path();
        let Ok(manifest) = SessionManifest::read_from(&dir) else {
            continue;
        };
        found.insert(manifest.number, (manifest.session, dir));
    }
    found
}

pub async fn marked(op: &mut WsClient, mark: &str, value: Option<&str>) {
    let mut frame = json!({"type": "mark", "mark": mark});
    if let Some(value) = value {
        frame["value"] = value.into();
    }
    op.send(frame).await;
    op.recv_type("marked").await;
}

/// Triggers WELCOME and waits for its answer and for its speech to be done (in either order).
pub async fn welcome(op: &mut WsClient) {
    op.send(json!({"type": "trigger", "label": "WELCOME"}))
        .await;
    let (mut answered, mut spoken) = (false, false);
    while !(answered && spoken) {
        let frame = op.recv().await;
        answered |= frame["type"] == "triggered";
        spoken |= frame["type"] == "event" && frame["event"]["type"] == "command.done";
    }
}

/// A run of an in-process server into `corpus`: session 1 (visitor group children, two
/// welcomes, its end marked), then session 2, ended by the shutdown.
pub async fn recorded_run(bundle: &Path, corpus: &Path) {
    let server = TestServer::start_with(bundle, |o| o.corpus_dir = corpus.into()).await;
    let mut op = server.operator().await;
    marked(&mut op, "session_start", None).await;
    marked(&mut op, "group", Some("children")).await;
    welcome(&mut op).await;
    welcome(&mut op).await;
    marked(&mut op, "session_end", None).await;
    marked(&mut op, "session_start", None).await;
    welcome(&mut op).await;
    drop(op);
    server.stop().await;
}

/// The real `docent` binary, killed with SIGKILL when the test is done with it, even when the
/// test fails half-way.
pub struct ServerProcess(pub std::process::Child);

impl ServerProcess {
    /// `kill -9`, and waits until it is gone.
    pub fn kill(&mut self) {
        self.0.kill().expect("SIGKILL");
        self.0.wait().expect("the killed server is reaped");
    }
}

impl Drop for ServerProcess {
    fn drop(&mut self) {
        if let Ok(None) = self.0.try_wait() {
            self.kill();
        }
    }
}

/// The real binary serving `bundle` into `corpus`, with session 1 running (visitor group
/// `group`, one welcome, every event of it written), its operator still connected (so that
/// nothing more is logged until the test acts: a leaving client would be), and the running
/// session's folder.
pub async fn recording_server(bundle: &Path, corpus: &Path) -> (ServerProcess, WsClient, PathBuf) {
    let before = session_dirs(corpus);
    let (child, addr) = spawn_docent(bundle, corpus);
    let child = ServerProcess(child);
    let mut op = WsClient::operator_at(&addr).await;
    marked(&mut op, "session_start", None).await;
    welcome(&mut op).await;
    // Acknowledged, so every event before it is in the log.
    marked(&mut op, "group", Some("group")).await;
    let running = (session_dirs(corpus).into_iter())
        .find(|d| !before.contains(d))
        .expect("the new session's folder");
    (child, op, running)
}

/// Two hand-made damaged sessions, older than any recorded: `2000-01-01T00-00-00Z` with a
/// line in the middle that is not JSON, `2000-01-01T00-00-00Z-1` without a manifest.
pub fn damaged_sessions(corpus: &Path, model: &Path) -> (PathBuf, PathBuf) {
    let text = std::fs::read_to_string(model.join("events.jsonl")).unwrap();
    let mut lines: Vec<&str> = text.lines().collect();
    lines.insert(2, "{\"type\":\"act.triggered\",");
    let bad = corpus.join("sessions/2000-01-01T00-00-00Z");
    std::fs::create_dir_all(&bad).unwrap();
    std::fs::write(bad.join("events.jsonl"), lines.join("\n") + "\n").unwrap();
    std::fs::copy(model.join("session.json"), bad.join("session.json")).unwrap();
    let bare = corpus.join("sessions/2000-01-01T00-00-00Z-1");
    std::fs::create_dir_all(&bare).unwrap();
    std::fs::write(bare.join("events.jsonl"), &text).unwrap();
    (bad, bare)
}
