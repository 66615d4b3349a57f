//! Live reload with a real server on `127.0.0.1:0` watching a bundle in a temporary folder:
//! good saves go live, broken ones are refused while the last good bundle keeps answering, and
//! clients triggering all the while (HTTP and websocket) get every answer they would have got
//! without a reload. Every wait is for an event or a frame, never a pause.

use crate::common;

use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use common::{OPERATOR_TOKEN, TempBundle, TestServer, WsClient};
use docent::reload::ReloadOptions;
use docent::serve::Server;
use serde_json::{Value, json};
use tokio::task::JoinHandle;

/// Short, so the tests run quickly; editors' bursts are not what is tested here.
const TEST_DEBOUNCE: Duration = Duration::from_millis(50);

fn acts(text: &str) -> String {
    format!("- Label: GREET\n  Text:\n    - {text}\n  TextChild:\n    - Hi, {text}\n")
}

const BROKEN: &str = "- Label: GREET\n  Text:\n    - Hello broken\n  Cmds:\n    - FLY_AWAY now\n";
const HOME: &str = "<!doctype html><title>home</title><button data-act=\"GREET\">hi</button>";

/// A server watching its bundle.
struct Watched(TestServer);

impl std::ops::Deref for Watched {
    type Target = TestServer;

    fn deref(&self) -> &TestServer {
        &self.0
    }
}

impl Watched {
    async fn start(bundle: &Path) -> Self {
        let watch = |server: &Server| {
            server.watch(ReloadOptions {
                debounce: TEST_DEBOUNCE,
                ..ReloadOptions::default()
            });
        };
        Watched(TestServer::start_prepared(bundle, |_| {}, watch).await)
    }

    /// What GREET says now, triggered over HTTP.
    async fn said(&self) -> String {
        let (status, body) = http_trigger(self.addr, &reqwest::Client::new()).await;
        assert_eq!(status, 202, "{body}");
        body["text"].as_str().expect("a text").to_owned()
    }

    async fn stop(self) {
        self.0.stop().await;
    }
}

async fn http_trigger(addr: std::net::SocketAddr, http: &reqwest::Client) -> (u16, Value) {
    let answer = http
        .post(format!("http://{addr}/api/acts/GREET/trigger"))
        .bearer_auth(OPERATOR_TOKEN)
        .json(&json!({"interrupt": true}))
        .send()
        .await
        .expect("POST");
    let status = answer.status().as_u16();
    (status, answer.json().await.unwrap_or(Value::Null))
}

/// Triggers GREET over HTTP until told to stop; returns every answer's status and text.
fn http_loop(addr: std::net::SocketAddr, stop: Arc<AtomicBool>) -> JoinHandle<Vec<(u16, Value)>> {
    tokio::spawn(async move {
        let http = reqwest::Client::new();
        let mut answers = Vec::new();
        while !stop.load(Ordering::Relaxed) {
            let (status, body) = http_trigger(addr, &http).await;
            answers.push((status, body["text"].clone()));
        }
        answers
    })
}

/// Triggers GREET over a websocket until told to stop; returns every answer frame.
fn ws_loop(mut client: WsClient, stop: Arc<AtomicBool>) -> JoinHandle<Vec<Value>> {
    tokio::spawn(async move {
        let mut answers = Vec::new();
        let mut n = 0;
        while !stop.load(Ordering::Relaxed) {
            n += 1;
            let reference = format!("t{n}");
            client
                .send(json!({"type": "trigger", "label": "GREET", "interrupt": true, "ref": reference}))
                .await;
            // The answer to the trigger; `outcome` frames about its commands (another client's
            // interrupting trigger may cut its speech short) are not answers.
            let answer = client
                .recv_where(|f| f["ref"] == reference && f["type"] != "outcome")
                .await;
            answers.push(answer);
        }
        answers
    })
}

/// The texts said, in order, must only move forward through `order` and never be `never`.
fn assert_progression(texts: &[String], order: &[&str], never: &str) {
    let mut at = 0;
    for text in texts {
        assert_ne!(text, never, "a refused bundle was live");
        let i = (order.iter().position(|o| o == text))
            .unwrap_or_else(|| panic!("unexpected text {text:?}"));
        assert!(i >= at, "went back from {:?} to {text:?}", order[at]);
        at = i;
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn triggers_across_good_and_broken_saves_all_get_their_normal_answer() {
    let bundle = TempBundle::new(&acts("Hello one")).with_file("pages/index.html", HOME);
    let server = Watched::start(bundle.path()).await;
    let mut watcher = server.operator().await;
    assert_eq!(watcher.welcome["state"]["reload"]["refused"], Value::Null);
    let stop = Arc::new(AtomicBool::new(false));
    let quiet = json!({"type": "hello", "role": "operator", "events": false});
    let ws = ws_loop(server.client(quiet).await, Arc::clone(&stop));
    let http = http_loop(server.addr, Arc::clone(&stop));
    assert_eq!(server.said().await, "Hello one");

    // A good save goes live.
    std::fs::write(bundle.path().join("acts.yaml"), acts("Hello two")).expect("save");
    let live = watcher.event("bundle.reloaded").await;
    assert_eq!(live["acts"], 1);
    assert_eq!(live["changed"], json!(["acts.yaml"]));
    assert_eq!(server.said().await, "Hello two");

    // A broken save is refused: the old text is still what is said, and the problem is told.
    std::fs::write(bundle.path().join("acts.yaml"), BROKEN).expect("save");
    let refused = watcher.event("bundle.refused").await;
    let problem = &refused["diagnostics"][0];
    assert_eq!(
        (
            &problem["code"],
            &problem["file"],
            &problem["line"],
            &problem["column"]
        ),
        (
            &json!("unknown-verb"),
            &json!("acts.yaml"),
            &json!(5),
            &json!(7)
        )
    );
    assert_eq!(server.said().await, "Hello two");
    // A console joining now sees the refusal too.
    let late = server.operator().await;
    assert_eq!(
        late.welcome["state"]["reload"]["refused"][0]["code"],
        "unknown-verb"
    );

    // The fix goes live and the banner's state is cleared.
    std::fs::write(bundle.path().join("acts.yaml"), acts("Hello four")).expect("save");
    watcher.event("bundle.reloaded").await;
    assert_eq!(server.said().await, "Hello four");
    let later = server.operator().await;
    assert_eq!(later.welcome["state"]["reload"]["refused"], Value::Null);

    stop.store(true, Ordering::Relaxed);
    let http = http.await.expect("http loop");
    let ws = ws.await.expect("ws loop");
    assert!(!http.is_empty() && !ws.is_empty());
    for (status, text) in &http {
        assert_eq!(
            *status, 202,
            "an HTTP trigger failed during reloads: {text}"
        );
    }
    for frame in &ws {
        assert_eq!(
            frame["type"], "triggered",
            "a websocket trigger failed: {frame}"
        );
    }
    let order = ["Hello one", "Hello two", "Hello four"];
    let http_texts: Vec<String> = http
        .iter()
        .map(|(_, t)| t.as_str().unwrap_or("").to_owned())
        .collect();
    let ws_texts: Vec<String> = ws
        .iter()
        .map(|f| f["text"].as_str().unwrap_or("").to_owned())
        .collect();
    assert_progression(&http_texts, &order, "Hello broken");
    assert_progression(&ws_texts, &order, "Hello broken");
    server.stop().await;
}

#[tokio::test]
async fn kiosks_learn_which_pages_changed_and_a_lost_context_falls_back_to_text() {
    let bundle = TempBundle::new(&acts("Hello"))
        .with_file("pages/index.html", HOME)
        .with_file("pages/other.html", "<!doctype html><title>other</title>");
    let server = Watched::start(bundle.path()).await;
    let mut watcher = server.operator().await;
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    watcher
        .send(json!({"type": "context", "context": "TextChild", "ref": "c"}))
        .await;
    watcher.recv_where(|f| f["ref"] == "c").await;
    assert_eq!(server.said().await, "Hi, Hello");

    // One save: the act loses its TextChild variant and a page changes.
    let plain = "- Label: GREET\n  Text:\n    - Hello again\n";
    std::fs::write(bundle.path().join("acts.yaml"), plain).expect("save");
    std::fs::write(bundle.path().join("pages/other.html"), "<title>new</title>").expect("save");
    // The two files may go live in one reload or in two: wait for what each one does.
    let fallback = watcher
        .event_where(|e| e["type"] == "context.changed" && e["context"] == "Text")
        .await;
    assert_eq!(fallback["source"], "server");
    let changed = kiosk
        .recv_where(|f| f["type"] == "changed" && f["pages"] == json!(["other.html"]))
        .await;
    assert_eq!(changed["shell"], false);
    assert_eq!(server.said().await, "Hello again");
    server.stop().await;
}

#[tokio::test]
async fn a_setting_fixed_at_start_up_is_reported_as_needing_a_restart() {
    let bundle = TempBundle::new(&acts("Hello")).with_file("pages/index.html", HOME);
    let server = Watched::start(bundle.path()).await;
    let mut watcher = server.operator().await;
    let mut kiosk = server
        .client(json!({"type": "hello", "role": "kiosk"}))
        .await;
    let settings = "speech: { voice: de }\nkiosk: { idle: 5s }\n";
    std::fs::write(bundle.path().join("docent.yaml"), settings).expect("save");
    let live = watcher.event("bundle.reloaded").await;
    let said = live["not_applied"].as_array().expect("a list");
    assert_eq!(said.len(), 1, "{said:?}");
    assert!(
        said[0]
            .as_str()
            .is_some_and(|s| s.starts_with("restart Docent for the speech settings")),
        "{said:?}"
    );
    let late = server.operator().await;
    assert_eq!(late.welcome["state"]["reload"]["not_applied"], json!(said));
    // The kiosk's own settings changed: it is told to reload its shell.
    let changed = kiosk.recv_type("changed").await;
    assert_eq!(changed["shell"], true);
    server.stop().await;
}

#[tokio::test]
async fn changed_server_limits_stay_as_started_and_the_operator_is_told_to_restart() {
    let bundle = TempBundle::new(&acts("Hello")).with_file("pages/index.html", HOME);
    let server = Watched::start(bundle.path()).await;
    let mut watcher = server.operator().await;
    let settings = "server:\n  connections: { per_address: 2 }\n";
    std::fs::write(bundle.path().join("docent.yaml"), settings).expect("save");
    let live = watcher.event("bundle.reloaded").await;
    assert_eq!(
        live["not_applied"],
        json!([
            "restart Docent for the server limits (server: connections, timeouts, messages, \
             queues) to take effect"
        ])
    );
    let (status, state) = server.get("/api/state").await;
    assert_eq!(status, 200);
    assert_eq!(
        state["limits"]["connections"]["per_address"], 128,
        "as started"
    );
    server.stop().await;
}

#[tokio::test]
async fn a_deleted_bundle_folder_is_reported_and_the_last_good_bundle_keeps_serving() {
    let bundle = TempBundle::new(&acts("Hello")).with_file("pages/index.html", HOME);
    let server = Watched::start(bundle.path()).await;
    let mut watcher = server.operator().await;
    std::fs::remove_dir_all(bundle.path()).expect("delete the bundle");
    let gone = watcher.event("bundle.watch-failed").await;
    assert_eq!(gone["code"], "folder-missing");
    assert!(
        gone["message"]
            .as_str()
            .is_some_and(|m| m.contains("is gone"))
    );
    assert_eq!(server.said().await, "Hello");
    let late = server.operator().await;
    assert!(late.welcome["state"]["reload"]["trouble"].is_string());

    // Put back (a fresh folder under the same name): watched and checked again.
    let back = TempBundle::new(&acts("Hello back")).with_file("pages/index.html", HOME);
    std::fs::rename(back.dir.keep(), bundle.path()).expect("put the folder back");
    watcher.event("bundle.reloaded").await;
    assert_eq!(server.said().await, "Hello back");
    server.stop().await;
}
