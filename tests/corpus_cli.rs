//! `docent corpus list | show | purge`, the real binary run against a corpus that real
//! servers recorded: sessions ended (marked, and by a shutdown), one being recorded by a
//! server in another process (which holds its log's lock), one that server left open when it
//! was killed with SIGKILL, and hand-made damaged folders. Outputs, exit codes and the files
//! left behind are checked; nothing is mocked.

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use common::process::spawn_docent;
use common::{TempBundle, TestServer, WsClient};
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

/// `docent corpus ARGS --corpus CORPUS`: exit status, stdout, stderr.
fn corpus_cmd(corpus: &Path, args: &[&str]) -> (i32, String, String) {
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
fn snapshot(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
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
fn events_by_type(log: &Path) -> BTreeMap<String, u64> {
    let mut counts = BTreeMap::new();
    for line in std::fs::read_to_string(log).unwrap().lines() {
        let event: Value = serde_json::from_str(line).unwrap();
        *counts
            .entry(event["type"].as_str().unwrap().to_owned())
            .or_default() += 1;
    }
    counts
}

fn events(log: &Path) -> u64 {
    events_by_type(log).values().sum()
}

/// Every folder in `corpus/sessions/`.
fn session_dirs(corpus: &Path) -> Vec<PathBuf> {
    match std::fs::read_dir(corpus.join("sessions")) {
        Ok(entries) => entries.map(|e| e.unwrap().path()).collect(),
        Err(_) => Vec::new(),
    }
}

/// The session folders of `corpus` (one run's), by their number within the run.
fn sessions_by_number(corpus: &Path) -> BTreeMap<u64, (String, PathBuf)> {
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

async fn marked(op: &mut WsClient, mark: &str, value: Option<&str>) {
    let mut frame = json!({"type": "mark", "mark": mark});
    if let Some(value) = value {
        frame["value"] = value.into();
    }
    op.send(frame).await;
    op.recv_type("marked").await;
}

/// Triggers WELCOME and waits for its answer and for its speech to be done (in either order).
async fn welcome(op: &mut WsClient) {
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
async fn recorded_run(bundle: &Path, corpus: &Path) {
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
struct ServerProcess(std::process::Child);

impl ServerProcess {
    /// `kill -9`, and waits until it is gone.
    fn kill(&mut self) {
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
async fn recording_server(bundle: &Path, corpus: &Path) -> (ServerProcess, WsClient, PathBuf) {
    let before = session_dirs(corpus);
    let (child, addr) = spawn_docent(bundle, corpus);
    let child = ServerProcess(child);
    let mut op = WsClient::connect(&format!("ws://{addr}/ws")).await;
    op.send(json!({"type": "hello", "role": "operator", "token": common::OPERATOR_TOKEN}))
        .await;
    op.recv_type("welcome").await;
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
fn damaged_sessions(corpus: &Path, model: &Path) -> (PathBuf, PathBuf) {
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

/// The rows of `list` as columns (split on two spaces or more), header and summary left out.
fn rows(out: &str) -> Vec<Vec<String>> {
    let lines: Vec<&str> = out.lines().collect();
    assert!(lines[0].starts_with("SESSION"), "{out}");
    lines[1..lines.len() - 1]
        .iter()
        .map(|l| {
            l.split("  ")
                .map(str::trim)
                .filter(|c| !c.is_empty())
                .map(str::to_owned)
                .collect()
        })
        .collect()
}

#[tokio::test]
async fn list_gives_each_session_its_state_events_and_group_oldest_first() {
    let b = tour();
    let folder = tempfile::tempdir().unwrap();
    let corpus = folder.path();
    recorded_run(b.path(), corpus).await;
    let recorded = sessions_by_number(corpus);
    let (a_name, a_dir) = recorded[&1].clone();
    let (b_name, b_dir) = recorded[&2].clone();
    let (bad, bare) = damaged_sessions(corpus, &a_dir);
    let (mut child, _op, running) = recording_server(b.path(), corpus).await;
    let c_name = running.file_name().unwrap().to_str().unwrap().to_owned();
    let c_events = events(&running.join("events.jsonl")).to_string();

    let (code, out, err) = corpus_cmd(corpus, &["list"]);
    assert_eq!(code, 0, "{err}");
    let table = rows(&out);
    let names: Vec<&str> = table.iter().map(|r| r[0].as_str()).collect();
    assert_eq!(
        names,
        [
            "2000-01-01T00-00-00Z",
            "2000-01-01T00-00-00Z-1",
            &a_name,
            &b_name,
            &c_name
        ]
    );
    let a_events = events(&a_dir.join("events.jsonl")).to_string();
    let b_events = events(&b_dir.join("events.jsonl")).to_string();
    // Columns: name, start, duration, state, events, group[, problem].
    let (a, b_row, c) = (&table[2], &table[3], &table[4]);
    assert_eq!(
        (a[3].as_str(), &a[4], a[5].as_str()),
        ("ended", &a_events, "children")
    );
    assert_eq!(
        (b_row[3].as_str(), &b_row[4], b_row[5].as_str()),
        ("ended", &b_events, "-")
    );
    assert_eq!(
        (c[2].as_str(), c[3].as_str(), &c[4], c[5].as_str()),
        ("open", "recording", &c_events, "group")
    );
    let manifest = SessionManifest::read_from(&a_dir).unwrap();
    assert_eq!(a[1], manifest.started.time[..19].replacen('T', " ", 1));
    assert!(a[2].ends_with('s'), "a duration: {a:?}");
    let bad_row = &table[0];
    assert_eq!(
        (
            bad_row[3].as_str(),
            bad_row[5].as_str(),
            bad_row[6].as_str()
        ),
        (
            "damaged",
            "children",
            "events.jsonl:3: a JSON line cut short at column 24"
        )
    );
    assert_eq!(bad_row[4], a_events, "the bad line is not an event");
    let bare_row = &table[1];
    assert_eq!(
        (
            bare_row[1].as_str(),
            bare_row[3].as_str(),
            bare_row[6].as_str()
        ),
        (a[1].as_str(), "damaged", "session.json is missing")
    );
    let summary = out.lines().last().unwrap();
    assert!(
        summary.starts_with("5 sessions (2 ended, 1 recording, 2 damaged), 2 day logs, "),
        "{summary}"
    );
    assert!(
        summary.ends_with(&format!(" in {}", corpus.display())),
        "{summary}"
    );

    child.kill();
    let (code, out, _) = corpus_cmd(corpus, &["list"]);
    assert_eq!(code, 0);
    let c = &rows(&out)[4];
    assert_eq!(
        (c[2].as_str(), c[3].as_str(), &c[4]),
        ("interrupted", "interrupted", &c_events)
    );
    assert!(
        out.contains("5 sessions (2 ended, 1 interrupted, 2 damaged), 2 day logs, "),
        "{out}"
    );
    drop((bad, bare));
}

#[tokio::test]
async fn show_tells_a_session_in_words_with_its_events_by_type_and_its_files() {
    let b = tour();
    let folder = tempfile::tempdir().unwrap();
    let corpus = folder.path();
    recorded_run(b.path(), corpus).await;
    let (name, dir) = sessions_by_number(corpus)[&1].clone();
    let manifest = SessionManifest::read_from(&dir).unwrap();
    let ended = manifest.ended.clone().unwrap();
    let log = dir.join("events.jsonl");
    let last: Value = serde_json::from_str(
        std::fs::read_to_string(&log)
            .unwrap()
            .lines()
            .last()
            .unwrap(),
    )
    .unwrap();

    let (code, out, err) = corpus_cmd(corpus, &["show", &name]);
    assert_eq!(code, 0, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    let by_type = events_by_type(&log);
    let mut expected = vec![
        format!("session   {name}"),
        format!("folder    {}", dir.display()),
        "state     ended".to_owned(),
        format!("bundle    {}", manifest.bundle.unwrap()),
        format!("docent    {}", env!("CARGO_PKG_VERSION")),
        format!("started   {} by operator", manifest.started.time),
        format!("ended     {} by operator (its end was marked)", ended.time),
        "group     children".to_owned(),
        "context   TextChild".to_owned(),
    ];
    let us = last["session_us"].as_u64().unwrap();
    assert_eq!(us, ended.mono_us - manifest.started.mono_us);
    assert_eq!(&lines[..expected.len()], &expected[..], "{out}");
    let duration = lines[expected.len()];
    assert!(
        duration.starts_with("duration  ")
            && duration.ends_with("s (on the session clock: session_us of its last line)"),
        "{duration}"
    );
    expected.clear();
    expected.push(format!("events    {}", by_type.values().sum::<u64>()));
    let width = by_type.keys().map(String::len).max().unwrap();
    expected.extend(
        by_type
            .iter()
            .map(|(kind, n)| format!("  {kind:<width$}  {n:>6}")),
    );
    expected.push("files".to_owned());
    let sizes =
        ["events.jsonl", "session.json"].map(|f| std::fs::metadata(dir.join(f)).unwrap().len());
    expected.push(format!("  events.jsonl  {:>10} bytes", sizes[0]));
    expected.push(format!("  session.json  {:>10} bytes", sizes[1]));
    expected.push(format!("  2 files, {} bytes", sizes[0] + sizes[1]));
    let start = lines.len() - expected.len();
    assert_eq!(&lines[start..], &expected[..], "{out}");
    assert_eq!(by_type["act.triggered"], 2);

    // The folder's path names the same session.
    let (code, by_path, _) = corpus_cmd(corpus, &["show", dir.to_str().unwrap()]);
    assert_eq!((code, by_path), (0, out));
}

#[tokio::test]
async fn show_of_a_damaged_session_says_what_is_wrong_and_what_it_still_knows() {
    let b = tour();
    let folder = tempfile::tempdir().unwrap();
    let corpus = folder.path();
    recorded_run(b.path(), corpus).await;
    let (_, model) = sessions_by_number(corpus)[&1].clone();
    let manifest = SessionManifest::read_from(&model).unwrap();
    damaged_sessions(corpus, &model);

    let (code, out, err) = corpus_cmd(corpus, &["show", "2000-01-01T00-00-00Z"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("\nstate     damaged (see the problems below)\n"),
        "{out}"
    );
    assert!(
        out.ends_with("problems\n  events.jsonl:3: a JSON line cut short at column 24\n"),
        "{out}"
    );

    let (code, out, _) = corpus_cmd(corpus, &["show", "2000-01-01T00-00-00Z-1"]);
    assert_eq!(code, 0);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines[3], "manifest  none readable (see the problems below)");
    assert_eq!(
        lines[4],
        format!("started   {} (from its first line)", manifest.started.time)
    );
    assert_eq!(lines[5], "ended     its log's last line ends it");
    assert!(
        out.ends_with("problems\n  session.json is missing\n"),
        "{out}"
    );
}

#[tokio::test]
async fn purge_removes_every_file_of_the_session_and_nothing_else() {
    let b = tour();
    let folder = tempfile::tempdir().unwrap();
    let corpus = folder.path();
    recorded_run(b.path(), corpus).await;
    let (name, dir) = sessions_by_number(corpus)[&1].clone();
    // What later slices will keep there: media in a folder of its own.
    std::fs::create_dir_all(dir.join("media")).unwrap();
    std::fs::write(dir.join("media/kiosk-0001.webm"), vec![7u8; 1500]).unwrap();
    let before = snapshot(corpus);
    let session = PathBuf::from("sessions").join(&name);
    let size = |f: &str| before[&session.join(f)].len();

    let (code, out, err) = corpus_cmd(corpus, &["purge", &name]);
    assert_eq!(code, 0, "{err}");
    let total = size("events.jsonl") + size("media/kiosk-0001.webm") + size("session.json");
    let expected = [
        format!(
            "removed sessions/{name}/events.jsonl  ({} bytes)",
            size("events.jsonl")
        ),
        format!("removed sessions/{name}/media/kiosk-0001.webm  (1500 bytes)"),
        format!(
            "removed sessions/{name}/session.json  ({} bytes)",
            size("session.json")
        ),
    ];
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(&lines[..3], &expected[..], "{out}");
    assert!(
        lines[3].starts_with(&format!("purged session {name}: 3 files, {total} bytes (")),
        "{out}"
    );
    assert!(
        lines[3].ends_with(&format!(
            "; sessions/{name} and 1 folder inside it removed with it, nothing else touched"
        )),
        "{out}"
    );
    assert!(!dir.exists());
    let mut rest = before;
    rest.retain(|path, _| !path.starts_with(&session));
    assert_eq!(snapshot(corpus), rest, "everything else is as it was");

    let (code, _, err) = corpus_cmd(corpus, &["purge", &name]);
    assert_eq!(code, 1);
    assert!(
        err.starts_with(&format!(
            "docent: no session {name} in {}",
            corpus.display()
        )),
        "{err}"
    );
}

#[tokio::test]
async fn purge_refuses_a_session_being_recorded_and_takes_it_once_its_server_was_killed() {
    let b = tour();
    let folder = tempfile::tempdir().unwrap();
    let corpus = folder.path();
    let (mut child, _op, running) = recording_server(b.path(), corpus).await;
    let name = running.file_name().unwrap().to_str().unwrap().to_owned();
    let before = snapshot(corpus);

    let (code, out, err) = corpus_cmd(corpus, &["purge", &name]);
    assert_eq!((code, out.as_str()), (1, ""));
    assert_eq!(
        err,
        format!(
            "docent: session {name} is being recorded by a running server (its events.jsonl is \
             locked): end the session from the operator console, or stop the server, then purge \
             it; nothing was removed\n"
        )
    );
    // The server still runs and may append (logs only grow): every file is still there,
    // holding at least what it held.
    let after = snapshot(corpus);
    assert_eq!(
        after.keys().collect::<Vec<_>>(),
        before.keys().collect::<Vec<_>>()
    );
    for (path, bytes) in &before {
        assert!(
            after[path].starts_with(bytes),
            "{} lost bytes",
            path.display()
        );
    }

    child.kill();
    let (code, out, err) = corpus_cmd(corpus, &["purge", &name]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains(&format!("removed sessions/{name}/events.jsonl  (")),
        "{out}"
    );
    assert!(!running.exists());
    assert!(corpus.join("days").exists(), "the day log stays");
}

#[tokio::test]
async fn purge_refuses_anything_but_a_session_folder_of_the_corpus() {
    let b = tour();
    let folder = tempfile::tempdir().unwrap();
    let corpus = folder.path();
    recorded_run(b.path(), corpus).await;
    let (name, dir) = sessions_by_number(corpus)[&1].clone();
    let elsewhere = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(elsewhere.path().join("sessions/x")).unwrap();
    std::fs::write(elsewhere.path().join("sessions/x/events.jsonl"), "{}\n").unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(
        elsewhere.path().join("sessions/x"),
        corpus.join("sessions/linked"),
    )
    .unwrap();
    let before = snapshot(corpus);
    let outside = snapshot(elsewhere.path());

    let not_a_session = |arg: &str| {
        format!(
            "docent: `{arg}` is not a session of {c}: name a session by its folder in {c}/sessions \
             (`docent corpus list` lists them), or give that folder's path\n",
            c = corpus.display()
        )
    };
    let other_corpus = elsewhere.path().join("sessions/x");
    let through_days = format!("{}/sessions/../days", corpus.display());
    for arg in [
        "..",
        "../x",
        "sessions/..",
        other_corpus.to_str().unwrap(),
        &through_days,
    ] {
        let (code, _, err) = corpus_cmd(corpus, &["purge", arg]);
        assert_eq!((code, err), (1, not_a_session(arg)), "{arg}");
    }
    let (code, _, err) = corpus_cmd(corpus, &["purge", "days"]);
    assert_eq!(
        (code, err),
        (
            1,
            format!(
                "docent: no session days in {}; `docent corpus list` lists the sessions\n",
                corpus.display()
            )
        )
    );
    // One letter short: no session has that name, and this one is the closest.
    let typo = name.trim_end_matches('Z').to_owned();
    let (code, _, err) = corpus_cmd(corpus, &["purge", &typo]);
    assert_eq!(code, 1);
    assert!(
        err.contains(&format!(
            "no session {typo} in {} (did you mean {name}?)",
            corpus.display()
        )),
        "{err}"
    );
    #[cfg(unix)]
    {
        let (code, _, err) = corpus_cmd(corpus, &["purge", "linked"]);
        assert_eq!(code, 1);
        assert!(
            err.contains("sessions/linked is a symbolic link, not a folder"),
            "{err}"
        );
    }
    assert_eq!(snapshot(corpus), before, "nothing in the corpus removed");
    assert_eq!(
        snapshot(elsewhere.path()),
        outside,
        "nothing outside it removed"
    );
    assert!(dir.exists());
}

#[test]
fn a_missing_corpus_is_an_error_naming_it_and_an_empty_one_is_said_plainly() {
    let folder = tempfile::tempdir().unwrap();
    let missing = folder.path().join("no-corpus-here");
    for args in [&["list"][..], &["show", "x"], &["purge", "x"]] {
        let (code, out, err) = corpus_cmd(&missing, args);
        assert_eq!((code, out.as_str()), (1, ""), "{args:?}");
        assert!(
            err.starts_with(&format!(
                "docent: there is no corpus folder at {}: ",
                missing.display()
            )),
            "{err}"
        );
    }
    let (code, out, _) = corpus_cmd(folder.path(), &["list"]);
    assert_eq!(
        (code, out),
        (
            0,
            format!(
                "no sessions in {} (0 day logs, 0 B)\n",
                folder.path().display()
            )
        )
    );
    std::fs::create_dir_all(folder.path().join("days/2026-11-24")).unwrap();
    std::fs::write(
        folder.path().join("days/2026-11-24/09-12-00Z.jsonl"),
        vec![b'\n'; 100],
    )
    .unwrap();
    let (code, out, _) = corpus_cmd(folder.path(), &["list"]);
    assert_eq!(
        (code, out),
        (
            0,
            format!(
                "no sessions in {} (1 day log, 100 B)\n",
                folder.path().display()
            )
        )
    );
}
